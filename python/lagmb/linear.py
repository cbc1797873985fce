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

That is dense (O(n^3)). For a large model ``count=k`` (automatic above 600
coordinates) finds the k modes nearest omega^2 = 0 without Z: the
constrained problem K x = omega^2 M x, Phi_q x = 0 in the model's
coordinates by shift-invert Lanczos, each step a solve with the sparse LU of
[[K - sigma M, Phi_q^T], [Phi_q, 0]] (the matrices of
``lagmb._core.tangent_at`` as triplets), sigma just below 0.
"""

import math
import numbers

import numpy as np

from . import _core, _output_names, registry
from ._checks import array, positive, real, show
from .errors import ModelError
from .handles import name_of
from .statics import Equilibrium, equilibrium


class Modes:
    """The vibration modes of a mechanism at an equilibrium (mb.modes).

    Attributes, one entry per mode (the number of degrees of freedom left by
    the joints and drivers; the lowest ``count`` of them from the sparse
    path), ordered by omega ascending:

    - omega_squared (rad^2/s^2): the eigenvalues of Kr phi = omega^2 Mr phi;
    - omega (rad/s): ``sqrt(abs(omega^2))``, for an unstable mode the rate
      exp(omega t) at which it grows; frequencies (Hz): omega / (2 pi);
    - kinds: "vibration", "rigid-body" (omega^2 within ``tol`` of 0 relative
      to the largest: a motion nothing resists, such as a free spin) or
      "unstable" (omega^2 < 0: the equilibrium is unstable in this mode);
    - damping_ratios: phi^T Cr phi / (2 omega) (NaN for a rigid-body mode);
    - shapes (k, n): each mode as a motion of the model's coordinates q,
      scaled so that its largest entry is +1;
    - eigenvalues (2k,): of the damped system, complex, ordered by magnitude
      (from the sparse path: of the system reduced to the modes found);
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

    def moves_most(self, i):
        """What mode ``i`` moves most, in words a user reads: a joint where
        the model has revolute, translational or cylindrical joints (the one
        whose angle changes most along the mode, else whose slide does:
        "joint 'elbow' (angle)"), else a body's direction ("top turns about
        x", "block moves along y"; a spatial body's turn from its Euler
        parameters, omega = 2 (w dv - dw v + v x dv), about the global
        axes)."""
        from . import registry

        eq = self.equilibrium
        core, q, shape = eq._core, np.asarray(eq.q, dtype=float), np.asarray(self.shapes[i], dtype=float)
        joints = []
        model = eq._snapshot  # (the model as it was solved)
        for kind, name, _ in model._spec.elements():
            coordinates = registry.BY_NAME[kind].coordinates if kind in registry.BY_NAME else ()
            if {"angle", "slide"} & set(coordinates):
                joints.append((name, "angle" not in coordinates))
        if joints:
            rates = np.abs(core.joint_motions(joints, q, shape, np.zeros(core.run_state_size))[:, 1])
            angles = [k for k, (_, slide) in enumerate(joints) if not slide]
            pool = angles if angles and rates[angles].max() > 1e-9 * rates.max() else range(len(joints))
            k = max(pool, key=lambda j: rates[j])
            if rates[k] > 0:
                return f"joint '{joints[k][0]}' ({'slide' if joints[k][1] else 'angle'})"
        names = model.coordinate_names
        k = int(np.abs(shape).argmax())
        body, coordinate = names[k].rsplit(".", 1)
        if coordinate == "angle":
            return f"{body} turns"
        if coordinate in ("e0", "e1", "e2", "e3"):
            at = names.index(f"{body}.e0")
            w, v = q[at], q[at + 1:at + 4]
            dw, dv = shape[at], shape[at + 1:at + 4]
            turn = 2.0 * (w * dv - dw * v + np.cross(v, dv))
            return f"{body} turns about {'xyz'[int(np.abs(turn).argmax())]}"
        return f"{body} moves along {coordinate}"

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


SPARSE_ABOVE = 600  # coordinates: above this mb.modes computes the lowest DEFAULT_COUNT modes sparsely
DEFAULT_COUNT = 10


def modes(model, at=None, *, tol=1e-9, count=None):
    """Vibration modes about a static equilibrium: natural frequencies,
    damping ratios and mode shapes (see :class:`Modes`).

    ``at``: the :class:`Equilibrium` to linearize about (from
    ``mb.equilibrium``), or None for ``mb.equilibrium(model,
    allow_unstable=True)`` (an unstable equilibrium has modes too: they say
    how it falls).

    ``count``: None (the default) for every mode by dense linear algebra
    (O(n^3) in the n coordinates: for models of up to a few hundred); or the
    number k of lowest-frequency modes (smallest ``abs(omega^2)``) to compute
    with SciPy's sparse linear algebra, for large models. A model of more
    than 600 coordinates (a 200-link planar chain) takes the sparse path on
    its own, with ``count=10`` (or all its degrees of freedom if fewer).

    The sparse path solves K x = omega^2 M x, Phi_q x = 0 (the rows of Phi
    kept at the equilibrium) in the model's coordinates, by shift-invert
    Lanczos (``scipy.sparse.linalg.eigsh``) with a sparse LU
    (``scipy.sparse.linalg.splu``) of [[K - sigma M, Phi_q^T], [Phi_q, 0]]
    as the operator: no dense n x n matrix. The shift sigma is just below 0
    (1e-9 times the largest ratio of a diagonal entry of K to M's), so the
    modes found are those nearest omega^2 = 0 on either side: rigid-body
    modes, the slowest vibrations and the slowest-growing unstable modes.
    An unstable mode growing faster than the k-th frequency is left out:
    ``mb.equilibrium``'s stability check says whether there is any (at=None
    finds the equilibrium without it there, ``stable`` is None). The
    computed modes are refined by a Rayleigh-Ritz step, mass-normalized
    (phi^T M phi = 1) and scaled like the dense ones; damping ratios are
    phi^T C phi / (2 omega) as there. ``eigenvalues`` are those of the damped
    system reduced to the k modes found (z'' + Cm z' + diag(omega^2) z = 0,
    Cm = Phi^T C Phi, 2k of them): the full system's own where the damping
    does not couple those modes to the others (damping proportional to M
    and K), otherwise an approximation. A mode is rigid-body when
    ``abs(omega^2)`` is below ``tol`` (in (0, 1)) times that diagonal ratio
    (on the dense path: times the largest omega^2). With few degrees of freedom (at most 2 k + 20)
    the sparse path takes them all from an orthonormal basis of the motions
    the joints allow (a sparse projection) and keeps the k lowest. SciPy is
    needed for the sparse path only.

    ModelError for an ``at`` that is not an equilibrium of this model, a
    ``count`` below 1 or above the number of degrees of freedom, the sparse
    path without SciPy, or a tangent stiffness that is not symmetric
    (non-conservative forces: its undamped modes are not real; the damped
    eigenvalues still say how the motion grows or decays, see
    ``mb.linearize``).
    """
    from .model import checked as _model

    _model(model, "modes")
    tol = positive(tol, "modes: tol")
    if not tol < 1:
        raise ModelError(f"modes: tol must be below 1 (a fraction of the largest omega^2), got {tol!r}")
    if count is not None:
        if isinstance(count, bool) or not isinstance(count, numbers.Real) or not (
                isinstance(count, numbers.Integral) or (math.isfinite(count) and float(count).is_integer())):
            raise ModelError(f"modes: count must be a whole number of modes or None, got {show(count)}")
        count = int(count)
        if count < 1:
            raise ModelError(f"modes: count must be at least 1, got {count}")
    if at is not None and not isinstance(at, Equilibrium):
        raise ModelError(f"modes: at must be an equilibrium from mb.equilibrium(model) or None, "
                         f"got {type(at).__name__}")
    if at is not None and at.model is not model:
        raise ModelError("modes: at is an equilibrium of another model")
    core = model.compiled()
    automatic = count is None and core.n_coordinates > SPARSE_ABOVE
    if count is not None or automatic:
        scipy = _scipy_sparse(automatic, core.n_coordinates)
        if at is None:  # the dense stability check is what the sparse path avoids
            at = equilibrium(model, allow_unstable=True, stability=False)
        return _sparse_modes(core, at, count, tol, scipy)
    if at is None:
        at = equilibrium(model, allow_unstable=True)
    tangent = _core.tangent_at_rest(core, at.q, at.lam, at.t, at.dropped_rows)
    M, K, C = (np.asarray(tangent[k]) for k in ("M", "K", "C"))
    kept = np.setdiff1d(np.arange(len(at.lam)), at.dropped_rows)
    Z = _null_space(np.asarray(tangent["Phi_q"])[kept], 1e-10)
    k = Z.shape[1]
    n = len(at.q)
    if k == 0:
        return Modes(at, np.zeros(0), [], np.zeros(0), np.zeros((0, n)), np.zeros(0, complex))
    Mr, Kr, Cr = Z.T @ M @ Z, Z.T @ K @ Z, Z.T @ C @ Z
    _check_symmetric(Kr)
    Kr = 0.5 * (Kr + Kr.T)
    L = np.linalg.cholesky(0.5 * (Mr + Mr.T))
    Linv = np.linalg.inv(L)
    omega_squared, Y = np.linalg.eigh(Linv @ Kr @ Linv.T)
    order = np.argsort(np.abs(omega_squared), kind="stable")  # by omega = sqrt(|omega^2|)
    omega_squared, Y = omega_squared[order], Y[:, order]
    phi = Linv.T @ Y  # mass-normalized: phi^T Mr phi = I
    largest = max(np.abs(omega_squared).max(), 1e-300)
    kinds = _kinds(omega_squared, tol * largest)
    omega = np.sqrt(np.abs(omega_squared))
    modal_damping = np.einsum("ij,ik,kj->j", phi, Cr, phi)
    damping_ratios = _damping_ratios(modal_damping, omega, kinds)
    shapes = _largest_entry_one((Z @ phi).T)
    A = np.block([[np.zeros((k, k)), np.eye(k)],
                  [-np.linalg.solve(Mr, Kr), -np.linalg.solve(Mr, Cr)]])
    eigenvalues = np.linalg.eigvals(A)
    eigenvalues = eigenvalues[np.argsort(np.abs(eigenvalues), kind="stable")]
    return Modes(at, omega_squared, kinds, damping_ratios, shapes, eigenvalues)


def _check_symmetric(Kr, scale=None):
    """ModelError unless the reduced tangent stiffness Kr is symmetric to
    1e-8 of its largest entry (or of ``scale``)."""
    scale = max(np.abs(Kr).max(initial=0.0) if scale is None else scale, 1e-300)
    asymmetry = np.abs(Kr - Kr.T).max(initial=0.0)
    if asymmetry > 1e-8 * scale:
        raise ModelError("modes: the tangent stiffness is not symmetric (largest difference "
                         f"{asymmetry:.3g} against {scale:.3g}): non-conservative forces "
                         "(a follower force, friction) have no real undamped modes")


def _kinds(omega_squared, rigid):
    return ["rigid-body" if abs(w2) <= rigid else "unstable" if w2 < 0 else "vibration" for w2 in omega_squared]


def _damping_ratios(modal_damping, omega, kinds):
    return np.array([c / (2.0 * w) if kind != "rigid-body" else np.nan
                     for c, w, kind in zip(modal_damping, omega, kinds)])


def _largest_entry_one(shapes):
    """Each row scaled (in place) so that its largest entry is +1."""
    for row in shapes:
        row /= row[np.argmax(np.abs(row))]
    return shapes


# --- the sparse path: the k lowest modes of a large model ---------------------


def _scipy_sparse(automatic, n):
    """(scipy.sparse, scipy.sparse.linalg, scipy.linalg), or ModelError."""
    try:
        from scipy import linalg, sparse
        from scipy.sparse import linalg as sparse_linalg
    except ImportError:
        why = (f"the model has {n} coordinates (more than {SPARSE_ABOVE}), so modes computes the "
               f"{DEFAULT_COUNT} lowest with sparse linear algebra" if automatic else "count=... asks for the sparse path")
        raise ModelError(f"modes: {why}, which needs SciPy (pip install scipy); without it, "
                         "mb.modes(model) on a model of up to a few hundred coordinates is dense") from None
    return sparse, sparse_linalg, linalg


def _sparse_matrix(triplet, sparse):
    """A (rows, cols, values, shape) triplet from the core as a CSC matrix
    (repeated entries summed)."""
    rows, cols, values, shape = triplet
    return sparse.csc_matrix((np.asarray(values, dtype=float),
                              (np.asarray(rows, dtype=int), np.asarray(cols, dtype=int))),
                             shape=tuple(int(s) for s in shape))


def _saddle_lu(A, J, sparse, sparse_linalg):
    """The sparse LU of [[A, J^T], [J, 0]] (A n x n, J rows x n), and a
    solve of [[A, J^T], [J, 0]] [x; mu] = [b; 0] for x (b n or n x p)."""
    n, rows = A.shape[0], J.shape[0]
    augmented = sparse.bmat([[A, J.T], [J, None]], format="csc") if rows else sparse.csc_matrix(A)
    lu = sparse_linalg.splu(augmented)

    def solve(b):
        b = np.asarray(b, dtype=float)
        padded = np.concatenate([b, np.zeros((rows,) + b.shape[1:])])
        return lu.solve(padded)[:n]

    return solve


def _sparse_modes(core, at, count, tol, scipy):
    sparse, sparse_linalg, linalg = scipy
    n = len(at.q)
    inputs = np.array([i["initial"] for i in core.inputs], dtype=float)
    tangent = _core.tangent_at(core, at.q, np.zeros(n), at.t, inputs, list(at.dropped_rows))
    M, K, C, Phi_q = (_sparse_matrix(tangent[k], sparse) for k in ("M", "K", "C", "Phi_q"))
    kept = np.setdiff1d(np.arange(Phi_q.shape[0]), np.asarray(tangent["dropped_rows"], dtype=int))
    J = Phi_q[kept]
    dof = n - len(kept)  # the kept rows are independent
    if count is None:
        count = min(DEFAULT_COUNT, dof)
    elif count > dof:
        raise ModelError(f"modes: count {count} is more than the {dof} degree{'' if dof == 1 else 's'} of "
                         "freedom the joints and drivers leave")
    if count == 0:
        return Modes(at, np.zeros(0), [], np.zeros(0), np.zeros((0, n)), np.zeros(0, complex))
    Ms, Ks = 0.5 * (M + M.T), 0.5 * (K + K.T)
    # the scale of omega^2: the largest ratio of K's diagonal to M's
    m_diag, k_diag = Ms.diagonal(), np.abs(Ks.diagonal())
    massive = m_diag > 0
    scale = float(np.max(k_diag[massive] / m_diag[massive])) if massive.any() else 0.0
    scale = scale if scale > 0 else 1.0  # nothing stiff: every mode rigid
    rng = np.random.default_rng(20240528)  # the same modes every call

    if dof <= 2 * count + 20:
        # few degrees of freedom (too few for Lanczos): all of them, in an
        # orthonormal basis of null(J) from the projection [[I, J^T], [J, 0]]
        project = _saddle_lu(sparse.identity(n, format="csc"), J, sparse, sparse_linalg)
        Z = np.linalg.svd(project(rng.standard_normal((n, dof + 5))), full_matrices=False)[0][:, :dof]
        Kr = Z.T @ (K @ Z)
        _check_symmetric(Kr)
        omega_squared, Y = linalg.eigh(0.5 * (Kr + Kr.T), Z.T @ (Ms @ Z))
        phi = Z @ Y
    else:
        sigma, solve = None, None
        for attempt in range(4):  # just below 0; away from an eigenvalue met exactly
            sigma = -1e-9 * scale * 7.0**attempt
            try:
                solve = _saddle_lu(Ks - sigma * Ms, J, sparse, sparse_linalg)
                break
            except RuntimeError:  # exactly singular: sigma is an eigenvalue
                continue
        if solve is None:
            raise ModelError("modes: the shifted tangent [[K - sigma M, Phi_q^T], [Phi_q, 0]] is singular "
                             "for every shift tried")
        # x = OP (M y) lies in null(J): (K - sigma M) x + J^T mu = M y, J x = 0
        operator = sparse_linalg.LinearOperator((n, n), matvec=solve, dtype=float)
        ncv = min(dof, max(2 * count + 1, 20))
        try:
            omega_squared, phi = sparse_linalg.eigsh(Ks, k=count, M=Ms, sigma=sigma, which="LM", OPinv=operator,
                                                     ncv=ncv, v0=rng.standard_normal(n))
        except sparse_linalg.ArpackError as e:  # (ArpackNoConvergence among them)
            raise ModelError(f"modes: the sparse eigensolver (ARPACK) failed: {e}") from None
        # Rayleigh-Ritz in the modes found: M-orthonormal, K diagonal
        Kr = phi.T @ (K @ phi)
        probes = solve(rng.standard_normal((n, 4)))  # and motions the joints allow of other kinds
        probes /= np.sqrt(np.einsum("ij,ij->j", probes, Ms @ probes))
        basis = np.hstack([phi, probes])
        _check_symmetric(basis.T @ (K @ basis), scale=max(scale, np.abs(basis.T @ (Ks @ basis)).max()))
        omega_squared, Y = linalg.eigh(0.5 * (Kr + Kr.T), phi.T @ (Ms @ phi))
        phi = phi @ Y
    order = np.argsort(np.abs(omega_squared), kind="stable")[:count]
    omega_squared, phi = omega_squared[order], phi[:, order]
    largest = max(scale, np.abs(omega_squared).max())
    kinds = _kinds(omega_squared, tol * largest)
    omega = np.sqrt(np.abs(omega_squared))
    Cm = phi.T @ (C @ phi)
    damping_ratios = _damping_ratios(np.diag(Cm), omega, kinds)
    shapes = _largest_entry_one(np.array(phi.T))
    k = len(omega)
    A = np.block([[np.zeros((k, k)), np.eye(k)], [-np.diag(omega_squared), -Cm]])
    eigenvalues = np.linalg.eigvals(A)
    eigenvalues = eigenvalues[np.argsort(np.abs(eigenvalues), kind="stable")]
    return Modes(at, omega_squared, kinds, damping_ratios, shapes, eigenvalues)


# --- linearization (mb.linearize) ---------------------------------------------


def _dense(triplet):
    """A (rows, cols, values, shape) triplet from the core as a dense array."""
    rows, cols, values, shape = triplet
    out = np.zeros(shape)
    np.add.at(out, (np.asarray(rows, dtype=int), np.asarray(cols, dtype=int)), np.asarray(values, dtype=float))
    return out


class LinearSystem:
    """A mechanism's motion linearized about an operating point
    (:func:`lagmb.linearize`)::

        x' = A x + B u,   y = C x + D u,

    x, u and y the deviations of the states, inputs and outputs from their
    values at the operating point.

    - A (2k, 2k), B (2k, p), C (r, 2k), D (r, p): numpy arrays.
    - states: the names of x: the k minimal coordinates (``"cart.x"``,
      ``"pole.angle"`` for independent coordinates; ``"z1"`` ... for an
      orthonormal basis), then their rates (``"der(cart.x)"``).
    - inputs: the names of u (the model's ``mb.Input`` elements);
      outputs: the names of y.
    - coordinates: "independent" or "orthonormal", the basis the states are
      in; basis (n, k) and velocity_basis (n, k): the motion of the model's
      coordinates, ``dq = basis z``, ``dv = basis w + velocity_basis z``
      (x = (z, w)).
    - q, v, a, lam, t and input_values: the operating point; y0: the outputs
      there; dropped_rows: the rows of Phi left out there (redundant, and
      the stops' rows not held);
      equilibrium: the :class:`Equilibrium` it is, if linearized about one.
    - eigenvalues: of A, ordered by magnitude.

    :meth:`to_scipy` gives a ``scipy.signal.StateSpace``; :meth:`descriptor`
    the same motion in the model's own (redundant) coordinates.
    """

    def __init__(self, **fields):
        self.__dict__.update(fields)

    @property
    def eigenvalues(self):
        values = np.linalg.eigvals(self.A) if self.A.size else np.zeros(0, complex)
        return values[np.argsort(np.abs(values), kind="stable")]

    def to_scipy(self):
        """This system as a ``scipy.signal.StateSpace`` (continuous time)."""
        from scipy import signal

        B, D = self.B, self.D
        if B.shape[1] == 0:  # scipy wants at least one input: a zero column
            B, D = np.zeros((B.shape[0], 1)), np.zeros((D.shape[0], 1))
        return signal.StateSpace(self.A, B, self.C, D)

    def descriptor(self):
        """The motion in the model's own coordinates, as a descriptor system
        ``E x' = A x + B u, y = C x + D u`` with x = (dq, dv, dlam) (n, n and
        one multiplier per kept row of Phi)::

            E = [[I, 0, 0], [0, M, 0], [0, 0, 0]]
            A = [[0, I, 0], [-K, -C_v, -Phi_q^T], [Phi_q, 0, 0]]
            B = [[0], [Q_u], [0]]

        (K the tangent stiffness, C_v = -Q_v). A constrained mechanism's
        pencil has index 3: its finite eigenvalues are those of the minimal
        ``A``, the others are infinite. Given about a static equilibrium only:
        elsewhere the constraint rows turn with the motion, which a constant
        pencil cannot say (ModelError). Returns an object with E, A, B, C, D,
        states, inputs and outputs."""
        if self._descriptor is None:
            raise ModelError("LinearSystem.descriptor: the operating point is not a static equilibrium "
                             f"(max abs(v) {np.abs(self.v).max(initial=0.0):.3g}, max abs(a) "
                             f"{np.abs(self.a).max(initial=0.0):.3g}): there the rows of Phi_q turn with the "
                             "motion and no constant pencil describes it; use the minimal form (A, B, C, D)")
        return self._descriptor

    def __repr__(self):
        return (f"<lagmb.LinearSystem: {len(self.states)} states ({', '.join(self.states)}), "
                f"{len(self.inputs)} inputs, {len(self.outputs)} outputs>")


class Descriptor:
    """A descriptor system E x' = A x + B u, y = C x + D u
    (:meth:`LinearSystem.descriptor`): E, A, B, C, D (numpy), states,
    inputs, outputs (names)."""

    def __init__(self, **fields):
        self.__dict__.update(fields)

    @property
    def eigenvalues(self):
        """The finite generalized eigenvalues of (A, E), ordered by magnitude."""
        from scipy import linalg

        alpha, beta = linalg.eigvals(self.A, self.E, homogeneous_eigvals=True)
        scale = max(np.abs(self.A).max(initial=0.0), np.abs(self.E).max(initial=0.0), 1e-300)
        finite = np.abs(beta) > 1e-7 * np.maximum(np.abs(alpha), scale)
        values = alpha[finite] / beta[finite]
        return values[np.argsort(np.abs(values), kind="stable")]

    def __repr__(self):
        return f"<lagmb.Descriptor: {len(self.states)} states, {len(self.inputs)} inputs, {len(self.outputs)} outputs>"


def _preference(names):
    """The order in which coordinates are taken as independent: angles (a
    planar body's angle, the vector part e1..e3 of a spatial body's Euler
    parameters) first, then positions, then e0; in the order of the
    bodies within each."""
    def rank(name):
        suffix = name.rsplit(".", 1)[-1]
        return 0 if suffix in ("angle", "e1", "e2", "e3") else 2 if suffix == "e0" else 1
    return sorted(range(len(names)), key=lambda j: (rank(names[j]), j))


def _independent(Z, names, chosen, who):
    """Rows of Z (indices into q) taken as the independent coordinates:
    ``chosen`` names, or the first rows in _preference order that add to the
    rank (each must keep more than 1e-3 of the largest row's length
    outside the span of those before)."""
    k = Z.shape[1]
    if chosen is not None:
        chosen = [chosen] if isinstance(chosen, str) else list(chosen)
        unknown = [c for c in chosen if c not in names]
        if unknown:
            raise ModelError(f"{who}: no coordinate {unknown[0]!r}; the coordinates are {', '.join(names)}")
        rows = [names.index(c) for c in chosen]
        if len(rows) != k or len(set(rows)) != k:
            raise ModelError(f"{who}: the mechanism has {k} degrees of freedom here; "
                             f"give {k} different coordinates, got {chosen}")
        s = np.linalg.svd(Z[rows], compute_uv=False) if k else np.zeros(0)
        if k and s[-1] < 1e-8 * max(s[0], 1e-300):
            raise ModelError(f"{who}: the coordinates {chosen} do not determine the motion here (the joints "
                             "tie them together); choose others")
        return rows
    rows, basis = [], np.zeros((0, k))
    threshold = 1e-3 * max(np.linalg.norm(Z, axis=1).max(initial=0.0), 1e-300)
    for j in _preference(names):
        if len(rows) == k:
            break
        r = Z[j] - basis.T @ (basis @ Z[j])
        size = np.linalg.norm(r)
        if size > threshold:
            rows.append(j)
            basis = np.vstack([basis, r / size])
    return sorted(rows)


def _elements_of_rows(core, rows):
    """The names of the elements that own constraint rows, quoted, each once."""
    names = list(dict.fromkeys(core.constraint_name_of_row(int(r)) for r in rows))
    return ", ".join(repr(x) for x in names) if names else "(none)"


def _operating_point(model, core, at, input_values, who):
    """(q, v, t, u, dropped_rows or None, the Equilibrium or None, the stops held)."""
    n = core.n_coordinates
    infos = core.inputs
    u = np.array([i["initial"] for i in infos], dtype=float)
    given = {}
    for where, values in (("input_values", input_values), ("at['inputs']", at.get("inputs") if isinstance(
            at, dict) else None)):
        if values is not None and not isinstance(values, dict):
            raise ModelError(f"{who}: {where} must be a dict {{input name: value}}, got {show(values)}")
        given.update(values or {})
    names = [i["name"] for i in infos]
    for name, value in given.items():
        if name not in names:
            raise ModelError(f"{who}: no input {show(name)}; the model's inputs are "
                             f"{', '.join(names) if names else '(none)'}")
        u[names.index(name)] = real(value, f"{who}: input {name!r}")
    if at is None:
        if input_values:
            raise ModelError(f"{who}: input_values with at=None: mb.equilibrium holds the inputs at their initial "
                             "values, so the equilibrium would not be one at these; give at= a consistent state")
        # at rest, a driver's rate is Phi_t: one that moves leaves no state at rest
        rates = np.abs(np.asarray(core.constraint_values(np.asarray(core.initial_state()[0], dtype=float),
                                                         0.0)[1], dtype=float))
        moving = np.flatnonzero(rates > 1e-8)
        if moving.size:
            raise ModelError(f"{who}: the model has no equilibrium to linearize about: its drivers "
                             f"{_elements_of_rows(core, moving)} move at t = 0 (a rate up to "
                             f"{rates.max():.3g}), so no state at rest follows them; give at=(q, v, t), a "
                             "state of the motion, e.g. a Result's point (r.q[i], r.v[i], r.t[i])")
        at = equilibrium(model, allow_unstable=True)
    if isinstance(at, Equilibrium):
        if at.model is not model:
            raise ModelError(f"{who}: at is an equilibrium of another model")
        return at.q, np.zeros(n), at.t, u, list(at.dropped_rows), at, []
    held = []
    if isinstance(at, dict):
        unknown = set(at) - {"q", "v", "t", "inputs", "held"}
        if unknown or "q" not in at:
            raise ModelError(f"{who}: at as a dict takes q (and v, t, inputs, held), got keys {sorted(at)}")
        q, v, t = at["q"], at.get("v"), at.get("t", 0.0)
        given = at.get("held", [])
        if isinstance(given, str) or not hasattr(given, "__iter__"):
            raise ModelError(f"{who}: at['held'] must be a list of stops, got {show(given)}")
        held = [name_of(model, stop, ("stop",), "stop", f"{who}: at['held']") for stop in given]
    elif isinstance(at, (tuple, list)) and len(at) in (2, 3):
        q, v, t = at[0], at[1], at[2] if len(at) == 3 else 0.0
    else:
        raise ModelError(f"{who}: at must be None, an Equilibrium, (q, v) or (q, v, t), or a dict with q, v, t "
                         f"(e.g. a Result's point: (r.q[i], r.v[i], r.t[i])), got {type(at).__name__}")
    q = array(q, f"{who}: q")
    v = np.zeros(n) if v is None else array(v, f"{who}: v")
    if q.shape != (n,) or v.shape != (n,):
        raise ModelError(f"{who}: q and v must have the model's {n} coordinates, got {q.size} and {v.size}")
    t = real(t, f"{who}: t")
    return q, v, t, u, None, None, held


class _Outputs:
    """The output rows y = Cq dq + Cv dv + Cl dlam + Cu du, by name."""

    def __init__(self, model, core, names, point, inputs_used, who):
        self.model, self.core, self.point, self.who = model, core, point, who
        q, v, lam, t, u = point
        n, m = len(q), len(lam)
        coords = list(core.coordinate_names())
        self.names, rows = [], []
        for name in names:
            if not isinstance(name, str):
                raise ModelError(f"{who}: output names are strings, got {name!r}")
            Cq, Cv, Cl, value = np.zeros(n), np.zeros(n), np.zeros(m), None
            out = _output_names.parse(name)
            rate, element, what = out.rate, out.element, out.what
            if out.base in coords:
                j = coords.index(out.base)
                (Cv if rate else Cq)[j] = 1.0
                value = (v if rate else q)[j]
            elif not rate and out.reaction_component is not None and self._is(element, "constraint"):
                value = self._reaction(element, out.reaction_component, Cq, Cl, name)
            elif not rate and what == "effort" and self._is(element, "driver"):
                row0, _ = core.constraint_rows(element)
                Cl[row0] = -1.0
                value = -lam[row0]
            elif what in _output_names.JOINT_COORDINATES and self._is(element, "joint"):
                value = self._joint(element, what, rate, Cq, Cv, name)
            else:
                raise ModelError(f"{who}: no output {name!r}; outputs are coordinates and their rates "
                                 f"({', '.join(coords[:3])}{', ...' if len(coords) > 3 else ''}, "
                                 f"der({coords[0] if coords else 'body.x'})), '<joint>.reaction.<x|y|torque>' "
                                 "('.z', '.torque.x' ... in space), '<driver>.effort', '<joint>.angle' or "
                                 "'<joint>.slide' and der() of those")
            self.names.append(name)
            rows.append((Cq, Cv, Cl, value))
        r = len(rows)
        self.Cq = np.array([x[0] for x in rows]).reshape(r, n)
        self.Cv = np.array([x[1] for x in rows]).reshape(r, n)
        self.Cl = np.array([x[2] for x in rows]).reshape(r, m)
        self.Cu = np.zeros((r, len(inputs_used)))
        self.y0 = np.array([x[3] for x in rows], dtype=float)

    def _is(self, element, what):
        core = self.core
        if not core.has(element):
            return False
        if what == "driver":
            return registry.is_driver(core, element)
        if what == "joint":
            return core.joint_coordinate(element) is not None
        try:
            core.constraint_rows(element)
            return True
        except Exception:  # not a joint or driver
            return False

    def _q_difference(self, f, q):
        """df/dq by central differences (f of q alone: a geometric relation,
        smooth), relative step 1e-6."""
        h = 1e-6 * np.maximum(1.0, np.abs(q))
        plus = q + np.diag(h)
        minus = q - np.diag(h)
        return (f(plus) - f(minus)) / (2.0 * h)

    def _reaction(self, element, component, Cq, Cl, name):
        core = self.core
        q, v, lam, t, u = self.point
        components = _output_names.REACTION_COMPONENTS[self.model.dimension]
        if component not in components:
            raise ModelError(f"{self.who}: no output {name!r}; a reaction's components are "
                             f"{', '.join(components)}")
        c = components.index(component)
        row0, rows = core.constraint_rows(element)
        inputs = np.asarray(u, dtype=float)[None, :] if len(u) else np.zeros((1, 0))

        def reaction(qs, lams):
            k = len(qs)
            return np.asarray(core.reaction(element, np.full(k, t), qs, lams, False,
                                            np.repeat(inputs, k, axis=0)))[:, c]

        # linear in lam: exact from unit multipliers; its q-dependence (the
        # geometry that turns -Phi_c^T lam into a force and torque) by differences
        units = np.zeros((rows, len(lam)))
        units[np.arange(rows), row0 + np.arange(rows)] = 1.0
        if rows:
            Cl[row0:row0 + rows] = reaction(np.repeat(q[None, :], rows, axis=0), units)
        at_lam = lambda qs: reaction(qs, np.repeat(lam[None, :], len(qs), axis=0))
        Cq[:] = self._q_difference(at_lam, q)
        return float(at_lam(q[None, :])[0])

    def _joint(self, element, what, rate, Cq, Cv, name):
        core = self.core
        q, v, lam, t, u = self.point
        info = core.joint_coordinate(element)
        slide = what == "slide"
        if not (info["slides"] if slide else info["turns"]):
            raise ModelError(f"{self.who}: no output {name!r}: {element!r} has no {what}")
        n = len(q)
        column = 1 if rate else 0

        def motion(qs, vs):
            return np.asarray(core.joint_motion(element, slide, qs, vs))[:, column]

        if rate:  # linear in v: exact from unit rates
            Cv[:] = motion(np.repeat(q[None, :], n, axis=0), np.eye(n))
        Cq[:] = self._q_difference(lambda qs: motion(qs, np.repeat(v[None, :], len(qs), axis=0)), q)
        return float(motion(q[None, :], v[None, :])[0])


def linearize(model, at=None, inputs=None, outputs=None, *, coordinates="independent", input_values=None):
    """The motion linearized about an operating point, in minimal
    coordinates: ``x' = A x + B u, y = C x + D u`` (a :class:`LinearSystem`).

    At the operating point (q, v, t), differentiating the equations of
    motion M a + Phi_q^T lam = Q(q, v, t, u), Phi_q a = gamma(q, v, t) gives
    the augmented system::

        [M      Phi_q^T] [da  ]   [-K dq - C_v dv + Q_u du]
        [Phi_q  0      ] [dlam] = [ G_q dq + G_v dv       ]

    K = (M a)_q + (Phi_q^T lam)_q - Q_q, C_v = -Q_v, G_q = gamma_q -
    (Phi_q a)_q, G_v = -2 (Phi_q v + Phi_t)_q, all the elements' exact
    derivatives (``_core.tangent_at``) except gamma_q, taken by central
    differences of gamma (it needs Phi's third derivatives; it vanishes at
    rest). The motions the joints allow are dq = T z with Phi_q T = 0; the
    velocity constraint Phi_q dv + (Phi_q v + Phi_t)_q dq = 0 gives dv = T w
    + V z with L V = 0, L the k x n map z = L dq. The state is x = (z, w)
    and z' = w, w' = L da.

    ``coordinates``: "independent" (the default): z is k of the model's
    coordinates, chosen by the rule: angles first (a planar body's angle, the
    vector part e1..e3 of a spatial body's Euler parameters), then positions
    (x, y, z), then e0, bodies in the order added, each taken if the joints
    leave it free given those taken before (the cart's x and the pole's angle
    of a cart-pole); or a list of k coordinate names to take instead;
    "orthonormal": z = T^T dq with T an orthonormal basis of the null space
    of Phi_q (states z1 ... zk). Both are the same motion in other
    coordinates: at an equilibrium A has the same eigenvalues. Away from an
    equilibrium the linearization depends on the coordinates chosen (the
    basis T is held fixed at the operating point).

    ``at``: None (the default) for ``mb.equilibrium(model,
    allow_unstable=True)``, an :class:`Equilibrium`, or a consistent state
    (q, v) or (q, v, t), or a dict with q, v, t, inputs and held (e.g. a
    Result's point ``(r.q[i], r.v[i], r.t[i])``). ``held``: the stops that
    hold their joints on a limit at that state (captured, as ``r.events``
    says), each the joint row it is then; the other stops are open.
    ``input_values``: {input name: value} at the operating point (default
    the inputs' initial values).

    ``inputs``: the names of the ``mb.Input`` elements that form u (None:
    all of the model's, in the order added; the others are held). Q is
    affine in an input's value for a force or torque that takes it, so B is
    exact. An input that drives a motion (a driver) is refused: its rate
    enters the motion, which B cannot carry.

    ``outputs``: names, as the FMU and ``lagmb info`` name them: coordinates
    ``"body.x"`` and rates ``"der(body.x)"``; ``"<joint>.reaction.x"`` (.y,
    .torque in the plane; .z, .torque.x ... in space: the force and torque on
    its second body, global axes); ``"<driver>.effort"``; ``"<joint>.angle"``,
    ``"<joint>.slide"`` and their der(). None: every coordinate of the model.
    A reaction is linear in the multipliers (exact); how it and a joint's
    angle depend on q is taken by central differences.

    ModelError for: ``at=None`` where a driver moves at t = 0 (naming it: no
    state at rest follows it, give ``at=(q, v, t)``), an ``at`` that is not
    a consistent state of this model (max abs(Phi) or abs(Phi_q v + Phi_t)
    above 1e-8, naming the elements), unknown input, output
    or coordinate names (the known ones listed), joint friction (its force
    switches with the sign of the rate), an input that drives a motion.
    Dense linear algebra: for models of up to a few hundred coordinates.
    """
    from .model import checked as _model
    from ._checks import string_list

    who = "linearize"
    _model(model, who)
    if (coordinates not in ("independent", "orthonormal") if isinstance(coordinates, str)
            else not hasattr(coordinates, "__iter__")):
        raise ModelError(f"{who}: coordinates must be 'independent', 'orthonormal' or a list of coordinate "
                         f"names, got {coordinates!r}")
    core = model.compiled()
    friction = [name for kind, name, _ in model._spec.elements() if "friction" in kind]
    if friction:
        raise ModelError(f"{who}: joint friction ({', '.join(repr(f) for f in friction)}) switches with the sign "
                         "of the joint's rate and has no linearization; remove it to linearize")
    q, v, t, u, dropped, eq, held = _operating_point(model, core, at, input_values, who)
    try:
        tangent = _core.tangent_at(core, q, v, t, u, dropped, held)
    except ModelError as e:  # (the core names its own function: said as linearize's, held as at['held'])
        if type(e) is not ModelError or not str(e).startswith("tangent_at: "):
            raise
        text = str(e)[len("tangent_at: "):]
        raise ModelError(f"{who}: " + ("at['held']: " + text[len("held: "):] if text.startswith("held: ") else text)
                         ) from None
    n, m = len(q), core.n_constraints
    scale = 1.0 + np.abs(q).max(initial=0.0)
    phi = np.abs(np.asarray(tangent["Phi"])).max(initial=0.0)
    vel = np.abs(np.asarray(tangent["velocity_residual"])).max(initial=0.0)
    if phi > 1e-8 * scale or vel > 1e-8 * (1.0 + np.abs(v).max(initial=0.0)):
        broken = _elements_of_rows(core, np.flatnonzero(
            (np.abs(np.asarray(tangent["Phi"])) > 1e-8 * scale)
            | (np.abs(np.asarray(tangent["velocity_residual"])) > 1e-8 * (1.0 + np.abs(v).max(initial=0.0)))))
        raise ModelError(f"{who}: at is not a consistent state of the model: max abs(Phi) {phi:.3g}, max "
                         f"abs(Phi_q v + Phi_t) {vel:.3g}, in the equations of {broken} (give a state the joints "
                         "and drivers allow, e.g. a Result's point, or an Equilibrium of a model whose drivers "
                         "are at rest)")
    dropped = [int(r) for r in tangent["dropped_rows"]]
    a, lam = np.asarray(tangent["a"]), np.asarray(tangent["lam"])

    infos = core.inputs
    all_inputs = [i["name"] for i in infos]
    if inputs is None:
        used = list(range(len(infos)))
    else:
        names = [inputs] if isinstance(inputs, str) else string_list(inputs, f"{who}: inputs", "input names")
        for name in names:
            if name not in all_inputs:
                raise ModelError(f"{who}: no input {name!r}; the model's inputs are "
                                 f"{', '.join(all_inputs) if all_inputs else '(none)'}")
        used = [all_inputs.index(name) for name in names]
    Phi_u = np.asarray(tangent["Phi_u"]).reshape(m, len(infos))
    for j in used:
        if np.abs(Phi_u[:, j]).max(initial=0.0) > 0.0:
            raise ModelError(f"{who}: input {all_inputs[j]!r} drives the motion of {infos[j]['element']!r}: its "
                             "rate enters the motion, which a state-space B cannot carry; leave it out of "
                             "inputs (it is held at its value)")
    Q_u = np.asarray(tangent["Q_u"]).reshape(n, len(infos))[:, used]
    p = len(used)

    M, K, Cv_ = (_dense(tangent[k]) for k in ("M", "K", "C"))
    Phi_q, G_q, G_v = (_dense(tangent[k]) for k in ("Phi_q", "G_q", "G_v"))
    kept = np.setdiff1d(np.arange(m), dropped)
    J, mk = Phi_q[kept], len(kept)

    # the minimal coordinates: dq = T z, z = L dq
    Z = _null_space(J, 1e-10)
    k = Z.shape[1]
    names = list(core.coordinate_names())
    if isinstance(coordinates, str) and coordinates == "orthonormal":
        T, L = Z, Z.T
        state_names = [f"z{i + 1}" for i in range(k)]
    else:
        rows = _independent(Z, names, None if isinstance(coordinates, str) else coordinates, who)
        T = Z @ np.linalg.inv(Z[rows]) if k else np.zeros((n, 0))
        L = np.zeros((k, n))
        L[np.arange(k), rows] = 1.0
        state_names = [names[j] for j in rows]
        coordinates = "independent"
    # dv = T w + V z: Phi_q V = -Vq T (Vq = -G_v / 2) and L V = 0
    N = np.vstack([J, L])
    V = np.linalg.lstsq(N, np.vstack([0.5 * G_v[kept] @ T, np.zeros((k, k))]), rcond=None)[0]

    # the augmented system, differentiated: da, dlam for unit dq, dv, du
    aug = np.block([[M, J.T], [J, np.zeros((mk, mk))]])
    rhs = np.block([[-K, -Cv_, Q_u], [G_q[kept], G_v[kept], np.zeros((mk, p))]])
    X = np.linalg.solve(aug, rhs)
    da_q, da_v, da_u = X[:n, :n], X[:n, n:2 * n], X[:n, 2 * n:]
    dl = np.zeros((m, 2 * n + p))
    dl[kept] = X[n:]
    dl_q, dl_v, dl_u = dl[:, :n], dl[:, n:2 * n], dl[:, 2 * n:]

    A = np.block([[np.zeros((k, k)), np.eye(k)], [L @ (da_q @ T + da_v @ V), L @ da_v @ T]])
    B = np.vstack([np.zeros((k, p)), L @ da_u])

    out = _Outputs(model, core, names if outputs is None else
                   ([outputs] if isinstance(outputs, str) else string_list(outputs, f"{who}: outputs", "output names")),
                   (q, v, lam, t, u), used, who)
    C = np.hstack([out.Cq @ T + out.Cv @ V + out.Cl @ (dl_q @ T + dl_v @ V), out.Cv @ T + out.Cl @ dl_v @ T])
    D = out.Cu + out.Cl @ dl_u

    descriptor = None
    at_rest = (np.abs(v).max(initial=0.0) == 0.0
               and np.abs(a).max(initial=0.0) <= 1e-8 * (1.0 + np.abs(np.asarray(tangent["Q"])).max(initial=0.0)))
    if at_rest:
        multipliers = []
        for r in kept:
            element = core.constraint_name_of_row(int(r))
            if core.has(element):
                row0, _ = core.constraint_rows(element)
                multipliers.append(f"{element}.lambda[{int(r) - row0}]")
            else:  # a row no element owns: a spatial body's Euler parameters' unit length
                multipliers.append(f"lambda[{int(r)}] ({element})")
        Z0 = np.zeros
        descriptor = Descriptor(
            E=np.block([[np.eye(n), Z0((n, n)), Z0((n, mk))], [Z0((n, n)), M, Z0((n, mk))],
                        [Z0((mk, n)), Z0((mk, n)), Z0((mk, mk))]]),
            A=np.block([[Z0((n, n)), np.eye(n), Z0((n, mk))], [-K, -Cv_, -J.T], [J, Z0((mk, n)), Z0((mk, mk))]]),
            B=np.vstack([Z0((n, p)), Q_u, Z0((mk, p))]),
            C=np.hstack([out.Cq, out.Cv, out.Cl[:, kept]]), D=out.Cu.copy(),
            states=names + [f"der({x})" for x in names] + multipliers,
            inputs=[all_inputs[j] for j in used], outputs=list(out.names))
    return LinearSystem(
        A=A, B=B, C=C, D=D, states=state_names + [f"der({s})" for s in state_names],
        inputs=[all_inputs[j] for j in used], outputs=list(out.names), coordinates=coordinates,
        basis=T, velocity_basis=V, q=q, v=v, a=a, lam=lam, t=t,
        input_values={all_inputs[j]: float(u[j]) for j in range(len(u))}, y0=out.y0,
        dropped_rows=dropped, equilibrium=eq, _descriptor=descriptor)
