"""The names of a run's outputs, as lagmb.view, linearize and the FMU give
them, read into their parts.

A name is a coordinate (``rod.x``, ``rod.angle``, ``base.e0``: the core
names them, Model.coordinate_names), ``<joint>.reaction.x`` (``.y``,
``.torque``; in space ``.z``, ``.torque.x`` ...), ``<driver>.effort``,
``<joint>.angle`` or ``<joint>.slide``; ``der(...)`` of one is its rate.
:func:`parse` splits a name into those parts; whether the element it names
is a joint or a driver of the model is for the caller to ask (its kind in
lagmb.registry), as is what to say when it is not.
"""

from typing import NamedTuple

from . import _core

#: A reaction's components, in the order of Result.reaction's columns, by the
#: model's dimension: the core's names, which the FMU's variables end in too.
REACTION_COMPONENTS = {d: tuple(_core.reaction_components(d)) for d in (2, 3)}

#: The joint coordinates an output may name (a kind's coordinates, lagmb.registry).
JOINT_COORDINATES = ("angle", "slide")


class OutputName(NamedTuple):
    """One output name in parts: ``der(hinge.reaction.x)`` is rate=True,
    base "hinge.reaction.x", element "hinge", what "reaction.x"."""

    name: str  # as given
    rate: bool  # der(...): the rate of what base names
    base: str  # the name inside der(...)
    element: str  # before the first "."
    what: str  # after it: "x", "angle", "reaction.x", "effort", ...

    @property
    def reaction_component(self):
        """The component of a reaction's name ("x", "torque.y"), else None."""
        return self.what[len("reaction."):] if self.what.startswith("reaction.") else None


def parse(name):
    """The parts of an output name (a str)."""
    rate = name.startswith("der(") and name.endswith(")")
    base = name[4:-1] if rate else name
    element, _, what = base.partition(".")
    return OutputName(name, rate, base, element, what)

