"""Contact between collision shapes in space (Model.add_contact with two
Shapes): the collision table's pairs under the one contact law.

References (closed forms, and SciPy for the law alone):
- Hertz impact (no damping, F = k d^1.5): peak penetration
  (5 m v^2 / (4 k))^(2/5); contact time 2 (d_max / v) int_0^1 (1 - x^2.5)^-1/2 dx
  = 2 (5/4)^(2/5) (2/5) B(2/5, 1/2) (m/k)^(2/5) v^(-1/5) = 3.2181 ...;
- with restitution e: the rebound ratio is e (the law's damping is exact
  for it, tests/elements/test_contact_restitution.py), the same law as the planar
  contact's;
- a block pushed along a floor stops after v0^2 / (2 mu g);
- a solid sphere (J = 2/5 m R^2) on an incline rolls on R - d0 (d0 its
  static penetration) with a = g sin(alpha) / (1 + J / (m (R - d0)^2)),
  creeping at a constant slip speed below v_s;
- a sphere thrown flat without spin slips until t* = v0 / (mu g (1 + m (R -
  d0)^2 / J)) (2 v0 / (7 mu g) on a rigid floor), then rolls at v* = v0 /
  (1 + J / (m (R - d0)^2)) (5 v0 / 7);
- Hertz statics: a body of weight W on n equal points sinks (W / (n k))^(2/3);
- derivatives: central differences of Q.
"""

import math
import os

import numpy as np
import pytest
from scipy.special import beta

import lagmb as mb

G = 9.81


def rotation_y(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def ball_over_floor(v=1.0, gap=1e-3, R=0.1, k=1e7, e=1.0, mu=0.0, gravity=0.0, vx=0.0, mass=1.0, plane_first=False):
    m = mb.Model(gravity=(0.0, 0.0, -gravity), dimension=3)
    centre = (0.0, 0.0, R + gap)
    m.add_body("ball", mass=mass, inertia=(0.4 * mass * R * R,) * 3, position=centre, velocity=(vx, 0.0, -v))
    floor = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), role="collision")
    ball = m.add_shape("ball", "sphere", (R,), centre, role="collision")
    shapes = (floor, ball) if plane_first else (ball, floor)
    m.add_contact("hit", *shapes, stiffness=k, restitution=e, friction=mu)
    return m


def hertz_time(m, k, v):
    return 2.0 * 1.25**0.4 * 0.4 * beta(0.4, 0.5) * (m / k) ** 0.4 * v**-0.2


def test_hertz_impact_peak_and_duration():
    """A sphere hits a plane at 1 m/s without damping or gravity: its peak
    penetration and its contact time are Hertz's to 1e-6, and it leaves at
    the speed it came (1e-6: nothing gained)."""
    mass, k, v = 1.0, 1e7, 1.0
    r = mb.simulate(ball_over_floor(v, k=k), 0.01, rtol=1e-10, atol=1e-12, n_out=4001)
    onset, release = r.events
    assert (onset["label"], release["label"]) == ("onset", "release")
    assert abs(onset["t"] - 1e-3 / v) <= 1e-12
    assert abs((release["t"] - onset["t"]) / hertz_time(mass, k, v) - 1.0) <= 1e-6
    peak = (5.0 * mass * v * v / (4.0 * k)) ** 0.4
    assert abs(r.contact("hit").penetration.max() / peak - 1.0) <= 1e-6
    assert abs(r.body("ball").velocity[-1, 2] - v) <= 1e-6 * v


def test_shapes_given_either_way_round():
    """The plane given first: the same motion; the reading is for the shape
    given first (the plane): the force on it points down, its normal too."""
    a = mb.simulate(ball_over_floor(mu=0.3, vx=0.5), 0.01, rtol=1e-9, atol=1e-11, n_out=101)
    b = mb.simulate(ball_over_floor(mu=0.3, vx=0.5, plane_first=True), 0.01, rtol=1e-9, atol=1e-11, n_out=101)
    assert np.array_equal(a.q, b.q)
    ca, cb = a.contact("hit"), b.contact("hit")
    assert np.array_equal(ca.normal_force, cb.normal_force)
    assert np.array_equal(ca.normal, -cb.normal) and np.array_equal(ca.friction_force, -cb.friction_force)
    pressing = ca.normal_force > 0
    assert pressing.any() and np.all(ca.normal[pressing] == (0.0, 0.0, 1.0))


def test_rebound_ratio_is_the_restitution():
    """With e = 0.8 the sphere leaves at e times its speed (the law's
    damping is exact for it, the same law as the planar contact's) to 1e-6
    (more speeds and e in tests/elements/test_contact_restitution.py)."""
    e, k, v = 0.8, 1e7, 1.0
    r = mb.simulate(ball_over_floor(v, k=k, e=e), 0.01, rtol=1e-10, atol=1e-12)
    assert abs(r.body("ball").velocity[-1, 2] / v - e) <= 1e-6


def test_bouncing_ball_impact_times():
    """Dropped from a 0.5 m gap: first onset at sqrt(2 h / g) (1e-9 s); the
    second at the onset plus the contact plus the flight 2 v_out / g of its
    rebound speed (1e-6 s)."""
    h = 0.5
    r = mb.simulate(ball_over_floor(v=0.0, gap=h, k=1e8, e=0.9, gravity=G), 1.2, rtol=1e-10, atol=1e-12)
    onsets = [x for x in r.events if x["label"] == "onset"]
    releases = [x for x in r.events if x["label"] == "release"]
    assert abs(onsets[0]["t"] - math.sqrt(2 * h / G)) <= 1e-9
    assert abs(onsets[1]["t"] - (releases[0]["t"] + 2 * releases[0]["speed_before"] / G)) <= 1e-6


def sliding_block(v0=1.0, mu=0.3, a=0.2, k=1e8, mass=1.0, t_push=0.0):
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    d0 = (mass * G / (4 * k)) ** (2.0 / 3.0)  # on its four lower corners
    centre = (0.0, 0.0, a / 2 - d0)
    m.add_body("block", mass=mass, inertia=(mass * a * a / 6,) * 3, position=centre, velocity=(v0, 0.0, 0.0))
    floor = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), role="collision")
    block = m.add_shape("block", "box", (a, a, a), centre, role="collision")
    m.add_contact("floor", block, floor, stiffness=k, restitution=0.5, friction=mu)
    return m, d0


def test_block_slides_to_rest_after_v0_squared_over_2_mu_g():
    """A cube pushed along a floor at 1 m/s (mu 0.3) on its four lower
    corners stops after v0^2 / (2 mu g) to 0.1 % (measured 1e-5), level
    and at its Hertz height, and sticks there (one "stick" event, at v0 /
    (mu g) to 1e-4 s); the floor carries its weight and holds no friction."""
    v0, mu = 1.0, 0.3
    m, d0 = sliding_block(v0, mu)
    r = mb.simulate(m, 0.5, rtol=1e-8, atol=1e-10, n_out=51)
    x = r.body("block").position
    assert abs(x[-1, 0] / (v0**2 / (2 * mu * G)) - 1.0) <= 1e-3
    assert abs(x[-1, 1]) <= 1e-12 and abs(x[-1, 2] - (0.1 - d0)) <= 1e-9
    (stick,) = r.events
    assert (stick["kind"], stick["label"]) == ("friction", "stick") and abs(stick["t"] - v0 / (mu * G)) <= 1e-4
    c = r.contact("floor")
    assert abs(c.normal_force[-1] - G) <= 1e-6 * G and np.linalg.norm(c.friction_force[-1]) <= 1e-6
    stuck = r.t > stick["t"]
    assert np.all(c.state[stuck] == "stick") and np.all(c.state[1:][~stuck[1:]] == "slip")


def block_on_slope(alpha, mu=0.5, static_friction=None, a=0.2, mass=1.0, k=1e8):
    """A cube resting on a slope of angle alpha (on its four lower corners
    at their Hertz depth), downhill along -x."""
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    axes = rotation_y(-alpha)
    d0 = (mass * G * math.cos(alpha) / (4 * k)) ** (2.0 / 3.0)
    centre = (a / 2 - d0) * axes[:, 2]
    m.add_body("block", mass=mass, inertia=(mass * a * a / 6,) * 3, position=tuple(centre), orientation=axes)
    slope = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), axes, role="collision")
    block = m.add_shape("block", "box", (a, a, a), tuple(centre), axes, role="collision")
    m.add_contact("slope", block, slope, stiffness=k, restitution=0.5, friction=mu, static_friction=static_friction)
    return m, axes, centre


def test_block_on_an_incline_below_its_friction_angle_sticks():
    """A cube on a 20 degree slope (mu 0.5, tan 20 deg = 0.36) sticks from
    the start: after settling (0.5 s) it moves less than 1e-9 m in 9.5 s
    (measured 0), the friction its rows hold is m g sin(alpha) up the slope
    (1e-6 relative), and every output reads "stick"."""
    alpha = math.radians(20.0)
    m, axes, centre = block_on_slope(alpha)
    r = mb.simulate(m, 10.0, rtol=1e-8, atol=1e-10, n_out=101)
    settled = r.body("block").position[r.t >= 0.5]
    assert np.max(np.linalg.norm(settled - settled[0], axis=1)) < 1e-9
    assert [(x["t"], x["label"]) for x in r.events] == [(0.0, "stick")]
    c = r.contact("slope")
    assert np.all(c.state == "stick")
    assert np.allclose(c.friction_force[-1], G * math.sin(alpha) * axes[:, 0], rtol=0, atol=1e-6 * G)
    assert abs(c.normal_force[-1] - G * math.cos(alpha)) <= 1e-6 * G


def test_block_on_an_incline_above_its_friction_angle_slides():
    """On a 30 degree slope (mu 0.5 < tan 30 deg) the cube lets go at once
    and slides with g (sin(alpha) - mu cos(alpha)) to 1e-6 (fitted over its
    second half second; the regularized friction at 0.3 m/s and v_s = 1e-4
    m/s is mu F_n to 1e-7)."""
    alpha, mu = math.radians(30.0), 0.5
    m, axes, centre = block_on_slope(alpha, mu)
    r = mb.simulate(m, 1.0, rtol=1e-9, atol=1e-11, n_out=201)
    s = (r.body("block").position - centre) @ axes[:, 0]
    late = r.t > 0.5
    a = -2.0 * np.polyfit(r.t[late], s[late], 2)[0]
    assert abs(a / (G * (math.sin(alpha) - mu * math.cos(alpha))) - 1.0) <= 1e-6
    assert [x["label"] for x in r.events[:2]] == ["stick", "slip"] and r.events[1]["t"] < 1e-3
    assert r.contact("slope").state[-1] == "slip"


def test_a_force_ramp_breaks_a_stuck_block_loose_at_mu_s_times_its_weight():
    """A cube stuck on a floor (mu_s 0.5, mu 0.3) pushed at its base by F =
    c t: it lets go at t = mu_s m g / c (to 1e-8 s; measured 7e-12 s) and
    then slides with (c t - mu m g) / m, its speed within v_s of that (the
    regularized friction starts from 0 and reaches mu F_n past v_s: the
    block gains 6e-5 m/s meanwhile)."""
    mu, mu_s, c, a, k = 0.3, 0.5, 1.0, 0.2, 1e8
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    d0 = (G / (4 * k)) ** (2.0 / 3.0)
    block = m.add_body("block", mass=1.0, inertia=(a * a / 6,) * 3, position=(0.0, 0.0, a / 2 - d0))
    floor = m.add_shape("ground", "plane", (), role="collision")
    box = m.add_shape(block, "box", (a, a, a), (0.0, 0.0, a / 2 - d0), role="collision")
    m.add_contact("floor", box, floor, stiffness=k, restitution=0.5, friction=mu, static_friction=mu_s)
    m.add_force("push", block, (mb.Linear(c), 0.0, 0.0), point=(0.0, 0.0, 0.0))
    r = mb.simulate(m, 6.0, rtol=1e-10, atol=1e-12, n_out=61)
    stick, slip = r.events
    assert (stick["t"], stick["label"], slip["label"]) == (0.0, "stick", "slip")
    t_slip = mu_s * G / c
    assert abs(slip["t"] - t_slip) <= 1e-8
    # after it: x'' = c t - mu g from rest at t_slip
    T = 6.0 - t_slip
    v = r.body("block").velocity[-1, 0]
    assert abs(v - (c * (6.0**2 - t_slip**2) / 2 - mu * G * T)) <= 1e-4  # v_s


def test_a_sphere_never_sticks_it_rolls():
    """A round shape's contact points are not material points: its contact
    has no stick rows and no friction events (rolling is the regularized
    law's, exact up to its creep)."""
    m, axes, centre, d0 = incline_ball(math.radians(20.0))
    r = mb.simulate(m, 0.2, rtol=1e-8, atol=1e-10, n_out=3)
    assert r.events == [] and set(r.contact("slope").state) == {"slip"}
    assert m.compiled().n_constraints == 1  # the sphere's Euler parameters only


def incline_ball(alpha, mu=0.5, R=0.1, mass=1.0, k=1e7, v0=0.0):
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    axes = rotation_y(-alpha)  # the plane's normal tilted towards -x: downhill is -x
    d0 = (mass * G * math.cos(alpha) / k) ** (2.0 / 3.0)
    centre = (R - d0) * axes[:, 2]
    m.add_body("ball", mass=mass, inertia=(0.4 * mass * R * R,) * 3, position=tuple(centre),
               velocity=tuple(v0 * axes[:, 0]))
    slope = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), axes, role="collision")
    ball = m.add_shape("ball", "sphere", (R,), tuple(centre), role="collision")
    m.add_contact("slope", ball, slope, stiffness=k, restitution=0.5, friction=mu)
    return m, axes, centre, d0


def test_sphere_rolls_down_an_incline():
    """A solid sphere on a 20 degree slope rolls with g sin(alpha) / (1 + 2
    R^2 / (5 (R - d0)^2)) to 1e-7 (fitted over its second half second)."""
    alpha, R = math.radians(20.0), 0.1
    m, axes, centre, d0 = incline_ball(alpha, R=R)
    r = mb.simulate(m, 1.0, rtol=1e-10, atol=1e-12, n_out=1001)
    s = (r.body("ball").position - centre) @ axes[:, 0]
    late = r.t > 0.5
    fit = np.polyfit(r.t[late], s[late], 2)
    a = -2.0 * fit[0]
    assert abs(a / (G * math.sin(alpha) / (1 + 2 * R * R / (5 * (R - d0) ** 2))) - 1.0) <= 1e-7
    assert r.contact("slope").slip_speed[-1] < 1e-4  # creeping below v_s


def test_sphere_thrown_without_spin_rolls_from_t_star_at_five_sevenths():
    """Thrown flat at 2 m/s without spin: it slips until t* = v0 / (mu g (1
    + 5 (R - d0)^2 / (2 R^2))) and then rolls at v0 / (1 + 2 R^2 / (5 (R -
    d0)^2)) (5 v0 / 7 on a rigid floor), each to 1e-4."""
    v0, mu, R, k = 2.0, 0.2, 0.1, 1e8
    m, axes, centre, d0 = incline_ball(0.0, mu=mu, R=R, k=k, v0=v0)
    r = mb.simulate(m, 1.0, rtol=1e-10, atol=1e-12, n_out=2001)
    t_star = v0 / (mu * G * (1 + 5 * (R - d0) ** 2 / (2 * R * R)))
    v_star = v0 / (1 + 2 * R * R / (5 * (R - d0) ** 2))
    slip = r.contact("slope").slip_speed
    early = (r.t > 0.05) & (r.t < 0.9 * t_star)  # slipping fast: the friction is mu F_n to (v_s / v)^2
    fit = np.polyfit(r.t[early], slip[early], 1)
    assert abs(-fit[1] / fit[0] / t_star - 1.0) <= 1e-4
    assert abs(r.body("ball").velocity[-1, 0] / v_star - 1.0) <= 1e-4
    assert abs(v_star / (5 * v0 / 7) - 1.0) < 1e-3


def test_box_dropped_flat_comes_to_rest_level():
    """A box dropped flat from 1 cm onto a plane (e = 0.5, mu = 0.5): at rest
    after 1 s, level (tilt below 1e-9 rad), without drift (1e-12 m), at its
    Hertz height (1e-9 m)."""
    a, mass, k = (0.3, 0.2, 0.1), 2.0, 1e8
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    centre = (0.0, 0.0, a[2] / 2 + 0.01)
    m.add_body("box", mass=mass, inertia=(0.01, 0.02, 0.025), position=centre)
    floor = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), role="collision")
    box = m.add_shape("box", "box", a, centre, role="collision")
    m.add_contact("floor", box, floor, stiffness=k, restitution=0.5, friction=0.5)
    r = mb.simulate(m, 1.0, rtol=1e-9, atol=1e-11, n_out=11)
    body = r.body("box")
    tilt = np.arccos(np.clip(body.rotation[-1][2, 2], -1.0, 1.0))
    assert tilt <= 1e-9
    assert np.max(np.abs(body.position[:, :2])) <= 1e-12
    assert abs(body.position[-1, 2] - (a[2] / 2 - (mass * G / (4 * k)) ** (2 / 3))) <= 1e-9
    assert np.linalg.norm(body.velocity[-1]) <= 1e-6
    assert len([x for x in r.events if x["label"] == "onset"]) >= 4


def assert_derivatives_are_differences(core, q, v, Qq, Qv, h=1e-6):
    """Q_q and Q_v against central differences of Q (step h), to 1e-6 of the
    largest entry."""
    for Jac, wrt in ((Qq, "q"), (Qv, "v")):
        fd = np.zeros_like(Jac)
        for j in range(q.size):
            dx = np.zeros(q.size)
            dx[j] = h
            args = ((q + dx, v), (q - dx, v)) if wrt == "q" else ((q, v + dx), (q, v - dx))
            fd[:, j] = (core.forces(*args[0], 0.0)[0] - core.forces(*args[1], 0.0)[0]) / (2 * h)
        assert np.max(np.abs(Jac - fd)) <= 1e-6 * np.max(np.abs(fd)), wrt


def spheres_and_friends(kind_b, size_b, centre_b=(0.0, 0.0, 0.0), centre_a=(0.15, 0.02, 0.1)):
    """A sphere (radius 0.1) pressed into a shape on a second free body."""
    m = mb.Model(gravity=(0.0, 0.0, 0.0), dimension=3)
    m.add_body("a", mass=1.5, inertia=(0.01, 0.012, 0.014), position=centre_a)
    m.add_body("b", mass=3.0, inertia=(0.03, 0.02, 0.025), position=centre_b,
               orientation=tuple(np.array([0.95, 0.1, -0.2, 0.2]) / np.linalg.norm([0.95, 0.1, -0.2, 0.2])))
    sa = m.add_shape("a", "sphere", (0.1,), centre_a, role="collision")
    sb = m.add_shape("b", kind_b, size_b, centre_b, np.eye(3), role="collision")
    m.add_contact("touch", sa, sb, stiffness=1e6, restitution=0.95, friction=0.4, slip_velocity=0.05)
    return m


@pytest.mark.parametrize("kind, size, centre_a", [
    ("sphere", (0.12,), (0.15, 0.02, 0.1)),
    ("capsule", (0.05, 0.3), (0.1, 0.05, 0.1)),
    ("box", (0.2, 0.3, 0.25), (0.12, 0.05, 0.1)),
    ("plane", (), (0.02, 0.03, 0.08)),
])
def test_contact_derivatives_match_finite_differences(kind, size, centre_a):
    """Q_q and Q_v of a sphere pressed into each kind of shape on a second
    moving body (both turning, slipping near the smoothing speed; slow
    enough that the damping, at the least impact speed a contact outside a
    run has, does not cancel the force), against central differences of Q
    (h = 1e-6), to 1e-6 of the largest entry."""
    core = spheres_and_friends(kind, size, centre_a=centre_a).compiled()
    q, _ = core.initial_state()
    rng = np.random.default_rng(7)
    v = 0.01 * rng.standard_normal(q.size)
    Q, Qq, Qv = core.forces(q, v, 0.0)
    assert np.max(np.abs(Q)) > 10.0  # the contact is active
    assert_derivatives_are_differences(core, q, v, Qq, Qv)


@pytest.mark.parametrize("under", ["table", "ground"])
def test_box_corners_derivatives_match_finite_differences(under):
    """A tilted box pressed into a plane on a moving body (its derivatives
    over both bodies' coordinates) or on the ground (over the box's alone):
    Q_q and Q_v against central differences (1e-6 of the largest entry)."""
    m = mb.Model(gravity=(0.0, 0.0, 0.0), dimension=3)
    m.add_body("box", mass=1.0, inertia=(0.01, 0.01, 0.01), position=(0.0, 0.0, 0.09),
               orientation=tuple(np.array([0.98, 0.1, 0.15, 0.05]) / np.linalg.norm([0.98, 0.1, 0.15, 0.05])))
    if under == "table":
        m.add_body("table", mass=5.0, inertia=(0.1, 0.1, 0.1), position=(0.0, 0.0, -0.05))
    box = m.add_shape("box", "box", (0.2, 0.2, 0.2), (0.0, 0.0, 0.09), role="collision")
    top = m.add_shape(under, "plane", (), (0.0, 0.0, 0.0), rotation_y(0.1), role="collision")
    m.add_contact("rest", box, top, stiffness=1e6, restitution=0.95, friction=0.3, slip_velocity=0.05)
    core = m.compiled()
    q, _ = core.initial_state()
    v = 0.01 * np.random.default_rng(2).standard_normal(q.size)
    Q, Qq, Qv = core.forces(q, v, 0.0)
    assert np.max(np.abs(Q)) > 10.0
    assert_derivatives_are_differences(core, q, v, Qq, Qv)


def test_apart_shapes_add_nothing():
    """Shapes 1 m apart: Q is gravity alone, its derivatives zero, no
    potential energy (exactly)."""
    m = ball_over_floor(gap=1.0, gravity=G)
    core = m.compiled()
    q, v = core.initial_state()
    Q, Qq, Qv = core.forces(q, v, 0.0)
    assert np.array_equal(Q[:3], [0.0, 0.0, -G]) and not np.any(Q[3:])
    assert not np.any(Qq.toarray() if hasattr(Qq, "toarray") else Qq)
    assert not np.any(Qv.toarray() if hasattr(Qv, "toarray") else Qv)


def test_equal_spheres_exchange_their_velocities():
    """Two equal spheres meet head on (e = 1, no friction): they exchange
    their velocities to 1e-6, momentum kept to 1e-12."""
    m = mb.Model(gravity=(0.0, 0.0, 0.0), dimension=3)
    for name, x, v in (("left", -0.15, 1.0), ("right", 0.15, -0.5)):
        m.add_body(name, mass=2.0, inertia=(0.008,) * 3, position=(x, 0.0, 0.0), velocity=(v, 0.0, 0.0))
    a = m.add_shape("left", "sphere", (0.1,), (-0.15, 0.0, 0.0), role="collision")
    b = m.add_shape("right", "sphere", (0.1,), (0.15, 0.0, 0.0), role="collision")
    m.add_contact("meet", a, b, stiffness=1e7, restitution=1.0)
    r = mb.simulate(m, 0.2, rtol=1e-10, atol=1e-12, n_out=3)
    left, right = r.body("left").velocity[-1], r.body("right").velocity[-1]
    assert abs(left[0] + 0.5) <= 1e-6 and abs(right[0] - 1.0) <= 1e-6
    assert abs(2.0 * (left[0] + right[0]) - 1.0) <= 1e-12


@pytest.mark.parametrize("kind, size, offset", [("capsule", (0.05, 0.4), 0.05), ("box", (0.4, 0.4, 0.1), 0.05)])
def test_sphere_rests_on_a_capsule_and_a_box_at_the_hertz_height(kind, size, offset):
    """A sphere dropped onto a capsule lying on the ground (its side) and
    onto a box's top face comes to rest at the Hertz static height (1e-9 m)."""
    R, mass, k = 0.05, 0.5, 1e7
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    axes = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])  # the capsule's z along x
    top = offset + R + 0.002
    centre = (0.03, 0.0 if kind == "capsule" else 0.01, top)  # (on the capsule's crest: off it, it slides off)
    m.add_body("ball", mass=mass, inertia=(0.4 * mass * R * R,) * 3, position=centre)
    ball = m.add_shape("ball", "sphere", (R,), centre, role="collision")
    below = m.add_shape("ground", kind, size, (0.0, 0.0, 0.0), axes if kind == "capsule" else None, role="collision")
    m.add_contact("rest", ball, below, stiffness=k, restitution=0.3, friction=0.0)
    r = mb.simulate(m, 1.5, rtol=1e-9, atol=1e-11, n_out=3)
    z = r.body("ball").position[-1, 2]
    assert abs(z - (offset + R - (mass * G / k) ** (2 / 3))) <= 1e-9


def test_bad_contacts_are_rejected():
    """A pair the table does not have names both kinds and lists the pairs;
    a visual shape, a shape of a planar model's kind, bad law values and
    two shapes on one body are ModelErrors naming the contact."""
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    m.add_body("b", mass=1.0, inertia=(0.01,) * 3, position=(0.0, 0.0, 1.0))
    m.add_body("c", mass=1.0, inertia=(0.01,) * 3, position=(0.0, 0.0, 2.0))
    box = m.add_shape("b", "box", (0.1, 0.1, 0.1), (0.0, 0.0, 1.0), role="collision")
    box2 = m.add_shape("c", "box", (0.1, 0.1, 0.1), (0.0, 0.0, 2.0), role="collision")
    ball = m.add_shape("c", "sphere", (0.1,), (0.0, 0.0, 2.0), role="collision")
    ball_b = m.add_shape("b", "sphere", (0.1,), (0.0, 0.0, 1.0), role="collision")
    seen = m.add_shape("b", "sphere", (0.1,), (0.0, 0.0, 1.0))
    floor = m.add_shape("ground", "plane", (), role="collision")
    with pytest.raises(mb.ModelError, match="'boxes'.*no contact between a box and a box.*sphere-plane"):
        m.add_contact("boxes", box, box2, stiffness=1e6, restitution=0.5)
    with pytest.raises(mb.ModelError, match="role 'visual'"):
        m.add_contact("seen", seen, floor, stiffness=1e6, restitution=0.5)
    with pytest.raises(mb.ModelError, match="'same'.*"):
        m.add_contact("same", box, ball_b, stiffness=1e6, restitution=0.5)
    for key, value, message in (("stiffness", -1.0, "stiffness"), ("restitution", 0.0, "restitution"),
                                ("friction", -0.1, "friction"), ("slip_velocity", 0.0, "slip_velocity")):
        law = dict(stiffness=1e6, restitution=0.5)
        law[key] = value
        with pytest.raises(mb.ModelError, match=f"'bad'.*{message}"):
            m.add_contact("bad", ball, floor, **law)
    with pytest.raises(mb.ModelError, match="must be a Shape"):
        m.add_contact("none", "b", floor, stiffness=1e6, restitution=0.5)
    for kind, size in (("plane", (1.0,)), ("capsule", (0.1, -1.0)), ("sphere", (0.0,))):
        with pytest.raises(mb.ModelError, match=f"a {kind}'s size"):
            m.add_shape("b", kind, size, role="collision")


def test_contact_round_trips_through_text_and_scene(tmp_path):
    """The model as text (what an FMU carries) and as a scene file gives the
    same run, to the bit."""
    m = ball_over_floor(mu=0.3, vx=0.5, gravity=G)
    r = mb.simulate(m, 0.02, rtol=1e-8, atol=1e-10, n_out=5)
    again = mb.Model.from_text(m.to_text())
    assert np.array_equal(mb.simulate(again, 0.02, rtol=1e-8, atol=1e-10, n_out=5).q, r.q)
    path = tmp_path / "ball.toml"
    mb.save_scene(m, path)
    scene = mb.load_scene(path)
    assert np.array_equal(mb.simulate(scene.model, 0.02, rtol=1e-8, atol=1e-10, n_out=5).q, r.q)
    assert sorted(s.kind for s in scene.model.shapes) == ["plane", "sphere"]  # drawn too


def test_no_energy_gained_in_elastic_bounces():
    """A frictionless elastic ball bouncing for 2 s: its energy at each
    output outside contact stays within 1e-7 of the start, never above it
    by more than that."""
    m = ball_over_floor(v=0.0, gap=0.3, k=1e7, e=1.0, gravity=G)
    r = mb.simulate(m, 2.0, rtol=1e-10, atol=1e-12, n_out=2001)
    E0 = G * (0.1 + 0.3)
    z, v = r.body("ball").position[:, 2], r.body("ball").velocity
    E = G * z + 0.5 * np.sum(v * v, axis=1)
    free = r.contact("hit").penetration < 0  # (in contact the law's potential holds the rest)
    assert np.max(E[free] - E0) <= 1e-7 * E0
    assert len([x for x in r.events if x["label"] == "onset"]) >= 4


def test_a_cylinder_rolls_on_its_side_and_stands_on_its_end():
    """A solid cylinder lying across a 15 degree slope rolls on its two
    rims' deepest points with g sin(alpha) / (1 + J / (m (R - d0)^2)), J =
    m R^2 / 2 (1e-7); standing on its end it rests level on four points of
    its rim at their Hertz depth (1e-9 m)."""
    alpha, R, L, mass, k = math.radians(15.0), 0.1, 0.2, 2.0, 1e8
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    axes = rotation_y(-alpha)
    d0 = (mass * G * math.cos(alpha) / (2 * k)) ** (2.0 / 3.0)
    centre = (R - d0) * axes[:, 2]
    across = np.column_stack([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])  # its axis along -y
    J = 0.5 * mass * R * R
    m.add_body("roll", mass=mass, inertia=(mass * (3 * R * R + L * L) / 12, J, mass * (3 * R * R + L * L) / 12),
               position=tuple(centre))
    slope = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), axes, role="collision")
    roll = m.add_shape("roll", "cylinder", (R, L), tuple(centre), across, role="collision")
    m.add_contact("slope", roll, slope, stiffness=k, restitution=0.5, friction=0.5)
    r = mb.simulate(m, 1.0, rtol=1e-10, atol=1e-12, n_out=1001)
    s = (r.body("roll").position - centre) @ axes[:, 0]
    late = r.t > 0.5
    a = -2.0 * np.polyfit(r.t[late], s[late], 2)[0]
    assert abs(a / (G * math.sin(alpha) / (1 + J / (mass * (R - d0) ** 2))) - 1.0) <= 1e-7

    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    top = (0.0, 0.0, L / 2 + 0.005)
    m.add_body("can", mass=mass, inertia=(0.01, 0.01, 0.01), position=top)
    floor = m.add_shape("ground", "plane", (), role="collision")
    can = m.add_shape("can", "cylinder", (R, L), top, role="collision")
    m.add_contact("floor", can, floor, stiffness=k, restitution=0.5, friction=0.5)
    r = mb.simulate(m, 1.0, rtol=1e-9, atol=1e-11, n_out=3)
    body = r.body("can")
    assert abs(body.position[-1, 2] - (L / 2 - (mass * G / (4 * k)) ** (2 / 3))) <= 1e-9
    assert np.arccos(min(1.0, body.rotation[-1][2, 2])) <= 1e-9


def write_stl(path, triangles):
    """A binary STL file of the triangles (n, 3, 3)."""
    triangles = np.asarray(triangles, dtype="<f4")
    with open(path, "wb") as f:
        f.write(b"lagmb test".ljust(80, b" ") + len(triangles).to_bytes(4, "little"))
        for tri in triangles:
            f.write(np.zeros(3, "<f4").tobytes() + tri.tobytes() + b"\0\0")


def test_a_mesh_touches_by_its_convex_hull():
    """A cube given as an STL mesh (12 triangles, and one more inside it,
    whose vertices no hull has) scaled by (0.2, 0.2, 0.2): dropped flat it
    touches, rests and sticks as the box does (the same events; the same
    height to 1e-12 m)."""
    import os
    import tempfile

    c = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6),
             (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    triangles = [c[list(f)] for f in faces] + [np.array([[0.1, 0.1, 0.1], [0.2, 0.1, 0.1], [0.1, 0.2, 0.1]])]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "cube.stl")
        write_stl(path, triangles)
        runs = []
        for kind, size, mesh in (("mesh", (0.2, 0.2, 0.2), path), ("box", (0.2, 0.2, 0.2), None)):
            m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
            centre = (0.0, 0.0, 0.11)
            m.add_body("cube", mass=1.0, inertia=(0.0067,) * 3, position=centre)
            floor = m.add_shape("ground", "plane", (), role="collision")
            cube = m.add_shape("cube", kind, size, centre, mesh=mesh, role="collision")
            m.add_contact("floor", cube, floor, stiffness=1e8, restitution=0.5, friction=0.5)
            assert dict(m.elements)["add_contact"]["shape_a"] == cube  # (the mesh, as given)
            runs.append(mb.simulate(m, 0.5, rtol=1e-9, atol=1e-11, n_out=3))
        mesh_run, box_run = runs
        assert abs(mesh_run.body("cube").position[-1, 2] - box_run.body("cube").position[-1, 2]) <= 1e-12
        assert [x["label"] for x in mesh_run.events] == [x["label"] for x in box_run.events]
        assert mesh_run.contact("floor").state[-1] == "stick"
        # as text (an FMU's): the hull's vertices go with it, the mesh file does not
        again = mb.Model.from_text(mesh_run.model.to_text())
        assert np.array_equal(mb.simulate(again, 0.5, rtol=1e-9, atol=1e-11, n_out=3).q, mesh_run.q)
        assert dict(again.elements)["add_contact"]["shape_a"][1] == "convex"


def slab_with_a_low_point(path, depth, at=(0.2, 0.1)):
    """A 1 m x 1 m x 0.1 m slab's surface as an STL file, its bottom face
    drawn down to a point `depth` under it at (x, y) = at (four triangles
    from its edges); -> its nine vertices (the corners, then the low point;
    in single precision, as the file holds them)."""
    corners = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.05, 0.05)])
    low = np.array([at[0], at[1], -0.05 - depth])
    faces = [(1, 3, 7), (1, 7, 5), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3), (0, 2, 3), (0, 3, 1),
             (4, 5, 7), (4, 7, 6)]  # the top and the sides
    bottom = [(0, 4), (4, 6), (6, 2), (2, 0)]
    write_stl(path, [corners[list(f)] for f in faces] + [np.array([corners[a], corners[b], low]) for a, b in bottom])
    return np.vstack([corners, low]).astype(np.float32).astype(float)


def vertex_heights(r, body, vertices):
    """(k, n) the heights of a body's vertices (body axes) at each output."""
    path = r.body(body)
    return path.position[:, 2][:, None] + np.einsum("kj,nj->kn", path.rotation[:, 2, :], vertices)


@pytest.mark.parametrize("depth", [0.02, 0.05])
def test_a_slab_lands_and_rests_on_the_low_point_of_its_mesh(depth, tmp_path):
    """A 10 kg slab whose mesh has a low point 2 cm (5 cm) under its bottom
    face, dropped flat from 5 mm (the low point's height), lands on that
    point and rests on it and an edge, as a 1 m slab with such a point
    must (every vertex of the hull is a contact point: a hull sampled
    along 162 directions left the point out, and the slab rested on its
    corners with the point 2.1 (5.0) cm below the floor, the contact
    reading 0.2 mm). At every output the contact reads the deepest
    vertex's depth (1e-9 m), whose elastic energy k d^2.5 / 2.5 is within
    what the drop has given up (the energy left; no energy gained); at
    rest the low point is no deeper than the whole weight presses one
    point, (W / k)^(2/3)."""
    mass, k = 10.0, 1e7
    vertices = slab_with_a_low_point(tmp_path / "slab.stl", depth)
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    z0 = 0.05 + depth + 0.005
    m.add_body("slab", mass=mass, inertia=(mass * 1.01 / 12, mass * 1.01 / 12, mass * 2.0 / 12),
               position=(0.0, 0.0, z0))
    floor = m.add_shape("ground", "plane", (), role="collision")
    slab = m.add_shape("slab", "mesh", (1.0, 1.0, 1.0), (0.0, 0.0, z0), mesh=str(tmp_path / "slab.stl"),
                       role="collision")
    m.add_contact("floor", slab, floor, stiffness=k, restitution=0.5, friction=0.5)
    r = mb.simulate(m, 2.0, rtol=1e-8, atol=1e-10, n_out=401)
    heights = vertex_heights(r, "slab", vertices)
    deepest = -heights.min(axis=1)
    reading = r.contact("floor").penetration
    assert np.max(np.abs(reading - deepest)) <= 1e-9
    path = r.body("slab")
    spent = mass * G * (z0 - path.position[:, 2]) - 0.5 * mass * np.sum(path.velocity ** 2, axis=1)
    assert np.all(k * np.maximum(deepest, 0.0) ** 2.5 / 2.5 <= spent + 1e-6)
    assert np.max(np.diff(r.energy)) <= 1e-6 * mass * G * z0
    assert deepest.max() > 0.0 and np.all(np.abs(r.v[-1]) < 1e-3)
    assert np.argmin(heights[-1]) == 8 and deepest[-1] <= (mass * G / k) ** (2 / 3)
    assert np.sum(heights[-1] < 1e-3) == 3  # (the low point and an edge's two corners)


def test_a_random_hull_dropped_tumbling_touches_by_its_deepest_point(tmp_path):
    """A mesh of 300 random points about an ellipsoid (their hull: 133
    vertices) dropped tumbling onto a plane: at every output the contact's penetration is the
    deepest of all 300 points (a brute-force minimum of their heights,
    1e-9 m), however the hull lands; the energy never rises (1e-7 J)."""
    from scipy.spatial import ConvexHull
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(5)
    directions = rng.normal(size=(300, 3))
    radii = 1.0 + 0.1 * rng.random((300, 1))  # (a rough ellipsoid: most points on its hull, some inside)
    points = (directions / np.linalg.norm(directions, axis=1)[:, None] * radii * (0.1, 0.06, 0.04))
    points = points.astype(np.float32).astype(float)  # (as the file holds them)
    write_stl(tmp_path / "cloud.stl", points.reshape(100, 3, 3))
    assert 100 <= len(ConvexHull(points).vertices) < 300
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    turn = Rotation.from_rotvec(0.8 * np.array([1.0, 2.0, -0.5]) / np.sqrt(5.25)).as_matrix()
    centre = (0.0, 0.0, 0.02 - float(np.min(points @ turn.T[:, 2])))
    m.add_body("rock", mass=1.0, inertia=(0.002, 0.004, 0.005), position=centre, orientation=turn,
               angular_velocity=(3.0, -2.0, 5.0), velocity=(0.3, 0.0, -0.5))
    floor = m.add_shape("ground", "plane", (), role="collision")
    rock = m.add_shape("rock", "mesh", (1.0, 1.0, 1.0), centre, turn, mesh=str(tmp_path / "cloud.stl"),
                       role="collision")
    m.add_contact("floor", rock, floor, stiffness=1e6, restitution=0.6, friction=0.4)
    r = mb.simulate(m, 1.0, rtol=1e-8, atol=1e-10, n_out=401)
    deepest = -vertex_heights(r, "rock", points).min(axis=1)
    assert np.max(np.abs(r.contact("floor").penetration - deepest)) <= 1e-9
    assert deepest.max() > 0.0 and len([e for e in r.events if e["label"] == "onset"]) >= 3
    assert np.max(r.energy - np.minimum.accumulate(r.energy)) <= 1e-7


def test_a_quadruped_dropped_on_the_ground_comes_to_rest():
    """Unitree Go1 (example-robot-data) on a floating base, its limits on,
    dropped from 0.35 m above the ground (load_urdf(ground=...)): after 3 s
    every speed is below 1e-3, the ground carries its weight (the normal
    forces sum to m g within 1e-3), and at rest no shape is deeper than the
    whole weight would press one point, (W / k)^(2/3)."""
    from formats import urdf_robots  # (skips without Pinocchio and example-robot-data)
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)  # (its inertias, as test_urdf reads them)
        m = mb.load_urdf(os.path.join(urdf_robots.ROBOTS, "go1_description/urdf/go1.urdf"), floating_base=True,
                         ground=-0.35)
    contacts = [kw["name"] for method, kw in m.elements if method == "add_contact"]
    assert len(contacts) == len([s for s in m.shapes if s.role == "collision"]) - 1  # (all but the floor)
    assert "FR_foot_ground" in contacts
    r = mb.simulate(m, 3.0, rtol=1e-6, atol=1e-8, n_out=31)
    assert np.abs(r.v[-1]).max() < 1e-3
    weight = sum(kw["mass"] for method, kw in m.elements if method == "add_body") * G
    readings = [r.contact(name) for name in contacts]
    assert abs(sum(c.normal_force[-1] for c in readings) / weight - 1.0) <= 1e-3
    assert max(c.penetration[-1] for c in readings) <= (weight / mb.urdf.GROUND_CONTACT["stiffness"]) ** (2 / 3)


def test_a_quadruped_loaded_into_the_ground_names_the_shapes_deep_in_it():
    """Go1 loaded with its base frame at the ground (ground=0.0): 35 of its
    collision shapes start in it, its calves' boxes deepest, 0.22 m in,
    each pressing 6.3e6 N, 49,000 times the robot's weight. A
    DeepContactWarning at the caller's line names them, the deepest first,
    with both shapes and the depth; the run then fails at t = 0, and its
    message (which said only that IDA's corrector failed) names them too."""
    from formats import urdf_robots  # (skips without Pinocchio and example-robot-data)
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        m = mb.load_urdf(os.path.join(urdf_robots.ROBOTS, "go1_description/urdf/go1.urdf"), floating_base=True,
                         ground=0.0)
    with pytest.warns(mb.DeepContactWarning) as seen:
        with pytest.raises(mb.SimulationError, match="failed at t = 0") as info:
            mb.simulate(m, 0.5)
    assert seen[0].filename == __file__
    deepest = "'FR_calf_ground' 0.221 m deep (a box on 'FR_calf' and a plane on the ground, pressing with 6.35e+06 N"
    assert str(seen[0].message).startswith("35 contacts start with their shapes deep inside each other: " + deepest)
    assert info.value.t == 0.0 and deepest in str(info.value) and "and 32 more" in str(info.value)


BLOCK_URDF = """<robot name="blocks">
  <link name="base">
    <inertial><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
    <collision><origin xyz="0 0 0.15"/><geometry><sphere radius="0.05"/></geometry></collision>
    <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual>
  </link>
</robot>
"""


def test_load_urdf_ground_pairs_every_collision_shape_with_a_floor(tmp_path):
    """ground=z: a plane through (0, 0, z) and one contact per collision
    shape of a moving body (LINK_ground, LINK_ground_2), with
    GROUND_CONTACT's values as `contact` updates them; bad arguments are
    UrdfErrors naming them. The block dropped on it sticks where it lands."""
    path = tmp_path / "blocks.urdf"
    path.write_text(BLOCK_URDF)
    m = mb.load_urdf(path, floating_base=True, ground=-0.1001, contact={"friction": 0.6})
    contacts = {kw["name"]: kw for method, kw in m.elements if method == "add_contact"}
    assert sorted(contacts) == ["base_ground", "base_ground_2"]
    assert contacts["base_ground"]["friction"] == 0.6
    assert contacts["base_ground"]["stiffness"] == mb.urdf.GROUND_CONTACT["stiffness"]
    floor = contacts["base_ground"]["shape_b"]
    assert (floor.kind, tuple(floor.position)) == ("plane", (0.0, 0.0, -0.1001))
    r = mb.simulate(m, 0.3, n_out=3)
    assert r.contact("base_ground").state[-1] == "stick"
    with pytest.raises(mb.UrdfError, match="load_urdf: contact has no keyword 'stiff'"):
        mb.load_urdf(path, floating_base=True, ground=0.0, contact={"stiff": 1.0})
    with pytest.raises(mb.UrdfError, match="load_urdf: ground"):
        mb.load_urdf(path, floating_base=True, ground="floor")


def test_capsules_touch_at_their_segments_nearest_points():
    """Two capsules crossed at right angles, one resting across the other
    on the ground: it rests at the Hertz height (radii and (m g / k)^(2/3),
    1e-9 m) above the lower segment; Q_q and Q_v of two moving capsules
    pressed together (skewed) match central differences (1e-6)."""
    R, L, mass, k = 0.05, 0.4, 1.0, 1e7
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    along_x = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])  # its z along x
    along_y = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])  # its z along y
    top = (0.0, 0.0, 2 * R + 0.003)  # (balanced over the crossing: off it, it tips off)
    m.add_body("upper", mass=mass, inertia=(0.01, 0.01, 0.002), position=top)
    upper = m.add_shape("upper", "capsule", (R, L), top, along_y, role="collision")
    lower = m.add_shape("ground", "capsule", (R, L), (0.0, 0.0, 0.0), along_x, role="collision")
    m.add_contact("cross", upper, lower, stiffness=k, restitution=0.3)
    r = mb.simulate(m, 1.0, rtol=1e-9, atol=1e-11, n_out=3)
    assert abs(r.body("upper").position[-1, 2] - (2 * R - (mass * G / k) ** (2 / 3))) <= 1e-9

    m = mb.Model(gravity=(0.0, 0.0, 0.0), dimension=3)
    m.add_body("a", mass=1.0, inertia=(0.01, 0.012, 0.014), position=(0.05, 0.02, 0.09))
    m.add_body("b", mass=2.0, inertia=(0.02, 0.01, 0.015), position=(0.0, 0.0, 0.0))
    skew = np.array([[0.8, 0.0, 0.6], [0.0, 1.0, 0.0], [-0.6, 0.0, 0.8]])
    a = m.add_shape("a", "capsule", (R, L), (0.05, 0.02, 0.09), along_y, role="collision")
    b = m.add_shape("b", "capsule", (R, L), (0.0, 0.0, 0.0), skew, role="collision")
    m.add_contact("press", a, b, stiffness=1e6, restitution=0.95, friction=0.3, slip_velocity=0.05)
    core = m.compiled()
    q, _ = core.initial_state()
    v = 0.01 * np.random.default_rng(5).standard_normal(q.size)
    Q, Qq, Qv = core.forces(q, v, 0.0)
    assert np.max(np.abs(Q)) > 1.0
    assert_derivatives_are_differences(core, q, v, Qq, Qv)


@pytest.mark.parametrize("mu", [1.5, 3.0])
def test_a_rod_sliding_on_its_end_past_painleves_friction_jams_and_goes_on(mu):
    """Painlevé's rod: a thin bar leaning at 30 degrees whose lower end
    slides at 2 m/s with mu above 4/3. With a rigid normal its contact has
    no consistent solution; with the compliant one here the end jams (its
    contact sticks: a tangential impact) and the run goes on; the energy
    never rises (1e-6 J)."""
    th, L, w = math.radians(30.0), 1.0, 0.02
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    floor = m.add_shape("ground", "plane", (), role="collision")
    R = rotation_y(-th)  # its x axis rising at 30 degrees
    centre = (0.5 * L * math.cos(th), 0.0, 0.5 * L * math.sin(th) + 0.5 * w * math.cos(th) - 1e-6)
    m.add_body("rod", mass=1.0, inertia=(1e-4, L * L / 12, L * L / 12), position=centre, orientation=R,
               velocity=(-2.0, 0.0, 0.0))
    rod = m.add_shape("rod", "box", (L, w, w), centre, R, role="collision")
    m.add_contact("end", rod, floor, stiffness=1e8, restitution=0.5, friction=mu)
    r = mb.simulate(m, 0.5, rtol=1e-8, atol=1e-10, n_out=501)
    assert "stick" in [x["label"] for x in r.events if x["kind"] == "friction"]
    assert np.max(np.diff(r.energy)) <= 1e-6


def test_a_box_at_rest_takes_fewer_steps_than_one_in_free_flight():
    """At rest the steps grow: a cube resting (stuck) on a floor for 10 s
    takes fewer steps than the same cube thrown through the air for 10 s
    (counts, deterministic: 11 against 96 at rtol 1e-6, both GGL)."""
    m, _ = sliding_block(v0=0.0, mu=0.5)
    rest = mb.simulate(m, 10.0, rtol=1e-6, atol=1e-8, n_out=11)
    free = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    free.add_body("block", mass=1.0, inertia=(0.2 * 0.2 / 6,) * 3, position=(0.0, 0.0, 500.0), velocity=(1.0, 0.0, 5.0),
                  angular_velocity=(0.1, 0.2, 0.3))
    flight = mb.simulate(free, 10.0, rtol=1e-6, atol=1e-8, n_out=11, method=rest.stats["method"])
    assert rest.contact("floor").state[-1] == "stick"
    assert rest.stats["steps"] <= 0.5 * flight.stats["steps"]


def test_bodies_at_rest_step_as_in_free_flight():
    """A box (stuck on its corners) and a ball resting on a floor at their
    Hertz depth (k = 1e7) take at most twice the steps over 10 s of the same
    box thrown through free space (the issue's "at rest the steps grow"; seen:
    11 and 11 steps against 12): nothing moves, so the error control lets the
    steps grow as in a parabola's flight."""
    mass, k = 2.0, 1e7

    def steps(shape, size, inertia, resting):
        m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
        if shape == "box":
            height = size[2] / 2 - (mass * G / (4 * k)) ** (2 / 3)  # four corners share the weight
        else:
            height = size[0] - (mass * G / k) ** (2 / 3)
        centre = (0.0, 0.0, height if resting else 10.0)
        m.add_body("b", mass=mass, inertia=inertia, position=centre,
                   velocity=(0.0, 0.0, 0.0) if resting else (1.0, 0.0, 50.0))
        s = m.add_shape("b", shape, size, centre, role="collision")
        if resting:
            floor = m.add_shape("ground", "plane", (), role="collision")
            m.add_contact("floor", s, floor, stiffness=k, restitution=0.5, friction=0.5)
        r = mb.simulate(m, 10.0, n_out=11)
        if resting:
            assert np.max(np.abs(r.body("b").position[-1] - centre)) <= 1e-9
        return r.stats["steps"]

    flight = steps("box", (0.3, 0.2, 0.1), (0.01, 0.02, 0.025), resting=False)
    assert steps("box", (0.3, 0.2, 0.1), (0.01, 0.02, 0.025), resting=True) <= 2 * flight
    assert steps("sphere", (0.1,), (0.008, 0.008, 0.008), resting=True) <= 2 * flight
