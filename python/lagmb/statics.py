"""Static equilibrium: mb.equilibrium(model) (cpp/include/lagmb/analyses/equilibrium.hpp)."""


import numpy as np

from . import _core
from .errors import EquilibriumError, ModelError
from .result import core_state, element_name, reaction_about, rebuilt_core, rotation_matrices


class EquilibriumBody:
    """Pose of one body in equilibrium. Planar: position (2,) of its centre
    of mass and angle (0 for a particle). Spatial: position (3,),
    orientation (4,), its Euler parameters (w, x, y, z), and rotation
    (3, 3), body axes into global axes."""

    def __init__(self, **pose):
        self.__dict__.update(pose)

    def __repr__(self):
        fields = ", ".join(f"{k}={np.asarray(v).tolist() if not isinstance(v, float) else v!r}"
                           for k, v in self.__dict__.items() if k != "rotation")
        return f"EquilibriumBody({fields})"


class Equilibrium:
    """A static equilibrium found by mb.equilibrium.

    Attributes:

    - q (n,), lam (m,): coordinates and multipliers (sign of docs/modelling.md,
      'Equations and signs': Q(q, 0, t) = Phi_q^T lam).
    - t: the time it holds at.
    - stable: the tangent stiffness reduced to the motions the joints
      allow is positive definite (a strict minimum of the potential);
      None when found with ``stability=False``.
    - stiffness_eigenvalues: its eigenvalues, ascending (N/m, N m/rad
      mixed; empty when nothing can move or unchecked), and softest_mode
      (n,) the motion of the smallest.
    - dropped_rows: the rows of Phi left out there (lam is 0 in them),
      ascending: those redundant there, and the rows of stops (which the
      search does not hold).
    - iterations: Newton iterations; force_residual (max
      ``|Q - Phi_q^T lam|``, N or N m) and constraint_residual (max ``|Phi|``).
    """

    def __init__(self, model, core, raw, t, snapshot=None):
        self.model = model
        self._core = core
        self._snapshot = snapshot if snapshot is not None else model  # the model as it was solved (pickling)
        self.t = float(t)
        self.q = np.asarray(raw["q"], dtype=float)
        self.lam = np.asarray(raw["lam"], dtype=float)
        self.stable = None if raw["stable"] is None else bool(raw["stable"])
        self.dropped_rows = [int(r) for r in raw["dropped_rows"]]
        self.iterations = int(raw["iterations"])
        self.stiffness_eigenvalues = np.asarray(raw["stiffness_eigenvalues"], dtype=float)
        self.softest_mode = np.asarray(raw["softest_mode"], dtype=float)
        self.force_residual = float(raw["force_residual"])
        self.constraint_residual = float(raw["constraint_residual"])

    def __reduce__(self):
        """Pickled as its model's description and its numbers (Result's way):
        the copy answers as this one, bit for bit; its .model is the copy's
        own model (Modes and LinearSystem pickle with it)."""
        raw = dict(q=self.q, lam=self.lam, stable=self.stable, dropped_rows=self.dropped_rows,
                   iterations=self.iterations, stiffness_eigenvalues=self.stiffness_eigenvalues,
                   softest_mode=self.softest_mode, force_residual=self.force_residual,
                   constraint_residual=self.constraint_residual)
        return _unpickled_equilibrium, (*core_state(self._snapshot, self._core), raw, self.t)

    def _name(self, item, accepts, what, context):
        return element_name(self.model, self._core, item, accepts, what, context)

    def body(self, body):
        """Pose of a body (handle or name): .position (2,) and .angle in the
        plane; .position (3,), .orientation (4,) and .rotation (3, 3) in space."""
        first, count = self._core.body_coordinates(self._name(body, ("body",), "body", "Equilibrium.body"))
        x = self.q[first:first + count]
        if count == 7:
            return EquilibriumBody(position=x[:3].copy(), orientation=x[3:].copy(),
                                   rotation=rotation_matrices(x[None, 3:])[0])
        return EquilibriumBody(position=x[:2].copy(), angle=float(x[2]) if count == 3 else 0.0)

    def reaction(self, element, frame="global", about="centre of mass"):
        """(3,): force (x, y) in N on the element's second body and the torque
        in N m about its centre of mass ((6,) in space), as Result.reaction;
        ``about="joint"``: the torque about the joint's point instead."""
        if frame not in ("global", "joint"):
            raise ModelError(f"frame must be 'global' or 'joint', got {frame!r}")
        about_joint = reaction_about(about)
        name = self._name(element, ("joint", "driver"), "element", "Equilibrium.reaction")
        out = self._core.reaction(name, np.array([self.t]), self.q[None, :],
                                  self.lam[None, :], frame == "joint", about_joint=about_joint)
        return np.asarray(out)[0]

    def __repr__(self):
        state = {True: "stable", False: "not stable", None: "stability not checked"}[self.stable]
        return (f"<lagmb.Equilibrium at t = {self.t:g}: {state}, "
                f"{self.iterations} Newton iterations>")


def _unpickled_equilibrium(model, parameters, raw, t):
    return Equilibrium(model, rebuilt_core(model, parameters), raw, t)


def equilibrium(model, t=0.0, *, tol=1e-12, max_iterations=100, allow_unstable=False, stability=True):
    """Static equilibrium of a model at time t (at rest: v = 0).

    Solves Q(q, 0, t) = Phi_q^T lam, Phi(q, t) = 0 by Newton with exact
    derivatives (step-limited, with a line search) from the assembled initial
    configuration, then checks stability: the tangent stiffness H(lam) - Q_q
    reduced to the null space of Phi_q must be positive definite (a dense
    check: O(n^3) in the coordinates, about 15 s for a 1,000-link chain;
    ``stability=False`` skips it, and then ``stable`` is None and
    ``allow_unstable`` has no effect). ``tol`` is relative (forces to
    ``tol |Q|``, constraints to ``tol (1 + |q|)``). Returns an
    :class:`Equilibrium`.

    Raises EquilibriumError (a ValueError) if a force or driver function
    raises (chained as its cause), if there is none nearby (naming
    the coordinates with the largest unbalanced force, e.g. a free body
    under gravity) or if the one found is unstable (naming the mode), unless
    ``allow_unstable=True``; AssemblyError if the joints cannot be closed.
    """
    from .result import translated_run

    from ._checks import INT_MAX, flag as _flag, integer as _integer, real as _real
    from .model import checked as _model

    _model(model, "equilibrium")
    t = _real(t, "t")
    tol = _real(tol, "tol")
    if not 0 < tol < 1:
        raise ModelError(f"tol must be in (0, 1), got {tol!r}")
    max_iterations = _integer(max_iterations, "max_iterations", 1, INT_MAX)
    allow_unstable = _flag(allow_unstable, "equilibrium: allow_unstable")
    stability = _flag(stability, "equilibrium: stability")
    snapshot = model._snapshot()  # an edit from another thread meanwhile changes nothing here
    core = snapshot.compiled()
    with translated_run(model, core, snapshot):
        try:
            raw = _core.equilibrium(core, t, tol, max_iterations, allow_unstable, stability)
        except _core.UserFunctionError as e:  # a force or driver function failed
            raise EquilibriumError(f"equilibrium: {e}") from e.__cause__
    return Equilibrium(model, core, raw, t, snapshot)
