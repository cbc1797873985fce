"""Stops cost nothing where nothing happens (issue 58): a control loop that
changes its inputs every tick, with joint limits that are never struck,
takes the same steps, right-hand sides, factorizations and projections as
the same loop without the limits, and its motion is the same.

A 3-link planar chain of rods (L = 1 m, m = 1 kg) hangs from a pin; a PD
law from Python (kp = 50 N m/rad, kd = 5 N m s/rad) drives each joint
towards q*(t) = 0.3 sin(pi t) at 1 kHz for 0.2 s through torque inputs,
by the explicit Runge-Kutta method at order 4 (the order a 1 kHz loop's
steps take: Simulator.advance resumes at order 4 where the ticks bound the
steps; at order 8, ARKODE's degree-5 interpolant at each stop time costs
two right-hand sides more where there are event functions).
Counts are deterministic: equality is exact. The formulation's right-hand
side at a step's end is shared by the root functions, the output and the
next step's first stage (Stepper::motion_at); an input change at the
state the steps reached continues from it without a projection
(Run::resume_in_place); a stop resting open on its limit, held there by
another (a mimic finger's), costs no solve (EventRunner::rest_contacts).
"""

import numpy as np
import pytest

import lagmb as mb

G = 9.81
TICK, TICKS = 1e-3, 200
KP, KD = 50.0, 5.0


def chain(stops=None, wheels=False, wheel_stops=True):
    """The hanging chain with a torque input at each pin; `stops`: limits
    (lower, upper) on every pin; `wheels`: two wheels pinned at their
    centres and geared together (ratio -1), each on a limit at its start
    (`wheel_stops`: the first's lower, the second's upper)."""
    m = mb.Model(gravity=(0.0, -G))
    prev = m.ground
    for k in range(3):
        rod = m.add_body(f"rod{k}", mass=1.0, inertia=1 / 12, position=(0.0, -k - 0.5), angle=-np.pi / 2)
        pin = m.add_revolute(f"pin{k}", prev, rod, at=(0.0, -float(k)))
        m.add_rotational_spring_damper(f"motor{k}", prev, rod, torque=mb.Input(0.0))
        if stops:
            m.add_stop(f"pin{k}_limit", pin, lower=stops[0], upper=stops[1])
        prev = rod
    if wheels:
        for k in range(2):
            wheel = m.add_body(f"wheel{k}", mass=0.5, inertia=0.01, position=(2.0 + 0.2 * k, 0.0))
            m.add_revolute(f"axle{k}", m.ground, wheel, at=(2.0 + 0.2 * k, 0.0))
        m.add_gear("mesh", "wheel0", "wheel1", ratio=-1.0, center_i=(2.0, 0.0), center_j=(2.2, 0.0))
        if wheel_stops:
            m.add_stop("axle0_limit", "axle0", lower=0.0)
            m.add_stop("axle1_limit", "axle1", upper=0.0)
    return m


def loop(model, **options):
    """The 1 kHz PD loop through a Simulator: (joint angles per tick, the
    loop's counts: the simulator's stats less those of its start)."""
    sim = mb.Simulator(model, method="projection-erk", max_order=4, **options)
    start = dict(sim.stats)
    names = [f"pin{k}" for k in range(3)]
    out = np.empty((TICKS, 3))
    for i in range(TICKS):
        angle, rate = sim.joints(names)
        out[i] = angle
        tau = KP * (0.3 * np.sin(np.pi * sim.t) - angle) - KD * rate
        sim.set_inputs({f"motor{k}": float(tau[k]) for k in range(3)})
        sim.advance(sim.t + TICK)
    return out, {k: v - start[k] if isinstance(v, int) else v for k, v in sim.stats.items()}


COUNTS = ("steps", "residual_evals", "augmented_factorizations", "projections", "restarts", "input_changes")


def test_limits_never_struck_cost_no_steps_solves_or_projections():
    free, free_stats = loop(chain())
    limited, limited_stats = loop(chain(stops=(-2.5, 2.5)))
    assert {k: limited_stats[k] for k in COUNTS} == {k: free_stats[k] for k in COUNTS}
    assert limited_stats["events"] == 0 and limited_stats["root_evals"] > 0
    assert np.max(np.abs(limited - free)) <= 1e-12


def test_an_input_change_continues_from_the_step_it_ends():
    """One step per tick (the ticks bound them), one projection per step:
    the step's own; an input change adds none."""
    _, stats = loop(chain(stops=(-2.5, 2.5)))
    assert stats["input_changes"] == TICKS - 1
    assert stats["projections"] == stats["steps"]


def test_a_stop_resting_open_on_its_limit_costs_no_solve():
    """Two wheels pinned at their centres (gravity has no moment on them)
    and geared together, each on a limit where it starts: nothing presses
    them on, so they rest there open, the second's stop duplicating the
    first's through the gear. The loop's counts and motion equal those of
    the same loop without the wheels' stops: at each input change the stops
    at rest are looked at with the accelerations the step's end has, and
    cost no solve of their own."""
    resting, resting_stats = loop(chain(stops=(-2.5, 2.5), wheels=True))
    free, free_stats = loop(chain(stops=(-2.5, 2.5), wheels=True, wheel_stops=False))
    assert resting_stats["events"] == 0
    assert {k: resting_stats[k] for k in COUNTS} == {k: free_stats[k] for k in COUNTS}
    assert np.max(np.abs(resting - free)) <= 1e-12


def test_a_closed_stop_evaluates_its_own_element_only():
    """A pendulum pressed by gravity on its stop (closed) beside two stops
    far from their limits on other joints: the stop group's kernels evaluate
    the closed stop alone, so the run evaluates as many elements as the same
    run with that one stop only."""
    def pressed(others):
        m = mb.Model(gravity=(0.0, -G))
        rods = []
        for k in range(3):
            x = 2.0 * k
            rod = m.add_body(f"rod{k}", mass=1.0, inertia=1 / 12, position=(x + 0.5, 0.0))
            m.add_revolute(f"pin{k}", m.ground, rod, at=(x, 0.0))
            rods.append(rod)
        m.add_stop("held", "pin0", lower=0.0)  # gravity presses the level rod on it
        if others:
            m.add_stop("far1", "pin1", lower=-3.0)
            m.add_stop("far2", "pin2", lower=-3.0)
        return mb.simulate(m, t_end=0.5, n_out=11, method="projection-erk")

    alone, beside = pressed(False), pressed(True)
    assert [e["kind"] for e in alone.events] == [e["kind"] for e in beside.events]
    assert np.allclose(alone.effort("held"), beside.effort("held"), rtol=0, atol=1e-9)
    assert beside.stats["element_evaluations"] == alone.stats["element_evaluations"]


@pytest.mark.parametrize("method", ["projection-erk", "projection-bdf", "ggl"])
def test_the_loop_with_limits_follows_the_loop_without(method):
    """Whatever the method, limits that are never struck leave the motion as it is."""
    free = loop_with(chain(), method)
    limited = loop_with(chain(stops=(-2.5, 2.5)), method)
    assert np.max(np.abs(limited - free)) <= 1e-9


def loop_with(model, method):
    sim = mb.Simulator(model, method=method, rtol=1e-8, atol=1e-10)
    names = [f"pin{k}" for k in range(3)]
    out = np.empty((50, 3))
    for i in range(50):
        angle, rate = sim.joints(names)
        out[i] = angle
        tau = KP * (0.3 * np.sin(np.pi * sim.t) - angle) - KD * rate
        sim.set_inputs({f"motor{k}": float(tau[k]) for k in range(3)})
        sim.advance(sim.t + TICK)
    return out
