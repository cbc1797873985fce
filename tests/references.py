"""Independent reference solutions for the lagmb test suite.

Nothing in here imports lagmb: these are closed forms and small SciPy/NumPy
computations that the tests compare the library against.  Each one is
checked on its own in ``test_references.py`` (energy conservation, special
cases, agreement between two independent formulations), so a failure in a
lagmb test points at lagmb and not at the reference.

Conventions (same as docs/modelling.md, "Equations and signs")
----------------------------------------
* A planar body has q = (x, y, phi): centre of mass and angle, phi measured
  counter-clockwise from the global +x axis.
* The rotation matrix is A(phi) = [[cos, -sin], [sin, cos]]; a point with
  local coordinates s sits at r + A(phi) s.
* A revolute joint between body i and body j with local points s_i, s_j has
  the two equations  Phi = (r_j + A_j s_j) - (r_i + A_i s_i) = 0.  The ground
  is body index -1; for it s_i is the global point.
* Equations of motion M qdd + Phi_q^T lam = Q, so the force a joint puts on
  the bodies is -Phi_q^T lam.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import ellipk

GROUND = -1


# --------------------------------------------------------------------------
# The seed pendulum: a uniform rod pinned at one end, released horizontal.
# --------------------------------------------------------------------------

def rod_pin_force(theta, L=1.0, m=1.0, g=9.81):
    """Pin force on a uniform rod released from rest horizontal, closed form.

    theta is the angle of the rod *below* the horizontal (theta = -phi), the
    pin is at the origin, the centre of mass at (L/2 cos theta, -L/2 sin theta).

    Energy (the pin does no work, rotation about the fixed pin with
    J_pin = J + m L^2/4 = m L^2/3):
        1/2 (m L^2/3) thetadot^2 = m g (L/2) sin(theta)
        => thetadot^2 = 3 g sin(theta) / L
    Moment about the pin:
        (m L^2/3) thetadd = m g (L/2) cos(theta)
        => thetadd = 3 g cos(theta) / (2 L)
    Acceleration of the centre of mass (differentiate r_G twice):
        a_x = -L/2 (cos(theta) thetadot^2 + sin(theta) thetadd)
        a_y = -L/2 (-sin(theta) thetadot^2 + cos(theta) thetadd)
    Newton for the rod: F_pin + m g_vec = m a_G with g_vec = (0, -g):
        F_pin = m a_G - m g_vec.
    At release (theta = 0): F = (0, m g/4); at the bottom (theta = pi/2):
    F = (0, 5/2 m g).  Returns an array (..., 2).
    """
    theta = np.asarray(theta, dtype=float)
    thd2 = 3.0 * g * np.sin(theta) / L
    thdd = 3.0 * g * np.cos(theta) / (2.0 * L)
    ax = -0.5 * L * (np.cos(theta) * thd2 + np.sin(theta) * thdd)
    ay = -0.5 * L * (-np.sin(theta) * thd2 + np.cos(theta) * thdd)
    return np.stack([m * ax, m * ay + m * g], axis=-1)


def compound_pendulum_period(theta0_amplitude, L=1.0, g=9.81):
    """Period of a uniform rod (compound pendulum) pinned at one end.

    A uniform rod pivoted at its end is a physical pendulum with
    omega0^2 = m g (L/2) / J_pin = 3 g / (2 L), i.e. equivalent simple
    pendulum length l_eq = 2 L / 3.  For amplitude alpha (measured from the
    downward vertical) the exact period is
        T = 4 sqrt(l_eq / g) K(k),   k = sin(alpha / 2),
    with K the complete elliptic integral of the first kind.  SciPy's
    ``ellipk`` takes the *parameter* m = k^2, not the modulus k.
    Released from horizontal, alpha = pi/2 and k = sin(pi/4): the rod
    reaches the opposite horizontal at T/2 and is back at T.
    """
    k = math.sin(0.5 * theta0_amplitude)
    return 4.0 * math.sqrt(2.0 * L / (3.0 * g)) * float(ellipk(k * k))


# --------------------------------------------------------------------------
# N-link chain of uniform rods, minimal (absolute-angle) coordinates.
# --------------------------------------------------------------------------

def chain_coefficients(n):
    """c[k, i]: the centre of rod k is  L * sum_i c[k, i] e(theta_i).

    Rod k hangs from the end of rod k-1, so its centre is the sum of the full
    lengths of rods 0..k-1 plus half of its own:
        c[k, i] = 1 (i < k),  1/2 (i == k),  0 (i > k).
    """
    c = np.tril(np.ones((n, n)), -1) + 0.5 * np.eye(n)
    return c


@dataclass(frozen=True)
class RodChain:
    """Uniform rods (length L, mass m, J = m L^2/12 unless given) in a chain
    pinned to the ground at the origin, gravity (0, -g).

    Derivation (Lagrange, absolute angles theta_i, CCW from +x):
        r_k = L sum_i c_ki e_i,        e_i = (cos theta_i, sin theta_i)
        v_k = L sum_i c_ki thetadot_i n_i,  n_i = (-sin theta_i, cos theta_i)
        T = 1/2 sum_ij [m L^2 S_ij cos(theta_i - theta_j) + J delta_ij]
                thetadot_i thetadot_j,   S_ij = sum_k c_ki c_kj
            (n_i . n_j = cos(theta_i - theta_j))
        V = m g sum_k y_k = m g L sum_i (sum_k c_ki) sin theta_i
    d/dt dT/dthetadot_i - dT/dtheta_i + dV/dtheta_i = 0 gives
        sum_j M_ij thetadd_j + sum_j m L^2 S_ij sin(theta_i - theta_j)
              thetadot_j^2 = -m g L cos(theta_i) sum_k c_ki
    with M_ij = m L^2 S_ij cos(theta_i - theta_j) + J delta_ij.
    (The terms in thetadot_i thetadot_j from d/dt of M and from dT/dtheta_i
    cancel except for the thetadot_j^2 term above.)
    N = 1: (m L^2/4 + m L^2/12) thetadd = -m g (L/2) cos theta
           => thetadd = -3 g cos(theta) / (2 L).
    """

    n: int
    L: float = 1.0
    m: float = 1.0
    g: float = 9.81
    J: float | None = None

    @property
    def inertia(self):
        return self.m * self.L**2 / 12.0 if self.J is None else self.J

    @property
    def c(self):
        return chain_coefficients(self.n)

    @property
    def S(self):
        c = self.c
        return c.T @ c

    def mass_matrix(self, theta):
        d = theta[:, None] - theta[None, :]
        return self.m * self.L**2 * self.S * np.cos(d) + self.inertia * np.eye(self.n)

    def accelerations(self, theta, thetadot):
        theta = np.asarray(theta, float)
        thetadot = np.asarray(thetadot, float)
        d = theta[:, None] - theta[None, :]
        M = self.mass_matrix(theta)
        rhs = (-self.m * self.L**2 * (self.S * np.sin(d)) @ (thetadot**2)
               - self.m * self.g * self.L * np.cos(theta) * self.c.sum(axis=0))
        return np.linalg.solve(M, rhs)

    def rhs(self, t, y):
        n = self.n
        return np.concatenate([y[n:], self.accelerations(y[:n], y[n:])])

    def energy(self, theta, thetadot):
        """Kinetic + potential (datum y = 0) for one state or arrays (k, n)."""
        theta = np.atleast_2d(theta)
        thetadot = np.atleast_2d(thetadot)
        out = np.empty(theta.shape[0])
        for r in range(theta.shape[0]):
            M = self.mass_matrix(theta[r])
            T = 0.5 * thetadot[r] @ M @ thetadot[r]
            V = self.m * self.g * self.L * np.sin(theta[r]) @ self.c.sum(axis=0)
            out[r] = T + V
        return out

    def solve(self, t_eval, theta0=None, thetadot0=None, rtol=1e-12, atol=1e-12):
        """Integrate with DOP853; returns (theta, thetadot), each (k, n)."""
        n = self.n
        theta0 = np.zeros(n) if theta0 is None else np.asarray(theta0, float)
        thetadot0 = np.zeros(n) if thetadot0 is None else np.asarray(thetadot0, float)
        t_eval = np.asarray(t_eval, float)
        sol = solve_ivp(self.rhs, (t_eval[0], t_eval[-1]),
                        np.concatenate([theta0, thetadot0]), method="DOP853",
                        t_eval=t_eval, rtol=rtol, atol=atol)
        if not sol.success:  # pragma: no cover - reference must not fail
            raise RuntimeError(sol.message)
        return sol.y[:n].T, sol.y[n:].T

    def centres(self, theta):
        """Centres of mass (k, n, 2) from absolute angles (k, n)."""
        theta = np.atleast_2d(theta)
        e = np.stack([np.cos(theta), np.sin(theta)], axis=-1)  # (k, n, 2)
        return self.L * np.einsum("ki,rid->rkd", self.c, e)

    def cartesian_state(self, theta, thetadot):
        """(q, v) in lagmb's body coordinates (x, y, phi) per rod."""
        theta = np.asarray(theta, float)
        thetadot = np.asarray(thetadot, float)
        e = np.stack([np.cos(theta), np.sin(theta)], axis=-1)
        nvec = np.stack([-np.sin(theta), np.cos(theta)], axis=-1)
        r = self.L * self.c @ e
        v = self.L * self.c @ (thetadot[:, None] * nvec)
        q = np.column_stack([r, theta]).ravel()
        qd = np.column_stack([v, thetadot]).ravel()
        return q, qd

    def joints(self):
        """Revolute joints of the chain in the Revolute form below."""
        L = self.L
        js = [Revolute(GROUND, (0.0, 0.0), 0, (-0.5 * L, 0.0))]
        for k in range(1, self.n):
            js.append(Revolute(k - 1, (0.5 * L, 0.0), k, (-0.5 * L, 0.0)))
        return js


# --------------------------------------------------------------------------
# Cartesian (body-coordinate) constraint equations, written out by hand.
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class Revolute:
    """Revolute between body i (or GROUND) and body j; points in local axes
    (for the ground: the global point)."""

    i: int
    s_i: Sequence[float]
    j: int
    s_j: Sequence[float]


def _rot(phi, s):
    c, sn = np.cos(phi), np.sin(phi)
    return np.stack([c * s[0] - sn * s[1], sn * s[0] + c * s[1]], axis=-1)


def _drot(phi, s):
    """d/dphi of A(phi) s  = A(phi + pi/2) s."""
    c, sn = np.cos(phi), np.sin(phi)
    return np.stack([-sn * s[0] - c * s[1], c * s[0] - sn * s[1]], axis=-1)


def local_point(position, angle, point):
    """Local coordinates of a global point on a body placed at (position, angle)."""
    d = np.asarray(point, float) - np.asarray(position, float)
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])


def _point(q, body, s):
    """Global position of local point s of `body` for q of shape (k, n)."""
    if body == GROUND:
        return np.broadcast_to(np.asarray(s, float), q.shape[:-1] + (2,))
    x, y, phi = q[..., 3 * body], q[..., 3 * body + 1], q[..., 3 * body + 2]
    return np.stack([x, y], axis=-1) + _rot(phi, s)


def _point_velocity(q, v, body, s):
    if body == GROUND:
        return np.zeros(q.shape[:-1] + (2,))
    phi = q[..., 3 * body + 2]
    w = v[..., 3 * body + 2]
    return (np.stack([v[..., 3 * body], v[..., 3 * body + 1]], axis=-1)
            + w[..., None] * _drot(phi, s))


def revolute_residuals(q, joints):
    """Phi for every revolute: array (k, 2 * n_joints) (rows x, y per joint)."""
    q = np.atleast_2d(np.asarray(q, float))
    out = [_point(q, jt.j, jt.s_j) - _point(q, jt.i, jt.s_i) for jt in joints]
    return np.concatenate(out, axis=-1)


def revolute_velocity_residuals(q, v, joints):
    """Phi_q v for every revolute (time-independent joints: Phi_t = 0)."""
    q = np.atleast_2d(np.asarray(q, float))
    v = np.atleast_2d(np.asarray(v, float))
    out = [_point_velocity(q, v, jt.j, jt.s_j) - _point_velocity(q, v, jt.i, jt.s_i)
           for jt in joints]
    return np.concatenate(out, axis=-1)


def revolute_jacobian(q, joints, n_bodies):
    """Phi_q (2 n_joints, 3 n_bodies) at one configuration q (n,)."""
    q = np.asarray(q, float)
    Jm = np.zeros((2 * len(joints), 3 * n_bodies))
    for r, jt in enumerate(joints):
        for body, s, sign in ((jt.j, jt.s_j, 1.0), (jt.i, jt.s_i, -1.0)):
            if body == GROUND:
                continue
            Jm[2 * r:2 * r + 2, 3 * body:3 * body + 2] += sign * np.eye(2)
            Jm[2 * r:2 * r + 2, 3 * body + 2] += sign * _drot(q[3 * body + 2], s)
    return Jm


def revolute_gamma(q, v, joints):
    """gamma = -(Phi_q qd)_q qd for revolutes: for each end,
    d^2/dt^2 (r + A s) = rdd + phidd B s - phidot^2 A s, so
    gamma = phidot_j^2 A_j s_j - phidot_i^2 A_i s_i."""
    q = np.asarray(q, float)
    v = np.asarray(v, float)
    out = []
    for jt in joints:
        g = np.zeros(2)
        for body, s, sign in ((jt.j, jt.s_j, 1.0), (jt.i, jt.s_i, -1.0)):
            if body == GROUND:
                continue
            g += sign * v[3 * body + 2] ** 2 * _rot(q[3 * body + 2], s)
        out.append(g)
    return np.concatenate(out)


def augmented_solve(q, v, masses, inertias, joints, gravity=(0.0, -9.81)):
    """Solve [[M, Phi_q^T], [Phi_q, 0]] [qdd; lam] = [Q; gamma] densely.

    Q is gravity only: (m g_x, m g_y, 0) per body.
    """
    nb = len(masses)
    M = np.diag(np.ravel([[mi, mi, Ji] for mi, Ji in zip(masses, inertias)]))
    Q = np.ravel([[mi * gravity[0], mi * gravity[1], 0.0] for mi in masses])
    Jm = revolute_jacobian(q, joints, nb)
    nc = Jm.shape[0]
    K = np.block([[M, Jm.T], [Jm, np.zeros((nc, nc))]])
    sol = np.linalg.solve(K, np.concatenate([Q, revolute_gamma(q, v, joints)]))
    return sol[:3 * nb], sol[3 * nb:]


def body_energy(q, v, masses, inertias, gravity=(0.0, -9.81)):
    """Kinetic + gravitational potential (datum at the origin), (k,)."""
    q = np.atleast_2d(q)
    v = np.atleast_2d(v)
    E = np.zeros(q.shape[0])
    for b, (mi, Ji) in enumerate(zip(masses, inertias)):
        vx, vy, w = v[:, 3 * b], v[:, 3 * b + 1], v[:, 3 * b + 2]
        E += 0.5 * mi * (vx**2 + vy**2) + 0.5 * Ji * w**2
        E -= mi * (gravity[0] * q[:, 3 * b] + gravity[1] * q[:, 3 * b + 1])
    return E


# --------------------------------------------------------------------------
# Four-bar geometry.
# --------------------------------------------------------------------------

def circle_intersection(c0, r0, c1, r1, upper=True):
    """Intersection of circle(c0, r0) and circle(c1, r1); the point to the
    left of the directed line c0 -> c1 if upper, else to the right."""
    c0 = np.asarray(c0, float)
    c1 = np.asarray(c1, float)
    d = np.linalg.norm(c1 - c0)
    if d > r0 + r1 or d < abs(r0 - r1):
        raise ValueError("circles do not intersect")
    a = (r0**2 - r1**2 + d**2) / (2.0 * d)
    h = math.sqrt(max(r0**2 - a**2, 0.0))
    u = (c1 - c0) / d
    nrm = np.array([-u[1], u[0]])
    return c0 + a * u + (h if upper else -h) * nrm


def cross2(a, b):
    """z-component of the 2-D cross product (works on (..., 2) arrays)."""
    a = np.asarray(a)
    b = np.asarray(b)
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def hermite_root(t, f, df, after=-np.inf):
    """First strict sign change of f(t) in samples with t > after (f sampled
    together with its derivative df), located by Newton iteration on the
    cubic Hermite interpolant of the bracketing interval (error O(h^4)).
    Returns the root time."""
    t = np.asarray(t, float)
    f = np.asarray(f, float)
    df = np.asarray(df, float)
    ok = (f[:-1] * f[1:] < 0.0) & (t[:-1] > after)
    idx = np.nonzero(ok)[0]
    if idx.size == 0:
        raise ValueError("no sign change")
    k = idx[0]
    t0, t1, f0, f1 = t[k], t[k + 1], f[k], f[k + 1]
    h = t1 - t0
    d0, d1 = df[k] * h, df[k + 1] * h

    def p(s):
        h00 = 2 * s**3 - 3 * s**2 + 1
        h10 = s**3 - 2 * s**2 + s
        h01 = -2 * s**3 + 3 * s**2
        h11 = s**3 - s**2
        return h00 * f0 + h10 * d0 + h01 * f1 + h11 * d1

    def dp(s):
        return ((6 * s**2 - 6 * s) * f0 + (3 * s**2 - 4 * s + 1) * d0
                + (-6 * s**2 + 6 * s) * f1 + (3 * s**2 - 2 * s) * d1)

    s = f0 / (f0 - f1)  # secant start
    for _ in range(50):
        step = p(s) / dp(s)
        s -= step
        if abs(step) < 1e-15:
            break
    return t0 + s * h
