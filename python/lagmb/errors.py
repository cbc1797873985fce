"""Exceptions raised by lagmb (docs/design.md, section 6)."""

import contextlib
import importlib

from . import _core

#: Bad input: a value or name that cannot make a model. A ValueError.
ModelError = _core.ModelError
ModelError.__doc__ = """Bad input: a value, a name or an option that cannot make a model or a
run. The message names the element, the key and the value as given. A
ValueError (raised by the C++ core as lagmb::ModelError)."""


class RedundantConstraintWarning(UserWarning):
    """Some constraint equations depend on the others (e.g. a parallelogram
    with a third crank). lagmb drops them (they read 0 = 0, their multipliers
    are 0) and simulates the unique motion; the reaction of a redundant set is
    carried by its remaining equations. Only sums over the set are physically
    determined."""


class AssemblyWarning(UserWarning):
    """Assembly moved bodies a long way from where the model put them: their
    given positions did not satisfy the joints (a joint point given off by
    a link's length, a crank angle that the loop cannot close with). The run
    goes on from the assembled configuration; the warning counts the bodies
    moved by more than 1e-3 of the mechanism's size or 1e-3 rad and names
    the five moved most, each with how far and how much it turned."""


class DeepContactWarning(UserWarning):
    """A run starts with the shapes of a contact deep inside each other:
    pressing them with more than ten times the weight of all the bodies
    (without gravity, their mass times 9.81 m/s^2), a start no part of the
    model can rest in. Such a start throws the bodies apart (or, the
    contact's damping holding them, lets them out slowly), or the solver
    fails at the first step. The warning names each such contact, its two
    shapes, its depth (m) and its force, the deepest first
    (docs/modelling.md, "Starting in contact")."""


class SimulationError(RuntimeError):
    """The solver could not go on.

    Attributes:

    - t: time reached (s).
    - result: the outputs computed before the failure, as a Result (None
      when nothing was computed, e.g. the model could not be assembled).
    """

    def __init__(self, message, t=float("nan"), result=None):
        super().__init__(message)
        self.t = t
        self.result = result


class AssemblyError(SimulationError):
    """The initial positions cannot be made to satisfy the constraints.

    Attributes:

    - violated: list of (element name, max ``|Phi|``), largest first.
    """

    def __init__(self, message, t=float("nan"), violated=()):
        super().__init__(message, t, None)
        self.violated = list(violated)


#: No static equilibrium, or an unstable one not allowed (mb.equilibrium).
#: A ModelError, so a ValueError.
EquilibriumError = _core.EquilibriumError
EquilibriumError.__doc__ = """No static equilibrium near the start, or an unstable one where a
stable one was asked (mb.equilibrium): the message says which. A
ModelError, so a ValueError."""


class KinematicOnlyError(ModelError):
    """A quantity a kinematic-only analysis does not compute (the multipliers
    and everything derived from them: reactions, driver efforts) was asked
    for. Run with analysis="inverse_dynamics" (all masses > 0) to get them."""


class MissingExtraError(ModelError, ModuleNotFoundError):
    """A feature needs a package of one of lagmb's optional extras, and it
    is not installed: the message names the feature, the package and the
    extra to install (``pip install "lagmb[sweep]"``). A ModelError and a
    ModuleNotFoundError (an ImportError): ``.name`` is the missing module,
    ``.extra`` the extra."""

    def __init__(self, message, name=None, extra=None):
        super().__init__(message)
        self.name, self.extra = name, extra


def extra_module(module, extra, who):
    """The module ``module`` (imported), which ``who`` needs from lagmb's
    optional extra ``extra``; MissingExtraError naming them where it
    cannot be imported."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        missing = getattr(e, "name", None) or module
        why = "" if missing.split(".")[0] == module.split(".")[0] else f" (it could not import {missing}: {e})"
        raise MissingExtraError(f"{who} needs {module.split('.')[0]}{why}, from lagmb's optional '{extra}' extra: "
                                f'pip install "lagmb[{extra}]"',
                                module, extra) from None


@contextlib.contextmanager
def translated(partial_result=None):
    """Turn the core's solver errors into lagmb's, with the exception a user
    function raised as their cause. ``partial_result(raw)`` makes the
    outputs a failed run reached into a Result (or None): a SimulationError
    carries it as ``.result``, and an interrupt (KeyboardInterrupt,
    SystemExit) passes unchanged, carrying it as ``.result`` too."""
    def partial(raw):
        return None if partial_result is None or raw is None else partial_result(raw)

    try:
        yield
    except _core.AssemblyError as e:
        raise AssemblyError(str(e), e.t, e.violated) from e.__cause__
    except _core.SimulationError as e:
        raise SimulationError(str(e), e.t, partial(e.partial)) from e.__cause__
    except (KeyboardInterrupt, SystemExit) as e:
        e.result = partial(getattr(e, "partial", None))
        raise
