"""One small mechanism per joint kind, with a closed-form reaction and an
energy check.

Conventions (docs/modelling.md, "Joints"): r.reaction(name) is the force
(x, y) the joint puts on its second body (body_j), in global axes, and the
torque on body_j about its centre of mass; frame="joint" gives the same
force in the joint's own axes:

    translational   (along the axis u_i, normal n_i = u_i turned +90 deg)
    pin_in_slot     (along the slot, normal)
    distance        (along d from p_i to p_j, across); lam > 0 is tension,
                    the first component is -tension
    gear            (along the centre line i -> j, tangential): the
                    tangential component is the tooth force
    rack_pinion     (along the rack axis, normal): the first component is
                    the tooth force

The force on body_i is equal and opposite.  Gravity (0, -g), g = 9.81,
wherever a mechanism stands in a vertical plane; gears run in a horizontal
plane (no gravity).  Every run: rtol 1e-10, atol 1e-12.
"""

import math

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid, solve_ivp
from scipy.special import ellipk

import lagmb as mb
from references import cross2

G = 9.81
GRAVITY = np.array([0.0, -G])
RTOL, ATOL = 1e-10, 1e-12


def _run(model, t_end, **kw):
    if "t_out" not in kw:
        kw.setdefault("n_out", 201)
    return mb.simulate(model, t_end=t_end, rtol=RTOL, atol=ATOL, **kw)


def _unit(angle):
    return np.array([math.cos(angle), math.sin(angle)])


# --------------------------------------------------------------------------
# Translational: a block on a frictionless incline
# --------------------------------------------------------------------------

ALPHA = math.radians(30.0)
U = _unit(ALPHA)                  # up the incline
N = np.array([-U[1], U[0]])       # its normal, away from the incline


def inclined_block(mass=2.0, speed=1.5):
    """A block (2 kg, 0.05 kg m^2) on a 30 deg incline: translational joint
    "incline" between the ground and the block, at the block's centre,
    axis u = (cos 30, sin 30); launched up the incline at 1.5 m/s."""
    m = mb.Model(gravity=(0.0, -G))
    start = np.array([0.3, 0.2])
    block = m.add_body("block", mass, 0.05, position=start, angle=ALPHA, velocity=speed * U)
    m.add_translational("incline", m.ground, block, at=start, axis=U)
    return m


@pytest.fixture(scope="module")
def incline_run():
    return _run(inclined_block(), 1.0)


def test_incline_acceleration(incline_run):
    """Along the incline only gravity's component acts: s'' = -g sin(alpha)
    (to 1e-9 m/s^2), nothing across it (1e-9 m/s^2), and no rotation."""
    block = incline_run.body("block")
    assert np.abs(block.acceleration @ U + G * math.sin(ALPHA)).max() <= 1e-9
    assert np.abs(block.acceleration @ N).max() <= 1e-9
    assert np.abs(block.angle - ALPHA).max() <= 1e-10
    # and so the path is the closed-form parabola s = v0 t - g sin(alpha) t^2 / 2
    s = (block.position - block.position[0]) @ U
    t = incline_run.t
    assert np.abs(s - (1.5 * t - 0.5 * G * math.sin(ALPHA) * t**2)).max() <= 1e-8


def test_incline_normal_force(incline_run):
    """Across the incline the block does not accelerate, so the joint holds
    gravity's normal component: N = m g cos(alpha) = 16.99 N along n, the
    second joint-axis component (1e-9 N); nothing along the axis and, as
    gravity acts at the centre of mass, no torque (1e-9).  In global axes
    the force is N n = m g cos(alpha) (-sin alpha, cos alpha)."""
    R = incline_run.reaction("incline", frame="joint")
    assert R.shape == (incline_run.t.size, 3)
    normal = 2.0 * G * math.cos(ALPHA)
    assert np.abs(R[:, 1] - normal).max() <= 1e-9
    assert np.abs(R[:, 0]).max() <= 1e-9
    assert np.abs(R[:, 2]).max() <= 1e-9
    Rg = incline_run.reaction("incline")
    assert np.abs(Rg[:, :2] - normal * N).max() <= 1e-9


def test_incline_energy(incline_run):
    """The joint does no work: r.energy is constant to 1e-9 relative to the
    initial kinetic energy (2.25 J), and equals 1/2 m v^2 + m g y plus a
    constant."""
    E = incline_run.energy
    ke0 = 0.5 * 2.0 * 1.5**2
    assert np.ptp(E) <= 1e-9 * ke0
    b = incline_run.body("block")
    mine = 0.5 * 2.0 * (b.velocity**2).sum(axis=1) + 2.0 * G * b.position[:, 1]
    assert np.ptp(E - mine) <= 1e-9 * ke0


def test_incline_with_spring_damper_dissipates_c_ldot_squared():
    """Add a spring-damper (k = 150 N/m, c = 3 N s/m, free length 0.5 m)
    from a ground point up the incline to the block.  Only the damper takes
    energy out: dE/dt = -c ldot^2 with E = kinetic + gravity + spring
    potential (r.energy).  Integrated by the trapezoid rule over 2001
    outputs in 2 s (quadrature error ~ h^2), E(t) - E(0) = -int c ldot^2 dt
    at every output to 1e-4 of the total dissipated energy (2.5 J).
    l = |top - p| with the block below the anchor on the incline line, so
    ldot = -v . u."""
    k, c = 150.0, 3.0
    top = np.array([0.0, 0.0])
    start = top - 0.4 * U
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", 2.0, 0.05, position=start, angle=ALPHA, velocity=0.8 * U)
    m.add_translational("incline", m.ground, block, at=start, axis=U)
    m.add_spring_damper("buffer", m.ground, top, block, start, stiffness=k, damping=c,
                        free_length=0.5)
    r = _run(m, 2.0, n_out=2001)
    b = r.body("block")
    ldot = -(b.velocity @ U)
    dissipated = cumulative_trapezoid(c * ldot**2, r.t, initial=0.0)
    dE = r.energy - r.energy[0]
    assert dissipated[-1] > 1.0
    assert np.abs(dE + dissipated).max() <= 1e-4 * dissipated[-1]

    # and r.energy is the sum of the three potentials named in the docs
    length = np.hypot(*(b.position - top).T)
    mine = (0.5 * 2.0 * (b.velocity**2).sum(axis=1) + 2.0 * G * b.position[:, 1]
            + 0.5 * k * (length - 0.5)**2)
    assert np.ptp(r.energy - mine) <= 1e-9


# --------------------------------------------------------------------------
# Revolute between two bodies: the double pendulum
# --------------------------------------------------------------------------

L1, L2, M1, M2 = 1.0, 0.7, 1.0, 0.6
J1, J2 = M1 * L1**2 / 12.0, M2 * L2**2 / 12.0
PHI2 = 0.5


@pytest.fixture(scope="module")
def double_pendulum_run():
    """Two uniform rods: "upper" (1 m, 1 kg) horizontal from the ground pivot
    "shoulder" at the origin, "lower" (0.7 m, 0.6 kg) hanging on at
    "elbow" = (1, 0) at 0.5 rad; released from rest, 2 s."""
    m = mb.Model(gravity=(0.0, -G))
    upper = m.add_body("upper", M1, J1, position=(0.5 * L1, 0.0))
    lower = m.add_body("lower", M2, J2, position=(L1, 0.0) + 0.5 * L2 * _unit(PHI2), angle=PHI2)
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("elbow", upper, lower, at=(L1, 0.0))
    return _run(m, 2.0)


def test_elbow_reaction_is_what_holds_the_lower_rod(double_pendulum_run):
    """Newton for the lower rod alone: the elbow is the only force on it
    besides gravity, so reaction("elbow") = m2 a2 - m2 g (to 1e-8 of m2 g),
    and its torque about the lower rod's centre equals J2 phi2'' and the
    moment of that force applied at the elbow end, local (-L2/2, 0):
    (A(phi2) s) x F (to 1e-8 of m2 g L2)."""
    r = double_pendulum_run
    lower = r.body("lower")
    R = r.reaction("elbow")
    force = M2 * lower.acceleration - M2 * GRAVITY
    assert np.abs(R[:, :2] - force).max() <= 1e-8 * M2 * G
    assert np.abs(R[:, 2] - J2 * lower.angular_acceleration).max() <= 1e-8 * M2 * G * L2
    arm = -0.5 * L2 * np.column_stack([np.cos(lower.angle), np.sin(lower.angle)])
    assert np.abs(R[:, 2] - cross2(arm, R[:, :2])).max() <= 1e-8 * M2 * G * L2
    assert np.abs(force).max() > M2 * G  # swinging, not static


def test_elbow_pushes_back_on_upper_rod(double_pendulum_run):
    """The force on body_i is equal and opposite: Newton for the upper rod,
    m1 a1 = F_shoulder + m1 g - F_elbow, so the shoulder reaction is
    m1 a1 - m1 g + m2 a2 - m2 g (to 1e-8 of (m1 + m2) g)."""
    r = double_pendulum_run
    upper, lower = r.body("upper"), r.body("lower")
    expected = (M1 * upper.acceleration - M1 * GRAVITY
                + M2 * lower.acceleration - M2 * GRAVITY)
    assert np.abs(r.reaction("shoulder")[:, :2] - expected).max() <= 1e-8 * (M1 + M2) * G


def test_revolute_joint_frame(double_pendulum_run):
    """frame="joint" for a revolute: radial axis e from the joint point to
    body_j's centre of mass, tangential e turned +90 deg.  With the elbow at
    the upper rod's end (local (L1/2, 0)): R_joint = (F . e, F . e_perp,
    torque), to 1e-10 N."""
    r = double_pendulum_run
    elbow = r.point("upper", (0.5 * L1, 0.0))
    d = r.body("lower").position - elbow
    e = d / np.hypot(*d.T)[:, None]
    e_perp = np.column_stack([-e[:, 1], e[:, 0]])
    R, Rj = r.reaction("elbow"), r.reaction("elbow", frame="joint")
    assert np.abs(Rj[:, 0] - np.einsum("kd,kd->k", R[:, :2], e)).max() <= 1e-10
    assert np.abs(Rj[:, 1] - np.einsum("kd,kd->k", R[:, :2], e_perp)).max() <= 1e-10
    assert np.array_equal(Rj[:, 2], R[:, 2])


def test_double_pendulum_energy(double_pendulum_run):
    """Frictionless pins: r.energy constant to 1e-8 of m1 g L1 over 2 s of
    chaotic motion."""
    assert np.ptp(double_pendulum_run.energy) <= 1e-8 * M1 * G * L1


# --------------------------------------------------------------------------
# Weld: two welded bodies are one rigid body
# --------------------------------------------------------------------------

ROD_L, ROD_M = 1.0, 1.0
BOB_M, BOB_R = 2.0, 0.1
ROD_J, BOB_J = ROD_M * ROD_L**2 / 12.0, 0.5 * BOB_M * BOB_R**2
WELD_PHI0 = 0.3
ROD_C = 0.5 * ROD_L * _unit(WELD_PHI0)
BOB_C = ROD_L * _unit(WELD_PHI0)


def _composite():
    """Mass, centre and centroidal inertia of rod + bob (parallel axes):
    M = m1 + m2, c = (m1 c1 + m2 c2)/M, J = sum (J_b + m_b |c_b - c|^2)."""
    mass = ROD_M + BOB_M
    c = (ROD_M * ROD_C + BOB_M * BOB_C) / mass
    J = (ROD_J + ROD_M * np.sum((ROD_C - c)**2) + BOB_J + BOB_M * np.sum((BOB_C - c)**2))
    return mass, c, J


@pytest.fixture(scope="module")
def weld_runs():
    """A uniform rod (1 m, 1 kg) pinned to the ground at the origin, start
    angle 0.3 rad, with a disk "bob" (2 kg, radius 0.1 m, angle 1.3 rad)
    welded ("glue") to its far end; and the equivalent single body (the
    composite's mass, centre and inertia) on the same pivot.  2 s each."""
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", ROD_M, ROD_J, position=ROD_C, angle=WELD_PHI0)
    bob = m.add_body("bob", BOB_M, BOB_J, position=BOB_C, angle=WELD_PHI0 + 1.0)
    m.add_revolute("pivot", m.ground, rod, at=(0.0, 0.0))
    m.add_weld("glue", rod, bob)

    mass, c, J = _composite()
    e = mb.Model(gravity=(0.0, -G))
    one = e.add_body("one", mass, J, position=c, angle=WELD_PHI0)
    e.add_revolute("pivot", e.ground, one, at=(0.0, 0.0))
    return m, _run(m, 2.0), _run(e, 2.0)


def test_weld_leaves_one_degree_of_freedom(weld_runs):
    """2 bodies (6 coordinates) - pivot (2) - weld (3) = 1."""
    assert weld_runs[0].degrees_of_freedom() == 1


def test_welded_pair_swings_like_one_body(weld_runs):
    """The rod's angle (and the bob's, minus its 1 rad offset) equals the
    equivalent body's angle to 1e-8 rad along 2 s, and both equal the
    compound-pendulum ODE J_O theta'' = -M g d cos(theta + beta) (J_O = J +
    M d^2, d and beta the distance and bearing of the composite centre from
    the pivot relative to the rod) solved by SciPy DOP853 at rtol 1e-12, to
    1e-7 rad.  The pivot forces agree to 1e-6 N."""
    _, r, eq = weld_runs
    phi = r.body("rod").angle
    assert np.abs(phi - eq.body("one").angle).max() <= 1e-8
    assert np.abs(r.body("bob").angle - 1.0 - eq.body("one").angle).max() <= 1e-8

    mass, c, J = _composite()
    d = float(np.hypot(*c))
    beta = math.atan2(c[1], c[0]) - WELD_PHI0
    J_O = J + mass * d**2
    sol = solve_ivp(lambda t, y: [y[1], -mass * G * d * math.cos(y[0] + beta) / J_O],
                    (0.0, 2.0), [WELD_PHI0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12,
                    t_eval=r.t)
    assert np.abs(sol.y[0] - phi).max() <= 1e-7
    assert np.abs(r.reaction("pivot")[:, :2] - eq.reaction("pivot")[:, :2]).max() <= 1e-6


def test_weld_reaction_holds_the_bob(weld_runs):
    """The weld is all that holds the bob against gravity: reaction("glue")
    = m a - m g of the bob (1e-8 of m g) and its torque about the bob's
    centre is J phi'' (1e-8 of m g L)."""
    _, r, _ = weld_runs
    bob = r.body("bob")
    R = r.reaction("glue")
    assert np.abs(R[:, :2] - (BOB_M * bob.acceleration - BOB_M * GRAVITY)).max() <= 1e-8 * BOB_M * G
    assert np.abs(R[:, 2] - BOB_J * bob.angular_acceleration).max() <= 1e-8 * BOB_M * G * ROD_L


def test_weld_joint_frame(weld_runs):
    """frame="joint" for a weld: body_i's (the rod's) axes, u = (cos phi,
    sin phi), n = u turned +90 deg (1e-10 N)."""
    _, r, _ = weld_runs
    phi = r.body("rod").angle
    u = np.column_stack([np.cos(phi), np.sin(phi)])
    n = np.column_stack([-np.sin(phi), np.cos(phi)])
    F, Rj = r.reaction("glue")[:, :2], r.reaction("glue", frame="joint")
    assert np.abs(Rj[:, 0] - np.einsum("kd,kd->k", F, u)).max() <= 1e-10
    assert np.abs(Rj[:, 1] - np.einsum("kd,kd->k", F, n)).max() <= 1e-10


def test_weld_energy(weld_runs):
    """Conservative: r.energy constant to 1e-8 of M g L (M g L = 29 J)."""
    _, r, _ = weld_runs
    assert np.ptp(r.energy) <= 1e-8 * (ROD_M + BOB_M) * G * ROD_L


# --------------------------------------------------------------------------
# Distance: a particle on a massless link is a simple pendulum
# --------------------------------------------------------------------------

LINK_L, BOB_MASS, THETA0 = 0.8, 0.5, math.radians(60.0)
# large-amplitude period of the simple pendulum, T = 4 sqrt(L/g) K(sin^2(theta0/2))
SIMPLE_T = 4.0 * math.sqrt(LINK_L / G) * float(ellipk(math.sin(0.5 * THETA0)**2))


@pytest.fixture(scope="module")
def link_run():
    """A particle (0.5 kg) at theta0 = 60 deg from the downward vertical,
    held by the distance joint "link" (0.8 m, the initial distance) to the
    ground point (0, 0); released from rest, one full period, output also
    at T/2."""
    p0 = LINK_L * np.array([math.sin(THETA0), -math.cos(THETA0)])
    m = mb.Model(gravity=(0.0, -G))
    bob = m.add_particle("bob", BOB_MASS, position=p0)
    m.add_distance("link", m.ground, (0.0, 0.0), bob, p0)
    t_out = np.union1d(np.linspace(0.0, SIMPLE_T, 201), [SIMPLE_T / 2])
    return _run(m, SIMPLE_T, t_out=t_out)


def test_link_tension_closed_form(link_run):
    """Tension of a simple pendulum at angle theta from the vertical: the
    radial equation m L thetadot^2 = T - m g cos(theta) and energy
    thetadot^2 = (2 g / L)(cos theta - cos theta0) give

        T = m g cos(theta) + m L thetadot^2 = m g (3 cos theta - 2 cos theta0).

    With theta = atan2(x, -y) from the simulated position, the multiplier
    (lam > 0 is tension) equals T, and the joint-frame reaction's first
    component is -T, to 1e-6 relative to m g; nothing across the link."""
    r = link_run
    x, y = r.body("bob").position.T
    theta = np.arctan2(x, -y)
    tension = BOB_MASS * G * (3.0 * np.cos(theta) - 2.0 * math.cos(THETA0))
    mg = BOB_MASS * G
    assert np.abs(r.multipliers("link")[:, 0] - tension).max() <= 1e-6 * mg
    R = r.reaction("link", frame="joint")
    assert np.abs(R[:, 0] + tension).max() <= 1e-6 * mg
    assert np.abs(R[:, 1]).max() <= 1e-6 * mg
    # in global axes: the tension pulls the bob toward the pivot
    pull = -tension[:, None] * np.column_stack([x, y]) / LINK_L
    assert np.abs(r.reaction("link")[:, :2] - pull).max() <= 1e-6 * mg


def test_link_pendulum_period(link_run):
    """At T/2 (elliptic-integral period, 1.93 s) the bob is at the opposite
    extreme theta = -theta0, at rest, and at T back at theta0: angles to
    1e-7 rad, speeds to 1e-6 m/s."""
    r = link_run
    x, y = r.body("bob").position.T
    theta = np.arctan2(x, -y)
    k = int(np.argmin(np.abs(r.t - SIMPLE_T / 2)))
    assert abs(theta[k] + THETA0) <= 1e-7
    assert np.abs(r.body("bob").velocity[k]).max() <= 1e-6
    assert abs(theta[-1] - THETA0) <= 1e-7
    assert np.abs(r.body("bob").velocity[-1]).max() <= 1e-6


def test_link_energy(link_run):
    """r.energy constant to 1e-8 of m g L."""
    assert np.ptp(link_run.energy) <= 1e-8 * BOB_MASS * G * LINK_L


# --------------------------------------------------------------------------
# Pin in slot: a bead in a straight, inclined, frictionless slot
# --------------------------------------------------------------------------

def test_bead_in_inclined_slot():
    """A bead (particle, 0.3 kg) in a slot fixed to the ground, through
    (0.1, 0.4) along u = (cos 30, sin 30), launched up it at 0.5 m/s.
    The slot holds the normal component of gravity: reaction("slot",
    frame="joint")[:, 1] = m g cos(alpha) (1e-9 N), nothing along the slot
    (1e-9 N); the bead accelerates at -g sin(alpha) along u (1e-9 m/s^2)
    and stays on the line (1e-10 m); r.energy is constant (1e-9 J)."""
    mass, at = 0.3, np.array([0.1, 0.4])
    m = mb.Model(gravity=(0.0, -G))
    bead = m.add_particle("bead", mass, position=at, velocity=0.5 * U)
    m.add_pin_in_slot("slot", m.ground, bead, at=at, axis=U)
    assert m.degrees_of_freedom() == 1
    r = _run(m, 1.0, n_out=101)
    R = r.reaction("slot", frame="joint")
    assert np.abs(R[:, 1] - mass * G * math.cos(ALPHA)).max() <= 1e-9
    assert np.abs(R[:, 0]).max() <= 1e-9
    b = r.body("bead")
    assert np.abs(b.acceleration @ U + G * math.sin(ALPHA)).max() <= 1e-9
    assert np.abs((b.position - at) @ N).max() <= 1e-10
    assert np.ptp(r.energy) <= 1e-9


def test_pin_in_slot_leaves_rotation_free():
    """A rod whose end pin runs in a horizontal ground slot along x: the pin
    rides the slot (y = 0 to 1e-9 m) while the rod swings freely.  The slot
    only pushes normal to itself, so horizontal momentum is conserved: the
    centre of mass keeps x = x0 (rod released from rest, to 1e-9 m), the
    joint-frame reaction has no component along the slot (1e-9 N), and
    r.energy is constant (1e-8 of m g L)."""
    L, mass = 0.6, 1.2
    phi0 = -0.4
    c0 = 0.5 * L * _unit(phi0)
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", mass, mass * L**2 / 12.0, position=c0, angle=phi0)
    m.add_pin_in_slot("slot", m.ground, rod, at=(0.0, 0.0), axis=(1.0, 0.0))
    assert m.degrees_of_freedom() == 2
    r = _run(m, 2.0)
    b = r.body("rod")
    assert np.abs(b.position[:, 0] - c0[0]).max() <= 1e-9
    assert np.abs(r.point("rod", (-0.5 * L, 0.0))[:, 1]).max() <= 1e-9
    assert np.abs(r.reaction("slot", frame="joint")[:, 0]).max() <= 1e-9
    assert np.ptp(b.angle) > 0.5  # it does swing
    assert np.ptp(r.energy) <= 1e-8 * mass * G * L


@pytest.mark.parametrize("kind", ["translational", "pin_in_slot"])
def test_bead_on_spinning_rod(kind):
    """A rod spinning at a constant omega = 2 rad/s about the ground pivot
    "hub" (driver "spin"), no gravity; a slider (translational joint "rail",
    the slider turns with the rod) or a bead (particle in a pin-in-slot
    "rail") runs frictionless along it, starting at r0 = 0.2 m at rest
    relative to the rod.  In the rotating frame r'' = omega^2 r, so

        r = r0 cosh(omega t),   theta = omega t,

    (1e-9 relative, 1e-9 rad); the rail pushes across the rod with the
    Coriolis force N = 2 m omega r' = 2 m omega^2 r0 sinh(omega t) (second
    joint-axis component, 1e-8 relative) and nothing along it; the motor
    supplies d/dt (m r^2 omega) = 2 m r r' omega (plus nothing for the rod
    and the slider's own spin, both constant), 1e-8 relative.  This checks
    the velocity-product terms of joints whose body_i moves."""
    w, r0, mass = 2.0, 0.2, 0.5
    m = mb.Model()
    rod = m.add_body("rod", 1.0, 0.1, angular_velocity=w)
    if kind == "translational":
        bead = m.add_body("bead", mass, 0.01, position=(r0, 0.0), velocity=(0.0, w * r0),
                          angular_velocity=w)
        m.add_translational("rail", rod, bead, at=(r0, 0.0), axis=(1.0, 0.0))
    else:
        bead = m.add_particle("bead", mass, position=(r0, 0.0), velocity=(0.0, w * r0))
        m.add_pin_in_slot("rail", rod, bead, at=(r0, 0.0), axis=(1.0, 0.0))
    m.add_revolute("hub", m.ground, rod, at=(0.0, 0.0))
    m.drive_joint("spin", "hub", mb.Linear(w))
    r = _run(m, 1.0, n_out=101)
    t = r.t
    p = r.body("bead").position
    radius = np.hypot(*p.T)
    assert np.abs(radius - r0 * np.cosh(w * t)).max() <= 1e-9 * r0 * math.cosh(w)
    assert np.abs(np.angle(np.exp(1j * (np.arctan2(p[:, 1], p[:, 0]) - w * t)))).max() <= 1e-9
    N = 2.0 * mass * w**2 * r0 * np.sinh(w * t)
    R = r.reaction("rail", frame="joint")
    assert np.abs(R[:, 1] - N).max() <= 1e-8 * N.max()
    assert np.abs(R[:, 0]).max() <= 1e-10
    tau = 2.0 * mass * radius * (w * r0 * np.sinh(w * t)) * w
    assert np.abs(r.effort("spin") - tau).max() <= 1e-8 * tau.max()


# --------------------------------------------------------------------------
# Gear pair
# --------------------------------------------------------------------------

GEAR_D = 0.3        # m, centre distance
J_A, J_B = 0.02, 0.05
TAU = 0.7           # N m on gear a


def pitch_radii(ratio, D=GEAR_D):
    """docs/modelling.md: r_j = D/(|ratio| + 1) external (ratio < 0),
    D/| |ratio| - 1 | internal (ratio > 0); r_i = |ratio| r_j."""
    rj = D / (abs(ratio) + 1.0) if ratio < 0 else D / abs(abs(ratio) - 1.0)
    return abs(ratio) * rj, rj


def contact_offsets(ratio):
    """Where the pitch circles touch, as multiples of e (unit vector from
    centre a to centre b), measured from each centre: external gears touch
    between the centres (a + r_a e = b - r_b e); for internal gears the
    contact lies beyond the small gear, on the far side from the ring's
    centre: a is the ring (r_a > r_b): a + r_a e = b + r_b e; b is the ring:
    a - r_a e = b - r_b e."""
    ra, rb = pitch_radii(ratio)
    if ratio < 0:
        return ra, -rb
    return (ra, rb) if ra > rb else (-ra, -rb)


def gear_pair(ratio, torque=None, drive=None):
    """Two disks in a horizontal plane (no gravity): "a" (1 kg, J = 0.02) on
    the ground pivot "pa" at the origin, "b" (1.5 kg, J = 0.05) on "pb" at
    (0.3, 0); gear "mesh" between a (body_i) and b (body_j) with the given
    ratio.  Either a torque "motor" on a, or a driver "motor" on pa."""
    m = mb.Model()
    a = m.add_body("a", 1.0, J_A, position=(0.0, 0.0))
    b = m.add_body("b", 1.5, J_B, position=(GEAR_D, 0.0))
    m.add_revolute("pa", m.ground, a, at=(0.0, 0.0))
    m.add_revolute("pb", m.ground, b, at=(GEAR_D, 0.0))
    m.add_gear("mesh", a, b, ratio)
    if torque is not None:
        m.add_torque("motor", a, torque)
    if drive is not None:
        m.drive_joint("motor", "pa", drive)
    return m


RATIOS = pytest.mark.parametrize(
    "ratio", [-2.0, -0.5, 3.0, 1.0 / 3.0],
    ids=["external-2", "external-0.5", "internal-ring-a", "internal-ring-b"])


@RATIOS
def test_gear_speed_ratio_when_driven(ratio):
    """Gear a driven at a constant 4 rad/s: omega_b / omega_a = ratio to
    1e-10 (negative: external gears turn opposite ways); the angles keep
    the ratio too (phi_b = ratio phi_a, from phi = 0, to 1e-10 rad); at
    constant speed the motor does nothing (effort 0 to 1e-10 N m)."""
    r = _run(gear_pair(ratio, drive=mb.Linear(4.0)), 1.0, n_out=101)
    wa, wb = r.body("a").angular_velocity, r.body("b").angular_velocity
    assert np.abs(wa - 4.0).max() <= 1e-10
    assert np.abs(wb / wa - ratio).max() <= 1e-10
    assert np.abs(r.body("b").angle - ratio * r.body("a").angle).max() <= 1e-10
    assert np.abs(r.effort("motor")).max() <= 1e-10


@RATIOS
def test_gear_effort_reflected_inertia(ratio):
    """Gear a driven with constant angular acceleration 3 rad/s^2
    (Polynomial([0, 0, 1.5])): virtual power tau omega_a = J_a alpha_a
    omega_a + J_b alpha_b omega_b with omega_b = ratio omega_a gives
    tau = (J_a + ratio^2 J_b) alpha_a, to 1e-10 N m."""
    r = _run(gear_pair(ratio, drive=mb.Polynomial([0.0, 0.0, 1.5])), 1.0, n_out=101)
    tau = (J_A + ratio**2 * J_B) * 3.0
    assert np.abs(r.effort("motor") - tau).max() <= 1e-10 * max(1.0, tau)


@RATIOS
def test_gear_tooth_force_under_torque(ratio):
    """A torque of 0.7 N m on gear a, both free to turn.  Reflected inertia:
    alpha_a = tau / (J_a + ratio^2 J_b), alpha_b = ratio alpha_a (1e-10).
    The tooth force F (on b; joint-frame tangential component F_t) acts at
    the contact point P (contact_offsets): on b its moment about b's centre,
    (P - c_b) x F = s_b e x F = s_b F_t, is J_b alpha_b and equals the
    reported torque; on a the equal and opposite force gives
    J_a alpha_a = tau - s_a F_t (1e-10 N m).  The centres do not move, so
    the ground pivots carry the tooth forces: reaction("pb") = -F and
    reaction("pa") = +F, i.e. the two pivot reactions are equal and
    opposite (1e-10 N).  Energy: kinetic = work of the torque,
    E - tau (phi_a - phi_a0) constant (1e-10 J)."""
    r = _run(gear_pair(ratio, torque=TAU), 1.0, n_out=101)
    alpha_a = TAU / (J_A + ratio**2 * J_B)
    a, b = r.body("a"), r.body("b")
    assert np.abs(a.angular_acceleration - alpha_a).max() <= 1e-10
    assert np.abs(b.angular_acceleration - ratio * alpha_a).max() <= 1e-10
    assert np.abs(b.angular_velocity - ratio * a.angular_velocity).max() <= 1e-10

    s_a, s_b = contact_offsets(ratio)
    R = r.reaction("mesh", frame="joint")
    F_t = R[:, 1]
    assert np.abs(R[:, 0]).max() <= 1e-10          # no radial force from ideal teeth
    assert np.abs(R[:, 2] - s_b * F_t).max() <= 1e-10
    assert np.abs(J_B * b.angular_acceleration - R[:, 2]).max() <= 1e-10
    assert np.abs(J_A * a.angular_acceleration - (TAU - s_a * F_t)).max() <= 1e-10
    assert np.abs(F_t).min() > 0.5

    F = r.reaction("mesh")[:, :2]
    assert np.abs(r.reaction("pb")[:, :2] + F).max() <= 1e-10
    assert np.abs(r.reaction("pa")[:, :2] - F).max() <= 1e-10

    work = TAU * (a.angle - a.angle[0])
    assert np.ptp(r.energy - work) <= 1e-10


@RATIOS
def test_gear_force_on_body_i_from_multiplier(ratio):
    """The force on body_i as -Phi_q^T lam, from the equation in the docs:
    Phi = r_i (phi_i - theta) + s r_j (phi_j - theta) - c, theta the angle
    of d = c_j - c_i; dtheta/dc_j = -dtheta/dc_i = g = (-d_y, d_x)/|d|^2 =
    (0, 1/D) here, so Phi_q for body i is ((r_i + s r_j) g, r_i) and for
    body j (-(r_i + s r_j) g, s r_j).  With lam = r.multipliers("mesh"):
    body j gets -lam(-(r_i + s r_j) g, s r_j), which is r.reaction("mesh")
    (1e-12), and body i gets -lam((r_i + s r_j) g, r_i): the opposite force
    (Newton's third law), and the torque that, with the motor's, turns a:
    J_a alpha_a = tau - lam r_i (1e-10 N m)."""
    r = _run(gear_pair(ratio, torque=TAU), 0.5, n_out=51)
    lam = r.multipliers("mesh")[:, 0]
    ri, rj = pitch_radii(ratio)
    s = 1.0 if ratio < 0 else -1.0
    g = np.array([0.0, 1.0 / GEAR_D])
    on_j = -lam[:, None] * np.concatenate([-(ri + s * rj) * g, [s * rj]])
    on_i = -lam[:, None] * np.concatenate([(ri + s * rj) * g, [ri]])
    assert np.abs(r.reaction("mesh") - on_j).max() <= 1e-12
    assert np.abs(on_i[:, :2] + on_j[:, :2]).max() <= 1e-12
    assert np.abs(J_A * r.body("a").angular_acceleration - (TAU + on_i[:, 2])).max() <= 1e-10


def test_ring_gear_on_the_ground():
    """An internal ring gear that is part of the ground (centre_i given,
    pitch radius 0.15 m) and a planet (0.05 m) on an arm driven at 2 rad/s
    about the ring's centre: centre distance 0.1 m, ratio = r_ring /
    r_planet = +3 (internal).  Willis with the ring fixed:
    (omega_p - omega_arm) / (0 - omega_arm) = 3, omega_p = -2 omega_arm
    = -4 rad/s (1e-10), over 1.5 s (the arm turns 3 rad)."""
    m = mb.Model()
    arm = m.add_body("arm", 0.5, 0.002, position=(0.05, 0.0))
    planet = m.add_body("planet", 0.3, 0.0005, position=(0.1, 0.0))
    m.add_revolute("arm_axle", m.ground, arm, at=(0.0, 0.0))
    m.add_revolute("planet_axle", arm, planet, at=(0.1, 0.0))
    m.add_gear("ring", m.ground, planet, 3.0, center_i=(0.0, 0.0))
    m.drive_joint("turn", "arm_axle", mb.Linear(2.0))
    r = _run(m, 1.5, n_out=101)
    assert np.abs(r.body("planet").angular_velocity + 4.0).max() <= 1e-10


def planetary_stage():
    """Planetary stage: the sun "sun" (pitch radius 0.1 m) on a ground
    pivot, an arm turning about the sun's centre, and a planet (pitch radius
    0.05 m) on the arm at (0.15, 0): external gear "mesh" sun -> planet,
    ratio -2.  The sun is held (driver "hold" = 0) and the arm driven at
    2 rad/s ("turn")."""
    m = mb.Model()
    sun = m.add_body("sun", 1.0, 0.01, position=(0.0, 0.0))
    arm = m.add_body("arm", 0.5, 0.002, position=(0.075, 0.0))
    planet = m.add_body("planet", 0.3, 0.0005, position=(0.15, 0.0))
    m.add_revolute("sun_axle", m.ground, sun, at=(0.0, 0.0))
    m.add_revolute("arm_axle", m.ground, arm, at=(0.0, 0.0))
    m.add_revolute("planet_axle", arm, planet, at=(0.15, 0.0))
    m.add_gear("mesh", sun, planet, -2.0)
    m.drive_joint("hold", "sun_axle", 0.0)
    m.drive_joint("turn", "arm_axle", mb.Linear(2.0))
    return m


def test_gear_on_moving_centres_keeps_rolling():
    """The planet's pitch circle rolls on the fixed sun: with the arm at
    omega_arm, omega_p - omega_arm = -(r_s / r_p)(omega_s - omega_arm)
    (Willis), so omega_p = omega_arm (r_s + r_p) / r_p = 6 rad/s, to 1e-10,
    over 1.5 s (the arm turns 3 rad)."""
    r = _run(planetary_stage(), 1.5, n_out=101)
    assert np.abs(r.body("planet").angular_velocity - 6.0).max() <= 1e-10
    assert abs(r.body("arm").angle[-1] - 3.0) <= 1e-10
    assert abs(r.body("planet").angle[-1] - 9.0) <= 1e-9


def test_planetary_arm_full_turns():
    """Regression: the same planetary stage over 4 s, the arm making 1.3
    turns.  The gear's centre-line angle used to be an atan2 from the initial
    direction, which jumped by 2 pi when the arm passed 180 deg (t = pi/2 s):
    Phi jumped and IDA failed there (h -> 1e-21).  Now the planet keeps
    6 rad/s throughout (1e-10) and has turned 24 rad at the end (1e-8)."""
    r = _run(planetary_stage(), 4.0, n_out=101)
    assert np.abs(r.body("planet").angular_velocity - 6.0).max() <= 1e-10
    assert abs(r.body("planet").angle[-1] - 24.0) <= 1e-8
    assert r.residual.max() <= 1e-9


# --------------------------------------------------------------------------
# Rack and pinion
# --------------------------------------------------------------------------

PINION_R, PINION_J, RACK_M = 0.05, 0.004, 2.0


@pytest.fixture(scope="module")
def rack_run():
    """A pinion (0.8 kg, J = 0.004, pitch radius 0.05 m) on the ground axle
    "axle" at (0, 0.05), above a rack (2 kg) on the horizontal translational
    joint "guide"; rack-pinion "mesh" (pinion = body_i, rack = body_j,
    axis x); a torque of 0.3 N m on the pinion; gravity; 1 s."""
    m = mb.Model(gravity=(0.0, -G))
    pinion = m.add_body("pinion", 0.8, PINION_J, position=(0.0, PINION_R))
    rack = m.add_body("rack", RACK_M, 0.1, position=(0.2, -0.02))
    m.add_revolute("axle", m.ground, pinion, at=(0.0, PINION_R))
    m.add_translational("guide", m.ground, rack, at=(0.2, -0.02), axis=(1.0, 0.0))
    m.add_rack_pinion("mesh", pinion, rack, PINION_R, axis=(1.0, 0.0))
    m.add_torque("motor", pinion, 0.3)
    assert m.degrees_of_freedom() == 1
    return _run(m, 1.0, n_out=101)


def test_rack_speed_from_pinion(rack_run):
    """docs: u . (c_p - c_r) + radius (phi_p - phi_r) = const.  Pinion
    centre fixed, rack not turning: -v_rack . u + radius omega_p = 0, i.e.
    v_rack = radius omega_p (the pinion's bottom moves with the rack),
    to 1e-10 m/s."""
    w = rack_run.body("pinion").angular_velocity
    v = rack_run.body("rack").velocity
    assert np.abs(v[:, 0] - PINION_R * w).max() <= 1e-10
    assert np.abs(v[:, 1]).max() <= 1e-10
    assert np.abs(w).max() > 1.0


def test_rack_tooth_force(rack_run):
    """Reflected inertia: the rack accelerates at tau R / (J_p + m_r R^2)
    (1e-10 m/s^2).  The tooth force on the rack (first joint-frame
    component) is what accelerates it, m_r a (1e-10 N), and it acts at the
    pitch point (0, 0): its moment about the rack's centre (0.2 + x,
    -0.02) is the reported torque, 0.02 F (1e-10).  Equal and opposite on
    the pinion, at (0, -R) from its centre: J_p alpha = tau - R F
    (1e-10 N m), and the pinion's axle takes F along x (1e-10 N)."""
    r = rack_run
    a_rack = 0.3 * PINION_R / (PINION_J + RACK_M * PINION_R**2)
    rack, pinion = r.body("rack"), r.body("pinion")
    assert np.abs(rack.acceleration[:, 0] - a_rack).max() <= 1e-10
    R = r.reaction("mesh", frame="joint")
    F = R[:, 0]
    assert np.abs(F - RACK_M * rack.acceleration[:, 0]).max() <= 1e-10
    assert np.abs(R[:, 1]).max() <= 1e-10
    arm = np.array([0.0, 0.0]) - rack.position
    assert np.abs(R[:, 2] - cross2(arm, r.reaction("mesh")[:, :2])).max() <= 1e-10
    assert np.abs(PINION_J * pinion.angular_acceleration - (0.3 - PINION_R * F)).max() <= 1e-10
    assert np.abs(r.reaction("axle")[:, 0] - F).max() <= 1e-10


def test_rack_energy_is_work_of_torque(rack_run):
    """Kinetic + gravity energy grows by the work of the torque:
    E - tau (phi_p - phi_p0) constant to 1e-10 J."""
    r = rack_run
    work = 0.3 * (r.body("pinion").angle - r.body("pinion").angle[0])
    assert np.ptp(r.energy - work) <= 1e-10


def test_pinion_rolls_down_inclined_rack():
    """The ground as the rack: a disk (1 kg, radius 0.1 m, J = m R^2/2)
    with its centre in a ground slot parallel to a 20 deg rack, rolling
    without slip.  Rolling: v . u = -R omega (1e-10).  Energy (or moments
    about the contact point): s'' = -g sin(alpha) / (1 + J/(m R^2))
    = -(2/3) g sin(alpha) (1e-9 m/s^2); the tooth force holding the disk
    back, on the disk +m g sin(alpha) J/(J + m R^2) u, appears on the rack
    (body_j, the ground) as its opposite: first joint-frame component
    -1.118 N (1e-9 N).  r.energy constant (1e-9 J)."""
    alpha, radius, mass = math.radians(20.0), 0.1, 1.0
    J = 0.5 * mass * radius**2
    u = _unit(alpha)
    n = np.array([-u[1], u[0]])
    centre = np.array([0.5, 0.3]) + radius * n
    m = mb.Model(gravity=(0.0, -G))
    disk = m.add_body("disk", mass, J, position=centre)
    m.add_pin_in_slot("track", m.ground, disk, at=centre, axis=u)
    m.add_rack_pinion("teeth", disk, m.ground, radius, axis=u)
    r = _run(m, 1.0, n_out=101)
    d = r.body("disk")
    assert np.abs(d.velocity @ u + radius * d.angular_velocity).max() <= 1e-10
    assert np.abs(d.acceleration @ u + G * math.sin(alpha) / (1.0 + J / (mass * radius**2))).max() <= 1e-9
    hold = mass * G * math.sin(alpha) * J / (J + mass * radius**2)
    assert np.abs(r.reaction("teeth", frame="joint")[:, 0] + hold).max() <= 1e-9
    assert np.ptp(r.energy) <= 1e-9
