"""Vibration modes of a mechanism about a static equilibrium (``mb.modes``).

About a state at rest, motions small enough to be linear obey

    M dq'' + C dq' + K dq + Phi_q^T dlam = 0,   Phi_q dq = 0,

with M = M(q), K = (Phi_q^T lam)_q - Q_q (the tangent stiffness) and
C = -Q_v, all exact (``lagmb._core.tangent_at_rest``, from the elements'
own derivatives). In an orthonormal basis Z of the motions the joints
allow (dq = Z z; Z spans the null space of the rows of Phi_q kept at the
equilibrium, from an SVD):

    Mr z'' + Cr z' + Kr z = 0,   Mr = Z^T M Z,  Kr = Z^T K Z,  Cr = Z^T C Z.

The modes are those of the undamped system, Kr phi = omega^2 Mr phi
(phi^T Mr phi = 1); a mode's damping ratio is phi^T Cr phi / (2 omega), exact
where C acts mode by mode (damping proportional to M and K) and the usual
modal estimate otherwise. The damped system's eigenvalues (of
[[0, I], [-Mr^-1 Kr, -Mr^-1 Cr]]) are given as they are.
"""

import numpy as np

from . import _core
from .errors import ModelError
from .statics import Equilibrium, equilibrium


class Modes:
    """The vibration modes of a mechanism at an equilibrium (mb.modes).

    Attributes, one entry per mode (the number of degrees of freedom left by
    the joints and drivers), ordered by omega ascending:

    - omega_squared (rad^2/s^2): the eigenvalues of Kr phi = omega^2 Mr phi;
    - omega (rad/s): ``sqrt(abs(omega^2))``, for an unstable mode the rate
      exp(omega t) at which it grows; frequencies (Hz): omega / (2 pi);
    - kinds: "vibration", "rigid-body" (omega^2 within ``tol`` of 0 relative
      to the largest: a motion nothing resists, such as a free spin) or
      "unstable" (omega^2 < 0: the equilibrium is unstable in this mode);
    - damping_ratios: phi^T Cr phi / (2 omega) (NaN for a rigid-body mode);
    - shapes (k, n): each mode as a motion of the model's coordinates q,
      scaled so that its largest entry is +1;
    - eigenvalues (2k,): of the damped system, complex, ordered by magnitude;
    - equilibrium: the :class:`Equilibrium` the modes are about.

    ``len(modes)`` is the number of modes.
    """

    def __init__(self, equilibrium, omega_squared, kinds, damping_ratios, shapes, eigenvalues):
        self.equilibrium = equilibrium
        self.omega_squared = omega_squared
        self.omega = np.sqrt(np.abs(omega_squared))
        self.frequencies = self.omega / (2.0 * np.pi)
        self.kinds = kinds
        self.damping_ratios = damping_ratios
        self.shapes = shapes
        self.eigenvalues = eigenvalues

    def __len__(self):
        return len(self.omega)

    def __repr__(self):
        rows = ", ".join(f"{f:.4g} Hz ({k})" for f, k in zip(self.frequencies, self.kinds))
        return f"<lagmb.Modes: {len(self)} modes{': ' + rows if rows else ''}>"


def _null_space(J, tol):
    """An orthonormal basis (columns) of the null space of J (rows x n)."""
    n = J.shape[1]
    if J.shape[0] == 0:
        return np.eye(n)
    _, s, vt = np.linalg.svd(J)
    rank = int(np.sum(s > tol * max(s[0], 1e-300))) if s.size else 0
    return vt[rank:].T


def modes(model, at=None, *, tol=1e-9):
    """Vibration modes about a static equilibrium: natural frequencies,
    damping ratios and mode shapes (see :class:`Modes`).

    ``at``: the :class:`Equilibrium` to linearize about (from
    ``mb.equilibrium``), or None for ``mb.equilibrium(model,
    allow_unstable=True)`` (an unstable equilibrium has modes too: they say
    how it falls). Dense linear algebra: for models of up to a few hundred
    coordinates. ModelError for an ``at`` that is not an equilibrium of this
    model, or a tangent stiffness that is not symmetric (non-conservative
    forces: its undamped modes are not real; the damped eigenvalues still
    say how the motion grows or decays).
    """
    from .model import checked as _model

    _model(model, "modes")
    if at is None:
        at = equilibrium(model, allow_unstable=True)
    elif not isinstance(at, Equilibrium):
        raise ModelError(f"modes: at must be an equilibrium from mb.equilibrium(model) or None, "
                         f"got {type(at).__name__}")
    elif at.model is not model:
        raise ModelError("modes: at is an equilibrium of another model")
    core = model.compiled()
    tangent = _core.tangent_at_rest(core, at.q, at.lam, at.t, at.dropped_rows)
    M, K, C = (np.asarray(tangent[k]) for k in ("M", "K", "C"))
    kept = np.setdiff1d(np.arange(len(at.lam)), at.dropped_rows)
    Z = _null_space(np.asarray(tangent["Phi_q"])[kept], 1e-10)
    k = Z.shape[1]
    n = len(at.q)
    if k == 0:
        return Modes(at, np.zeros(0), [], np.zeros(0), np.zeros((0, n)), np.zeros(0, complex))
    Mr, Kr, Cr = Z.T @ M @ Z, Z.T @ K @ Z, Z.T @ C @ Z
    scale = max(np.abs(Kr).max(), 1e-300)
    if np.abs(Kr - Kr.T).max() > 1e-8 * scale:
        raise ModelError("modes: the tangent stiffness is not symmetric (largest difference "
                         f"{np.abs(Kr - Kr.T).max():.3g} against {scale:.3g}): non-conservative forces "
                         "(a follower force, friction) have no real undamped modes")
    Kr = 0.5 * (Kr + Kr.T)
    L = np.linalg.cholesky(0.5 * (Mr + Mr.T))
    Linv = np.linalg.inv(L)
    omega_squared, Y = np.linalg.eigh(Linv @ Kr @ Linv.T)
    order = np.argsort(np.abs(omega_squared), kind="stable")  # by omega = sqrt(|omega^2|)
    omega_squared, Y = omega_squared[order], Y[:, order]
    phi = Linv.T @ Y  # mass-normalized: phi^T Mr phi = I
    largest = max(np.abs(omega_squared).max(), 1e-300)
    kinds = ["rigid-body" if abs(w2) <= tol * largest else "unstable" if w2 < 0 else "vibration"
             for w2 in omega_squared]
    omega = np.sqrt(np.abs(omega_squared))
    modal_damping = np.einsum("ij,ik,kj->j", phi, Cr, phi)
    damping_ratios = np.array([c / (2.0 * w) if kind != "rigid-body" else np.nan
                               for c, w, kind in zip(modal_damping, omega, kinds)])
    shapes = (Z @ phi).T
    for row in shapes:
        big = row[np.argmax(np.abs(row))]
        row /= big
    A = np.block([[np.zeros((k, k)), np.eye(k)],
                  [-np.linalg.solve(Mr, Kr), -np.linalg.solve(Mr, Cr)]])
    eigenvalues = np.linalg.eigvals(A)
    eigenvalues = eigenvalues[np.argsort(np.abs(eigenvalues), kind="stable")]
    return Modes(at, omega_squared, kinds, damping_ratios, shapes, eigenvalues)
