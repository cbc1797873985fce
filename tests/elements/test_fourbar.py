"""A closed loop: the four-bar linkage with revolute joints only.

Ground pivots A = (0, 0) and D = (4, 0); crank AB (a = 1 m), coupler BC
(b = 3.5 m), rocker DC (c = 3 m), ground AD (d = 4 m).  Grashof: the shortest
link s = a = 1 and the longest l = d = 4 give s + l = 5 < p + q = 6.5, and the
shortest link is the crank, pinned to the ground: a crank-rocker (the crank
turns fully, the rocker swings).  Transmission angles stay between 54 and
100 degrees, far from the singular (folded) configurations.

The crank starts at 60 degrees: B = A + a (cos 60, sin 60); C is the upper
intersection of the circles |C - B| = b and |C - D| = c (open assembly).
Each bar is a uniform rod: centre at the midpoint of its end points, angle
atan2 of its direction (A->B, B->C, D->C), mass 1 kg/m times its length,
J = m l^2/12.  Joints: "A" ground-crank at A, "B" crank-coupler at B,
"C" coupler-rocker at C, "D" rocker-ground at D.  Gravity (0, -9.81).

Counting: 3 bodies -> n = 9 coordinates; 4 revolutes -> 8 equations, of
rank 8 (smallest singular value of Phi_q ~ 0.5 along the motion), so
9 - 8 = 1 degree of freedom (Gruebler: 3 (4 - 1) - 2 * 4 = 1).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import lagmb as mb
from references import (
    GROUND,
    Revolute,
    augmented_solve,
    body_energy,
    circle_intersection,
    local_point,
    revolute_jacobian,
    revolute_residuals,
    revolute_velocity_residuals,
)

G = 9.81
A = np.array([0.0, 0.0])
D = np.array([4.0, 0.0])
CRANK, COUPLER, ROCKER = 1.0, 3.5, 3.0
CRANK_ANGLE = math.radians(60.0)
OMEGA = 5.0  # initial crank angular velocity, rad/s

B = A + CRANK * np.array([math.cos(CRANK_ANGLE), math.sin(CRANK_ANGLE)])
C = circle_intersection(B, COUPLER, D, ROCKER, upper=True)

NAMES = ["crank", "coupler", "rocker"]
ENDS = [(A, B), (B, C), (D, C)]
POS = [0.5 * (p + q) for p, q in ENDS]
ANGLE = [math.atan2(q[1] - p[1], q[0] - p[0]) for p, q in ENDS]
LENGTH = [float(np.hypot(*(q - p))) for p, q in ENDS]
MASS = [1.0 * l for l in LENGTH]
INERTIA = [m * l**2 / 12.0 for m, l in zip(MASS, LENGTH)]

# The same joints written out for the independent checks (local points).
JOINTS = [
    Revolute(GROUND, A, 0, local_point(POS[0], ANGLE[0], A)),
    Revolute(0, local_point(POS[0], ANGLE[0], B), 1, local_point(POS[1], ANGLE[1], B)),
    Revolute(1, local_point(POS[1], ANGLE[1], C), 2, local_point(POS[2], ANGLE[2], C)),
    Revolute(2, local_point(POS[2], ANGLE[2], D), GROUND, D),
]


def _perp(w, r):
    """omega x r in the plane."""
    return w * np.array([-r[1], r[0]])


def consistent_velocities():
    """Velocity analysis: v_B = omega1 x (B - A); the loop closes with
    v_B + omega2 x (C - B) = omega3 x (C - D), two linear equations for the
    coupler and rocker rates.  Centre velocities follow from each bar's
    fixed or known point.  Returns v (9,) in body order (vx, vy, omega)."""
    vB = _perp(OMEGA, B - A)
    K = np.column_stack([_perp(1.0, C - B), -_perp(1.0, C - D)])
    w2, w3 = np.linalg.solve(K, -vB)
    return np.concatenate([
        [*_perp(OMEGA, POS[0] - A), OMEGA],
        [*(vB + _perp(w2, POS[1] - B)), w2],
        [*_perp(w3, POS[2] - D), w3],
    ])


Q0 = np.ravel([[*p, a] for p, a in zip(POS, ANGLE)])
V0 = consistent_velocities()


def four_bar(full_velocities=True):
    """The four-bar model; with full_velocities the initial velocities of
    all three bars are the consistent ones from consistent_velocities(),
    otherwise only the crank's angular velocity is given and the rest is
    left to the library's velocity projection."""
    m = mb.Model(gravity=(0.0, -G))
    bodies = []
    for k, name in enumerate(NAMES):
        kw = dict(mass=MASS[k], inertia=INERTIA[k], position=tuple(POS[k]), angle=ANGLE[k])
        if full_velocities:
            kw.update(velocity=tuple(V0[3 * k:3 * k + 2]), angular_velocity=V0[3 * k + 2])
        elif name == "crank":
            kw.update(angular_velocity=OMEGA)
        bodies.append(m.add_body(name, **kw))
    crank, coupler, rocker = bodies
    m.add_revolute("A", m.ground, crank, at=tuple(A))
    m.add_revolute("B", crank, coupler, at=tuple(B))
    m.add_revolute("C", coupler, rocker, at=tuple(C))
    m.add_revolute("D", rocker, m.ground, at=tuple(D))
    return m


@pytest.fixture(scope="module")
def run():
    """10 s at rtol 1e-9, atol 1e-11, output every 10 ms."""
    return mb.simulate(four_bar(), t_end=10.0, n_out=1001, rtol=1e-9, atol=1e-11)


def test_geometry_is_a_grashof_crank_rocker():
    """Checks of the test's own set-up (no lagmb): the computed C closes the
    loop (1e-14 m), the link lengths satisfy Grashof with the crank shortest,
    and the hand-written velocities satisfy Phi_q v = 0 (1e-14)."""
    links = sorted([CRANK, COUPLER, ROCKER, float(np.hypot(*(D - A)))])
    assert links[0] + links[3] < links[1] + links[2]
    assert CRANK == links[0]
    assert abs(np.hypot(*(C - B)) - COUPLER) <= 1e-14
    assert abs(np.hypot(*(C - D)) - ROCKER) <= 1e-14
    assert C[1] > 0.0
    assert np.abs(revolute_residuals(Q0, JOINTS)).max() <= 1e-14
    assert np.abs(revolute_velocity_residuals(Q0, V0, JOINTS)).max() <= 1e-14
    assert np.linalg.matrix_rank(revolute_jacobian(Q0, JOINTS, 3)) == 8


def test_one_degree_of_freedom():
    """n = 9 coordinates, 8 constraint equations of rank 8: 1 DOF."""
    m = four_bar()
    assert m.n_coordinates == 9
    assert m.n_constraints == 8
    assert m.degrees_of_freedom() == 1


def test_consistent_initial_velocities_are_kept(run):
    """Given velocities that already satisfy Phi_q v = 0, the projection onto
    the constraint manifold leaves them unchanged (1e-10 of the crank speed);
    the given positions are consistent too (1e-12 m)."""
    assert np.abs(run.q[0] - Q0).max() <= 1e-12
    assert np.abs(run.v[0] - V0).max() <= 1e-10 * OMEGA


def test_energy_conserved_over_10_s(run):
    """Revolutes do no work and nothing dissipates: r.energy is constant over
    10 s to 1e-6 relative.  The scale is the largest kinetic energy along the
    run (computed here from r.v; ~100 J), since the potential datum is
    arbitrary.  Also r.energy differs from the hand-computed
    sum 1/2 m |v|^2 + 1/2 J omega^2 + m g y only by a constant (1e-9)."""
    E = np.asarray(run.energy)
    mine = body_energy(run.q, run.v, MASS, INERTIA, (0.0, -G))
    kinetic = mine - body_energy(run.q, np.zeros_like(run.v), MASS, INERTIA, (0.0, -G))
    scale = kinetic.max()
    assert np.ptp(E) <= 1e-6 * scale
    assert np.ptp(E - mine) <= 1e-9 * scale


def test_loop_stays_closed(run):
    """r.residual (max |Phi| per output) stays below 1e-8 m over 10 s, and so
    does max |Phi| recomputed here from r.q with the hand-written joints
    (which also checks that r.q is laid out as (x, y, phi) per body)."""
    assert run.residual.max() < 1e-8
    assert np.abs(revolute_residuals(run.q, JOINTS)).max() < 1e-8


def test_crank_turns_fully(run):
    """A crank-rocker with enough energy: the crank keeps turning the same
    way (its rate never changes sign; minimum kinetic energy along the run is
    ~28 J) while the rocker only swings (its angle range stays below pi)."""
    assert run.v[:, 2].min() > 0.0
    assert run.q[-1, 2] - run.q[0, 2] > 4 * 2 * math.pi
    assert np.ptp(run.q[:, 8]) < math.pi


def test_motion_matches_cartesian_reference_at_2s():
    """Independent reference: integrate M qdd = Q - Phi_q^T lam with
    Phi_q qdd = gamma (dense NumPy augmented solve, hand-written Phi_q and
    gamma) as an ODE with DOP853 at rtol = atol = 1e-12 for 2 s (constraint
    drift stays ~1e-12).  lagmb's coordinates at t = 1 s and 2 s agree to
    1e-6 (m, rad)."""
    t_out = [0.0, 1.0, 2.0]
    r = mb.simulate(four_bar(), t_end=2.0, t_out=t_out, rtol=1e-10, atol=1e-12)

    def rhs(t, y):
        qdd, _ = augmented_solve(y[:9], y[9:], MASS, INERTIA, JOINTS, (0.0, -G))
        return np.concatenate([y[9:], qdd])

    sol = solve_ivp(rhs, (0.0, 2.0), np.concatenate([Q0, V0]), method="DOP853",
                    t_eval=t_out, rtol=1e-12, atol=1e-12)
    assert sol.success
    q_ref = sol.y[:9].T
    assert np.abs(revolute_residuals(q_ref, JOINTS)).max() <= 1e-10
    assert np.abs(r.q[1:] - q_ref[1:]).max() <= 1e-6


def test_velocity_projection_from_crank_rate_only():
    """Only the crank's angular velocity is given (5 rad/s; its centre
    velocity and the other bars' velocities left 0).  The library projects
    the initial velocities onto Phi_q v = 0: the result satisfies the
    velocity constraints to 1e-10 of the crank speed and is not trivial."""
    r = mb.simulate(four_bar(full_velocities=False), t_end=0.01, n_out=2,
                    rtol=1e-9, atol=1e-11)
    v0 = r.v[0]
    assert np.abs(revolute_velocity_residuals(r.q[0], v0, JOINTS)).max() <= 1e-10 * OMEGA
    assert np.abs(v0).max() > 0.1
