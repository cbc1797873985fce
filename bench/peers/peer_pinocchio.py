"""Pinocchio (minimal coordinates, ABA) + SciPy solve_ivp on the peer chain.

The chain is built in code as a serial chain of revolute-Z joints: joint 0
at the origin, joint i (i >= 1) 1 m along the x axis of link i-1's frame;
each link carries a rod of 1 kg with its centre 0.5 m along its x axis and
rotational inertia diag(1e-3, 1/12, 1/12) kg m^2 about that centre (only
the z entry, 1/12, acts in planar motion; the x entry is any small positive
number). Gravity is set to (0, -9.81, 0).

Pinocchio's joint angles are *relative*: q_0 is rod 0's angle from +x, q_i
(i >= 1) is rod i's angle minus rod i-1's. So the rest angle 0 of the stiff
variant's springs is q_i = 0, and their torques act directly on the joint
coordinates:  tau_i = -k q_i - c qdot_i  (i >= 1), tau_0 = 0.
The forward dynamics qdd = ABA(q, qdot, tau) is integrated by SciPy's
solve_ivp (state (q, qdot)): DOP853 for the non-stiff chain; DOP853,
Radau, BDF and LSODA for the stiff one, the implicit ones with the
analytic Jacobian from computeABADerivatives:
    d qdd/dq = ddq_dq + Minv d tau/dq = ddq_dq - k Minv[:, i >= 1],
    d qdd/dv = ddq_dv - c Minv[:, i >= 1].
rtol levels as lagmb's (half decades), atol = 1e-2 rtol. The time is that
of the solve_ivp call (Python right-hand side around pin.aba). The tip is
rod N-1's centre from forward kinematics (oMi[N] applied to (0.5, 0, 0)).

Self-check against the reference:

    /tmp/peers-venv/bin/python bench/peers/peer_pinocchio.py [--n 8] [--stiff]
"""

import os
import sys
import time

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

NAME = "pinocchio"
RTOLS = tuple(10.0 ** (-k / 2) for k in range(6, 23))


def available():
    try:
        import pinocchio as pin
        import scipy
    except ImportError as e:
        return False, f"not importable: {e}"
    return True, f"pinocchio {pin.__version__} + SciPy {scipy.__version__} solve_ivp"


def build(n):
    import pinocchio as pin

    model = pin.Model()
    model.gravity.linear = np.array([0.0, -9.81, 0.0])
    parent = 0  # the universe
    rod = pin.Inertia(1.0, np.array([0.5, 0.0, 0.0]), np.diag([1e-3, 1.0 / 12.0, 1.0 / 12.0]))
    for i in range(n):
        placement = pin.SE3(np.eye(3), np.array([0.0 if i == 0 else 1.0, 0.0, 0.0]))
        jid = model.addJoint(parent, pin.JointModelRZ(), placement, f"j{i}")
        model.appendBodyToJoint(jid, rod, pin.SE3.Identity())
        parent = jid
    return model


class Engine:
    name = NAME

    def __init__(self, n, k=0.0, c=0.0):
        import pinocchio as pin

        self.pin = pin
        self.n = n
        self.model = build(n)
        self.data = self.model.createData()
        mask = np.ones(n)
        mask[0] = 0.0  # no spring-damper at the ground pin
        self.kvec = k * mask
        self.cvec = c * mask
        self.stiff = bool(k or c)

    def methods(self, stiff):
        names = ["DOP853"] + (["Radau", "BDF", "LSODA"] if stiff else [])
        return [{"method": m, "kind": "rtol", "levels": RTOLS} for m in names]

    def rhs(self, t, y):
        n = self.n
        q, v = y[:n], y[n:]
        tau = -(self.kvec * q + self.cvec * v)
        a = self.pin.aba(self.model, self.data, q, v, tau)
        return np.concatenate([v, a])  # copies data.ddq

    def jac(self, t, y):
        n = self.n
        q, v = y[:n], y[n:]
        tau = -(self.kvec * q + self.cvec * v)
        ddq_dq, ddq_dv, minv = self.pin.computeABADerivatives(self.model, self.data, q, v, tau)
        minv = np.triu(minv) + np.triu(minv, 1).T  # only the upper triangle is filled
        J = np.zeros((2 * n, 2 * n))
        J[:n, n:] = np.eye(n)
        J[n:, :n] = ddq_dq - minv * self.kvec[None, :]
        J[n:, n:] = ddq_dv - minv * self.cvec[None, :]
        return J

    def tip(self, q):
        pin = self.pin
        pin.forwardKinematics(self.model, self.data, q)
        return (self.data.oMi[self.n].act(np.array([0.5, 0.0, 0.0])))[:2]

    def run(self, method, rtol):
        from scipy.integrate import solve_ivp

        n = self.n
        y0 = np.zeros(2 * n)
        kw = {"jac": self.jac} if method in ("Radau", "BDF", "LSODA") else {}
        t0 = time.perf_counter()
        sol = solve_ivp(self.rhs, (0.0, 1.0), y0, method=method, rtol=rtol, atol=1e-2 * rtol, **kw)
        wall = time.perf_counter() - t0
        if not sol.success:
            raise RuntimeError(sol.message)
        tip = self.tip(sol.y[:n, -1].copy())
        return {"tip": [float(tip[0]), float(tip[1])], "time": wall, "steps": int(sol.t.size - 1),
                "evals": int(sol.nfev), "jacobians": int(sol.njev)}


def check_jacobian(n=5, k=300.0, c=2.0, seed=2):
    """Relative difference of the analytic Jacobian to central differences."""
    e = Engine(n, k, c)
    y = np.random.default_rng(seed).normal(size=2 * n)
    J = e.jac(0.0, y)
    F = np.empty_like(J)
    for j in range(2 * n):
        h = 1e-6
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        F[:, j] = (e.rhs(0.0, yp) - e.rhs(0.0, ym)) / (2 * h)
    return float(np.max(np.abs(J - F)) / np.max(np.abs(J)))


if __name__ == "__main__":
    from bench.peers.selfcheck import selfcheck

    if available()[0]:
        print(f"analytic Jacobian vs central differences (N = 5): {check_jacobian():.1e}")
    selfcheck(sys.modules[__name__])
