"""One continuous joint angle (issue 41, item 3).

A spatial revolute's angle is read from its bodies' orientations, atan2 in
(-pi, pi]: from a configuration alone it is known only up to whole turns.
A run counts the turns (model/joint_turns.hpp: after every step the angle
moves on from where it was, the whole turns chosen by the rates), and every
element that acts on the angle reads it within half a turn of that. So a
torsion spring winds through any number of turns, a coupling follows its
leader through them, and r.joint(name).angle is right however far apart
the outputs are. Each check is against a closed form or the planar model,
whose angles are coordinates and never wrap.
"""

import pickle

import numpy as np
import pytest

import lagmb as mb

I_AXIS = 0.01   # kg m^2, the wheel's inertia about its axle
SPIN = 50.0     # rad/s, the wheel's initial rate
TIGHT = dict(rtol=1e-10, atol=1e-12)


def wheel(dimension, stiffness=1.0, start=0.0):
    """A wheel on an axle along z through its centre, spun at SPIN, held by a
    torsion spring of `stiffness` (N m/rad; 0: none) relaxed at angle 0;
    in space the axle is a revolute whose angle starts at `start`."""
    if dimension == 3:
        m = mb.Model(dimension=3, gravity=(0.0, 0.0, 0.0))
        m.add_body("wheel", 1.0, (I_AXIS, I_AXIS, I_AXIS), angular_velocity=(0.0, 0.0, SPIN))
        m.add_revolute("axle", m.ground, "wheel", (0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0), angle=start)
        if stiffness:
            m.add_rotational_spring_damper("torsion", "axle", stiffness=stiffness)
    else:
        m = mb.Model(gravity=(0.0, 0.0))
        m.add_body("wheel", 1.0, I_AXIS, angular_velocity=SPIN)
        m.add_revolute("axle", m.ground, "wheel", (0.0, 0.0))
        if stiffness:
            m.add_rotational_spring_damper("torsion", m.ground, "wheel", stiffness=stiffness)
    return m


def test_a_torsion_wheel_winds_its_spring_to_five_radians_and_swings_back():
    # theta = (SPIN / omega) sin(omega t), omega = sqrt(k / I) = 10 rad/s:
    # wound to 50 / 10 = 5 rad at t = pi / 20, back through 0 at pi / 10
    omega = np.sqrt(1.0 / I_AXIS)
    t_out = np.linspace(0.0, 1.0, 401)
    t_out[50] = np.pi / (2 * omega)
    t_out = np.sort(t_out)
    space = mb.simulate(wheel(3), t_out=t_out, **TIGHT)
    plane = mb.simulate(wheel(2), t_out=t_out, **TIGHT)
    theta = space.joint("axle").angle
    assert theta.max() == pytest.approx(SPIN / omega, rel=1e-6)
    np.testing.assert_allclose(theta, SPIN / omega * np.sin(omega * t_out), atol=1e-6)
    np.testing.assert_allclose(theta, plane.joint("axle").angle, atol=1e-6)
    # the spring holds the energy it is given: nothing gained or lost
    E0 = 0.5 * I_AXIS * SPIN**2
    assert np.abs(space.energy - E0).max() < 1e-8 * E0


def test_the_angle_counts_turns_between_outputs_far_apart():
    # a free wheel (no spring) turns SPIN t: 50 rad (8 turns) in 1 s, and
    # three outputs say so; the joint starts at 3 rad (its given angle)
    r = mb.simulate(wheel(3, stiffness=0.0, start=3.0), t_end=1.0, n_out=3, **TIGHT)
    np.testing.assert_allclose(r.joint("axle").angle, 3.0 + SPIN * r.t, rtol=1e-9)
    # a cylindrical joint's angle counts its turns too
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, 0.0))
    m.add_body("wheel", 1.0, (I_AXIS, I_AXIS, I_AXIS), angular_velocity=(0.0, 0.0, SPIN))
    m.add_cylindrical("sleeve", m.ground, "wheel", (0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    turning = mb.simulate(m, t_end=1.0, n_out=3, **TIGHT)
    np.testing.assert_allclose(turning.joint("sleeve").angle, SPIN * turning.t, rtol=1e-9)
    # the count travels with the result (a process pool pickles it)
    copy = pickle.loads(pickle.dumps(r))
    np.testing.assert_array_equal(copy.joint("axle").angle, r.joint("axle").angle)


def test_a_driver_turns_a_joint_three_turns_in_three_outputs():
    # theta = 0.5 + 6 pi t: r.joint(...).angle ends at 0.5 + 6 pi, both in
    # the kinematic analysis (the driven wheel has no freedom left) and
    # integrating the dynamics
    for analysis in ("auto", "dynamic"):
        m = wheel(3, stiffness=0.0, start=0.5)
        m.drive_joint("motor", "axle", mb.Linear(6 * np.pi, 0.5))
        r = mb.simulate(m, t_end=1.0, n_out=3, analysis=analysis, **TIGHT)
        assert (r.stats["analysis"] == "dynamic") == (analysis == "dynamic")
        np.testing.assert_allclose(r.joint("axle").angle, 0.5 + 6 * np.pi * r.t, rtol=1e-9)


def coupled_wheels(dimension):
    """Two wheels on parallel axles; the second turns twice as fast as the
    first (in space a joint_coupling of the axles, multiplier 2; in the
    plane a gear, ratio 2); a torsion spring (k = 1) on the first. Started
    consistently: SPIN and 2 SPIN."""
    if dimension == 3:
        m = mb.Model(dimension=3, gravity=(0.0, 0.0, 0.0))
        for k, (name, rate) in enumerate((("first", SPIN), ("second", 2 * SPIN))):
            m.add_body(name, 1.0, (I_AXIS, I_AXIS, I_AXIS), (float(k), 0.0, 0.0), angular_velocity=(0.0, 0.0, rate))
            m.add_revolute(f"{name}_axle", m.ground, name, (float(k), 0.0, 0.0), axis=(0.0, 0.0, 1.0))
        m.add_joint_coupling("belt", "second_axle", "first_axle", multiplier=2.0)
        m.add_rotational_spring_damper("torsion", "first_axle", stiffness=1.0)
    else:
        m = mb.Model(gravity=(0.0, 0.0))
        for k, (name, rate) in enumerate((("first", SPIN), ("second", 2 * SPIN))):
            m.add_body(name, 1.0, I_AXIS, (float(k), 0.0), angular_velocity=rate)
            m.add_revolute(f"{name}_axle", m.ground, name, (float(k), 0.0))
        m.add_gear("belt", "first", "second", ratio=2.0)
        m.add_rotational_spring_damper("torsion", m.ground, "first", stiffness=1.0)
    return m


def test_a_coupling_follows_its_leader_through_several_turns():
    # the spring sees the inertia I + 2^2 I: omega = sqrt(1 / 0.05), and the
    # first wheel winds to SPIN / omega = 11.2 rad, the second to 22.4 rad
    # (3.6 turns) and back
    omega = np.sqrt(1.0 / (5 * I_AXIS))
    space = mb.simulate(coupled_wheels(3), t_end=1.5, n_out=301, **TIGHT)
    plane = mb.simulate(coupled_wheels(2), t_end=1.5, n_out=301, **TIGHT)
    first, second = space.joint("first_axle").angle, space.joint("second_axle").angle
    np.testing.assert_allclose(first, SPIN / omega * np.sin(omega * space.t), atol=1e-6)
    np.testing.assert_allclose(second, 2 * first, atol=1e-8)
    assert second.max() > 3 * 2 * np.pi
    np.testing.assert_allclose(first, plane.joint("first_axle").angle, atol=1e-6)
    np.testing.assert_allclose(second, plane.joint("second_axle").angle, atol=1e-6)
    E0 = 0.5 * I_AXIS * SPIN**2 + 0.5 * I_AXIS * (2 * SPIN)**2
    assert np.abs(space.energy - E0).max() < 1e-8 * E0


def test_joint_friction_slows_a_wheel_through_many_turns():
    # viscous c: theta = (SPIN I / c)(1 - exp(-c t / I)); c = 0.01 N m s/rad
    # lets it coast 50 rad (8 turns) in all
    c = 0.01
    m = wheel(3, stiffness=0.0)
    m.add_joint_friction("bearing", "axle", viscous=c)
    r = mb.simulate(m, t_end=2.0, n_out=5, **TIGHT)
    np.testing.assert_allclose(r.joint("axle").angle, SPIN * I_AXIS / c * (1 - np.exp(-c * r.t / I_AXIS)),
                               rtol=1e-8)


def test_a_simulator_restored_past_a_turn_and_a_half_counts_on_from_there():
    # k = 0.1: omega = sqrt(10), wound to 15.8 rad (2.5 turns); saved at
    # t = 0.25 (10.3 rad, past 1.5 turns), run on, restored and run on again
    k = 0.1
    omega = np.sqrt(k / I_AXIS)
    exact = lambda t: SPIN / omega * np.sin(omega * t)  # noqa: E731
    sim = mb.Simulator(wheel(3, stiffness=k), **TIGHT)
    sim.advance(0.25)
    saved = sim.state()
    sim.advance(0.45)
    sim.set_state(saved)
    sim.advance(0.4)
    r = sim.result()
    assert r.t[-1] == pytest.approx(0.4)
    assert exact(0.25) > 3 * np.pi
    np.testing.assert_allclose(r.joint("axle").angle, exact(r.t), atol=1e-6)


def test_joint_space_reads_an_angle_past_pi_from_its_initial_one():
    # without a run, a configuration's angle is read within half a turn of
    # the joint's initial angle (3 rad here): 3.5 rad is 3.5, not 3.5 - 2 pi
    js = mb.JointSpace(wheel(3, stiffness=0.0, start=3.0))
    q, v, _ = js.coordinates({"axle": 3.5}, {"axle": 2.0})
    value, rate, _ = js.motion("axle", q, v)
    assert value == pytest.approx(3.5, abs=1e-12)
    assert rate == pytest.approx(2.0, abs=1e-12)


def test_a_step_that_turns_a_read_joint_half_a_turn_stops_the_run():
    # ali3p's fixed step of 0.1 s turns the wheel 5 rad: its spring would
    # read the angle across the wrap; the run says so instead of going on
    with pytest.raises(mb.SimulationError, match="half a turn"):
        mb.simulate(wheel(3), t_end=0.5, formulation="ali3p", step=0.1)


def test_counting_turns_adds_no_event_functions():
    # the count is kept after each step, not by root finding: a spatial
    # model with revolutes and springs on them has no event functions and
    # no events (the planar chain's costs: test_effect_costs.py)
    r = mb.simulate(coupled_wheels(3), t_end=0.5)
    assert r.stats["root_evals"] == 0 and r.stats["events"] == 0 and r.events == []
    assert r._run_state.shape == (len(r.t), 4)  # two doubles per turning joint


def test_a_joint_given_an_angle_past_pi_reads_it_in_a_run():
    # a revolute given angle=3.96 in its initial configuration (a robot
    # built at a joint value past pi): the run's angle starts at 3.96, not at
    # 3.96 - 2 pi, and counts on from there (free spin at SPIN: 3.96 + SPIN t)
    r = mb.simulate(wheel(3, stiffness=0.0, start=3.96), t_end=0.1, n_out=3, **TIGHT)
    assert r.joint("axle").angle == pytest.approx(3.96 + SPIN * r.t, abs=1e-8)
