"""Force elements: springs, dampers, actuators, point forces and torques.

Conventions (docs/modelling.md, "Forces"):

    spring-damper   along e = d / l, d = p_j - p_i: the force on body_j is
                    F e, F = -k (l - l0) - c ldot + f_act(t) (positive F
                    pushes the points apart); body_i gets -F e
    rotational      torque on body_j: -k (theta - theta0) - c thetadot
                    + tau(t), theta = phi_j - phi_i; body_i gets the opposite
    add_force       (fx, fy) at `point` (global, initial configuration; the
                    point is fixed in the body); local=True: components in
                    the body's axes
    add_torque      a pure torque

Oscillators are checked against their closed-form solutions (rtol 1e-10,
atol 1e-12 runs), single instants with mb.solve_accelerations against
Newton-Euler written out by hand (to 1e-12).
"""

import math

import numpy as np
import pytest

import lagmb as mb
from references import cross2

G = 9.81
RTOL, ATOL = 1e-10, 1e-12


def _rot(phi, s):
    c, sn = math.cos(phi), math.sin(phi)
    return np.array([c * s[0] - sn * s[1], sn * s[0] + c * s[1]])


def damped_free_response(t, x0, omega0, zeta):
    """x'' + 2 zeta omega0 x' + omega0^2 x = 0, x(0) = x0, x'(0) = 0.

    Characteristic roots s = -zeta omega0 +- omega0 sqrt(zeta^2 - 1).
      under-damped (zeta < 1), omega_d = omega0 sqrt(1 - zeta^2):
          x = e^(-zeta omega0 t) (x0 cos omega_d t + (zeta omega0 x0 / omega_d) sin omega_d t)
      critically damped (zeta = 1):  x = x0 (1 + omega0 t) e^(-omega0 t)
      over-damped (zeta > 1), real roots s1 > s2:
          x = A e^(s1 t) + B e^(s2 t),  A + B = x0,  s1 A + s2 B = 0
          => A = -s2 x0 / (s1 - s2),  B = s1 x0 / (s1 - s2).
    Each satisfies x(0) = x0 and x'(0) = 0 (checked in
    test_free_response_formula).
    """
    t = np.asarray(t, float)
    if zeta < 1.0:
        wd = omega0 * math.sqrt(1.0 - zeta**2)
        return np.exp(-zeta * omega0 * t) * (x0 * np.cos(wd * t)
                                             + zeta * omega0 * x0 / wd * np.sin(wd * t))
    if zeta == 1.0:
        return x0 * (1.0 + omega0 * t) * np.exp(-omega0 * t)
    q = omega0 * math.sqrt(zeta**2 - 1.0)
    s1, s2 = -zeta * omega0 + q, -zeta * omega0 - q
    return (-s2 * x0 * np.exp(s1 * t) + s1 * x0 * np.exp(s2 * t)) / (s1 - s2)


@pytest.mark.parametrize("zeta", [0.0, 0.1, 1.0, 2.5])
def test_free_response_formula(zeta):
    """The closed forms used below solve their ODE: residual of
    x'' + 2 zeta w x' + w^2 x by central differences (h = 1e-4) below 1e-5
    of w^2 x0, and x(0) = x0 (1e-15), x'(0) = 0 (central difference, to
    1e-5 of w x0)."""
    w, x0, h = 10.0, 0.05, 1e-4
    t = np.linspace(0.1, 2.0, 50)
    x = damped_free_response(t, x0, w, zeta)
    xp = (damped_free_response(t + h, x0, w, zeta) - damped_free_response(t - h, x0, w, zeta)) / (2 * h)
    xpp = (damped_free_response(t + h, x0, w, zeta) - 2 * x
           + damped_free_response(t - h, x0, w, zeta)) / h**2
    assert np.abs(xpp + 2 * zeta * w * xp + w**2 * x).max() <= 1e-5 * w**2 * x0
    assert abs(damped_free_response(0.0, x0, w, zeta) - x0) <= 1e-15
    dx0 = (damped_free_response(h, x0, w, zeta) - damped_free_response(-h, x0, w, zeta)) / (2 * h)
    assert abs(dx0) <= 1e-5 * w * x0


# --------------------------------------------------------------------------
# Spring-damper oscillator
# --------------------------------------------------------------------------

MASS, K, L0, ANCHOR_Y = 2.0, 200.0, 0.5, 1.0
OMEGA0 = math.sqrt(K / MASS)   # 10 rad/s
Y_EQ = ANCHOR_Y - L0 - MASS * G / K   # hangs l0 + m g / k below the anchor
X0 = 0.05


def hanging_oscillator(zeta, x0=X0):
    """A block (2 kg) on a vertical translational joint "rail" under a
    spring-damper "spring" (k = 200 N/m, free length 0.5 m, c = 2 zeta
    sqrt(k m)) from the ground point (0, 1).  Equilibrium: the spring is
    stretched by m g / k, so the block hangs at y_eq = 1 - 0.5 - m g / k;
    released from rest at y_eq + x0.  The spring runs from the anchor
    (body_i) down to the block (body_j): e = (0, -1), l = 1 - y,
    ldot = -ydot, and the force on the block is F e with
    F = -k (l - l0) - c ldot, so

        m y'' = k (l - l0) + c ldot - m g = -k (y - y_eq) - c ydot,

    i.e. m x'' + c x' + k x = 0 for x = y - y_eq."""
    c = 2.0 * zeta * math.sqrt(K * MASS)
    m = mb.Model(gravity=(0.0, -G))
    start = (0.0, Y_EQ + x0)
    block = m.add_body("block", MASS, 0.01, position=start)
    m.add_translational("rail", m.ground, block, at=start, axis=(0.0, 1.0))
    m.add_spring_damper("spring", m.ground, (0.0, ANCHOR_Y), block, start, stiffness=K,
                        damping=c, free_length=L0)
    return m


@pytest.mark.parametrize("zeta", [0.0, 0.1, 1.0, 2.5],
                         ids=["undamped", "under-damped", "critical", "over-damped"])
def test_spring_damper_oscillator(zeta):
    """Displacement from equilibrium against damped_free_response at 201
    times over 2 s (3 periods of the undamped oscillator), to 1e-7 of the
    initial displacement x0 = 5 cm."""
    r = mb.simulate(hanging_oscillator(zeta), t_end=2.0, rtol=RTOL, atol=ATOL, n_out=201)
    x = r.body("block").position[:, 1] - Y_EQ
    expected = damped_free_response(r.t, X0, OMEGA0, zeta)
    assert np.abs(x - expected).max() <= 1e-7 * X0


def test_spring_rail_reaction_and_energy():
    """Undamped: the block does not rotate or move sideways, so the rail
    carries nothing (1e-9 N; the spring pulls along the rail), and
    r.energy = 1/2 m v^2 + m g y + 1/2 k (l - l0)^2 + const is conserved
    to 2e-7 of the oscillation's energy 1/2 k x0^2 = 0.25 J (r.energy itself
    is 9.1 J: the spring is stretched 15 cm at rest), and matches that sum
    up to a constant to 1e-9 J."""
    r = mb.simulate(hanging_oscillator(0.0), t_end=2.0, rtol=RTOL, atol=ATOL, n_out=201)
    assert np.abs(r.reaction("rail")).max() <= 1e-9
    b = r.body("block")
    mine = (0.5 * MASS * (b.velocity**2).sum(axis=1) + MASS * G * b.position[:, 1]
            + 0.5 * K * ((ANCHOR_Y - b.position[:, 1]) - L0)**2)
    assert np.ptp(r.energy) <= 2e-7 * 0.5 * K * X0**2
    assert np.ptp(r.energy - mine) <= 1e-9


def test_spring_damper_force_on_both_bodies():
    """Two free bodies (no gravity), a spring-damper between off-centre
    points: p_i = r_i + A_i s_i, p_j = r_j + A_j s_j, d = p_j - p_i, l = |d|,
    e = d / l, ldot = e . (pdot_j - pdot_i) with pdot = v + omega A (s turned
    +90 deg).  F = -k (l - l0) - c ldot + f_act; body_j gets F e at p_j and
    body_i -F e at p_i, so

        m_j a_j = F e,        J_j alpha_j = (A_j s_j) x (F e)
        m_i a_i = -F e,       J_i alpha_i = (A_i s_i) x (-F e).

    solve_accelerations at a moved, spinning state reproduces this to
    1e-12 (relative to the largest term)."""
    k, c, l0, f_act = 30.0, 1.5, 0.8, 0.7
    m = mb.Model()
    bi = m.add_body("i", 1.0, 0.05, position=(0.0, 0.0), angle=0.2)
    bj = m.add_body("j", 2.0, 0.08, position=(1.0, 0.5), angle=-0.4)
    Pi, Pj = np.array([0.1, 0.05]), np.array([0.9, 0.6])
    m.add_spring_damper("sd", bi, Pi, bj, Pj, stiffness=k, damping=c, free_length=l0,
                        force=mb.Constant(f_act))
    # local points, from the initial poses
    si = _rot(-0.2, Pi - np.array([0.0, 0.0]))
    sj = _rot(0.4, Pj - np.array([1.0, 0.5]))

    q = np.array([0.1, -0.2, 0.7, 1.3, 0.4, -1.1])
    v = np.array([0.3, 0.1, -2.0, -0.4, 0.2, 1.5])
    qdd, lam = mb.solve_accelerations(m, q, v)
    assert np.asarray(lam).size == 0

    ai, aj = _rot(q[2], si), _rot(q[5], sj)
    d = (q[3:5] + aj) - (q[0:2] + ai)
    length = float(np.hypot(*d))
    e = d / length
    pdot_i = v[0:2] + v[2] * np.array([-ai[1], ai[0]])
    pdot_j = v[3:5] + v[5] * np.array([-aj[1], aj[0]])
    ldot = float(e @ (pdot_j - pdot_i))
    F = -k * (length - l0) - c * ldot + f_act
    expected = np.concatenate([-F * e / 1.0, [cross2(ai, -F * e) / 0.05],
                               F * e / 2.0, [cross2(aj, F * e) / 0.08]])
    assert np.abs(np.asarray(qdd) - expected).max() <= 1e-12 * np.abs(expected).max()


# --------------------------------------------------------------------------
# Rotational spring-damper
# --------------------------------------------------------------------------

def test_torsion_oscillator():
    """A disk (J = 0.02 kg m^2) on the ground revolute "axle" at its centre
    (gravity gives no moment), torsion spring-damper "coil" to the ground,
    k = 3 N m/rad, c = 0.03 N m s/rad, free angle 0.3 rad; released at
    0.3 + 0.4 rad.  J theta'' + c theta' + k theta = 0 for theta = phi - 0.3:
    omega0 = sqrt(k/J) = 12.2 rad/s, zeta = c / (2 sqrt(k J)) = 0.061.
    Angle against damped_free_response at 201 times over 2 s, to 1e-7 of
    the initial 0.4 rad; the coil's torque is the only moment, so
    J phi'' = -k theta - c theta' (1e-9 N m)."""
    J, k, c, theta0 = 0.02, 3.0, 0.03, 0.4
    m = mb.Model(gravity=(0.0, -G))
    disk = m.add_body("disk", 1.0, J, position=(0.2, 0.1), angle=0.3 + theta0)
    m.add_revolute("axle", m.ground, disk, at=(0.2, 0.1))
    m.add_rotational_spring_damper("coil", m.ground, disk, stiffness=k, damping=c, free_angle=0.3)
    r = mb.simulate(m, t_end=2.0, rtol=RTOL, atol=ATOL, n_out=201)
    d = r.body("disk")
    theta = d.angle - 0.3
    expected = damped_free_response(r.t, theta0, math.sqrt(k / J), c / (2.0 * math.sqrt(k * J)))
    assert np.abs(theta - expected).max() <= 1e-7 * theta0
    assert np.abs(J * d.angular_acceleration - (-k * theta - c * d.angular_velocity)).max() <= 1e-9


def test_rotational_spring_damper_acts_on_both_bodies():
    """Two free bodies joined by a torsion spring-damper with an actuator
    torque: tau = -k (theta - theta0) - c thetadot + tau_act with
    theta = phi_j - phi_i; J_j alpha_j = tau, J_i alpha_i = -tau, no force
    (solve_accelerations, to 1e-12)."""
    k, c, theta0, act = 4.0, 0.5, 0.2, 0.1
    m = mb.Model()
    a = m.add_body("a", 1.0, 0.1)
    b = m.add_body("b", 2.0, 0.3, position=(1.0, 0.0), angle=0.5)
    m.add_rotational_spring_damper("twist", a, b, stiffness=k, damping=c, free_angle=theta0,
                                   torque=mb.Constant(act))
    q = np.array([0.0, 0.0, 0.1, 1.0, 0.0, 0.7])
    v = np.array([0.0, 0.0, 0.3, 0.0, 0.0, -0.2])
    qdd, _ = mb.solve_accelerations(m, q, v)
    tau = -k * ((0.7 - 0.1) - theta0) - c * (-0.2 - 0.3) + act
    expected = [0.0, 0.0, -tau / 0.1, 0.0, 0.0, tau / 0.3]
    assert np.abs(np.asarray(qdd) - expected).max() <= 1e-12 * abs(tau / 0.1)


def test_rotational_free_angle_defaults_to_initial():
    """Without free_angle the spring is relaxed in the initial configuration:
    a disk at rest at 0.9 rad on a torsion spring to the ground stays there
    (angle 0.9 to 1e-12 rad, no angular acceleration)."""
    m = mb.Model()
    disk = m.add_body("disk", 1.0, 0.02, angle=0.9)
    m.add_revolute("axle", m.ground, disk, at=(0.0, 0.0))
    m.add_rotational_spring_damper("coil", m.ground, disk, stiffness=5.0, damping=0.1)
    r = mb.simulate(m, t_end=1.0, rtol=RTOL, atol=ATOL, n_out=11)
    assert np.abs(r.body("disk").angle - 0.9).max() <= 1e-12
    assert np.abs(r.body("disk").angular_acceleration).max() <= 1e-12


# --------------------------------------------------------------------------
# Applied forces and torques
# --------------------------------------------------------------------------

PLATE_M, PLATE_J = 3.0, 0.2
PLATE_C, PLATE_PHI = np.array([1.0, 2.0]), 0.3
PUSH = np.array([2.0, -1.0])
PUSH_AT = np.array([1.4, 2.1])
# the point of application in the plate's own axes
PUSH_LOCAL = _rot(-PLATE_PHI, PUSH_AT - PLATE_C)


def _plate(local):
    m = mb.Model()
    plate = m.add_body("plate", PLATE_M, PLATE_J, position=PLATE_C, angle=PLATE_PHI)
    m.add_force("push", plate, tuple(PUSH), point=tuple(PUSH_AT), local=local)
    return m


@pytest.mark.parametrize("phi", [PLATE_PHI, PLATE_PHI + math.pi / 2, -2.0])
def test_point_force_gives_moment(phi):
    """A global force F = (2, -1) N at a point fixed in a free plate (given
    at (1.4, 2.1) in the initial pose): a = F/m and alpha = (A(phi) s) x F / J
    with s the point in the plate's axes -- the lever arm turns with the
    plate, the force keeps its direction.  At the initial pose the moment is
    (0.4, 0.1) x (2, -1) = -0.6 N m.  Velocities do not matter (no gyroscopic
    terms in the plane).  solve_accelerations, to 1e-12."""
    qdd, _ = mb.solve_accelerations(_plate(local=False), [5.0, -2.0, phi], [1.0, 2.0, 3.0])
    arm = _rot(phi, PUSH_LOCAL)
    expected = np.concatenate([PUSH / PLATE_M, [cross2(arm, PUSH) / PLATE_J]])
    assert np.abs(np.asarray(qdd) - expected).max() <= 1e-12
    if phi == PLATE_PHI:
        assert abs(cross2(PUSH_AT - PLATE_C, PUSH) - (-0.6)) <= 1e-12


@pytest.mark.parametrize("phi", [PLATE_PHI, PLATE_PHI + math.pi / 2, -2.0])
def test_body_fixed_force_turns_with_body(phi):
    """local=True: the components (2, -1) are in the plate's axes, so the
    force in global axes is A(phi) F and a = A(phi) F / m; the moment is
    rotation-invariant, s x F in body axes.  Turning the plate by 90 deg
    turns the acceleration by 90 deg.  solve_accelerations, to 1e-12."""
    qdd, _ = mb.solve_accelerations(_plate(local=True), [0.0, 0.0, phi], [0.0, 0.0, 0.0])
    expected = np.concatenate([_rot(phi, PUSH) / PLATE_M, [cross2(PUSH_LOCAL, PUSH) / PLATE_J]])
    assert np.abs(np.asarray(qdd) - expected).max() <= 1e-12


def test_body_fixed_thrust_path():
    """A body spinning at omega = 2 rad/s (from angle 0) with a body-fixed
    thrust F = (1.5, 0) N at its centre (no moment: omega stays constant).
    In global axes the thrust is F (cos omega t, sin omega t), so from rest

        v = F/(m omega) (sin omega t, 1 - cos omega t)
        r = F/(m omega^2) (1 - cos omega t, omega t - sin omega t)

    over 3 s, to 1e-8 m/s and 1e-8 of the distance covered (4.7 m).  A
    global (local=False) thrust instead gives the straight line
    x = F t^2 / (2 m) (1e-8 relative)."""
    mass, w, F = 0.5, 2.0, 1.5
    m = mb.Model()
    body = m.add_body("rocket", mass, 0.01, angular_velocity=w)
    m.add_force("thrust", body, (F, 0.0), local=True)
    r = mb.simulate(m, t_end=3.0, rtol=RTOL, atol=ATOL, n_out=151)
    t = r.t
    b = r.body("rocket")
    v = F / (mass * w) * np.column_stack([np.sin(w * t), 1.0 - np.cos(w * t)])
    p = F / (mass * w**2) * np.column_stack([1.0 - np.cos(w * t), w * t - np.sin(w * t)])
    assert np.abs(b.angular_velocity - w).max() <= 1e-10
    assert np.abs(b.velocity - v).max() <= 1e-8
    assert np.abs(b.position - p).max() <= 1e-8 * np.abs(p).max()

    m = mb.Model()
    body = m.add_body("rocket", mass, 0.01, angular_velocity=w)
    m.add_force("thrust", body, (F, 0.0), local=False)
    r = mb.simulate(m, t_end=3.0, rtol=RTOL, atol=ATOL, n_out=151)
    straight = np.column_stack([0.5 * F / mass * r.t**2, 0.0 * r.t])
    assert np.abs(r.body("rocket").position - straight).max() <= 1e-8 * straight.max()


def test_force_time_functions():
    """add_force with time-function components: ((Linear(0.6), Harmonic(1, 2))
    on a 2 kg particle from rest: x = 0.1 t^3 / 2, y'' = sin(2 t)/2 so
    y = (t - sin(2 t)/2)/4, to 1e-8 m over 2 s; a callable t -> (fx, fy)
    giving the same numbers gives the same path (1e-12 m)."""
    paths = []
    for force in [(mb.Linear(0.6), mb.Harmonic(1.0, 2.0)),
                  lambda t: (0.6 * t, math.sin(2.0 * t))]:
        m = mb.Model()
        p = m.add_particle("p", 2.0, position=(0.0, 0.0))
        m.add_force("f", p, force)
        r = mb.simulate(m, t_end=2.0, rtol=RTOL, atol=ATOL, n_out=101)
        paths.append(r.body("p").position)
        t = r.t
        assert np.abs(paths[-1][:, 0] - 0.05 * t**3).max() <= 1e-8
        assert np.abs(paths[-1][:, 1] - 0.25 * (t - 0.5 * np.sin(2.0 * t))).max() <= 1e-8
    assert np.abs(paths[0] - paths[1]).max() <= 1e-12


# --------------------------------------------------------------------------
# Actuator in a spring-damper
# --------------------------------------------------------------------------

@pytest.mark.parametrize("kind", ["harmonic", "callable"])
def test_spring_actuator_forced_oscillation(kind):
    """A cart (1.5 kg) on a horizontal rail, spring k = 60 N/m to the ground
    (relaxed at the start) with an actuator F(t) = 2 sin(3 t) (positive
    pushes the cart away from the anchor, i.e. along +x): m x'' + k x =
    F0 sin(w t) from rest gives

        x = F0 / (m (w0^2 - w^2)) (sin w t - (w / w0) sin w0 t),  w0^2 = k/m

    (particular solution plus the free motion that cancels x'(0)).  Over
    3 s, to 1e-7 of max |x| (6 cm); mb.Harmonic and a Python callable give
    the same."""
    m_, k, F0, w = 1.5, 60.0, 2.0, 3.0
    w0 = math.sqrt(k / m_)
    force = mb.Harmonic(F0, w) if kind == "harmonic" else (lambda t: F0 * math.sin(w * t))
    m = mb.Model()
    cart = m.add_body("cart", m_, 0.01, position=(0.5, 0.0))
    m.add_translational("rail", m.ground, cart, at=(0.5, 0.0), axis=(1.0, 0.0))
    m.add_spring_damper("act", m.ground, (0.0, 0.0), cart, (0.5, 0.0), stiffness=k, force=force)
    r = mb.simulate(m, t_end=3.0, rtol=RTOL, atol=ATOL, n_out=301)
    t = r.t
    expected = F0 / (m_ * (w0**2 - w**2)) * (np.sin(w * t) - (w / w0) * np.sin(w0 * t))
    x = r.body("cart").position[:, 0] - 0.5
    assert np.abs(x - expected).max() <= 1e-7 * np.abs(expected).max()


# --------------------------------------------------------------------------
# Pure torque
# --------------------------------------------------------------------------

@pytest.mark.parametrize("torque, alpha, angle_end", [
    (0.3, lambda t: 6.0 + 0 * t, 1.0 + 3.0),                       # 0.3 / 0.05
    (mb.Polynomial([0.0, 0.6]), lambda t: 12.0 * t, 1.0 + 2.0),     # 0.6 t / 0.05
    (lambda t: 0.6 * t, lambda t: 12.0 * t, 1.0 + 2.0),
], ids=["constant", "polynomial", "callable"])
def test_torque_on_free_body(torque, alpha, angle_end):
    """add_torque on a free body (2 kg, J = 0.05) spinning at 1 rad/s under
    gravity: alpha = tau / J at every output (1e-10 rad/s^2), the angle after
    1 s is 1 + int int alpha (constant 0.3 N m: 1 + 6/2 = 4 rad; tau = 0.6 t:
    1 + 12/6 = 3 rad), to 1e-9 rad, and the centre just falls (y = -g t^2/2,
    1e-9 m): a pure torque has no resultant force."""
    m = mb.Model(gravity=(0.0, -G))
    body = m.add_body("spinner", 2.0, 0.05, angular_velocity=1.0)
    m.add_torque("tq", body, torque)
    r = mb.simulate(m, t_end=1.0, rtol=RTOL, atol=ATOL, n_out=11)
    b = r.body("spinner")
    assert np.abs(b.angular_acceleration - alpha(r.t)).max() <= 1e-10
    assert abs(b.angle[-1] - angle_end) <= 1e-9
    assert np.abs(b.position[:, 1] + 0.5 * G * r.t**2).max() <= 1e-9
    assert np.abs(b.position[:, 0]).max() <= 1e-12


def test_torque_solve_accelerations():
    """One instant: alpha = tau / J exactly, no linear acceleration without
    gravity (1e-12)."""
    m = mb.Model()
    body = m.add_body("wheel", 4.0, 0.25, position=(1.0, -1.0), angle=2.0)
    m.add_torque("tq", body, -1.5)
    qdd, _ = mb.solve_accelerations(m, [1.0, -1.0, 2.0], [0.3, 0.0, 5.0])
    assert np.abs(np.asarray(qdd) - [0.0, 0.0, -6.0]).max() <= 1e-12


# --------------------------------------------------------------------------
# Internal forces: action and reaction
# --------------------------------------------------------------------------

def test_internal_springs_conserve_momentum_and_energy():
    """Two free bodies in space (no gravity) joined only by a linear
    spring-damper between off-centre points and a torsion spring: the forces
    on body_i are the opposites of those on body_j, acting along one line,
    so the total linear momentum sum m v and the angular momentum about the
    origin sum (m r x v + J omega) stay at their initial values (1e-9 of
    their scale); without damping, r.energy (kinetic + both spring
    potentials k (l - l0)^2/2 and k_t (theta - theta0)^2/2) is constant to
    1e-8 J, and equals the sum computed here plus a constant (1e-9 J)."""
    masses, inertias = (1.0, 2.0), (0.1, 0.3)
    for damping in (0.0, 0.4):
        m = mb.Model()
        a = m.add_body("a", masses[0], inertias[0], velocity=(0.2, -0.1))
        b = m.add_body("b", masses[1], inertias[1], position=(1.0, 0.0), angle=0.5,
                       angular_velocity=1.0)
        m.add_rotational_spring_damper("twist", a, b, stiffness=4.0, damping=damping, free_angle=0.2)
        m.add_spring_damper("spring", a, (0.1, 0.0), b, (1.0, 0.2), stiffness=20.0,
                            damping=damping, free_length=0.7)
        r = mb.simulate(m, t_end=2.0, rtol=RTOL, atol=ATOL, n_out=201)
        P = np.zeros((r.t.size, 2))
        H = np.zeros(r.t.size)
        for name, mass, J in zip(("a", "b"), masses, inertias):
            body = r.body(name)
            P += mass * body.velocity
            H += mass * cross2(body.position, body.velocity) + J * body.angular_velocity
        assert np.abs(P - P[0]).max() <= 1e-9 * max(1.0, np.abs(P[0]).max())
        assert np.abs(H - H[0]).max() <= 1e-9 * max(1.0, abs(H[0]))
        assert np.ptp(r.body("b").angle - r.body("a").angle) > 0.1  # the springs work
        if damping == 0.0:
            assert np.ptp(r.energy) <= 1e-8
            pa, pb = r.point("a", (0.1, 0.0)), r.point("b", _rot(-0.5, (0.0, 0.2)))
            length = np.hypot(*(pb - pa).T)
            theta = r.body("b").angle - r.body("a").angle
            mine = sum(0.5 * mass * (r.body(n).velocity**2).sum(axis=1)
                       + 0.5 * J * r.body(n).angular_velocity**2
                       for n, mass, J in zip(("a", "b"), masses, inertias))
            mine = mine + 0.5 * 20.0 * (length - 0.7)**2 + 0.5 * 4.0 * (theta - 0.2)**2
            assert np.ptp(r.energy - mine) <= 1e-9
        else:
            assert r.energy[-1] < r.energy[0] - 0.01
