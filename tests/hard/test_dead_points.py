"""Dead points and run-time rank loss (issue 5, case 4).

1. A crank-rocker (crank 1 m, coupler 3.5 m, rocker 3 m, ground 4 m, uniform
   bars of 1 kg/m, gravity) whose crank turns on its own inertia: twice a
   turn crank and coupler align, the dead points of the linkage when the
   rocker is the input (the rocker's limit positions). The full Jacobian of
   the free four-bar does NOT lose rank there: its smallest singular value
   stays above 0.1 of the largest along the run (measured 0.17; checked
   below with numpy),
   so no Newton matrix becomes singular and the default formulation (GGL)
   runs through them, as does "ali3p". Reference: the one-coordinate energy
   equation theta' = sqrt(2 (E - V(theta)) / m(theta)) (the crank turns
   fully, theta' > 0), m(theta) and V(theta) from the closed-form position
   analysis and velocity coefficients, integrated with SciPy DOP853 at rtol
   1e-12; compared on the crank angle at every output.
2. Run-time rank loss that does make the Newton matrix singular: a single
   parallelogram (2 cranks of 1 m, coupler 1 m) turning through the
   horizontal, where every crank and the coupler are in line and Phi_q
   loses rank (its smallest singular value is proportional to |sin theta|).
   "ali3p" passes it (its Newton matrix [T0 Phi_q^T; Phi_q -eps I] stays
   invertible); reference theta'' = -g c cos(theta) / I as in
   test_singular_passages.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

import lagmb as mb

G = 9.81
A, D = np.array([0.0, 0.0]), np.array([4.0, 0.0])
L1, L2, L3 = 1.0, 3.5, 3.0


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def positions(theta):
    """B and C for crank angle theta (the upper assembly branch)."""
    B = A + L1 * np.array([math.cos(theta), math.sin(theta)])
    d = np.linalg.norm(D - B)
    a = (L2**2 - L3**2 + d**2) / (2 * d)
    h = math.sqrt(L2**2 - a**2)
    u = (D - B) / d
    return B, B + a * u + h * np.array([-u[1], u[0]])


def velocity_coefficients(theta):
    """dB/dtheta, dC/dtheta, and the coupler's and rocker's angular rates per unit theta'."""
    B, C = positions(theta)
    dB = L1 * np.array([-math.sin(theta), math.cos(theta)])
    # (C - B).(dC - dB) = 0, (C - D).dC = 0
    dC = np.linalg.solve(np.array([C - B, C - D]), np.array([(C - B) @ dB, 0.0]))
    return B, C, dB, dC, cross(C - B, dC - dB) / L2**2, cross(C - D, dC) / L3**2


def generalized_mass_and_potential(theta):
    B, C, dB, dC, w2, w3 = velocity_coefficients(theta)
    m1, m2, m3 = L1, L2, L3  # 1 kg/m
    J = [m1 * L1**2 / 12, m2 * L2**2 / 12, m3 * L3**2 / 12]
    mass = (m1 * (0.5 * dB) @ (0.5 * dB) + J[0] + m2 * (0.5 * (dB + dC)) @ (0.5 * (dB + dC))
            + J[1] * w2**2 + m3 * (0.5 * dC) @ (0.5 * dC) + J[2] * w3**2)
    V = G * (m1 * 0.5 * B[1] + m2 * 0.5 * (B[1] + C[1]) + m3 * 0.5 * C[1])
    return mass, V


def crank_rocker(theta0=math.radians(60.0), omega=12.0):
    B, C, dB, dC, w2, w3 = velocity_coefficients(theta0)
    m = mb.Model(gravity=(0.0, -G))

    def bar(name, p, q, v, w):
        length = float(np.linalg.norm(q - p))
        return m.add_body(name, mass=length, inertia=length**3 / 12, position=0.5 * (p + q),
                          angle=math.atan2(q[1] - p[1], q[0] - p[0]), velocity=v, angular_velocity=w)
    crank = bar("crank", A, B, 0.5 * omega * dB, omega)
    coupler = bar("coupler", B, C, 0.5 * omega * (dB + dC), omega * w2)
    rocker = bar("rocker", D, C, 0.5 * omega * dC, omega * w3)
    m.add_revolute("A", m.ground, crank, at=A)
    m.add_revolute("B", crank, coupler, at=B)
    m.add_revolute("C", coupler, rocker, at=C)
    m.add_revolute("D", rocker, m.ground, at=D)
    return m


def jacobian_singular_value_ratio(q):
    """min / max singular value of Phi_q for a four-bar of revolutes, from
    q = (x, y, phi) of crank, coupler, rocker (numerical derivative of the
    closure equations, independent of lagmb's Jacobian)."""
    def phi(q):
        (x1, y1, p1), (x2, y2, p2), (x3, y3, p3) = q.reshape(3, 3)
        e = lambda p, l: 0.5 * l * np.array([math.cos(p), math.sin(p)])
        c1, c2, c3 = np.array([x1, y1]), np.array([x2, y2]), np.array([x3, y3])
        return np.concatenate([c1 - e(p1, L1) - A, c1 + e(p1, L1) - (c2 - e(p2, L2)),
                               c2 + e(p2, L2) - (c3 + e(p3, L3)), c3 - e(p3, L3) - D])
    J = np.column_stack([(phi(q + 1e-7 * np.eye(9)[k]) - phi(q - 1e-7 * np.eye(9)[k])) / 2e-7
                         for k in range(9)])
    s = np.linalg.svd(J, compute_uv=False)
    return s[-1] / s[0]


def test_crank_rocker_passes_its_dead_points_on_inertia():
    """3 s from 60 deg at 12 rad/s: the crank turns > 4 times, so crank and
    coupler align (dead points) > 8 times; Phi_q keeps full rank (ratio of
    singular values > 0.1 at every other output). GGL (rtol 1e-10) and
    ali3p (step 1e-4 s) both: energy to 1e-6 relative (measured 2.9e-8;
    ali3p: 1e-5, measured 1.6e-6, O(step^2)), crank angle within 1e-6 rad
    (measured 3.5e-7) / 2e-5 rad (ali3p, measured 6.2e-6) of the
    one-coordinate reference."""
    model = crank_rocker()
    for kw, e_tol, th_tol in [(dict(rtol=1e-10, atol=1e-12), 1e-6, 1e-6),
                              (dict(newton_rtol=1e-10, newton_atol=1e-12, formulation="ali3p", step=1e-4), 1e-5, 2e-5)]:
        r = mb.simulate(model, t_end=3.0, n_out=301, **kw)
        theta = r.body("crank").angle
        assert (theta[-1] - theta[0]) / (2 * math.pi) > 4.0
        B = r.point("crank", (0.5 * L1, 0.0))
        C = r.point("rocker", (0.5 * L3, 0.0))
        # dead points: crank and coupler in line, cross(B - A, C - B) changes sign
        s = np.sign([cross(b - A, c - b) for b, c in zip(B, C)])
        assert np.sum(s[1:] != s[:-1]) >= 8
        assert min(jacobian_singular_value_ratio(q) for q in r.q[::2]) > 0.1
        E0 = r.energy[0]
        assert np.abs(r.energy - E0).max() / abs(E0) <= e_tol
        # reference: theta' = sqrt(2 (E - V) / m)
        rate = lambda _, y: [math.sqrt(2 * (E0 - generalized_mass_and_potential(y[0])[1])
                                       / generalized_mass_and_potential(y[0])[0])]
        ref = solve_ivp(rate, (0.0, 3.0), [theta[0]], method="DOP853", rtol=1e-12, atol=1e-12,
                        t_eval=r.t).y[0]
        assert np.abs(theta - ref).max() <= th_tol


def test_parallelogram_rank_loss_at_run_time():
    """One parallelogram window (cranks of 1 m, 1 kg on pivots 1 m apart,
    coupler 1 m, cranks vertical, top moving at 1 m/s): 3 s, 4 passages of
    the horizontal where Phi_q loses rank (its smallest singular value is
    proportional to |sin theta|; an output passes within 2 mm of it). ali3p
    with step 2e-4 s: energy to 1e-6, crank tip within 1e-5 m of the
    reference, max |Phi| <= 1e-12 m."""
    m = mb.Model(gravity=(0.0, -G))
    c0 = m.add_body("crank0", 1.0, 1 / 12, position=(0.0, 0.5), angle=math.pi / 2,
                    velocity=(0.5, 0.0), angular_velocity=-1.0)
    c1 = m.add_body("crank1", 1.0, 1 / 12, position=(1.0, 0.5), angle=math.pi / 2,
                    velocity=(0.5, 0.0), angular_velocity=-1.0)
    cp = m.add_body("coupler", 1.0, 1 / 12, position=(0.5, 1.0), velocity=(1.0, 0.0))
    m.add_revolute("A0", m.ground, c0, at=(0.0, 0.0))
    m.add_revolute("A1", m.ground, c1, at=(1.0, 0.0))
    m.add_revolute("B0", c0, cp, at=(0.0, 1.0))
    m.add_revolute("B1", c1, cp, at=(1.0, 1.0))
    r = mb.simulate(m, t_end=3.0, n_out=3001, formulation="ali3p", step=2e-4)
    tip = r.point("crank0", (0.5, 0.0))
    # crank angle 0 or pi: the Jacobian (from the crank angles) loses rank
    assert np.abs(tip[:, 1]).min() < 2e-3
    inertia, c = 2 / 3 + 1, 1.0 + 1.0
    ref = solve_ivp(lambda _, y: [y[1], -G * c * math.cos(y[0]) / inertia], (0.0, 3.0),
                    [math.pi / 2, -1.0], method="DOP853", rtol=1e-12, atol=1e-12, t_eval=r.t).y[0]
    assert np.abs(tip - np.column_stack([np.cos(ref), np.sin(ref)])).max() <= 1e-5
    assert np.abs(r.energy - r.energy[0]).max() / abs(r.energy[0]) <= 1e-6
    assert r.residual.max() <= 1e-12
