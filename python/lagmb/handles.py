"""Handles: what Model.add_* and drive_* return, accepted wherever the
element's name is.

A handle knows its model, its name, its kind (the element type: "revolute",
"joint_driver", "spring_damper", ...) and its role (what it may stand for:
"body", "joint", "driver", "force", "friction", "stop" or "contact"). It
prints as its name, so ``f"{pin}"`` and ``str(pin)`` are ``"pin"``.

Every place that takes a body or element by name (Model methods, Result and
Equilibrium accessors, plotting, scene output lists) turns "name or handle"
into a name with :func:`name_of`, and nowhere else: a handle of another
model, or of the wrong role (a driver where a joint belongs), is a
ModelError there, saying what was expected.

Equality: two handles are equal when they stand for the same element of the
same model (same model object, same name), and hash alike then. A handle is
*not* equal to its name string: "pin" == handle would make equality
intransitive (the "pin" of two models would both equal "pin" but not each
other) and would put a handle and its name in one dict slot by accident.
Compare names for that: ``handle.name == "pin"`` (or ``str(handle)``).
"""

from ._checks import show
from .errors import ModelError
from .registry import KINDS as _KINDS, ROLES

#: Model method -> (kind, role) of the element it adds, from the registry of
#: element kinds (lagmb.registry).
KINDS = {k.method: (k.name, k.role) for k in _KINDS}

_ROLE_WORDS = {"body": "a body", "joint": "a joint", "driver": "a driver", "force": "a force",
               "friction": "a joint friction", "stop": "a stop", "contact": "a contact"}


class Handle:
    """A body or element of a model, as Model.add_* and drive_* return it.

    Pass it wherever the element's name goes (joints, drivers, stops,
    friction, r.reaction, r.effort, r.body, ...). ``str(handle)`` is its
    name; ``repr`` shows its kind, e.g. ``<lagmb revolute 'pin'>``.
    Attributes (read-only): name, model, kind, role. Equal to another handle
    of the same element of the same model, never to a string (see the
    module docstring).
    """

    __slots__ = ("_name", "_model", "_kind", "_role")

    def __init__(self, name, model, kind, role):
        if role not in ROLES:
            raise ModelError(f"handle role must be one of {', '.join(ROLES)}, got {show(role)}")
        self._name, self._model, self._kind, self._role = name, model, kind, role

    name = property(lambda self: self._name, doc="The element's name (str).")
    model = property(lambda self: self._model, doc="The model the element belongs to.")
    kind = property(lambda self: self._kind, doc='The element type: "revolute", "body", ...')
    role = property(lambda self: self._role,
                    doc='What it stands for: "body", "joint", "driver", "force", "friction", '
                        '"stop" or "contact".')

    def __str__(self):
        return self._name

    def __format__(self, spec):
        return format(self._name, spec)

    def __repr__(self):
        return f"<lagmb {self._kind} {self._name!r}>"

    def __eq__(self, other):
        if not isinstance(other, Handle):
            return NotImplemented
        return self._model is other._model and self._name == other._name

    def __hash__(self):
        return hash((id(self._model), self._name))


class Body(Handle):
    """Handle of a body or particle (or the ground, index -1) in a model:
    a Handle with role "body" and the index of the body in the model."""

    __slots__ = ("_index",)

    def __init__(self, name, model, index, kind="body"):
        super().__init__(name, model, kind, "body")
        self._index = index

    index = property(lambda self: self._index,
                     doc="Position among the model's bodies (-1: the ground).")


def _model_text(model):
    bodies = [b.name for b in getattr(model, "bodies", [])]
    listed = ", ".join(bodies[:4]) + (", ..." if len(bodies) > 4 else "")
    return f"the Model at 0x{id(model):x}" + (f" with bodies {listed}" if bodies else " without bodies")


def name_of(model, item, accepts, what, context):
    """The name of a body or element of ``model`` given by its handle or its
    name: the one way "name or handle" becomes a name.

    accepts: the roles a handle may have here, e.g. ("joint",) or
    ("joint", "driver"); what: the argument ("body_i", "joint", "element");
    context: who asks, for messages ("stop 'limit'", "Result.reaction").
    A string is returned as given (the caller or the core says if there is
    no such element); a handle must belong to ``model`` (or to the model
    that ``model``, a run's snapshot, copies) and have one of the accepted
    roles; anything else is refused. Raises ModelError.
    """
    expected = " or ".join(_ROLE_WORDS[r] for r in accepts)
    if isinstance(item, str):
        return item
    if isinstance(item, Handle):
        # (a run's snapshot of a model takes the handles of the model it copies)
        if item.model is not model and item.model is not getattr(model, "_source", None):
            raise ModelError(
                f"{context}: {what} {item!r} is a handle of another model ({_model_text(item.model)}), "
                f"not of this one ({_model_text(model)})")
        if item.role not in accepts:
            role = "" if item.kind == item.role else f" ({_ROLE_WORDS[item.role]})"
            raise ModelError(f"{context}: {what}: expected {expected} (its handle or name), "
                             f"got {item!r}{role}")
        return item.name
    raise ModelError(f"{context}: {what}: expected {expected} (its handle or name), got {show(item)}")
