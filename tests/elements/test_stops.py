"""Joint stops: impacts found by the integrators' root finding.

References (all closed form, none from lagmb):
- pendulum: a uniform rod (L = 1, m = 1, J_O = m L^2 / 3) released at rest
  from the horizontal reaches the vertical after a quarter of its period,
  t* = sqrt(2 L / (3 g)) K(1/2) (K: the complete elliptic integral of the
  first kind, scipy.special.ellipk with parameter m = 1/2), with angular
  speed sqrt(3 g / L) (energy: J_O w^2 / 2 = m g L / 2);
- slider: a block on a frictionless incline at angle a under gravity has the
  constant acceleration g sin(a) along it; from rest it slides d in
  t* = sqrt(2 d / (g sin a)) and hits at v* = g sin(a) t*; a rebound at
  e v* returns after 2 e v* / (g sin a).
Each formulation gets the same checks: IDA (ggl, index3, index1) and CVODE
(projection).
"""

import math

import numpy as np
import pytest
from scipy.special import ellipk

import lagmb as mb
import builders

G = 9.81
FORMULATIONS = ["ggl", "index3", "index1", "projection"]
# index-3 BDF resolves the event time only to O(tol / h) (see dae.hpp): looser
TIME_TOL = {"ggl": 1e-8, "index3": 1e-6, "index1": 1e-8, "projection": 1e-8}


def pendulum(restitution, lower=-math.pi / 2, angle=0.0, angular_velocity=0.0, **stop):
    m = builders.pendulum(g=G, angle=angle, angular_velocity=angular_velocity)
    m.add_stop("stop", "pin", lower=lower, restitution=restitution, **stop)
    return m


def incline(restitution, a=math.radians(30.0), d=0.3, **stop):
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", mass=2.0, inertia=0.1, position=(0.0, 0.0))
    m.add_translational("rail", m.ground, block, at=(0.0, 0.0), axis=(math.cos(a), math.sin(a)))
    m.add_stop("end", "rail", lower=-d, restitution=restitution, **stop)
    return m


@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_pendulum_hits_stop_at_quarter_period(formulation):
    """Impact time = the closed-form quarter period (to 1e-8 s; index3 1e-6),
    impact speed sqrt(3 g) (1e-6 relative), rebound e times it (1e-6), and
    after the impact the energy is J_O (e w)^2 / 2 - m g L / 2 (1e-6 J;
    index3, whose velocities are only index-2 accurate, 1e-5 J)."""
    e = 0.5
    r = mb.simulate(pendulum(e), t_end=0.9, rtol=1e-10, atol=1e-12, formulation=formulation, n_out=91)
    t_star = math.sqrt(2.0 / (3.0 * G)) * float(ellipk(0.5))
    w = math.sqrt(3.0 * G)
    first = r.events[0]
    assert first["element"] == "stop" and first["kind"] == "impact" and first["label"] == "lower"
    assert abs(first["t"] - t_star) <= TIME_TOL[formulation]
    assert abs(first["speed_before"] + w) <= 1e-6 * w
    assert abs(first["speed_after"] - e * w) <= 1e-6 * w
    assert r.stats["impacts"] == len(r.events) == 1
    after = r.t > t_star
    energy = 0.5 * (1.0 / 3.0) * r.v[after, 2] ** 2 + G * r.q[after, 1]
    energy_tol = 1e-5 if formulation == "index3" else 1e-6
    assert np.max(np.abs(energy - (0.5 * (1.0 / 3.0) * (e * w) ** 2 - 0.5 * G))) <= energy_tol
    # the joint never goes through the stop
    assert np.min(r.q[:, 2]) >= -math.pi / 2 - 1e-9


@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_slider_hits_translational_stop(formulation):
    """Block on a 30 deg incline, stop 0.3 m down the rail, e = 0.6: first
    impact at sqrt(2 d / (g sin a)) (1e-8 s; index3 1e-6), speed g sin(a) t*
    (1e-6 relative), rebound e v*, second impact 2 e v* / (g sin a) later."""
    e, a, d = 0.6, math.radians(30.0), 0.3
    acc = G * math.sin(a)
    t1 = math.sqrt(2.0 * d / acc)
    v1 = acc * t1
    t2 = t1 + 2.0 * e * v1 / acc
    r = mb.simulate(incline(e), t_end=t2 + 0.05, rtol=1e-10, atol=1e-12, formulation=formulation)
    ev = r.events
    assert [x["kind"] for x in ev] == ["impact", "impact"]
    assert abs(ev[0]["t"] - t1) <= TIME_TOL[formulation]
    assert abs(ev[0]["speed_before"] + v1) <= 1e-6 * v1
    assert abs(ev[0]["speed_after"] - e * v1) <= 1e-6 * v1
    assert abs(ev[1]["t"] - t2) <= 10 * TIME_TOL[formulation]
    assert abs(ev[1]["speed_before"] + e * v1) <= 1e-6 * v1
    # the rail keeps its joint through the jumps
    assert np.max(r.residual) <= 1e-9
    assert np.max(r.velocity_residual) <= 1e-7


@pytest.mark.parametrize("formulation", ["ggl", "projection"])
def test_bouncing_on_the_incline_comes_to_rest_on_the_stop(formulation):
    """e = 0.5 on the incline: the bounce speeds are e^k v* at the closed-form
    times t1 + sum_{i<k} 2 e^(i+1) v* / (g sin a) (1e-6 s); the first rebound
    slower than rest_speed = 1e-2 m/s is captured at its impact (the run goes
    on: the block rests on the stop, which carries m g sin a, 1e-9)."""
    e, a, d, rest = 0.5, math.radians(30.0), 0.3, 1e-2
    acc = G * math.sin(a)
    t1 = math.sqrt(2.0 * d / acc)
    v1 = acc * t1
    times, speeds, t, v = [], [], t1, v1
    while True:
        times.append(t)
        speeds.append(v)
        if e * v < rest:
            break
        t += 2.0 * e * v / acc
        v *= e
    r = mb.simulate(incline(e, rest_speed=rest), t_end=3.0, rtol=1e-10, atol=1e-12, formulation=formulation,
                    n_out=301)
    ev = r.events
    assert [x["kind"] for x in ev] == ["impact"] * len(times) + ["capture"]
    assert abs(ev[-1]["t"] - times[-1]) <= 1e-6
    for x, tk, vk in zip(ev, times, speeds):
        assert abs(x["t"] - tk) <= 1e-6
        assert abs(x["speed_before"] + vk) <= 1e-6 * v1
    resting = r.t > times[-1]
    assert np.max(np.abs(r.joint("rail").slide[resting] + d)) <= 1e-10
    assert np.max(np.abs(r.effort("end")[resting] - 2.0 * acc)) <= 1e-9 * 2.0 * acc


def test_plastic_impact_pressed_on_the_stop_is_resting():
    """e = 0 with gravity pressing the block down the incline: it comes to
    rest at the first impact (t1 closed form, 1e-8 s), captured: the stop
    then carries m g sin(a) (1e-9) and the block stays at the limit (1e-10 m)."""
    acc = G * math.sin(math.radians(30.0))
    t1 = math.sqrt(2.0 * 0.3 / acc)
    r = mb.simulate(incline(0.0), t_end=1.0, rtol=1e-10, atol=1e-12)
    assert [x["kind"] for x in r.events] == ["impact", "capture"]
    assert abs(r.events[0]["t"] - t1) <= 1e-8
    assert r.events[0]["speed_after"] == pytest.approx(0.0, abs=1e-12)
    resting = r.t > t1
    assert np.max(np.abs(r.joint("rail").slide[resting] + 0.3)) <= 1e-10
    assert np.max(np.abs(r.effort("end")[resting] - 2.0 * acc)) <= 1e-9 * 2.0 * acc


@pytest.mark.parametrize("formulation", ["ggl", "projection"])
def test_plastic_impact_then_falling_back(formulation):
    """e = 0 where gravity pulls away from the limit: the hanging rod swung
    up at w0 = 4 rad/s hits the upper stop at -pi/4 (speed from energy:
    w^2 = w0^2 - 3 g sin(pi/4) ... closed form below, 1e-6), stops dead there
    and falls back: afterwards its energy is that of rest at -pi/4, i.e.
    -m g (L/2) cos(pi/4) (1e-6 J), and it swings down to -3 pi/4 at most."""
    m = mb.Model(gravity=(0.0, -G))
    w0 = 4.0
    rod = m.add_body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.0, -0.5), angle=-math.pi / 2,
                     velocity=(0.5 * w0, 0.0), angular_velocity=w0)
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    m.add_stop("stop", "pin", upper=-math.pi / 4, restitution=0.0)
    r = mb.simulate(m, t_end=0.8, rtol=1e-10, atol=1e-12, formulation=formulation, n_out=801)
    # J_O w^2 / 2 = J_O w0^2 / 2 - m g (L/2) (cos(pi/4) ... height gain of the centre)
    w_hit = math.sqrt(w0**2 - 2.0 * G * 0.5 * (1.0 - math.cos(math.pi / 4)) / (1.0 / 3.0))
    ev = r.events
    assert ev[0]["label"] == "upper"
    assert abs(ev[0]["speed_before"] + w_hit) <= 1e-6 * w_hit
    assert ev[0]["speed_after"] == pytest.approx(0.0, abs=1e-12)
    after = r.t > ev[0]["t"] + 1e-9
    energy = 0.5 * (1.0 / 3.0) * r.v[after, 2] ** 2 + G * r.q[after, 1]
    assert np.max(np.abs(energy + G * 0.5 * math.cos(math.pi / 4))) <= 1e-6
    assert np.min(r.q[after, 2]) >= -3 * math.pi / 4 - 1e-6
    assert np.max(r.q[:, 2]) <= -math.pi / 4 + 1e-9


def test_starting_at_the_limit():
    """At the limit and moving into it: the impact happens at t0 (speed
    2 rad/s, rebound e * 2); at the limit and moving away: no event; beyond
    the limit: ValueError naming the stop."""
    r = mb.simulate(pendulum(0.5, lower=0.0, angular_velocity=-2.0), t_end=0.05, rtol=1e-10, atol=1e-12)
    assert r.events[0]["t"] == 0.0
    assert abs(r.events[0]["speed_before"] + 2.0) <= 1e-9
    assert abs(r.v[0, 2] - 1.0) <= 1e-9  # the recorded initial state is after the jump
    r = mb.simulate(pendulum(0.5, lower=0.0, angular_velocity=2.0), t_end=0.05, rtol=1e-10, atol=1e-12)
    assert r.events == []
    with pytest.raises(ValueError, match="stop 'stop'.*beyond its lower limit"):
        mb.simulate(pendulum(0.5, lower=0.1), t_end=0.05)


def test_bad_stops_are_rejected():
    """Unknown joint, a joint that is not a revolute or translational,
    lower >= upper, restitution outside [0, 1], no limit: ValueError naming
    the stop."""
    m = mb.Model(gravity=(0.0, -G))
    a = m.add_body("a", mass=1.0, inertia=0.1, position=(0.5, 0.0))
    b = m.add_body("b", mass=1.0, inertia=0.1, position=(1.5, 0.0))
    m.add_revolute("pin", m.ground, a, at=(0.0, 0.0))
    m.add_weld("glue", a, b)
    with pytest.raises(ValueError, match="stop 's1'.*'nope' is not a joint of this model"):
        m.add_stop("s1", "nope", lower=0.0)
    with pytest.raises(ValueError, match="stop 's2'.*not a revolute or translational"):
        m.add_stop("s2", "glue", lower=0.0)
    with pytest.raises(ValueError, match="stop 's3'.*lower = 1 must be below upper = -1"):
        m.add_stop("s3", "pin", lower=1.0, upper=-1.0)
    with pytest.raises(ValueError, match="stop 's4'.*restitution must be in \\[0, 1\\]"):
        m.add_stop("s4", "pin", lower=-1.0, restitution=1.5)
    with pytest.raises(ValueError, match="stop 's5'.*lower or an upper"):
        m.add_stop("s5", "pin")


@pytest.mark.parametrize("formulation", ["ggl", "projection"])
def test_a_stop_never_reached_changes_nothing(formulation):
    """A stop that is never reached leaves the motion as without it (to the
    run's accuracy at rtol 1e-8: 1e-6 rad)
    and logs no event; a model without stops evaluates no root function. (The
    step counts are not compared: they move with rounding -- a change of
    4e-16 in the rod's mass changes them by some 9 % at rtol 1e-8 -- and the
    stop's rows, left out while open, change the order of a factorization's
    sums.)"""
    plain = mb.Model(gravity=(0.0, -G))
    rod = plain.add_body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0))
    plain.add_revolute("pin", plain.ground, rod, at=(0.0, 0.0))
    r0 = mb.simulate(plain, t_end=2.0, rtol=1e-8, formulation=formulation)
    r1 = mb.simulate(pendulum(0.5, lower=-3.5), t_end=2.0, rtol=1e-8, formulation=formulation)
    assert r0.stats["root_evals"] == 0 and r0.events == []
    assert r1.stats["root_evals"] > 0 and r1.events == [] and r1.stats["captures"] == 0
    assert np.max(np.abs(r1.joint("pin").angle - r0.joint("pin").angle)) <= 1e-6
    assert np.all(r1.effort("stop") == 0.0)


def test_stop_in_a_scene_file(tmp_path):
    """A [[stops]] table reads into the same model: the same impact to the bit."""
    m = pendulum(0.5)
    path = tmp_path / "stop.toml"
    mb.save_scene(m, path, settings={"t_end": 0.6, "rtol": 1e-9})
    scene = mb.load_scene(path)
    assert "[[stops]]" in path.read_text()
    r1, r2 = scene.run(), mb.simulate(m, t_end=0.6, rtol=1e-9)
    assert r1.events == r2.events and len(r1.events) == 1
    bad = path.read_text().replace("restitution = 0.5", "restitution = 0.5\nbounce = 1")
    path.write_text(bad)
    with pytest.raises(mb.SceneError, match="stops\\[0\\] 'stop', key 'bounce'"):
        mb.load_scene(path)


@pytest.mark.parametrize("formulation", ["ggl", "projection"])
def test_elastic_elbow_stop_conserves_energy(formulation):
    """Double pendulum (two uniform rods from the horizontal) with an elbow
    stop |phi_b - phi_a| <= 0.5 and e = 1: the impulses act on both moving
    bodies; perfectly elastic impacts keep the energy (conservation law:
    spread below 1e-6 J over 3 s and at least 3 impacts), the joints hold
    (|Phi| < 1e-9) and the elbow stays within its limits (1e-9 rad)."""
    m = mb.Model(gravity=(0.0, -G))
    a = m.add_body("a", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0))
    b = m.add_body("b", mass=1.0, inertia=1.0 / 12.0, position=(1.5, 0.0))
    m.add_revolute("p0", m.ground, a, at=(0.0, 0.0))
    m.add_revolute("p1", a, b, at=(1.0, 0.0))
    m.add_stop("elbow", "p1", lower=-0.5, upper=0.5, restitution=1.0)
    r = mb.simulate(m, t_end=3.0, rtol=1e-10, atol=1e-12, n_out=301, formulation=formulation)
    assert r.stats["impacts"] >= 3
    assert all(abs(x["speed_after"] + x["speed_before"]) <= 1e-9 * abs(x["speed_before"]) for x in r.events)
    assert np.ptp(r.energy) <= 1e-6
    assert np.max(r.residual) <= 1e-9
    rel = r.q[:, 5] - r.q[:, 2]
    assert rel.min() >= -0.5 - 1e-9 and rel.max() <= 0.5 + 1e-9


def test_a_driver_pushing_through_its_own_stop_is_refused():
    """A pendulum whose pin angle is driven at -1 rad/s against a stop at
    -0.5 rad: no impulse can change a prescribed motion (the joints leave no
    mobility along the limit), so the run stops at the limit, t = 0.5 s,
    naming the stop, instead of recording impacts that never happen. The
    kinematic analysis, which cannot see events, is not chosen."""
    m = builders.pendulum()
    m.add_stop("st", "pin", lower=-0.5, restitution=0.5)
    m.drive_joint("d", "pin", mb.Linear(-1.0))
    with pytest.raises(mb.SimulationError, match="'st'.*prescribe") as info:
        mb.simulate(m, 1.0)
    assert abs(info.value.t - 0.5) < 1e-8
    assert info.value.result.stats["analysis"] == "dynamic"
    assert len(info.value.result.t) >= 50


def test_rest_speed_must_be_positive():
    """rest_speed = 0 would let rebounds shrink to rounding level before the
    rest test fires."""
    m = builders.pendulum()
    with pytest.raises(ValueError, match="rest_speed"):
        m.add_stop("st", "pin", lower=-0.5, restitution=0.5, rest_speed=0.0)


def test_equilibrium_beyond_a_stop_is_refused():
    """A pendulum hanging at -pi/2 with a stop at -1 rad: the unconstrained
    equilibrium lies beyond the limit and resting on a stop is not
    modelled, so mb.equilibrium says so, naming the stop (by 0.5708 rad)."""
    m = builders.pendulum()
    m.add_stop("st", "pin", lower=-1.0, restitution=0.5)
    with pytest.raises(mb.EquilibriumError, match=r"'st' \(by 0\.5707") :
        mb.equilibrium(m)


@pytest.mark.parametrize("formulation", ["ggl", "projection"])
def test_a_spatial_stop_acts_as_the_planar_one(formulation):
    """The pendulum of test_pendulum_hits_stop_at_quarter_period in space: a
    1 m rod level along x, hinged at the origin about -y (so that falling is
    a negative angle), gravity -z, a lower stop at -pi/2 with e = 0.5: the
    impact at the closed-form quarter period (1e-8 s), speed sqrt(3 g) and
    rebound e sqrt(3 g) (1e-6 relative); and a block on a 30 deg incline
    stopped by a translational stop as test_slider_hits_translational_stop's
    (times 1e-8 s, speeds 1e-6)."""
    e = 0.5
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    rod = m.add_body("rod", 1.0, (1e-3, 1.0 / 12.0, 1.0 / 12.0), position=(0.5, 0.0, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, -1.0, 0.0))
    m.add_stop("stop", "pin", lower=-math.pi / 2, restitution=e)
    r = mb.simulate(m, t_end=0.9, rtol=1e-10, atol=1e-12, formulation=formulation, n_out=91)
    t_star = math.sqrt(2.0 / (3.0 * G)) * float(ellipk(0.5))
    w = math.sqrt(3.0 * G)
    first = r.events[0]
    assert first["element"] == "stop" and first["kind"] == "impact" and first["label"] == "lower"
    assert abs(first["t"] - t_star) <= 1e-8
    assert abs(first["speed_before"] + w) <= 1e-6 * w
    assert abs(first["speed_after"] - e * w) <= 1e-6 * w
    assert np.min(r.joint("pin").angle) >= -math.pi / 2 - 1e-9

    e, a, d = 0.6, math.radians(30.0), 0.3
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    block = m.add_body("block", 2.0, (0.1, 0.1, 0.1))
    m.add_translational("rail", m.ground, block, at=(0.0, 0.0, 0.0), axis=(math.cos(a), 0.0, math.sin(a)))
    m.add_stop("end", "rail", lower=-d, restitution=e)
    acc = G * math.sin(a)
    t1 = math.sqrt(2.0 * d / acc)
    v1 = acc * t1
    r = mb.simulate(m, t_end=t1 + 0.05, rtol=1e-10, atol=1e-12, formulation=formulation)
    assert [x["kind"] for x in r.events] == ["impact"]
    assert abs(r.events[0]["t"] - t1) <= 1e-8
    assert abs(r.events[0]["speed_before"] + v1) <= 1e-6 * v1
    assert abs(r.events[0]["speed_after"] - e * v1) <= 1e-6 * v1
    assert np.max(r.residual) <= 1e-9


def test_a_spatial_stop_takes_a_revolute_or_translational_joint():
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    rod = m.add_body("rod", 1.0, (1e-3, 1.0 / 12.0, 1.0 / 12.0), position=(0.5, 0.0, 0.0))
    m.add_cylindrical("cyl", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    with pytest.raises(mb.ModelError, match="'cyl' turns and slides"):
        m.add_stop("stop", "cyl", lower=-1.0)


def test_a_spatial_stop_holds_limits_turns_apart():
    """The stop reads the joint's angle with its turns counted: a wheel
    spinning at 10 rad/s about a vertical axis (no torque) between limits
    -2 pi - 1 and 6 pi + 1 hits the upper one at t1 = (6 pi + 1) / 10 and,
    with e = 0.5, the lower one (8 pi + 2) / 5 later (closed form, 1e-8 s),
    the angle never beyond either (1e-8 rad)."""
    lower, upper = -2 * math.pi - 1.0, 6 * math.pi + 1.0
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    wheel = m.add_body("wheel", 1.0, (0.5, 0.5, 1.0), angular_velocity=(0.0, 0.0, 10.0))
    m.add_revolute("axle", m.ground, wheel, at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    m.add_stop("stop", "axle", lower=lower, upper=upper, restitution=0.5)
    t1 = upper / 10.0
    t2 = t1 + (upper - lower) / 5.0
    r = mb.simulate(m, t_end=t2 + 0.5, rtol=1e-10, atol=1e-12, n_out=301)
    assert [(x["kind"], x["label"]) for x in r.events[:2]] == [("impact", "upper"), ("impact", "lower")]
    assert abs(r.events[0]["t"] - t1) <= 1e-8 and abs(r.events[1]["t"] - t2) <= 1e-8
    angle = r.joint("axle").angle
    assert np.all(angle <= upper + 1e-8) and np.all(angle >= lower - 1e-8)
    assert angle.max() > upper - 0.1 and angle.min() < lower + 0.1


def test_a_spatial_stop_holds_a_limit_beyond_pi():
    """A spatial angle is read with its turns: the rod, hinged about -y and
    started level turning at 8 rad/s (so the angle rises through pi), hits an
    upper limit at 3.6 rad, and the angle never passes it."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    rod = m.add_body("rod", 1.0, (1e-3, 1.0 / 12.0, 1.0 / 12.0), position=(0.5, 0.0, 0.0),
                     velocity=(0.0, 0.0, 4.0), angular_velocity=(0.0, -8.0, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, -1.0, 0.0))
    m.add_stop("stop", "pin", lower=-0.5, upper=3.6, restitution=0.5)
    r = mb.simulate(m, t_end=1.0, rtol=1e-10, atol=1e-12, n_out=1001)
    impact = r.events[0]
    assert impact["label"] == "upper" and impact["kind"] == "impact"
    angle = r.joint("pin").angle  # continued across pi from output to output
    before = r.t <= impact["t"]
    assert angle[before].max() <= 3.6 + 1e-8 and angle[before].max() > 3.5
    assert abs(impact["speed_after"] + 0.5 * impact["speed_before"]) <= 1e-6 * abs(impact["speed_before"])


def two_pendulums(restitution, dimension=2, apart=0.0):
    """Two separate 1 m, 1 kg rods released level side by side, each hinged
    at one end and falling onto its own lower stop at -pi/2 (the second's
    limit `apart` rad lower): two impacts at the same instant that nothing
    couples."""
    if dimension == 2:
        m = mb.Model(gravity=(0.0, -G))
    else:
        m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    for i, x in enumerate([0.0, 2.0]):
        if dimension == 2:
            rod = m.add_body(f"rod{i}", mass=1.0, inertia=1.0 / 12.0, position=(x + 0.5, 0.0))
            m.add_revolute(f"pin{i}", m.ground, rod, at=(x, 0.0))
        else:
            rod = m.add_body(f"rod{i}", 1.0, (1e-3, 1.0 / 12.0, 1.0 / 12.0), position=(x + 0.5, 0.0, 0.0))
            m.add_revolute(f"pin{i}", m.ground, rod, at=(x, 0.0, 0.0), axis=(0.0, -1.0, 0.0))
        m.add_stop(f"stop{i}", f"pin{i}", lower=-math.pi / 2 - (apart if i else 0.0), restitution=restitution)
    return m


@pytest.mark.parametrize("method", ["ggl", "index3", "index1", "projection-bdf", "projection-adams", "projection-erk"])
@pytest.mark.parametrize("dimension", [2, 3])
def test_independent_stops_struck_at_the_same_instant_each_rebound_by_their_own_restitution(method, dimension):
    """Each rod strikes at sqrt(3 g) (1e-6 relative; index3 1e-4) and leaves
    at e times its approach (e = 1 and 0.5), whether the limits are equal or 1e-9 rad apart (the
    root functions flag one, the other is within rounding of its limit):
    two impacts the joints do not couple are no plastic impact (both were
    captured at 0 rad/s, all energy lost at e = 1, under GGL and
    projection-bdf)."""
    w = math.sqrt(3.0 * G)
    for e, apart in [(1.0, 0.0), (0.5, 1e-9)]:
        r = mb.simulate(two_pendulums(e, dimension, apart), t_end=0.7, rtol=1e-8, method=method)
        impacts = [x for x in r.events if x["kind"] == "impact"][:2]
        assert sorted(x["element"] for x in impacts) == ["stop0", "stop1"]
        for x in impacts:  # (index3's velocities are only index-2 accurate)
            assert x["speed_before"] == pytest.approx(-w, rel=1e-4 if method == "index3" else 1e-6)
            assert x["speed_after"] == pytest.approx(-e * x["speed_before"], rel=1e-9)
        assert not [x for x in r.events if x["kind"] == "capture"]
