"""Contacts whose shapes start deep inside each other (docs/modelling.md,
"Starting in contact"): a DeepContactWarning where a run starts, and what a
run that fails at its start says about them.

A contact at rest presses its shapes in until it carries its load: under
the weight W of all the bodies on one point, (W / k)^(2/3). A start whose
elastic force (the law at the start's positions, at rest) exceeds
DEEP_LOAD W cannot be a resting state of any part of the model under
gravity alone: its point is more than DEEP_LOAD^(2/3) = 4.6 times deeper than the
whole weight would press it, and the contact throws the bodies apart (or
holds them in, creeping out at the pace its damping allows), or the
integrator fails at the first step. Without gravity, W is the bodies' mass
times 9.81 m/s^2 (a load of one g).
"""

import contextlib

import numpy as np

from .errors import AssemblyError, DeepContactWarning, SimulationError
from .result import ContactPath

DEEP_LOAD = 10.0  # x the bodies' weight: a contact pressing harder at the start starts deep
G_REFERENCE = 9.81  # m/s^2: the load of one g, without gravity
LISTED = 3  # contacts named in a message (the deepest), then a count


def _shape_text(value, bodies):
    """'a sphere on 'ball'' for a core shape (body index, kind, ...)."""
    kind = "convex hull" if value[1] == "convex" else value[1]
    return f"a {kind} on " + ("the ground" if value[0] < 0 else f"'{bodies[value[0]]}'")


def _shapes(kind, values, bodies):
    """What the contact pairs, for messages."""
    if kind == "spatial_contact":
        return f"{_shape_text(values['shape_a'], bodies)} and {_shape_text(values['shape_b'], bodies)}"
    on = [("the ground" if values[b] < 0 else f"'{bodies[values[b]]}'") for b in ("circle_body", "line_body")]
    return f"a circle of radius {values['radius']:.3g} m on {on[0]} and a line on {on[1]}"


def pressed(snapshot, core, q, t0):
    """The contacts pressed in at positions q (at rest): [(depth m, elastic
    force N, name, what it pairs)], deepest first; and the bodies' weight W
    (N; 0: no mass)."""
    bodies = [name for name, _ in snapshot._spec.bodies]
    contacts = [(kind, name, values) for kind, name, values in snapshot._spec.elements()
                if kind in ("contact", "spatial_contact")]
    if not contacts:
        return [], 0.0
    q = np.asarray(q, dtype=float)
    # the total mass: twice the kinetic energy of every body moving at 1 m/s along x
    v = np.zeros_like(q)
    for name in bodies:
        v[core.body_coordinates(name)[0]] = 1.0
    g = float(np.linalg.norm(snapshot.gravity or 0.0)) or G_REFERENCE
    weight = 2.0 * core.kinetic_energy(q, v) * g
    out = []
    at_rest, lam = np.zeros((1, q.size)), np.zeros((1, core.n_constraints))  # (lam: the stick rows' friction, none)
    for kind, name, values in contacts:
        reading = ContactPath(core.contact(name, np.array([t0]), q[None], at_rest, lam=lam), core.dimension)
        depth, force = float(reading.penetration[0]), float(reading.normal_force[0])
        if depth > 0.0:
            out.append((depth, force, name, _shapes(kind, values, bodies)))
    return sorted(out, key=lambda c: -c[0]), weight


def _listed(contacts, weight):
    text = "; ".join(f"'{name}' {depth:.3g} m deep ({shapes}, pressing with {force:.3g} N"
                     + (f", {force / weight:.3g} times the bodies' weight)" if weight > 0 else ")")
                     for depth, force, name, shapes in contacts[:LISTED])
    return text + (f"; and {len(contacts) - LISTED} more" if len(contacts) > LISTED else "")


def deep(contacts, weight):
    """Those of `pressed`'s contacts that start deep (their force above DEEP_LOAD W)."""
    return [c for c in contacts if weight > 0.0 and c[1] > DEEP_LOAD * weight]


def warn(snapshot, core, q, t0, into=None, stacklevel=3):
    """A DeepContactWarning naming the contacts that start deep at
    positions q (the deepest first, with their depths and forces); -> the
    contacts pressed in at q and the weight (for `failure_note`)."""
    contacts, weight = pressed(snapshot, core, q, t0)
    found = deep(contacts, weight)
    if found:
        import warnings

        warning = DeepContactWarning(
            (f"{len(found)} contacts start with their shapes" if len(found) > 1 else "a contact starts with its shapes")
            + f" deep inside each other: {_listed(found, weight)}. At rest a contact carries at most the bodies' weight "
            f"({weight:.3g} N); one pressing with more than {DEEP_LOAD:g} times that throws the bodies apart (or, its "
            "damping holding them, lets them out slowly), or the solver fails at the start. Place the shapes "
            "touching, or apart.")
        (into.append if into is not None else lambda w: warnings.warn(w, stacklevel=stacklevel + 1))(warning)
    return contacts, weight


def failure_note(contacts, weight):
    """What a run that failed at its start adds to its message: the contacts
    it started deepest in ('' if none presses)."""
    if not contacts:
        return ""
    found = deep(contacts, weight)
    return (f" It started with {'contacts deep' if found else 'contacts pressed in'} (the deepest first): "
            f"{_listed(found or contacts, weight)}.")


@contextlib.contextmanager
def noted(start, t0):
    """A SimulationError at t0 (not an AssemblyError) with `failure_note`
    of `start` (what `warn` returned) added to its message."""
    try:
        yield
    except SimulationError as e:
        note = "" if isinstance(e, AssemblyError) or e.t > t0 else failure_note(*start)
        if not note:
            raise
        raise SimulationError(str(e) + note, e.t, e.result) from e.__cause__
