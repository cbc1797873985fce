"""Reference solutions and stiffness set-up for bench/peers/compare.py.

The problem: N uniform rods (L = 1 m, m = 1 kg, J = 1/12 kg m^2), pinned to
the ground at the origin, released horizontal at rest, gravity 9.81 m/s^2
in -y, 1 s. The quantity compared is the tip rod's centre at t = 1 s.

* Non-stiff: tests/references.py RodChain (Lagrange's equations in absolute
  angles theta_i, DOP853 at rtol = atol = 1e-12), used unchanged.
* Stiff: the same equations plus a rotational spring-damper at every joint
  between consecutive rods (none at the ground pin). In absolute angles the
  relative angle of joint i (i = 1 .. N-1) is theta_i - theta_{i-1}, so with
  the difference matrix D ((N-1) x N, rows e_i - e_{i-1}) the potential
  1/2 k |D theta|^2 and Rayleigh function 1/2 c |D thetadot|^2 give the
  generalised forces  Q = -k D^T D theta - c D^T D thetadot  (rest angle 0 =
  the initial relative angle). StiffRodChain integrates that with SciPy's
  Radau and an analytic Jacobian at rtol = atol = 1e-11: at 1e-12 SciPy's
  Radau repeats its Newton iterations and LU factorisations (N = 8: 506k
  right-hand sides and 99.5k LUs instead of 46k and 4.9k at 1e-11, the
  two tips within 3e-14 of each other), which is out of reach at N >= 128.
* The stiffness k: the linearisation about the hanging equilibrium
  (theta_i = -pi/2, all relative angles 0, so the springs are at rest there)
  is  M0 x'' + (K_g + k D^T D) x = 0  with M0 = m L^2 S + J I and
  K_g = m g L diag(sum_k c_ki) (gravity's second derivative); k is found by
  bisection on log k so that omega_max / omega_min = 1e4 (generalised
  symmetric eigenproblem). The damping c per joint gives the fastest
  undamped mode the modal damping ratio zeta (1 by default):
  c = 2 zeta omega_max / (phi^T D^T D phi), phi mass-normalised.

Run on its own it checks the references and writes
bench/results/peers_reference.json (the cache compare.py reads):

    python bench/peers/reference.py [--n 8 32 128 512] [--stiff-n 8 32 128]

Checks: the analytic Jacobian against finite differences; the stiff
reference against itself at two tolerances (Radau 1e-11 vs 1e-10), against
an explicit method (DOP853 at 1e-11, stable here because its step control
keeps h inside the stability region) and against lagmb (GGL and
projection-bdf at rtol 1e-11); the non-stiff RodChain against the faster
re-implementation here at 1e-12 (identical equations, S cached).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh, lu_factor, lu_solve

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.chain import stiff_chain  # noqa: E402
from bench.common.paths import RESULTS  # noqa: E402
from bench.common.repo import RodChain, chain_coefficients  # noqa: E402

CACHE = os.path.join(RESULTS, "peers_reference.json")
RATIO = 1e4  # omega_max / omega_min of the linearised stiff chain
STIFF_TOL = 1e-11  # Radau rtol = atol of the stiff reference
ZETA = 1.0  # damping ratio given to the fastest mode
G = 9.81


def difference_matrix(n):
    """D ((n-1) x n): (D theta)_i = theta_{i+1} - theta_i, the relative angle
    of the joint between rod i and rod i+1."""
    d = np.zeros((max(n - 1, 0), n))
    for i in range(n - 1):
        d[i, i], d[i, i + 1] = -1.0, 1.0
    return d


def linearisation(n, L=1.0, m=1.0, g=G):
    """(M0, K_g, D^T D) about the hanging equilibrium theta = -pi/2."""
    c = chain_coefficients(n)
    S = c.T @ c
    J = m * L * L / 12.0
    M0 = m * L * L * S + J * np.eye(n)
    Kg = m * g * L * np.diag(c.sum(axis=0))
    D = difference_matrix(n)
    return M0, Kg, D.T @ D


def frequencies(n, k):
    """Undamped angular frequencies (rad/s) and mass-normalised modes."""
    M0, Kg, DtD = linearisation(n)
    w2, phi = eigh(Kg + k * DtD, M0)
    return np.sqrt(w2), phi


def stiffness_for_ratio(n, ratio=RATIO, lo=1e-6, hi=1e12, iters=200):
    """k such that omega_max / omega_min = ratio, by bisection on log k.

    The ratio grows with k (omega_max ~ sqrt(k), omega_min tends to the
    rigid-pendulum value); the function checks it is monotone on a grid
    of the bracket before bisecting."""
    M0, Kg, DtD = linearisation(n)

    def r(k):
        lo_ = eigh(Kg + k * DtD, M0, eigvals_only=True, subset_by_index=[0, 0])[0]
        hi_ = eigh(Kg + k * DtD, M0, eigvals_only=True, subset_by_index=[n - 1, n - 1])[0]
        return math.sqrt(hi_ / lo_)

    grid = np.logspace(math.log10(lo), math.log10(hi), 37)
    vals = [r(k) for k in grid]
    if any(b < a * (1 - 1e-9) for a, b in zip(vals, vals[1:])):
        raise RuntimeError(f"omega_max/omega_min not monotone in k for N = {n}")
    if r(lo) >= ratio:
        return lo
    a, b = math.log(lo), math.log(hi)
    for _ in range(iters):
        mid = 0.5 * (a + b)
        if r(math.exp(mid)) < ratio:
            a = mid
        else:
            b = mid
        if b - a < 1e-10:
            break
    return math.exp(0.5 * (a + b))


def damping_for_zeta(n, k, zeta=ZETA):
    """c such that the fastest undamped mode has modal damping ratio zeta."""
    w, phi = frequencies(n, k)
    D = difference_matrix(n)
    top = phi[:, -1]
    return float(2.0 * zeta * w[-1] / (top @ (D.T @ D) @ top))


def damped_spectrum(n, k, c):
    """Eigenvalues of the damped linearisation (state space, 2n)."""
    M0, Kg, DtD = linearisation(n)
    Minv = np.linalg.inv(M0)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ (Kg + k * DtD), -Minv @ (c * DtD)]])
    return np.linalg.eigvals(A)


def stiff_parameters(n, ratio=RATIO, zeta=ZETA):
    """k, c and what they give (frequencies, damped eigenvalues)."""
    k = stiffness_for_ratio(n, ratio)
    c = damping_for_zeta(n, k, zeta)
    w, _ = frequencies(n, k)
    lam = damped_spectrum(n, k, c)
    top = lam[np.argmax(np.abs(lam))]
    return {
        "n": n, "stiffness": k, "damping": c, "ratio": ratio, "zeta_fastest_mode": zeta,
        "omega_min": float(w[0]), "omega_max": float(w[-1]),
        "damped_max_abs_eig": float(abs(top)),
        "damped_zeta_of_max_abs_eig": float(-top.real / abs(top)),
        "damped_min_abs_eig": float(np.min(np.abs(lam))),
    }


class StiffRodChain:
    """RodChain's equations (tests/references.py) plus joint spring-dampers.

        M(theta) thetadd = -m L^2 (S o sin d) thetadot^2
                           - m g L cos(theta) o s - k D^T D theta - c D^T D thetadot

    with d_ij = theta_i - theta_j, s_i = sum_k c_ki, M = m L^2 S o cos d + J I.
    S and D^T D are computed once (RodChain recomputes S at every call).
    k = c = 0 gives the non-stiff chain."""

    def __init__(self, n, k=0.0, c=0.0, L=1.0, m=1.0, g=G):
        self.n, self.k, self.c_damp, self.L, self.m, self.g = n, k, c, L, m, g
        cc = chain_coefficients(n)
        self.coef = cc
        self.S = cc.T @ cc
        self.s = cc.sum(axis=0)
        self.J = m * L * L / 12.0
        D = difference_matrix(n)
        self.DtD = D.T @ D
        self.nrhs = 0
        self.njac = 0

    def _parts(self, theta):
        d = theta[:, None] - theta[None, :]
        mL2 = self.m * self.L ** 2
        SC = self.S * np.cos(d)
        SN = self.S * np.sin(d)
        M = mL2 * SC
        M[np.diag_indices(self.n)] += self.J
        return mL2, SC, SN, M

    def _forces(self, theta, w, mL2, SN):
        return (-mL2 * (SN @ (w * w)) - self.m * self.g * self.L * np.cos(theta) * self.s
                - self.DtD @ (self.k * theta + self.c_damp * w))

    def rhs(self, t, y):
        self.nrhs += 1
        n = self.n
        theta, w = y[:n], y[n:]
        mL2, _, SN, M = self._parts(theta)
        a = np.linalg.solve(M, self._forces(theta, w, mL2, SN))
        return np.concatenate([w, a])

    def jac(self, t, y):
        """d(rhs)/dy, analytic:  da/dtheta = M^-1 (dr/dtheta - dM/dtheta a),
        da/dw = M^-1 dr/dw (derivation in the module docstring's terms):
            (dM/dtheta_p a)_i = m L^2 (SN_ip a_p - delta_ip (SN a)_i)
            d r_gyro/dtheta   = m L^2 (SC diag(w^2) - diag(SC w^2))
            d r_grav/dtheta   = diag(m g L s_i sin theta_i)
            d r/dw            = -2 m L^2 SN diag(w) - c D^T D."""
        self.njac += 1
        n = self.n
        theta, w = y[:n], y[n:]
        mL2, SC, SN, M = self._parts(theta)
        lu = lu_factor(M)
        a = lu_solve(lu, self._forces(theta, w, mL2, SN))
        dM_a = mL2 * (SN * a[None, :] - np.diag(SN @ a))
        dr_gyro = mL2 * (SC * (w * w)[None, :] - np.diag(SC @ (w * w)))
        dr_grav = np.diag(self.m * self.g * self.L * self.s * np.sin(theta))
        dth = lu_solve(lu, dr_gyro + dr_grav - self.k * self.DtD - dM_a)
        dw = lu_solve(lu, -2.0 * mL2 * SN * w[None, :] - self.c_damp * self.DtD)
        top = np.hstack([np.zeros((n, n)), np.eye(n)])
        return np.vstack([top, np.hstack([dth, dw])])

    def solve(self, method="Radau", rtol=1e-12, atol=1e-12, t_end=1.0):
        """State (theta, thetadot) at t_end, and solver counts."""
        n = self.n
        y0 = np.zeros(2 * n)
        kw = {"jac": self.jac} if method in ("Radau", "BDF", "LSODA") else {}
        sol = solve_ivp(self.rhs, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, **kw)
        if not sol.success:
            raise RuntimeError(sol.message)
        return sol.y[:n, -1], sol.y[n:, -1], {"nfev": int(sol.nfev), "njev": int(sol.njev), "nlu": int(sol.nlu)}

    def tip(self, theta):
        """The tip rod's centre: L (sum_{i<N-1} e_i + e_{N-1} / 2)."""
        e = np.stack([np.cos(theta), np.sin(theta)], axis=-1)
        return self.L * (self.coef[-1] @ e)


def tip_rodchain(n):
    """Non-stiff reference exactly as bench/accuracy/chains_accuracy.py computes it."""
    ref = RodChain(n)
    theta, _ = ref.solve([0.0, 1.0])
    return ref.centres(theta[1])[0, -1]


def load_cache(path=CACHE):
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)
    return {"nonstiff": {}, "stiff": {}}


def save_cache(cache, path=CACHE):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    cache["machine"] = platform.platform()
    with open(path, "w") as f:
        json.dump(cache, f, indent=1)


def nonstiff_reference(n, cache, use_rodchain=None, log=print):
    """Tip (x, y) at 1 s of the non-stiff chain, cached.

    RodChain (tests/references.py) itself for N <= 128; above that its
    per-call recomputation of S makes it take hours, so the same equations
    are integrated by StiffRodChain(k = c = 0) with the same DOP853 at
    1e-12 (the two agree at N <= 128, see check_nonstiff)."""
    key = str(n)
    if key in cache["nonstiff"]:
        return np.array(cache["nonstiff"][key]["tip"])
    if use_rodchain is None:
        use_rodchain = n <= 128
    t0 = time.perf_counter()
    if use_rodchain:
        tip, how = tip_rodchain(n), "tests/references.py RodChain, DOP853 rtol=atol=1e-12"
    else:
        ch = StiffRodChain(n)
        theta, _, _ = ch.solve("DOP853", 1e-12, 1e-12)
        tip, how = ch.tip(theta), "bench/peers/reference.py StiffRodChain(k=c=0), DOP853 rtol=atol=1e-12"
    cache["nonstiff"][key] = {"tip": [float(tip[0]), float(tip[1])], "how": how,
                              "seconds": time.perf_counter() - t0}
    log(f"  non-stiff reference N = {n}: tip {tip} ({how}, {time.perf_counter() - t0:.1f} s)")
    return np.asarray(tip)


def stiff_reference(n, cache, log=print):
    """Parameters (k, c) and tip at 1 s of the stiff chain, cached."""
    key = str(n)
    if key in cache["stiff"]:
        e = cache["stiff"][key]
        return e["params"], np.array(e["tip"])
    t0 = time.perf_counter()
    params = stiff_parameters(n)
    ch = StiffRodChain(n, params["stiffness"], params["damping"])
    theta, _, counts = ch.solve("Radau", STIFF_TOL, STIFF_TOL)
    tip = ch.tip(theta)
    cache["stiff"][key] = {"params": params, "tip": [float(tip[0]), float(tip[1])],
                           "how": f"bench/peers/reference.py StiffRodChain, Radau rtol=atol={STIFF_TOL:g}, "
                                  "analytic Jacobian",
                           "counts": counts, "seconds": time.perf_counter() - t0}
    log(f"  stiff reference N = {n}: k = {params['stiffness']:.6g}, c = {params['damping']:.6g}, "
        f"tip {tip} ({time.perf_counter() - t0:.1f} s)")
    return params, tip


# --------------------------------------------------------------------------
# Checks
# --------------------------------------------------------------------------

def check_jacobian(n=5, k=300.0, c=2.0, seed=1):
    ch = StiffRodChain(n, k, c)
    rng = np.random.default_rng(seed)
    y = rng.normal(size=2 * n)
    J = ch.jac(0.0, y)
    Jfd = np.empty_like(J)
    for j in range(2 * n):
        h = 1e-6 * max(1.0, abs(y[j]))
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        Jfd[:, j] = (ch.rhs(0.0, yp) - ch.rhs(0.0, ym)) / (2 * h)
    return float(np.max(np.abs(J - Jfd)) / np.max(np.abs(J)))


def check_nonstiff(n, cache):
    """RodChain (the cached reference, N <= 128) vs StiffRodChain(0, 0),
    both DOP853 at 1e-12; and RodChain at 1e-10 against 1e-12."""
    ref = nonstiff_reference(n, cache, use_rodchain=True)
    ch = StiffRodChain(n)
    theta, _, _ = ch.solve("DOP853", 1e-12, 1e-12)
    rc = RodChain(n)
    th, _ = rc.solve([0.0, 1.0], rtol=1e-10, atol=1e-10)
    return {"reimplementation_vs_rodchain": float(np.max(np.abs(ch.tip(theta) - ref))),
            "rodchain_1e-10_vs_1e-12": float(np.max(np.abs(rc.centres(th[1])[0, -1] - ref)))}


def check_stiff(n, params, tip, out, save=lambda: None):
    """Radau at 1e-10, DOP853 at 1e-11 and lagmb (GGL, projection-bdf at
    rtol 1e-11; 1e-10 where 1e-11 fails) against the reference (Radau at
    STIFF_TOL). Fills `out` (calling save() after each check; checks
    already in `out` are not repeated)."""
    ch = StiffRodChain(n, params["stiffness"], params["damping"])
    for method, tol in (("Radau", 1e-10), ("DOP853", 1e-11)):
        key = f"{method}_{tol:g}_vs_reference"
        if key not in out:
            theta, _, _ = ch.solve(method, tol, tol)
            out[key] = float(np.max(np.abs(ch.tip(theta) - tip)))
            save()
    try:
        import lagmb as mb
    except ImportError as e:  # pragma: no cover
        out["lagmb"] = f"not checked: {e}"
        return out
    model = stiff_chain(n, params["stiffness"], params["damping"])
    for name in ("ggl", "projection-bdf"):
        for rtol in (1e-11, 1e-10):
            key = f"lagmb_{name}_rtol{rtol:g}_vs_reference"
            if key not in out:
                try:
                    r = mb.simulate(model, t_end=1.0, rtol=rtol, atol=1e-2 * rtol, n_out=2, **mb.METHODS[name])
                    out[key] = float(np.max(np.abs(r.q[-1, 3 * n - 3:3 * n - 1] - tip)))
                except mb.SimulationError as e:
                    out[key] = "failed: " + str(e).splitlines()[0][:160]
                save()
            if isinstance(out[key], float):
                break
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="*", default=[8, 32, 128, 512], help="non-stiff references")
    p.add_argument("--stiff-n", type=int, nargs="*", default=[8, 32, 128, 512], help="stiff references")
    p.add_argument("--check-nonstiff-n", type=int, nargs="*", default=[8, 32, 128],
                   help="N at which RodChain and the re-implementation are compared")
    args = p.parse_args()
    cache = load_cache()
    checks = cache.setdefault("checks", {})
    checks["jacobian_fd_rel_error_n5"] = check_jacobian()
    print(f"analytic Jacobian vs finite differences (N = 5): rel. error {checks['jacobian_fd_rel_error_n5']:.1e}")
    for n in args.check_nonstiff_n:
        key = f"nonstiff_n{n}"
        if key not in checks:
            checks[key] = check_nonstiff(n, cache)
            save_cache(cache)
        print(f"N = {n} (non-stiff): " + ", ".join(f"{a} {b:.1e}" for a, b in checks[key].items()), flush=True)
    for n in args.n:
        nonstiff_reference(n, cache)
        save_cache(cache)
    for n in args.stiff_n:
        params, tip = stiff_reference(n, cache)
        save_cache(cache)
        check_stiff(n, params, tip, checks.setdefault(f"stiff_n{n}", {}), lambda: save_cache(cache))
        key = f"stiff_n{n}"
        print(f"N = {n} (stiff): " + ", ".join(f"{a} {b:.1e}" if isinstance(b, float) else f"{a} {b}"
                                               for a, b in checks[key].items()), flush=True)
    save_cache(cache)
    print(f"written {CACHE}")


if __name__ == "__main__":
    main()
