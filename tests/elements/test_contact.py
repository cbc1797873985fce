"""Circle-line contact: compliant normal force, friction, onset/release events.

References:
- free fall: first touch after sqrt(2 h / g) at sqrt(2 g h) (closed form);
- the contact law's rebound is exactly e (tests/elements/test_contact_restitution.py:
  its damping c, c (1 + e) = ln((1 + c) / (1 - c e)), is `damping` there),
  so apex gaps follow e^2 to the effect of gravity during the ~1 ms
  contact;
- rolling: a uniform disk on an incline rolls with (2/3) g sin(a) on a rigid
  surface; on the compliant contact it rolls on R - d0 (d0 the static
  penetration) and creeps at a constant slip speed below v_s, so
  g sin a / (1 + J / (m (R - d0)^2)) holds exactly in the steady state;
- derivatives: central differences of Q.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import lagmb as mb
from elements.test_contact_restitution import damping

G = 9.81


def ball(e=0.8, k=1e8, R=0.1, height=1.0):
    m = mb.Model(gravity=(0.0, -G))
    b = m.add_body("ball", mass=1.0, inertia=0.4 * R * R, position=(0.0, height))
    m.add_contact("floor", b, (0.0, height), R, m.ground, (0.0, 0.0), (1.0, 0.0), stiffness=k, restitution=e)
    return m


def law_rebound(e, k, v0, mass=1.0, gravity=0.0):
    """Rebound ratio of the contact law (damping from the closed form) with
    gravity pressing the ball down during the contact: SciPy DOP853."""
    c = damping(e)

    def f(t, y):
        d, dd = -y[0], -y[1]
        F = k * d**1.5 * (1.0 + c * dd / v0) if d > 0 else 0.0
        return [y[1], max(F, 0.0) / mass - gravity]

    def out(t, y):
        return y[0] if t > 1e-7 else -1.0
    out.terminal, out.direction = True, 1
    s = solve_ivp(f, [0.0, 1.0], [0.0, -v0], method="DOP853", rtol=1e-12, atol=1e-15, events=out)
    return s.y_events[0][0][1] / v0


@pytest.mark.parametrize("formulation", ["ggl", "projection"])
def test_bouncing_ball_apex_heights(formulation):
    """Dropped from 0.9 m gap: first onset at sqrt(2 h / g) (1e-8 s) with
    speed sqrt(2 g h) (1e-7 relative); each bounce leaves at the rebound
    ratio of the law with gravity pressing during the contact (SciPy, 1e-6;
    measured 4e-8), below e = 0.8 by gravity's push over the 1.6 ms contact
    (7e-4 of it at the first bounce, 1.2e-3 at the third, slower, one), so
    each apex gap v_release^2 / (2 g) is e^2 times the previous one to 3e-3
    (measured 1.4e-3 to 2.4e-3)."""
    e, k, h = 0.8, 1e8, 0.9
    r = mb.simulate(ball(e, k), t_end=2.2, rtol=1e-9, atol=1e-11, n_out=11, formulation=formulation)
    onsets = [x for x in r.events if x["label"] == "onset"]
    releases = [x for x in r.events if x["label"] == "release"]
    assert len(onsets) >= 3 and len(releases) >= 3
    assert all(x["kind"] == "restart" for x in r.events)
    assert abs(onsets[0]["t"] - math.sqrt(2 * h / G)) <= 1e-8
    v0 = math.sqrt(2 * G * h)
    assert abs(-onsets[0]["speed_before"] - v0) <= 1e-7 * v0
    for on, off in zip(onsets[:3], releases[:3]):
        v = -on["speed_before"]
        with_gravity = law_rebound(e, k, v, gravity=G)
        assert abs(off["speed_before"] / v - with_gravity) <= 1e-6
        assert -1.5e-3 <= with_gravity / e - 1.0 < 0.0
    apex = [h] + [x["speed_before"] ** 2 / (2 * G) for x in releases]
    for a, b in zip(apex, apex[1:4]):
        assert abs(b / a - e**2) <= 3e-3 * e**2


def incline_disk(k=1e9, mu=0.5, alpha=math.radians(20.0), R=0.2, mass=2.0, vs=1e-4):
    d0 = (mass * G * math.cos(alpha) / k) ** (2.0 / 3.0)
    n = np.array([math.sin(alpha), math.cos(alpha)])
    centre = tuple((R - d0) * n)
    m = mb.Model(gravity=(0.0, -G))
    disk = m.add_body("disk", mass=mass, inertia=0.5 * mass * R * R, position=centre)
    m.add_contact("incline", disk, centre, R, m.ground, (0.0, 0.0), (math.cos(alpha), -math.sin(alpha)),
                  stiffness=k, restitution=0.5, friction=mu, slip_velocity=vs)
    return m, d0


def test_disk_rolls_down_incline():
    """Acceleration of the centre along the incline (quadratic fit over
    0.2..1 s): (2/3) g sin a to 3 d0 / R (rigid vs compliant rolling radius,
    1e-4 here) and the compliant closed form to 1e-7 relative; the slip
    speed stays below the smoothing velocity v_s = 1e-4 m/s (creep, set by
    v_s: F_t = mu F_n v_t / sqrt(v_t^2 + v_s^2) needs v_t = 0.25 v_s here)."""
    alpha, R = math.radians(20.0), 0.2
    m, d0 = incline_disk()
    r = mb.simulate(m, t_end=1.0, rtol=1e-9, atol=1e-11, n_out=201)
    u = np.array([math.cos(alpha), -math.sin(alpha)])
    s = r.body("disk").position @ u
    late = r.t >= 0.2
    accel = 2.0 * np.polyfit(r.t[late], s[late], 2)[0]
    rigid = 2.0 / 3.0 * G * math.sin(alpha)
    compliant = G * math.sin(alpha) / (1.0 + 0.5 * R * R / (R - d0) ** 2)
    assert abs(accel - rigid) <= 3 * d0 / R * rigid
    assert abs(accel - compliant) <= 1e-7 * compliant
    slip = r.body("disk").velocity[late] @ u + r.body("disk").angular_velocity[late] * (R - d0)
    assert np.max(np.abs(slip)) < 1e-4
    assert r.events == []  # it never leaves the incline


def test_frictionless_disk_slides():
    """mu = 0: no torque, the disk slides with g sin a (1e-7 relative) and
    does not turn (1e-9 rad/s)."""
    alpha = math.radians(20.0)
    m, _ = incline_disk(mu=0.0)
    r = mb.simulate(m, t_end=0.5, rtol=1e-9, atol=1e-11, n_out=101)
    u = np.array([math.cos(alpha), -math.sin(alpha)])
    s = r.body("disk").position @ u
    accel = 2.0 * np.polyfit(r.t[r.t >= 0.1], s[r.t >= 0.1], 2)[0]
    assert abs(accel - G * math.sin(alpha)) <= 1e-7 * G
    assert np.max(np.abs(r.body("disk").angular_velocity)) <= 1e-9


def two_body_contact():
    """A circle on a moving body against a line on another moving body."""
    m = mb.Model(gravity=(0.0, -G))
    wheel = m.add_body("wheel", mass=1.5, inertia=0.03, position=(0.1, 0.25), angle=0.4)
    plate = m.add_body("plate", mass=3.0, inertia=0.2, position=(0.0, 0.0), angle=0.1)
    m.add_contact("touch", wheel, (0.12, 0.24), 0.25, plate, (0.0, 0.0), (math.cos(0.1), math.sin(0.1)),
                  stiffness=2e5, restitution=0.7, friction=0.4, slip_velocity=0.05)
    return m


def test_contact_derivatives_match_finite_differences():
    """Q_q and Q_v of a contact between two moving bodies, in contact
    (penetration about 2 cm) and slipping near the smoothing speed, against
    central differences of Q (h = 1e-6), to 1e-6 of the largest entry."""
    core = two_body_contact().compiled()
    q, _ = core.initial_state()
    rng = np.random.default_rng(3)
    v = 0.1 * rng.standard_normal(q.size)
    Q, Qq, Qv = core.forces(q, v, 0.0)
    gravity = np.array([0.0, -1.5 * G, 0.0, 0.0, -3.0 * G, 0.0])
    assert np.max(np.abs(Q - gravity)) > 10.0  # the contact is active
    h = 1e-6
    for Jac, wrt in ((Qq, "q"), (Qv, "v")):
        fd = np.zeros_like(Jac)
        for a in range(q.size):
            dx = np.zeros(q.size)
            dx[a] = h
            if wrt == "q":
                fd[:, a] = (core.forces(q + dx, v, 0.0)[0] - core.forces(q - dx, v, 0.0)[0]) / (2 * h)
            else:
                fd[:, a] = (core.forces(q, v + dx, 0.0)[0] - core.forces(q, v - dx, 0.0)[0]) / (2 * h)
        assert np.max(np.abs(Jac - fd)) <= 1e-6 * np.max(np.abs(fd)), wrt


def test_no_force_when_separated():
    """The ball above the floor: Q is gravity alone, Q_q = Q_v = 0, and the
    contact has no potential energy (exactly)."""
    core = ball(height=0.5).compiled()
    q, _ = core.initial_state()
    v = np.array([0.3, -2.0, 1.0])
    Q, Qq, Qv = core.forces(q, v, 0.0)
    assert np.array_equal(Q, [0.0, -G, 0.0])
    assert not Qq.any() and not Qv.any()
    assert core.energy(np.zeros(1), q[None, :], np.zeros((1, 3)))[0] == pytest.approx(G * 0.5, rel=1e-15)


def test_bad_contacts_are_rejected():
    """Non-positive radius or stiffness, restitution outside (0, 1], negative
    friction, a circle and line on the same body: ValueError naming the contact."""
    m = mb.Model()
    b = m.add_body("b", mass=1.0, inertia=0.1)
    args = dict(center=(0, 0), radius=0.1, line_body=m.ground, point=(0, -1), direction=(1, 0),
                stiffness=1e6, restitution=0.5)
    for key, value, text in (("radius", 0.0, "radius must be positive"),
                             ("stiffness", -1.0, "stiffness must be positive"),
                             ("restitution", 0.0, "restitution must be in \\(0, 1\\]"),
                             ("friction", -0.1, "friction must be finite and >= 0"),
                             ("line_body", b, "to itself")):
        with pytest.raises(ValueError, match=f"'c'.*{text}"):
            m.add_contact("c", b, **{**args, key: value})


def test_contact_in_a_scene_file(tmp_path):
    """A contact is a [[forces]] table of type "contact"; the scene gives the
    same run to the bit."""
    m = ball()
    path = tmp_path / "ball.toml"
    mb.save_scene(m, path, settings={"t_end": 0.6, "rtol": 1e-8})
    assert 'type = "contact"' in path.read_text()
    r1, r2 = mb.load_scene(path).run(), mb.simulate(m, t_end=0.6, rtol=1e-8)
    assert r1.events == r2.events and len(r1.events) == 2
    assert np.array_equal(r1.q, r2.q)


def _ball_driven_into_floor():
    """A ball (R = 0.1 m) whose x, angle and height are all driven: its
    height falls at V = 0.1 m/s from 0.01 m above the floor contact."""
    m = mb.Model()
    b = m.add_body("ball", 1.0, 0.004, position=(0.0, 0.11))
    m.add_contact("floor", b, (0.0, 0.11), 0.1, m.ground, (0.0, 0.0), (1.0, 0.0), 1e6, 0.5)
    m.drive_body("dx", b, "x", 0.0)
    m.drive_body("dphi", b, "angle", 0.0)
    m.drive_body("dy", b, "y", mb.Linear(-0.1, start=0.11))
    return m


def test_fully_driven_contact_is_integrated_and_its_effort_is_the_contact_law():
    """0 DOF, but a contact switches on an event the kinematic analysis would
    not see: "auto" picks the dynamic run, records the onset at t = 0.1 s,
    and the driver holds exactly the contact force. Closed form with the
    impact speed V: F = k d^1.5 (1 + c d'/V), d' = V, so F = (1 + c) k
    d^1.5, c = 1.4328 at e = 0.5 (to 1e-9 relative). Asking for the kinematic
    analysis names the contact."""
    r = mb.simulate(_ball_driven_into_floor(), t_end=0.15, n_out=16, rtol=1e-10, atol=1e-12)
    assert r.stats["analysis"] == "dynamic"
    assert [(round(e["t"], 9), e["label"]) for e in r.events] == [(0.1, "onset")]
    d = np.maximum(0.1 - r.body("ball").position[:, 1], 0.0)
    expected = -1e6 * d**1.5 * (1.0 + damping(0.5))
    np.testing.assert_allclose(r.effort("dy"), expected, rtol=1e-9, atol=1e-9)
    with pytest.raises(ValueError, match="floor"):
        mb.simulate(_ball_driven_into_floor(), t_end=0.15, analysis="inverse_dynamics")


def test_accelerations_reported_during_a_contact_use_its_own_impact_speed():
    """The contact damping depends on the impact speed recorded at onset, so
    the outputs' accelerations must be solved with the contact in progress,
    not after the run (when a later bounce has replaced it). Inside the
    first contact of a ball (e = 0.5) dropped from 0.4 m: a_y = F_n/m - g
    with F_n = k d^1.5 (1 + c d'/v_i), v_i the first impact
    speed, at nine outputs, to 1e-6 relative."""
    m = mb.Model(gravity=(0.0, -9.81))
    ball = m.add_body("ball", mass=1.0, inertia=0.01, position=(0.0, 0.5))
    m.add_contact("c", ball, center=(0.0, 0.5), radius=0.1, line_body=m.ground, point=(0.0, 0.0),
                  direction=(1.0, 0.0), stiffness=1e6, restitution=0.5)
    first = mb.simulate(m, 1.5, n_out=3, rtol=1e-9, atol=1e-12)
    t_on, t_off = first.events[0]["t"], first.events[1]["t"]
    inside = np.linspace(t_on + 0.1 * (t_off - t_on), t_on + 0.9 * (t_off - t_on), 9)
    r = mb.simulate(m, 1.5, t_out=np.concatenate([[0.0], inside, [1.5]]), rtol=1e-9, atol=1e-12)
    assert len(r.events) > 2  # later bounces happened after these outputs
    v_impact = -r.events[0]["speed_before"]
    y, vy = r.q[1:10, 1], r.v[1:10, 1]
    d = 0.1 - y
    force = np.maximum(1e6 * d**1.5 * (1.0 + damping(0.5) / v_impact * (-vy)), 0.0)
    np.testing.assert_allclose(r.a[1:10, 1], force - 9.81, rtol=1e-6)


def test_result_contact_reads_a_ball_coming_to_rest():
    """Result.contact: a 1 kg ball (R = 0.1 m) dropped from 5 cm onto the
    floor (k = 1e8 N/m^1.5, e = 0.5) is open and 5 cm above it at t0
    (penetration -0.05 m, no force); it bounces to rest, where the contact
    carries m g (1e-9 relative) at the Hertz penetration (m g / k)^(2/3)
    (1e-9), at the point below the centre with the normal up, slipping at
    nothing."""
    m = ball(e=0.5, height=0.15)
    r = mb.simulate(m, t_end=3.0, n_out=31, rtol=1e-10, atol=1e-12)
    c = r.contact("floor")
    assert isinstance(c, mb.ContactPath)
    assert c.state[0] == "open" and c.normal_force[0] == 0.0 and abs(c.penetration[0] + 0.05) <= 1e-12
    assert np.all(c.friction_force[0] == 0.0)
    assert c.state[-1] == "slip"  # in contact (the regularized friction never sticks)
    assert abs(c.normal_force[-1] - G) <= 1e-9 * G
    assert abs(c.penetration[-1] - (G / 1e8) ** (2.0 / 3.0)) <= 1e-9 * (G / 1e8) ** (2.0 / 3.0)
    centre = r.body("ball").position[-1]
    assert np.allclose(c.point[-1], (centre[0], 0.0), rtol=0.0, atol=1e-12)
    assert np.allclose(c.normal[-1], (0.0, 1.0), rtol=0.0, atol=1e-15)
    assert c.slip_speed[-1] <= 1e-9


def test_result_contact_friction_is_the_regularized_coulomb_law():
    """A disk thrown along the floor without spin (pressed in about its
    static depth, (m g / k)^(2/3) = 2.1e-5 m) slides: at each output in
    contact the friction force opposes the slip, |F_t| = mu F_n s /
    sqrt(s^2 + v_s^2) (1e-12 relative), along the floor (its normal
    component 0); a name that is no contact is a ModelError."""
    m = mb.Model(gravity=(0.0, -G))
    disk = m.add_body("disk", mass=1.0, inertia=0.005, position=(0.0, 0.09998), velocity=(2.0, 0.0))
    m.add_contact("floor", disk, (0.0, 0.09998), 0.1, m.ground, (0.0, 0.0), (1.0, 0.0), stiffness=1e8,
                  restitution=0.5, friction=0.3)
    r = mb.simulate(m, t_end=0.2, n_out=21, rtol=1e-10, atol=1e-12)
    c = r.contact("floor")
    on = c.normal_force > 0.0
    assert np.count_nonzero(on) >= 15
    s = c.slip_speed[on]
    expected = 0.3 * c.normal_force[on] * s / np.sqrt(s * s + 1e-8)
    assert np.allclose(np.linalg.norm(c.friction_force[on], axis=1), expected, rtol=1e-12, atol=0.0)
    assert np.all(c.friction_force[on][:, 0] < 0.0)  # against the slip (+x)
    assert np.all(np.abs(np.sum(c.friction_force[on] * c.normal[on], axis=1)) <= 1e-12)
    with pytest.raises(mb.ModelError, match="'disk' is a body, not a contact"):
        r.contact("disk")
    with pytest.raises(mb.ModelError, match=r"'floor' is a contact.*Result.contact\('floor'\)"):
        r.reaction("floor")
