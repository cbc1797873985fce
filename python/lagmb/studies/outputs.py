"""The built-in outputs of a sweep (``mb.sweep.final``, ...): module-level
classes, so that a process pool or a Dask client pickles them, each with
the unit its values carry.
"""

import numpy as np

from .. import _output_names, registry
from ..errors import ModelError


class Final:
    """The value of a coordinate (``"slider.x"``, ``"rod.angle"``; ``der(...)``
    for its rate) at the run's last output."""

    def __init__(self, coordinate):
        self.coordinate = str(coordinate)

    def __call__(self, r):
        output = _output_names.parse(self.coordinate)
        names = r._core.coordinate_names()
        if output.base not in names:
            body = output.base.rpartition(".")[0]
            first, count = r._core.body_coordinates(body)
            has = ", ".join(n.rpartition(".")[2] for n in names[first:first + count])
            raise ModelError(f"final: no coordinate {output.base!r} (body {body!r} has {has})")
        return float((r.v if output.rate else r.q)[-1, names.index(output.base)])

    def unit(self, model):
        """m, rad (or 1 for an Euler parameter), per s for a rate."""
        output = _output_names.parse(self.coordinate)
        unit = {"x": "m", "y": "m", "z": "m", "angle": "rad"}.get(output.base.rpartition(".")[2], "")
        return (f"{unit}/s" if unit else "1/s") if output.rate else unit

    def __repr__(self):
        return f"final({self.coordinate!r})"


class PeakReaction:
    """The largest magnitude of the force a joint or driver applies on its
    second body over the run (N): max over outputs of the norm of the
    reaction's force components."""

    def __init__(self, element):
        self.element = str(element)

    def __call__(self, r):
        R = r.reaction(self.element)
        force = R[:, :3] if R.shape[1] == 6 else R[:, :2]
        return float(np.linalg.norm(force, axis=1).max())

    def unit(self, model):
        return "N"

    def __repr__(self):
        return f"peak_reaction({self.element!r})"


class PeakEffort:
    """The largest magnitude of a driver's effort over the run (N along a
    slide or a body's x, y, z; N m along an angle)."""

    def __init__(self, driver):
        self.driver = str(driver)

    def __call__(self, r):
        return float(np.abs(r.effort(self.driver)).max())

    def unit(self, model):
        kinds = registry.BY_METHOD if model.dimension == 2 else registry.SPATIAL_BY_METHOD
        return registry.effort_unit(model.elements, kinds, self.driver)

    def __repr__(self):
        return f"peak_effort({self.driver!r})"


class EnergyDrift:
    """max abs(E(t) - E(0)) over the run (J): for a conservative model, the
    integration error in energy."""

    def __call__(self, r):
        E = r.energy
        return float(np.abs(E - E[0]).max())

    def unit(self, model):
        return "J"

    def __repr__(self):
        return "energy_drift()"


def final(coordinate):
    """Output: the coordinate's value at the last output (:class:`Final`)."""
    return Final(coordinate)


def peak_reaction(element):
    """Output: the largest force magnitude of a joint or driver (:class:`PeakReaction`)."""
    return PeakReaction(element)


def peak_effort(driver):
    """Output: the largest magnitude of a driver's effort (:class:`PeakEffort`)."""
    return PeakEffort(driver)


def energy_drift():
    """Output: the largest change of the energy over the run (:class:`EnergyDrift`)."""
    return EnergyDrift()



#: The built-in outputs' classes: what a store records of each is its repr.
BUILT_IN = (Final, PeakReaction, PeakEffort, EnergyDrift)
