"""Lock-up (issue 5, case 9): a driver pushes a mechanism into a position it
cannot pass, and the run stops there with a message that says why.

A slider-crank (crank r = 0.1 m on a ground pivot at the origin, rod
l = 0.3 m, slider on a horizontal guide) whose slider is driven outwards at
0.1 m/s from x0 = sqrt(l^2 - r^2) (crank at 90 deg). The slider cannot go
beyond x = r + l, where crank and rod align (the toggle): that is reached at
t* = (r + l - x0) / 0.1 = 1.1716 s, and the crank's angular speed
x' / |dx/dtheta| grows without bound on the way. The run must stop near t*
(within 2 % of it, not later) with mb.SimulationError naming the driver and
the joints whose equations become dependent, keep the outputs before, and
print nothing.
"""

import math

import pytest

import lagmb as mb

R, L, SPEED = 0.1, 0.3, 0.1
X0 = math.sqrt(L * L - R * R)
T_TOGGLE = (R + L - X0) / SPEED


def slider_pushed_to_toggle():
    m = mb.Model()
    crank = m.add_body("crank", 1.0, 1e-3, position=(0.0, 0.5 * R), angle=math.pi / 2)
    phi = -math.asin(R / L)
    rod = m.add_body("rod", 2.0, 0.015, position=(0.5 * X0, 0.5 * R), angle=phi)
    slider = m.add_body("slider", 0.5, 1e-4, position=(X0, 0.0))
    m.add_revolute("pivot", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("crank_pin", crank, rod, at=(0.0, R))
    m.add_revolute("wrist_pin", rod, slider, at=(X0, 0.0))
    m.add_translational("guide", m.ground, slider, at=(X0, 0.0), axis=(1.0, 0.0))
    m.drive_body("push", slider, "x", mb.Linear(SPEED, start=X0))
    return m


def test_toggle_stops_the_run_naming_the_driver_and_joints(capfd):
    m = slider_pushed_to_toggle()
    assert m.degrees_of_freedom() == 0
    with pytest.raises(mb.SimulationError) as info:
        mb.simulate(m, t_end=2.0, n_out=201, rtol=1e-8, atol=1e-10)
    e = info.value
    assert 0.98 * T_TOGGLE <= e.t <= T_TOGGLE + 1e-9
    message = str(e)
    assert "singular" in message and "'push'" in message
    assert "'crank_pin'" in message or "'wrist_pin'" in message or "'pivot'" in message
    partial = e.result
    assert partial is not None and partial.t[-1] <= e.t
    assert partial.t[-1] >= 0.95 * T_TOGGLE
    # up to there the slider followed its driver exactly
    x = partial.body("slider").position[:, 0]
    assert abs(x[-1] - (X0 + SPEED * partial.t[-1])) < 1e-8
    assert capfd.readouterr().err == ""
