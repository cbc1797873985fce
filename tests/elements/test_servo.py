"""The joint servo (Model.add_servo): a PD law toward a target inside the
integrator, checked against the closed forms of the linear systems it makes,
and the Simulator's joint readers and set_inputs that a control loop uses."""

import math

import numpy as np
import pytest

import lagmb as mb

J = 0.2  # kg m^2: the arm's inertia about the hinge (through its centre of mass)


def arm(**servo):
    """A body turning about the z axis through its centre (no gravity), a servo on the hinge."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, 0.0))
    m.add_body("arm", mass=1.0, inertia=(0.1, 0.1, J), position=(0.0, 0.0, 0.0),
               angular_velocity=(0.0, 0.0, servo.pop("rate0", 0.0)))
    hinge = m.add_revolute("hinge", "ground", "arm", at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    m.add_servo("servo", hinge, **servo)
    return m


def test_a_servo_steps_the_arm_as_a_damped_oscillator():
    """J theta'' = kp (theta* - theta) - kd theta' toward a constant theta* =
    0.5 rad from rest: theta = theta* (1 - e^(-zeta w0 t) (cos wd t + zeta /
    sqrt(1 - zeta^2) sin wd t)), w0 = sqrt(kp / J), zeta = kd / (2 sqrt(kp
    J)) (to 1e-10 rad)."""
    kp, kd = 8.0, 1.6
    r = mb.simulate(arm(target=0.5, kp=kp, kd=kd), 3.0, n_out=31, rtol=1e-11, atol=1e-13)
    w0, zeta = math.sqrt(kp / J), kd / (2.0 * math.sqrt(kp * J))
    wd = w0 * math.sqrt(1.0 - zeta * zeta)
    t = r.t
    exact = 0.5 * (1.0 - np.exp(-zeta * w0 * t) * (np.cos(wd * t) + zeta / math.sqrt(1 - zeta * zeta) * np.sin(wd * t)))
    assert np.max(np.abs(r.joint("hinge").angle - exact)) <= 1e-10


def test_a_saturated_servo_gives_its_limit():
    """Far from its target the servo's demand exceeds its limit: a constant
    torque of 0.3 N m, theta = 0.3 t^2 / (2 J) (to 1e-12 rad)."""
    r = mb.simulate(arm(target=0.5, kp=8.0, kd=1.6, limit=0.3), 0.5, n_out=11, rtol=1e-11, atol=1e-13)
    assert np.max(np.abs(r.joint("hinge").angle - 0.3 * r.t ** 2 / (2 * J))) <= 1e-12


def test_a_servo_with_feedforward_tracks_a_moving_target_exactly():
    """theta*(t) = A sin(w t), feedforward J theta*'' and the arm started on
    the path (theta' = A w): the error equation J e'' + kd e' + kp e = 0
    from e = e' = 0 keeps e = 0: the servo uses theta*' (its kd term)."""
    A, w = 0.4, 3.0
    def target(t):  # (theta*, theta*', theta*'')
        return A * math.sin(w * t), A * w * math.cos(w * t), -A * w * w * math.sin(w * t)

    m = arm(target=target, kp=50.0, kd=5.0, feedforward=lambda t: -J * A * w * w * math.sin(w * t), rate0=A * w)
    r = mb.simulate(m, 2.0, n_out=41, rtol=1e-10, atol=1e-12)
    assert np.max(np.abs(r.joint("hinge").angle - A * np.sin(w * r.t))) <= 1e-8


def test_a_slide_servo_is_critically_damped():
    """A 1 kg slider on a rail, kp = 100 N/m, kd = 20 N s/m (zeta = 1),
    target 0.2 m: x = 0.2 (1 - (1 + 10 t) e^(-10 t)) (to 1e-10 m)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
    m.add_body("slider", mass=1.0, inertia=(0.1, 0.1, 0.1), position=(0.0, 0.0, 0.0))
    rail = m.add_translational("rail", "ground", "slider", at=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0))
    m.add_servo("servo", rail, target=0.2, kp=100.0, kd=20.0)
    r = mb.simulate(m, 1.0, n_out=21, rtol=1e-11, atol=1e-13)
    t = r.t
    assert np.max(np.abs(r.joint("rail").slide - 0.2 * (1.0 - (1.0 + 10.0 * t) * np.exp(-10.0 * t)))) <= 1e-10


def test_a_simulator_moves_the_target_and_reads_the_joints():
    """A servo whose target is an mb.Input, driven from a Simulator: the
    joint settles at each new target (set_inputs by name and as an array,
    4 s each); joint() and joints() read what r.joint reads."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, 0.0))
    m.add_body("arm", mass=1.0, inertia=(0.1, 0.1, J), position=(0.0, 0.0, 0.0))
    hinge = m.add_revolute("hinge", "ground", "arm", at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    m.add_servo("servo", hinge, target=mb.Input(0.0, "aim"), kp=8.0, kd=1.6)
    sim = mb.Simulator(m, rtol=1e-10, atol=1e-12)
    assert sim.joint_names == ("hinge",)
    sim.set_inputs({"aim": 1.0})
    sim.advance(4.0)
    assert abs(sim.joint("hinge").angle - 1.0) <= 1e-4
    sim.set_inputs([7.0])  # beyond a turn: the angle counts it
    sim.advance(12.0)
    values, rates = sim.joints()
    assert abs(values[0] - 7.0) <= 1e-4 and abs(rates[0]) <= 1e-3
    now = sim.joint(hinge)
    r = sim.result()
    assert now.angle == pytest.approx(r.joint("hinge").angle[-1], abs=1e-12)
    assert now.rate == pytest.approx(r.joint("hinge").rate[-1], abs=1e-12)
    for bad in ([1.0, 2.0], "7", [[1.0, "a"]]):
        with pytest.raises(mb.ModelError, match="set_inputs takes"):
            sim.set_inputs(bad)
    with pytest.raises(mb.ModelError, match="input 'aim' must be a number, got 'x'"):
        sim.set_inputs(["x"])
    with pytest.raises(mb.ModelError, match="input 'aim' must be finite"):
        sim.set_inputs([float("nan")])
    with pytest.raises(mb.ModelError, match="not a revolute"):
        sim.joints(["servo"])


@pytest.mark.parametrize("given, message", [
    ({"kp": -1.0}, "kp"),
    ({"kd": -1.0}, "kd"),
    ({"limit": 0.0}, "limit must be > 0"),
])
def test_bad_servo_gains_are_refused(given, message):
    with pytest.raises(mb.ModelError, match=message):
        arm(target=0.0, **{"kp": 1.0, **given})


@pytest.mark.parametrize("given, message", [
    ({"target": math.nan}, "target must be finite, got nan"),
    ({"target": math.inf}, "target must be finite, got inf"),
    ({"feedforward": math.nan}, "feedforward must be finite, got nan"),
    ({"kp": 1e300}, r"kp = 1e\+300 is beyond 1e\+150 N m/rad, the largest lagmb takes for a gain or an input: the "
                    r"integrator's error norms square the forces it makes, and beyond that those squares overflow "
                    r"double precision \(1.8e308\)"),
    ({"kd": 1e200}, r"kd = 1e\+200 is beyond 1e\+150 N m s/rad"),
    ({"limit": 1e151}, r"limit = 1e\+151 is beyond 1e\+150 N m"),
])
def test_a_servo_value_beyond_what_a_run_can_hold_is_named_where_it_is_given(given, message):
    """Issue 56: kp = 1e300 was taken and the run failed at t = 0 with
    IDA_REP_RES_ERR, naming neither the servo nor the value; a target of nan
    was "Constant: c must be finite" (an internal class). Each names the
    servo, its argument and the value, at add_servo."""
    with pytest.raises(mb.ModelError, match="spatial joint servo 'servo': " + message):
        arm(**{"target": 0.0, "kp": 1.0, **given})


def test_a_servo_on_a_slide_names_its_gains_in_newtons():
    m = mb.Model(dimension=3)
    m.add_body("slider", mass=1.0, inertia=(0.1, 0.1, 0.1), position=(0.0, 0.0, 0.0))
    rail = m.add_translational("rail", "ground", "slider", at=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0))
    with pytest.raises(mb.ModelError, match=r"'servo': kp = 1e\+160 is beyond 1e\+150 N/m"):
        m.add_servo("servo", rail, target=0.0, kp=1e160)
    m.add_servo("servo", rail, target=0.0, kp=1e150)  # (the largest is taken)


def test_a_servo_needs_a_joint_with_a_coordinate():
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, 0.0))
    m.add_body("ball", mass=1.0, inertia=(0.1, 0.1, 0.1), position=(0.0, 0.0, 0.0))
    ball = m.add_spherical("ball_joint", "ground", "ball", at=(0.0, 0.0, 0.0))
    with pytest.raises(mb.ModelError, match="ball_joint"):
        m.add_servo("servo", ball, target=0.0, kp=1.0)
        mb.simulate(m, 0.1)


def test_auto_rates_a_servo_by_what_its_joint_moves():
    """A light hub (I = 1e-3 kg m^2) on a hinge with a heavy arm welded to
    it (10 kg at 0.5 m: I = 2.5 + 0.1 kg m^2 about the hinge), a servo with kp
    = I_total * (10 rad/s)^2: the automatic method rates the forces at 10
    1/s (the joints' inverse mass: every body the hinge carries), not at
    sqrt(kp / I_hub) = 510 1/s, and takes the explicit method."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, 0.0))
    m.add_body("hub", mass=0.1, inertia=(1e-3, 1e-3, 1e-3), position=(0.0, 0.0, 0.0))
    m.add_body("arm", mass=10.0, inertia=(0.1, 0.1, 0.1), position=(0.5, 0.0, 0.0))
    hinge = m.add_revolute("hinge", "ground", "hub", at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    m.add_weld("fix", "hub", "arm")
    total = 1e-3 + 0.1 + 10.0 * 0.5 ** 2
    m.add_servo("servo", hinge, target=0.3, kp=total * 100.0, kd=0.0)
    r = mb.simulate(m, 1.0, n_out=3)
    choice = r.stats["method_choice"]
    rate = float(choice.split("fastest rate ")[1].split(" ")[0])
    assert rate == pytest.approx(10.0, rel=1e-2), choice
    assert r.stats["method"] == "projection-erk"


def test_a_control_loop_at_1_khz_takes_one_low_order_step_per_tick():
    """A pendulum held by a PD law computed in Python every 1 ms (the torque
    an mb.Input, held between ticks), 300 ticks: the explicit method takes
    one step per tick, and once the ticks rather than its error test bound
    its steps it uses the order-4 pair (fewer stages for the same
    tolerance), each tick's step as long as the last (3.5 times it, the
    tick cutting it) without a new first-step estimate: at most 7
    right-hand sides per tick (6.1 seen; the order-8 pair took two steps
    and 31, each estimate 2 more), the angles within 1e-9 rad of the same
    loop at rtol 1e-11."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
    m.add_body("arm", mass=1.0, inertia=(0.01, 0.05, 0.05), position=(0.5, 0.0, 0.0))
    hinge = m.add_revolute("hinge", "ground", "arm", at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    m.add_rotational_spring_damper("motor", hinge, torque=mb.Input(0.0, "tau"))

    def loop(**options):
        sim = mb.Simulator(m, method="projection-erk", **options)
        for _ in range(300):
            (theta,), (rate,) = sim.joints(["hinge"])
            sim.set_inputs({"tau": 40.0 * (0.3 - theta) - 4.0 * rate - 9.81 * 0.5 * math.cos(theta)})
            sim.advance(sim.t + 1e-3)
        return sim.joints(["hinge"])[0][0], sim.stats

    angle, stats = loop(rtol=1e-6)
    reference, _ = loop(rtol=1e-11, atol=1e-13)
    assert stats["steps"] <= 301
    assert stats["residual_evals"] <= 7 * 300
    assert abs(angle - reference) <= 1e-9
