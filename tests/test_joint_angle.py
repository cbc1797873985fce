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


def test_the_angle_counts_turns_between_outputs_far_apart():
    # a free wheel (no spring) turns SPIN t: 50 rad (8 turns) in 1 s, and
    # three outputs say so; the joint starts at 3 rad (its given angle)
    r = mb.simulate(wheel(3, stiffness=0.0, start=3.0), t_end=1.0, n_out=3, **TIGHT)
    np.testing.assert_allclose(r.joint("axle").angle, 3.0 + SPIN * r.t, rtol=1e-9)


def test_a_driver_turns_a_joint_three_turns_in_three_outputs():
    # theta = 0.5 + 6 pi t: r.joint(...).angle ends at 0.5 + 6 pi, both in
    # the kinematic analysis (the driven wheel has no freedom left) and
    # integrating the dynamics
    for analysis in ("auto", "dynamic"):
        m = wheel(3, stiffness=0.0, start=0.5)
        m.drive_joint("motor", "axle", mb.Linear(6 * np.pi, 0.5))
        r = mb.simulate(m, t_end=1.0, n_out=3, analysis=analysis, **TIGHT)
        np.testing.assert_allclose(r.joint("axle").angle, 0.5 + 6 * np.pi * r.t, rtol=1e-9)


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
    # a free wheel turns SPIN t: saved at t = 0.2 (10 rad, past 1.5 turns),
    # run on, restored and run on again
    sim = mb.Simulator(wheel(3, stiffness=0.0), **TIGHT)
    sim.advance(0.2)
    saved = sim.state()
    sim.advance(0.45)
    sim.set_state(saved)
    sim.advance(0.4)
    r = sim.result()
    assert r.t[-1] == pytest.approx(0.4)
    np.testing.assert_allclose(r.joint("axle").angle, SPIN * r.t, rtol=1e-9)


def test_joint_space_reads_an_angle_past_pi_from_its_initial_one():
    # without a run, a configuration's angle is read within half a turn of
    # the joint's initial angle (3 rad here): 3.5 rad is 3.5, not 3.5 - 2 pi
    js = mb.JointSpace(wheel(3, stiffness=0.0, start=3.0))
    q, v, _ = js.coordinates({"axle": 3.5}, {"axle": 2.0})
    value, rate, _ = js.motion("axle", q, v)
    assert value == pytest.approx(3.5, abs=1e-12)
    assert rate == pytest.approx(2.0, abs=1e-12)
