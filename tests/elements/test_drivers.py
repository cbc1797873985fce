"""Drivers: prescribed motion, and the effort it takes.

A driver adds one equation g(q) - f(t) = 0 (docs/modelling.md, "Drivers");
f's first and second derivatives enter Phi_t and gamma exactly, so the
driven coordinate follows f, f' and f'' to the accuracy of the constraint
solve, not of the integrator.  r.effort(name) is the generalized force that
imposes the motion, positive along the driven coordinate: -lam of the
driver's row.

1. The slider-crank driven at constant crank speed: a mechanism with zero
   degrees of freedom, so its motion is pure kinematics (closed form) and
   the motor torque follows from the closed-form motion by virtual power.
2. Each time function driving one coordinate of a free body.
3. A Python callable that raises: the run stops with mb.SimulationError,
   naming the driver, and keeps the outputs computed so far.
"""

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

import lagmb as mb

G = 9.81
GRAVITY = np.array([0.0, -G])
RTOL, ATOL = 1e-10, 1e-12


# --------------------------------------------------------------------------
# 1. Slider-crank at constant crank speed
# --------------------------------------------------------------------------

R_CRANK = 0.1    # m, crank O-B
L_ROD = 0.3      # m, connecting rod B-C
OMEGA = 10.0     # rad/s, constant crank speed
THETA0 = math.pi / 3   # crank angle at t = 0
# uniform bars for crank and rod, a small block for the slider
M_CRANK, J_CRANK = 1.0, 1.0 * R_CRANK**2 / 12.0
M_ROD, J_ROD = 2.0, 2.0 * L_ROD**2 / 12.0
M_SLIDER, J_SLIDER = 0.5, 1e-4


def slider_crank_kinematics(theta, omega):
    """Closed-form motion of the in-line slider-crank at constant crank speed.

    Crank pin B = r (cos th, sin th); the slider C = (x, 0) stays on the x axis
    at distance l from B:  (x - r cos th)^2 + r^2 sin^2 th = l^2, so (the
    branch with the slider to the right of the crank pivot)

        x = r cos th + S,                     S = sqrt(l^2 - r^2 sin^2 th).

    With thdot = omega, thddot = 0:  xdot = omega dx/dth, xddot = omega^2
    d2x/dth2, where

        dx/dth   = -r sin th - r^2 sin th cos th / S
        d2x/dth2 = -r cos th - r^2 (cos^2 th - sin^2 th) / S
                   - r^4 sin^2 th cos^2 th / S^3

    (dS/dth = -r^2 sin th cos th / S).  The rod angle psi (from B to C)
    satisfies l sin psi = -r sin th; differentiating once and twice:

        psidot  = -r omega cos th / (l cos psi)
        psiddot = (r omega^2 sin th + l sin psi psidot^2) / (l cos psi).

    Centres of mass: crank (r/2)(cos th, sin th); rod B + (l/2) e(psi),
    e = (cos psi, sin psi), so  v = vB + (l/2) psidot e_perp and
    a = aB + (l/2)(psiddot e_perp - psidot^2 e); slider (x, 0).
    Returns a dict of arrays (k,) and (k, 2).
    """
    r, l = R_CRANK, L_ROD
    s, c = np.sin(theta), np.cos(theta)
    S = np.sqrt(l**2 - r**2 * s**2)
    x = r * c + S
    dx = -r * s - r**2 * s * c / S
    d2x = -r * c - r**2 * (c**2 - s**2) / S - r**4 * s**2 * c**2 / S**3

    sp = -r * s / l
    cp = np.sqrt(1.0 - sp**2)
    psid = -r * omega * c / (l * cp)
    psidd = (r * omega**2 * s + l * sp * psid**2) / (l * cp)

    e = np.column_stack([cp, sp])
    e_perp = np.column_stack([-sp, cp])
    vB = r * omega * np.column_stack([-s, c])
    aB = -r * omega**2 * np.column_stack([c, s])
    zeros = np.zeros_like(theta)
    return {
        "x": x, "xd": omega * dx, "xdd": omega**2 * d2x,
        "psi": np.arcsin(sp), "psid": psid, "psidd": psidd,
        "crank_v": 0.5 * vB, "crank_a": 0.5 * aB,
        "rod_v": vB + 0.5 * l * psid[:, None] * e_perp,
        "rod_a": aB + 0.5 * l * (psidd[:, None] * e_perp - (psid**2)[:, None] * e),
        "slider_v": np.column_stack([omega * dx, zeros]),
        "slider_a": np.column_stack([omega**2 * d2x, zeros]),
    }


def slider_crank(omega=OMEGA, theta0=THETA0):
    """Crank O-B pinned to the ground at O = (0, 0) ("O"), rod B-C ("B"),
    slider at C ("C"), slider on a translational joint "guide" to the ground
    along x; "motor" drives the revolute O: the crank's angle = theta0 +
    omega t (mb.Linear(omega, start=theta0)).  Gravity (0, -g)."""
    B = R_CRANK * np.array([math.cos(theta0), math.sin(theta0)])
    C = np.array([R_CRANK * math.cos(theta0)
                  + math.sqrt(L_ROD**2 - (R_CRANK * math.sin(theta0))**2), 0.0])
    psi = math.atan2(C[1] - B[1], C[0] - B[0])
    m = mb.Model(gravity=(0.0, -G))
    crank = m.add_body("crank", M_CRANK, J_CRANK, position=0.5 * B, angle=theta0,
                       angular_velocity=omega)
    rod = m.add_body("rod", M_ROD, J_ROD, position=0.5 * (B + C), angle=psi)
    slider = m.add_body("slider", M_SLIDER, J_SLIDER, position=C)
    m.add_revolute("O", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, rod, at=B)
    m.add_revolute("C", rod, slider, at=C)
    m.add_translational("guide", m.ground, slider, at=C, axis=(1.0, 0.0))
    m.drive_joint("motor", "O", mb.Linear(omega, start=theta0))
    return m


@pytest.fixture(scope="module")
def crank_run():
    """1 s (1.6 turns) at rtol 1e-10, atol 1e-12, 401 outputs."""
    return mb.simulate(slider_crank(), t_end=1.0, rtol=RTOL, atol=ATOL, n_out=401)


def test_slider_crank_is_fully_driven():
    """3 bodies (9 coordinates), 3 revolutes + 1 translational (8 equations)
    and the motor (1): 9 - 9 = 0 degrees of freedom."""
    assert slider_crank().degrees_of_freedom() == 0


def test_slider_crank_crank_follows_driver(crank_run):
    """The crank's angle, speed and angular acceleration are theta0 + omega t,
    omega and 0 (to 1e-10 rad, rad/s, rad/s^2)."""
    crank = crank_run.body("crank")
    assert np.abs(crank.angle - (THETA0 + OMEGA * crank_run.t)).max() <= 1e-10
    assert np.abs(crank.angular_velocity - OMEGA).max() <= 1e-10
    assert np.abs(crank.angular_acceleration).max() <= 1e-10


def test_slider_kinematics_closed_form(crank_run):
    """Slider position, velocity and acceleration equal the closed form
    x = r cos th + sqrt(l^2 - r^2 sin^2 th) and its exact time derivatives
    (slider_crank_kinematics) to 1e-8 (m, m/s, m/s^2; the acceleration
    reaches 13 m/s^2); the slider stays on the guide (y = 0, to 1e-10 m)."""
    ref = slider_crank_kinematics(THETA0 + OMEGA * crank_run.t, OMEGA)
    slider = crank_run.body("slider")
    assert np.abs(slider.position[:, 0] - ref["x"]).max() <= 1e-8
    assert np.abs(slider.velocity[:, 0] - ref["xd"]).max() <= 1e-8
    assert np.abs(slider.acceleration[:, 0] - ref["xdd"]).max() <= 1e-8
    assert np.abs(slider.position[:, 1]).max() <= 1e-10
    assert np.abs(ref["xdd"]).max() > 10.0  # the check is not vacuous


def test_rod_kinematics_closed_form(crank_run):
    """The connecting rod's angle psi = -asin(r sin th / l), its rate and
    angular acceleration (slider_crank_kinematics) to 1e-8 (rad, rad/s,
    rad/s^2)."""
    ref = slider_crank_kinematics(THETA0 + OMEGA * crank_run.t, OMEGA)
    rod = crank_run.body("rod")
    assert np.abs(rod.angle - ref["psi"]).max() <= 1e-8
    assert np.abs(rod.angular_velocity - ref["psid"]).max() <= 1e-8
    assert np.abs(rod.angular_acceleration - ref["psidd"]).max() <= 1e-8


def test_motor_torque_by_virtual_power(crank_run):
    """Inverse dynamics, independent of the multipliers: the motor is the
    only force that does work besides gravity (frictionless joints do none),
    so its power equals the rate of change of kinetic plus potential energy,
    written body by body with the closed-form motion:

        tau omega = sum_b [(m_b a_b - m_b g) . v_b + J_b phiddot_b phidot_b]

    (crank: phidot = omega, phiddot = 0; rod: psidot, psiddot; slider: no
    rotation).  r.effort("motor") equals tau to 1e-6 of max |tau|
    (about 2.4 N m)."""
    ref = slider_crank_kinematics(THETA0 + OMEGA * crank_run.t, OMEGA)
    power = np.zeros_like(crank_run.t)
    for m, v, a in ((M_CRANK, ref["crank_v"], ref["crank_a"]),
                    (M_ROD, ref["rod_v"], ref["rod_a"]),
                    (M_SLIDER, ref["slider_v"], ref["slider_a"])):
        power += np.einsum("kd,kd->k", m * a - m * GRAVITY, v)
    power += J_CRANK * 0.0 * OMEGA + J_ROD * ref["psidd"] * ref["psid"]
    tau = power / OMEGA

    effort = crank_run.effort("motor")
    assert effort.shape == crank_run.t.shape
    scale = np.abs(tau).max()
    assert scale > 1.0
    assert np.abs(effort - tau).max() <= 1e-6 * scale


def test_motor_effort_is_minus_multiplier(crank_run):
    """docs/modelling.md: effort = -lam of the driver's row (exactly)."""
    lam = crank_run.multipliers("motor")
    assert lam.shape == (crank_run.t.size, 1)
    assert np.array_equal(crank_run.effort("motor"), -lam[:, 0])


# --------------------------------------------------------------------------
# 2. Every time function drives a coordinate exactly
# --------------------------------------------------------------------------

SPLINE_T = [0.0, 0.4, 0.9, 1.3, 2.0]
SPLINE_Y = [0.0, 0.3, -0.2, 0.4, 0.1]


def _spline_reference():
    cs = CubicSpline(SPLINE_T, SPLINE_Y, bc_type="natural")
    return lambda t: (float(cs(t)), float(cs(t, 1)), float(cs(t, 2)))


def _smooth_step_reference(t0, t1, y0, y1):
    """y0 + (y1 - y0) p(s), s = (t - t0)/(t1 - t0), p = 10 s^3 - 15 s^4 + 6 s^5;
    p' = 30 s^2 (1 - s)^2, p'' = 60 s (1 - s)(1 - 2 s); constant outside."""
    T, dy = t1 - t0, y1 - y0

    def f(t):
        if t <= t0:
            return (y0, 0.0, 0.0)
        if t >= t1:
            return (y1, 0.0, 0.0)
        s = (t - t0) / T
        return (y0 + dy * (10 * s**3 - 15 * s**4 + 6 * s**5),
                dy * 30 * s**2 * (1 - s)**2 / T,
                dy * 60 * s * (1 - s) * (1 - 2 * s) / T**2)
    return f


def _callable(t):
    """A driver written in Python: y = 0.2 cos(2 t) + 0.1 t, with its
    derivatives."""
    return (0.2 * math.cos(2 * t) + 0.1 * t, -0.4 * math.sin(2 * t) + 0.1,
            -0.8 * math.cos(2 * t))


# (driver, independent reference t -> (y, y', y''))
TIME_FUNCTIONS = {
    "polynomial": (mb.Polynomial([0.1, -0.3, 0.5, 0.2]),
                   lambda t: (0.1 - 0.3 * t + 0.5 * t**2 + 0.2 * t**3,
                              -0.3 + 1.0 * t + 0.6 * t**2, 1.0 + 1.2 * t)),
    "harmonic": (mb.Harmonic(0.2, 3.0, 0.4, 0.1),
                 lambda t: (0.1 + 0.2 * math.sin(3 * t + 0.4), 0.6 * math.cos(3 * t + 0.4),
                            -1.8 * math.sin(3 * t + 0.4))),
    "smooth_step": (mb.SmoothStep(0.5, 1.5, 0.1, 0.7), _smooth_step_reference(0.5, 1.5, 0.1, 0.7)),
    "spline": (mb.Spline(SPLINE_T, SPLINE_Y), _spline_reference()),
    "linear": (mb.Linear(-0.4, start=0.2), lambda t: (0.2 - 0.4 * t, -0.4, 0.0)),
    "callable": (_callable, _callable),
}


def _driven_body(coordinate, f, ref):
    """A free body (2 kg, 0.1 kg m^2) under gravity with one coordinate
    driven by f; its initial value and rate are set to f(0), f'(0) so that
    the start is consistent.  The other two coordinates move freely."""
    y0, dy0, _ = ref(0.0)
    pos, vel, angle, rate = [0.0, 0.3], [0.5, 0.0], 0.2, -1.0
    if coordinate == "angle":
        angle, rate = y0, dy0
    else:
        k = "xy".index(coordinate)
        pos[k], vel[k] = y0, dy0
    m = mb.Model(gravity=(0.0, -G))
    body = m.add_body("block", 2.0, 0.1, position=pos, angle=angle, velocity=vel,
                      angular_velocity=rate)
    m.drive_body("drv", body, coordinate, f)
    return m


@pytest.mark.parametrize("coordinate", ["x", "y", "angle"])
@pytest.mark.parametrize("kind", list(TIME_FUNCTIONS))
def test_time_function_drives_body_coordinate(kind, coordinate):
    """drive_body(coordinate, f): the driven coordinate, its rate and its
    acceleration equal f, f', f'' (independent references: the polynomial,
    harmonic and smooth step differentiated by hand, the natural spline by
    SciPy's CubicSpline) at 201 outputs over 2 s, to 1e-8; the driver's
    effort is what Newton asks for the driven coordinate alone, m f'' - m g_k
    (N) or J f'' (N m), to 1e-8 relative (the coordinates of a free body
    are uncoupled).  rtol 1e-10, atol 1e-12."""
    f, ref = TIME_FUNCTIONS[kind]
    r = mb.simulate(_driven_body(coordinate, f, ref), t_end=2.0, rtol=RTOL, atol=ATOL,
                    n_out=201)
    Y = np.array([ref(t) for t in r.t])
    body = r.body("block")
    if coordinate == "angle":
        got = (body.angle, body.angular_velocity, body.angular_acceleration)
        effort = 0.1 * Y[:, 2]
    else:
        k = "xy".index(coordinate)
        got = (body.position[:, k], body.velocity[:, k], body.acceleration[:, k])
        effort = 2.0 * Y[:, 2] - 2.0 * GRAVITY[k]
    for value, expected in zip(got, Y.T):
        assert np.abs(value - expected).max() <= 1e-8
    assert np.abs(r.effort("drv") - effort).max() <= 1e-8 * max(1.0, np.abs(effort).max())


@pytest.mark.parametrize("kind", ["smooth_step", "spline"])
def test_time_function_values_match_reference(kind):
    """The C++ time function itself, sampled on a grid that straddles the
    knots / step ends (and extrapolates the spline linearly past its last
    knot): value, first and second derivative match the reference to 1e-12."""
    f, ref = TIME_FUNCTIONS[kind]
    for t in np.linspace(0.0, 2.0, 57):
        assert np.allclose(f(t), ref(t), rtol=0.0, atol=1e-12)
    if kind == "spline":
        y, dy, _ = ref(2.0)
        assert np.allclose(f(2.5), (y + 0.5 * dy, dy, 0.0), rtol=0.0, atol=1e-12)


@pytest.mark.parametrize("kind, rtol", [("smooth_step", 1e-10), ("spline", 1e-11)])
def test_breakpoints_at_tight_tolerance(kind, rtol):
    """Regression: a body at rest at (f(0), 0) with x driven by the smooth
    step (third derivative jumps at t0 = 0.5 and t1 = 1.5 s) or the spline
    (third derivative jumps at every knot), 2 s at a tight but legal rtol,
    atol = rtol / 100.  Before the integrator stopped at the time functions'
    breakpoints, IDA failed its error test repeatedly (h -> 1e-6) at
    t = 1.484 s (smooth step, rtol 1e-10) or near a knot (spline, rtol
    1e-11).  The run completes and x follows f to 1e-8 m."""
    f, ref = TIME_FUNCTIONS[kind]
    m = mb.Model(gravity=(0.0, -G))
    body = m.add_body("block", 2.0, 0.1, position=(ref(0.0)[0], 0.0), velocity=(ref(0.0)[1], 0.0))
    m.drive_body("drv", body, "x", f)
    r = mb.simulate(m, t_end=2.0, rtol=rtol, atol=rtol / 100)
    x = r.body("block").position[:, 0]
    assert np.abs(x - [ref(t)[0] for t in r.t]).max() <= 1e-8


def test_drive_joint_translational_slide():
    """drive_joint on a translational joint prescribes the slide
    u . (p_j - p_i), 0 in the initial configuration: a block on a 30 deg
    incline driven by 0.2 sin(3 t) along the incline is at
    start + 0.2 sin(3 t) u (1e-9 m), and the effort is the force along u
    that moves it, m s'' + m g sin(30 deg) (1e-8 N)."""
    alpha = math.radians(30.0)
    u = np.array([math.cos(alpha), math.sin(alpha)])
    start = np.array([0.4, 0.1])
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", 1.5, 0.02, position=start, angle=alpha, velocity=0.6 * u)
    m.add_translational("incline", m.ground, block, at=start, axis=u)
    m.drive_joint("push", "incline", mb.Harmonic(0.2, 3.0))
    r = mb.simulate(m, t_end=2.0, rtol=RTOL, atol=ATOL, n_out=101)
    s = 0.2 * np.sin(3.0 * r.t)
    assert np.abs(r.body("block").position - (start + s[:, None] * u)).max() <= 1e-9
    effort = 1.5 * (-9.0 * s) + 1.5 * G * math.sin(alpha)
    assert np.abs(r.effort("push") - effort).max() <= 1e-8


def test_drive_joint_revolute_between_two_bodies():
    """drive_joint on a revolute between two bodies prescribes the relative
    angle phi_j - phi_i: a double pendulum of uniform rods whose elbow is
    driven by 0.5 sin(3 t) (the upper rod swings freely) keeps
    phi_lower - phi_upper = 0.5 sin(3 t) (1e-12 rad; initial relative angle
    0, relative rate 1.5 rad/s made consistent at t = 0).  The effort is the
    torque on the lower rod: with the elbow force F (reaction "p1", on the
    lower rod, at its local end (-1/2, 0)), J phi'' = effort + (A s) x F
    (1e-9 N m)."""
    m = mb.Model(gravity=(0.0, -G))
    upper = m.add_body("upper", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    lower = m.add_body("lower", 1.0, 1.0 / 12.0, position=(1.5, 0.0), angular_velocity=1.5)
    m.add_revolute("p0", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("p1", upper, lower, at=(1.0, 0.0))
    m.drive_joint("elbow_motor", "p1", mb.Harmonic(0.5, 3.0))
    r = mb.simulate(m, t_end=2.0, rtol=RTOL, atol=ATOL, n_out=101)
    lo, up = r.body("lower"), r.body("upper")
    assert np.abs(lo.angle - up.angle - 0.5 * np.sin(3.0 * r.t)).max() <= 1e-12
    F = r.reaction("p1")[:, :2]
    arm = -0.5 * np.column_stack([np.cos(lo.angle), np.sin(lo.angle)])
    moment = arm[:, 0] * F[:, 1] - arm[:, 1] * F[:, 0]
    assert np.abs(lo.angular_acceleration / 12.0 - (r.effort("elbow_motor") + moment)).max() <= 1e-9


# --------------------------------------------------------------------------
# 3. A callable that fails
# --------------------------------------------------------------------------

def test_raising_callable_stops_run_with_partial_result():
    """A driver table that ends: the callable raises ValueError("table ends
    at 0.7 s") for t > 0.7.  The run stops with mb.SimulationError (no crash)
    whose message names the driver ("feeder") and repeats the original
    message; e.t is the time reached (<= 0.7 s, the integrator stops at the
    start of the step that asked for t > 0.7), and e.result keeps the
    outputs up to there, on which x = 0.3 t holds (to 1e-12 m)."""
    def table(t):
        if t > 0.7:
            raise ValueError("table ends at 0.7 s")
        return (0.3 * t, 0.3, 0.0)

    m = mb.Model(gravity=(0.0, -G))
    body = m.add_body("block", 2.0, 0.1, position=(0.0, 0.0), velocity=(0.3, 0.0))
    m.drive_body("feeder", body, "x", table)
    with pytest.raises(mb.SimulationError) as info:
        mb.simulate(m, t_end=2.0, rtol=1e-8, atol=1e-10, n_out=201)
    err = info.value
    assert "feeder" in str(err)
    assert "table ends at 0.7 s" in str(err)
    assert 0.0 < err.t <= 0.7
    partial = err.result
    assert isinstance(partial, mb.Result)
    assert 2 <= len(partial.t) < 201
    assert partial.t[-1] <= err.t + 1e-12
    x = partial.body("block").position[:, 0]
    assert np.abs(x - 0.3 * partial.t).max() <= 1e-12
