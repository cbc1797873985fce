"""The seed pendulum: a uniform rod pinned at one end, released horizontal.

L = 1 m, m = 1 kg, J = m L^2/12, q = (x, y, phi) with the centre of mass at
(L/2, 0) and phi = 0 at release; the revolute "pin" joins the ground and the
rod at the global origin, i.e. at the rod's local point (-L/2, 0); gravity
(0, -g), g = 9.81.  Released from rest, the rod swings down through the
vertical (t = T/4), reaches the opposite horizontal phi = -pi at T/2 and is
back at phi = 0 at T = 1.9333 s.

Sign convention (docs/modelling.md, "Equations and signs"): M qdd + Phi_q^T lam = Q.  The revolute's
equations are Phi = (point on body j) - (point on body i); here body i is
the ground, so

    Phi   = [x - (L/2) cos phi,  y - (L/2) sin phi]
    Phi_q = [[1, 0,  (L/2) sin phi],
             [0, 1, -(L/2) cos phi]]

and the five equations of the lecture (in our signs) read

    m xdd + lam1                                      = 0
    m ydd + lam2                                      = -m g
    J phidd + (L/2) sin(phi) lam1 - (L/2) cos(phi) lam2 = 0
    x - (L/2) cos phi = 0,   y - (L/2) sin phi = 0.

The force of the joint on the rod is -Phi_q^T lam: (-lam1, -lam2) and the
torque -(L/2)(sin(phi) lam1 - cos(phi) lam2) about the centre of mass.
"""

import math

import numpy as np
import pytest

import lagmb as mb
from builders import pendulum
from references import compound_pendulum_period, cross2, hermite_root, rod_pin_force

L = 1.0
M = 1.0
J = M * L**2 / 12.0
G = 9.81
MG = M * G
MGL = M * G * L
T = compound_pendulum_period(math.pi / 2, L, G)  # 1.93333 s

RTOL, ATOL = 1e-10, 1e-12
# a 0.01 s grid plus the closed-form instants T/4 (bottom), T/2 (opposite
# horizontal), 3T/4 (bottom again) and T (back at the start)
T_OUT = np.union1d(np.linspace(0.0, 2.0, 201), [T / 4, T / 2, 3 * T / 4, T])


@pytest.fixture(scope="module")
def run():
    """One run of the seed pendulum over 2 s at rtol 1e-10, atol 1e-12,
    output at T_OUT."""
    return mb.simulate(pendulum(L, M, G), t_end=2.0, t_out=T_OUT,
                       rtol=RTOL, atol=ATOL)


def _index(r, t):
    k = int(np.argmin(np.abs(r.t - t)))
    assert abs(r.t[k] - t) <= 1e-12, "requested output time missing from r.t"
    return k


# (a) ---------------------------------------------------------------------

def test_result_shapes(run):
    """One body (3 coordinates), one revolute (2 multipliers), one row per
    requested output time (t_out is returned as r.t, to 1e-15)."""
    k = T_OUT.size
    assert run.t.shape == (k,)
    assert run.q.shape == (k, 3)
    assert run.v.shape == (k, 3)
    assert run.a.shape == (k, 3)
    assert run.lam.shape == (k, 2)
    assert np.abs(run.t - T_OUT).max() <= 1e-15


def test_lecture_equations_hold_along_trajectory(run):
    """The five equations, written out (see module docstring), at every
    output: the three equations of motion to 1e-9 of m g (the torque
    equation to 1e-9 of m g L), the two constraints to 1e-8 m."""
    x, y, phi = run.q.T
    xdd, ydd, phidd = run.a.T
    lam1, lam2 = run.lam.T
    half = 0.5 * L

    eq_x = M * xdd + lam1
    eq_y = M * ydd + lam2 + M * G
    eq_phi = J * phidd + half * np.sin(phi) * lam1 - half * np.cos(phi) * lam2
    assert np.abs(eq_x).max() <= 1e-9 * MG
    assert np.abs(eq_y).max() <= 1e-9 * MG
    assert np.abs(eq_phi).max() <= 1e-9 * MGL

    assert np.abs(x - half * np.cos(phi)).max() <= 1e-8 * L
    assert np.abs(y - half * np.sin(phi)).max() <= 1e-8 * L


def test_velocity_and_acceleration_constraints_hold(run):
    """Differentiating Phi once and twice:
        xd + (L/2) sin(phi) phid = 0,      yd - (L/2) cos(phi) phid = 0
        xdd + (L/2)(cos(phi) phid^2 + sin(phi) phidd) = 0
        ydd + (L/2)(sin(phi) phid^2 - cos(phi) phidd) = 0
    Velocity level to 1e-8 m/s (speeds reach sqrt(3 g L) ~ 5.4 m/s at the tip);
    acceleration level to 1e-9 of g (qdd and lam solve the augmented system
    at the output state)."""
    x, y, phi = run.q.T
    xd, yd, phid = run.v.T
    xdd, ydd, phidd = run.a.T
    half = 0.5 * L
    assert np.abs(xd + half * np.sin(phi) * phid).max() <= 1e-8
    assert np.abs(yd - half * np.cos(phi) * phid).max() <= 1e-8
    ax = xdd + half * (np.cos(phi) * phid**2 + np.sin(phi) * phidd)
    ay = ydd + half * (np.sin(phi) * phid**2 - np.cos(phi) * phidd)
    assert np.abs(ax).max() <= 1e-9 * G
    assert np.abs(ay).max() <= 1e-9 * G


# (b) ---------------------------------------------------------------------

def test_pin_reaction_matches_closed_form(run):
    """r.reaction("pin") is the force of the joint on the rod (the second
    body) and its moment about the rod's centre of mass.

    Closed form with theta = -phi (angle below horizontal): energy gives
    thetadot^2 = 3 g sin(theta)/L, the moment about the pin
    thetadd = 3 g cos(theta)/(2L); with r_G = (L/2)(cos theta, -sin theta)
    the pin force is F = m a_G - m g_vec (references.rod_pin_force).
    Evaluated at the simulated theta of every output, the reaction agrees to
    1e-6 of m g across the whole 2 s (through the bottom, the far horizontal
    and back)."""
    R = run.reaction("pin")
    assert R.shape == (run.t.size, 3)
    theta = -run.q[:, 2]
    F = rod_pin_force(theta, L, M, G)
    assert np.abs(R[:, :2] - F).max() <= 1e-6 * MG


@pytest.mark.parametrize(
    "when, expected",
    [
        (0.0, (0.0, 0.25)),         # release: m g / 4 upward
        (T / 4, (0.0, 2.5)),        # lowest point: 5/2 m g upward
        (T / 2, (0.0, 0.25)),       # opposite horizontal, at rest again
        (3 * T / 4, (0.0, 2.5)),    # lowest point on the way back
    ],
    ids=["release", "bottom", "far-horizontal", "bottom-again"],
)
def test_pin_reaction_textbook_values(run, when, expected):
    """At rest horizontal: thetadot = 0, thetadd = 3g/(2L), so
    a_G = (0, -3g/4) and F = m a_G + (0, m g) = (0, m g/4).  At the bottom
    (t = T/4 by symmetry of the swing): thetadot^2 = 3g/L, thetadd = 0,
    a_G = (0, 3g/2) (centripetal, toward the pin) and F = (0, 5/2 m g).
    Tolerance 1e-6 of m g."""
    k = _index(run, when)
    R = run.reaction("pin")[k]
    assert abs(R[0] - expected[0] * MG) <= 1e-6 * MG
    assert abs(R[1] - expected[1] * MG) <= 1e-6 * MG


def test_pin_reaction_torque_is_moment_of_pin_force(run):
    """The third column is the torque of the joint about the rod's centre of
    mass: the pin force acts at the rod's material point s = (-L/2, 0), so
    tau = (A(phi) s) x F = (-(L/2) cos phi, -(L/2) sin phi) x F
    (2-D cross product).  The body-fixed point is used, not the global
    origin, so constraint drift does not enter.  Tolerance 1e-9 m g L."""
    R = run.reaction("pin")
    phi = run.q[:, 2]
    arm = np.column_stack([-0.5 * L * np.cos(phi), -0.5 * L * np.sin(phi)])
    assert np.abs(R[:, 2] - cross2(arm, R[:, :2])).max() <= 1e-9 * MGL


def test_pin_reaction_is_minus_phi_q_transpose_lambda(run):
    """Our sign convention ties the reported physical reaction to the
    multipliers: on the rod, -Phi_q^T lam =
    (-lam1, -lam2, -(L/2)(sin(phi) lam1 - cos(phi) lam2)).  Tolerance 1e-10
    of m g (and m g L for the torque)."""
    R = run.reaction("pin")
    phi = run.q[:, 2]
    lam1, lam2 = run.lam.T
    assert np.abs(R[:, 0] + lam1).max() <= 1e-10 * MG
    assert np.abs(R[:, 1] + lam2).max() <= 1e-10 * MG
    tau = -0.5 * L * (np.sin(phi) * lam1 - np.cos(phi) * lam2)
    assert np.abs(R[:, 2] - tau).max() <= 1e-10 * MGL


# (c) ---------------------------------------------------------------------

def test_body_accessor_matches_coordinates(run):
    """r.body("rod").position is (x, y) and .angle is phi, the rod's columns
    of r.q (to 1e-14)."""
    body = run.body("rod")
    assert body.position.shape == (run.t.size, 2)
    assert body.angle.shape == (run.t.size,)
    assert np.abs(body.position - run.q[:, :2]).max() <= 1e-14
    assert np.abs(body.angle - run.q[:, 2]).max() <= 1e-14


def test_point_paths(run):
    """r.point takes a point in the rod's own axes.  The free tip (L/2, 0)
    is at (x + (L/2) cos phi, y + (L/2) sin phi) (to 1e-13 m, pure geometry
    from r.q), so it stays at distance L from the pin (1e-8 m); the pinned
    end (-L/2, 0) stays at the origin (1e-8 m)."""
    x, y, phi = run.q.T
    tip = run.point("rod", (0.5 * L, 0.0))
    assert tip.shape == (run.t.size, 2)
    expected = np.column_stack([x + 0.5 * L * np.cos(phi), y + 0.5 * L * np.sin(phi)])
    assert np.abs(tip - expected).max() <= 1e-13
    assert np.abs(np.hypot(tip[:, 0], tip[:, 1]) - L).max() <= 1e-8

    pinned = run.point("rod", (-0.5 * L, 0.0))
    assert np.abs(pinned).max() <= 1e-8


def test_tip_swings_through_lowest_point(run):
    """At t = T/4 the rod hangs straight down: phi = -pi/2 and the tip is at
    (0, -L).  There the rod turns fastest (|phidot| = sqrt(3g/L) = 5.4 rad/s),
    so a timing error dt shows as 5.4 dt in phi; 1e-7 rad and 1e-7 m leave
    room for the global error of an rtol 1e-10 run."""
    k = _index(run, T / 4)
    assert abs(run.q[k, 2] + math.pi / 2) <= 1e-7
    tip = run.point("rod", (0.5 * L, 0.0))[k]
    assert abs(tip[0]) <= 1e-7 and abs(tip[1] + L) <= 1e-7


# (d) ---------------------------------------------------------------------

def test_energy_conserved(run):
    """No friction, the pin does no work: T + V is constant.  r.energy stays
    within 1e-8 m g L of its initial value over 2 s, and differs from
    1/2 m |v_G|^2 + 1/2 J phid^2 + m g y (computed here from r.q, r.v) only by
    a constant (the potential datum is the library's choice), to 1e-9 m g L."""
    E = run.energy
    assert E.shape == (run.t.size,)
    assert np.abs(E - E[0]).max() <= 1e-8 * MGL

    x, y, phi = run.q.T
    xd, yd, phid = run.v.T
    mine = 0.5 * M * (xd**2 + yd**2) + 0.5 * J * phid**2 + M * G * y
    offset = E - mine
    assert np.ptp(offset) <= 1e-9 * MGL


def test_residual_is_max_constraint_violation(run):
    """r.residual is max |Phi| per output: below 1e-9 m, and equal (to
    1e-14) to max(|x - (L/2) cos phi|, |y - (L/2) sin phi|) from r.q."""
    x, y, phi = run.q.T
    mine = np.maximum(np.abs(x - 0.5 * L * np.cos(phi)), np.abs(y - 0.5 * L * np.sin(phi)))
    assert run.residual.shape == (run.t.size,)
    assert run.residual.max() <= 1e-9
    assert np.abs(run.residual - mine).max() <= 1e-14


# (e) ---------------------------------------------------------------------

def test_period_large_amplitude():
    """Large-amplitude compound pendulum (omega0^2 = 3g/(2L)):
    T = 4 sqrt(2L/(3g)) K(k), k = sin(alpha/2), alpha = pi/2 for a release
    from horizontal; scipy.special.ellipk takes m = k^2 = 1/2.  The rod is
    momentarily at rest at the opposite horizontal (phi = -pi) at T/2 and
    back at phi = 0 at T.

    The turning points are located as the sign changes of phidot on a 1 ms
    output grid, refined on the cubic Hermite interpolant built from phidot
    and phidd (interpolation error ~1e-12 s).  Both times agree with the
    closed form to 1e-6 relative, and the turning angles are -pi and 0 to
    1e-6 rad."""
    r = mb.simulate(pendulum(L, M, G), t_end=2.0, n_out=2001,
                    rtol=RTOL, atol=ATOL)
    phi, phid, phidd = r.q[:, 2], r.v[:, 2], r.a[:, 2]

    t_half = hermite_root(r.t, phid, phidd, after=0.1)
    t_full = hermite_root(r.t, phid, phidd, after=t_half + 0.1)
    assert abs(t_half - T / 2) <= 1e-6 * (T / 2)
    assert abs(t_full - T) <= 1e-6 * T

    for t_turn, phi_turn in ((t_half, -math.pi), (t_full, 0.0)):
        k = int(np.argmin(np.abs(r.t - t_turn)))
        dt = t_turn - r.t[k]
        # second-order Taylor step from the nearest sample to the turning time
        phi_at_turn = phi[k] + phid[k] * dt + 0.5 * phidd[k] * dt**2
        assert abs(phi_at_turn - phi_turn) <= 1e-6


def test_at_rest_at_closed_form_half_period(run):
    """At t = T/2 from the closed form, phi = -pi to 1e-7 rad and the
    angular velocity vanishes: phidot(T/2) = phidd * (T/2 - t_turn), so
    |phidot/phidd| is the timing error, below 1e-6 T/2."""
    k = _index(run, T / 2)
    assert abs(run.q[k, 2] + math.pi) <= 1e-7
    assert abs(run.v[k, 2] / run.a[k, 2]) <= 1e-6 * (T / 2)


# (f) ---------------------------------------------------------------------

def test_solve_accelerations_at_release():
    """At rest horizontal, q = (L/2, 0, 0), v = 0: the moment about the pin
    gives phidd = -m g (L/2) / (m L^2/3) = -3g/(2L), so the centre of mass
    accelerates at (0, -3g/4); then m ydd + lam2 = -m g gives
    lam = (0, -m g/4), i.e. the reaction on the rod -lam = (0, m g/4).
    Tolerance 1e-12 of g (m g)."""
    qdd, lam = mb.solve_accelerations(pendulum(L, M, G),
                                      np.array([0.5 * L, 0.0, 0.0]), np.zeros(3), t=0.0)
    qdd = np.asarray(qdd)
    lam = np.asarray(lam)
    assert qdd.shape == (3,) and lam.shape == (2,)
    assert np.abs(qdd - [0.0, -0.75 * G, -1.5 * G / L]).max() <= 1e-12 * G
    assert np.abs(lam - [0.0, -0.25 * MG]).max() <= 1e-12 * MG
    assert np.abs(-lam - [0.0, 0.25 * MG]).max() <= 1e-12 * MG


@pytest.mark.parametrize("phi, phid", [(-0.7, 2.3), (0.4, -1.1), (-2.9, 0.0)])
def test_solve_accelerations_general_state(phi, phid):
    """At any consistent state the answer is fixed by the five equations:
    with theta = -phi, thetadd = 3 g cos(theta)/(2L) (moment about the pin,
    independent of the speed) and a_G = d^2/dt^2 (L/2)(cos phi, sin phi)
    = (L/2)(-sin(phi) phidd - cos(phi) phid^2, cos(phi) phidd - sin(phi) phid^2);
    lam = -m a_G + Q_xy (from m r_G'' + lam = (0, -m g)).
    Tolerance 1e-12 of g (m g)."""
    model = pendulum(L, M, G)
    half = 0.5 * L
    q = np.array([half * math.cos(phi), half * math.sin(phi), phi])
    v = np.array([-half * math.sin(phi) * phid, half * math.cos(phi) * phid, phid])
    qdd, lam = mb.solve_accelerations(model, q, v, t=0.0)

    phidd = -1.5 * G * math.cos(phi) / L
    ax = half * (-math.sin(phi) * phidd - math.cos(phi) * phid**2)
    ay = half * (math.cos(phi) * phidd - math.sin(phi) * phid**2)
    assert np.abs(np.asarray(qdd) - [ax, ay, phidd]).max() <= 1e-12 * G
    assert np.abs(np.asarray(lam) - [-M * ax, -M * ay - MG]).max() <= 1e-12 * MG


# statistics ----------------------------------------------------------------

def test_stats_reported_and_deterministic(run):
    """r.stats reports the integrator's work.  Counts are deterministic, so
    a second identical run reports exactly the same steps, residual and
    Jacobian evaluations and LU factorizations, and the same trajectory
    (bit for bit, 0 tolerance).  Sanity relations: at least one step, at
    least one residual evaluation per step, at least one factorization (of
    GGL's Newton matrix, or the explicit method's augmented matrix), a
    non-negative wall time."""
    s = run.stats
    for key in ("steps", "residual_evals", "jacobian_evals", "lu_factorizations", "wall_time"):
        assert key in s, key
    assert s["steps"] >= 1
    assert s["residual_evals"] >= s["steps"]
    assert s["lu_factorizations"] + s["augmented_factorizations"] >= 1
    assert s["wall_time"] >= 0.0

    again = mb.simulate(pendulum(L, M, G), t_end=2.0, t_out=T_OUT,
                        rtol=RTOL, atol=ATOL)
    for key in ("steps", "residual_evals", "jacobian_evals", "lu_factorizations"):
        assert again.stats[key] == s[key], key
    assert np.array_equal(again.q, run.q)
