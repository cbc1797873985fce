"""Forward sensitivities (simulate(..., sensitivities=[...]), r.sensitivity),
each against something independent of them:

- central differences of whole simulations run with the parameter moved by
  +- 1e-4 of its value at rtol 1e-12 (their error is then about
  1e-12 / 1e-4 = 1e-8 of the derivative), to 1e-6 relative: a compound
  pendulum (mass, inertia, where its centre starts: the length), a
  slider-crank (a closed loop) driven at constant speed (its motor torque
  and a joint's reaction to where the crank pin is, i.e. the link
  lengths), and a body on a ball joint in space;
- closed forms: a simple pendulum's period T(L) = sqrt(L/g) f(theta0), so
  dT/dL = T / (2 L) at any amplitude (the quarter period's sensitivity is
  -x_L / x' at the crossing of the vertical), and a damped mass on a spring,
  x(t; k, c) = the underdamped closed form, whose derivatives in k and c
  (central differences of the closed form itself, no integration) the
  sensitivities match.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import lagmb as mb
import builders
import paths  # noqa: E402  (tests/paths.py)

G = 9.81
EXAMPLES = Path(paths.EXAMPLES)


def finite_difference(model, name, t_end, accessor, rel=1e-4, **run):
    """d accessor(result) / d p by central differences of two whole runs."""
    p = model.parameters[name]
    step = rel * (abs(p) if p else 1.0)
    settings = dict(rtol=1e-12, atol=1e-14, method="ggl")
    settings.update(run)
    plus = mb.simulate(model, t_end, parameters={name: p + step}, **settings)
    minus = mb.simulate(model, t_end, parameters={name: p - step}, **settings)
    return (accessor(plus) - accessor(minus)) / (2 * step)


def assert_close(actual, expected, rel=1e-6):
    """Agreement to rel of the largest entry (entries that pass through 0
    are compared at the scale of the whole history)."""
    actual, expected = np.asarray(actual), np.asarray(expected)
    scale = np.abs(expected).max()
    assert scale > 0
    assert np.abs(actual - expected).max() <= rel * scale, (np.abs(actual - expected).max(), scale)


def compound_pendulum(L=1.3, mass=2.0):
    return builders.pendulum(L=L, m=mass, g=G)


@pytest.mark.parametrize("name", ["rod.mass", "rod.inertia", "rod.position.x"])
def test_a_pendulum_s_sensitivities_equal_differences_of_whole_runs(name):
    model = compound_pendulum()
    r = mb.simulate(model, 1.0, n_out=11, rtol=1e-10, atol=1e-12, sensitivities=[name])
    assert r.sensitivity_names == [name]
    assert r.stats["method_choice"].startswith("auto: ggl, the run has sensitivities")
    s = r.sensitivity(name)
    assert s.q.shape == r.q.shape and s.v.shape == r.v.shape and s.lam.shape == r.lam.shape
    assert_close(s.q, finite_difference(model, name, 1.0, lambda x: x.q, n_out=11))
    assert_close(s.v, finite_difference(model, name, 1.0, lambda x: x.v, n_out=11))
    assert_close(s.lam, finite_difference(model, name, 1.0, lambda x: x.lam, n_out=11))
    assert_close(s.reaction("pin"), finite_difference(model, name, 1.0, lambda x: x.reaction("pin"), n_out=11))
    assert_close(s.body("rod").angle, finite_difference(model, name, 1.0, lambda x: x.body("rod").angle, n_out=11))


def test_a_simple_pendulum_s_period_grows_with_its_length_as_T_over_2L():
    L, theta0 = 0.8, 1.0  # released 1 rad from the vertical: far from the small-swing period
    m = mb.Model(gravity=(0.0, -G))
    bob = m.add_particle("bob", 0.5, position=(L * math.sin(theta0), -L * math.cos(theta0)))
    m.add_distance("link", m.ground, (0.0, 0.0), bob, (L * math.sin(theta0), -L * math.cos(theta0)), length=L)
    # the quarter period: where the bob first passes below the pin (x = 0)
    dense = mb.simulate(m, 1.0, n_out=20001, rtol=1e-11, atol=1e-13)
    x = dense.body("bob").position[:, 0]
    k = int(np.nonzero(x <= 0)[0][0])
    t = dense.t[k - 1] - x[k - 1] * (dense.t[k] - dense.t[k - 1]) / (x[k] - x[k - 1])
    for _ in range(3):  # Newton on x(t) = 0 with the run's own rate
        r = mb.simulate(m, t, t_out=[0.0, t], rtol=1e-11, atol=1e-12, sensitivities=["link.length"])
        t -= r.q[-1, 0] / r.v[-1, 0]
    r = mb.simulate(m, t, t_out=[0.0, t], rtol=1e-11, atol=1e-12, sensitivities=["link.length"])
    assert abs(r.q[-1, 0]) < 1e-10
    period = 4 * t
    # x(t*(L), L) = 0  =>  dt*/dL = -x_L / x'
    dperiod = -4 * r.sensitivity("link.length").q[-1, 0] / r.v[-1, 0]
    assert dperiod == pytest.approx(period / (2 * L), rel=1e-7)


def damped_block():
    scene = mb.load_scene(EXAMPLES / "spring_damper.toml")
    scene.model  # block on a vertical guide, spring to (0, 0) of free length 1 m
    return scene.model


def closed_form_height(t, k, c, m=1.0, y0=-1.0, free=1.0, g=G):
    """The block's height y(t): released at rest at y0 on a spring of free
    length `free` from y = 0 (stiffness k, damping c), under gravity."""
    rest = -free - m * g / k  # where the spring holds the weight
    wn, zeta = math.sqrt(k / m), c / (2 * math.sqrt(k * m))
    wd = wn * math.sqrt(1 - zeta**2)
    a = y0 - rest
    return rest + np.exp(-zeta * wn * t) * (a * np.cos(wd * t) + zeta * wn * a / wd * np.sin(wd * t))


@pytest.mark.parametrize("name", ["spring.stiffness", "spring.damping"])
def test_a_damped_spring_s_sensitivities_are_the_closed_form_s_derivatives(name):
    model = damped_block()
    k, c = model.parameters["spring.stiffness"], model.parameters["spring.damping"]
    r = mb.simulate(model, 3.0, n_out=31, rtol=1e-10, atol=1e-12, sensitivities=[name])
    np.testing.assert_allclose(r.body("block").position[:, 1], closed_form_height(r.t, k, c), atol=1e-8)
    h = 1e-5 * (k if name == "spring.stiffness" else c)
    if name == "spring.stiffness":
        expected = (closed_form_height(r.t, k + h, c) - closed_form_height(r.t, k - h, c)) / (2 * h)
    else:
        expected = (closed_form_height(r.t, k, c + h) - closed_form_height(r.t, k, c - h)) / (2 * h)
    s = r.sensitivity(name)
    assert_close(s.body("block").position[:, 1], expected, rel=1e-6)
    assert_close(s.q[:, 1], expected, rel=1e-6)


def slider_crank():
    """examples/slider_crank.toml: crank 0.1 m driven at 10 rad/s, rod 0.3 m, slider."""
    return mb.load_scene(EXAMPLES / "slider_crank.toml").model


@pytest.mark.parametrize("name", ["B.at.y", "rod.mass"])
def test_a_driven_slider_crank_s_reactions_and_motor_torque_have_the_sensitivities_of_whole_runs(name):
    model = slider_crank()  # fully driven: its sensitivities come from a dynamic run
    r = mb.simulate(model, 0.5, n_out=11, rtol=1e-10, atol=1e-12, sensitivities=[name])
    assert r.stats["analysis"] == "dynamic"
    s = r.sensitivity(name)
    run = dict(n_out=11, analysis="dynamic")
    assert_close(s.reaction("C"), finite_difference(model, name, 0.5, lambda x: x.reaction("C"), **run))
    driver = [e for kind, e in ((k, v["name"]) for k, v in model.elements) if kind == "drive_joint"][0]
    assert_close(s.effort(driver), finite_difference(model, name, 0.5, lambda x: x.effort(driver), **run))
    if name == "rod.mass":  # the drivers prescribe the motion: no mass moves it
        np.testing.assert_allclose(s.q, 0.0, atol=1e-9)
    else:
        assert_close(s.q, finite_difference(model, name, 0.5, lambda x: x.q, **run))


def test_a_body_on_a_ball_joint_in_space_has_the_sensitivities_of_whole_runs():
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    bob = m.add_body("bob", 3.0, (0.05, 0.06, 0.08), position=(0.3, 0.0, -0.2), angular_velocity=(0.0, 0.0, 4.0))
    m.add_spherical("ball", m.ground, bob, at=(0.0, 0.0, 0.0))
    names = ["bob.mass", "bob.position.x", "bob.angular_velocity.z"]
    r = mb.simulate(m, 0.8, n_out=9, rtol=1e-10, atol=1e-12, sensitivities=names)
    for name in names:
        s = r.sensitivity(name)
        assert_close(s.q, finite_difference(m, name, 0.8, lambda x: x.q, n_out=9))
        assert_close(s.reaction("ball"), finite_difference(m, name, 0.8, lambda x: x.reaction("ball"), n_out=9))
        assert_close(s.body("bob").angular_velocity,
                     finite_difference(m, name, 0.8, lambda x: x.body("bob").angular_velocity, n_out=9))


def test_what_cannot_be_differentiated_is_named():
    model = compound_pendulum()
    with pytest.raises(mb.ModelError, match=r"no parameter 'rod\.length'; the model's parameters are rod\.mass"):
        mb.simulate(model, 0.1, sensitivities=["rod.length"])
    with pytest.raises(mb.ModelError, match="asked for twice"):
        mb.simulate(model, 0.1, sensitivities=["rod.mass", "rod.mass"])
    with pytest.raises(mb.ModelError, match="with the GGL form"):
        mb.simulate(model, 0.1, method="projection-erk", sensitivities=["rod.mass"])
    with pytest.raises(mb.ModelError, match="list of parameter names"):
        mb.simulate(model, 0.1, sensitivities="rod.mass")
    r = mb.simulate(model, 0.1, sensitivities=["rod.mass"])
    with pytest.raises(mb.ModelError, match=r"no sensitivity to 'rod\.inertia'; it has 'rod\.mass'"):
        r.sensitivity("rod.inertia")
    with pytest.raises(mb.ModelError, match=r"run simulate\(\.\.\., sensitivities"):
        mb.simulate(model, 0.1).sensitivity("rod.mass")
    ball = mb.load_scene(EXAMPLES / "bouncing_ball.toml").model
    with pytest.raises(mb.ModelError, match="the motion jumps"):
        mb.simulate(ball, 0.1, sensitivities=[next(iter(ball.parameters))])
    rubbing = compound_pendulum()
    rubbing.add_joint_friction("rub", "pin", mu=0.1, pin_radius=0.01)
    with pytest.raises(mb.ModelError, match="joint friction \\('rub'\\)"):
        mb.simulate(rubbing, 0.1, sensitivities=["rod.mass"])
    with pytest.raises(mb.ModelError, match="integrates nothing"):
        mb.simulate(slider_crank(), 0.1, analysis="kinematic", sensitivities=["rod.mass"])


def test_a_parameter_at_the_bound_of_its_range_is_differentiated_one_sided():
    """Every damping defaults to 0, where a central difference would build a
    model with a negative damping (refused): the sensitivity takes the model
    at 0 and at +delta instead (issue 39). Its run agrees with the closed
    form's derivative at c = 0 (a central difference of the formula, which
    takes c < 0) and with a one-sided second-order difference of whole runs."""
    model = damped_block()
    k = model.parameters["spring.stiffness"]
    undamped = {"spring.damping": 0.0}
    r = mb.simulate(model, 3.0, n_out=31, rtol=1e-10, atol=1e-12, parameters=undamped,
                    sensitivities=["spring.damping"])
    s = r.sensitivity("spring.damping")
    assert s.value == 0.0
    h = 1e-5
    expected = (closed_form_height(r.t, k, h) - closed_form_height(r.t, k, -h)) / (2 * h)
    assert_close(s.q[:, 1], expected, rel=1e-6)
    assert_close(s.body("block").position[:, 1], expected, rel=1e-6)  # its accessors too

    def height(c):
        run = mb.simulate(model, 3.0, n_out=31, rtol=1e-12, atol=1e-14, method="ggl",
                          parameters={"spring.damping": c})
        return run.body("block").position[:, 1]

    step = 1e-4
    whole_runs = (-3 * height(0.0) + 4 * height(step) - height(2 * step)) / (2 * step)
    assert_close(s.q[:, 1], whole_runs, rel=1e-6)


def test_a_parameter_without_a_sensitivity_is_named_with_the_reason():
    """model.parameters lists numbers a run cannot be differentiated in:
    the message names the parameter and says why, not a model the user did
    not build (issue 39)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    arm = m.add_body("arm", 1.0, (0.1, 0.1, 0.1), position=(0.0, 0.0, -0.5))
    m.add_universal("u", m.ground, arm, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    # a component across the other axis: no nearby value keeps them perpendicular
    with pytest.raises(mb.ModelError, match=r"'u\.axis_i\.y' = 0 has no sensitivity: the model takes no other "
                                            r"value of it nearby \(at 0\.0001: universal 'u': axis_i and axis_j "
                                            r"must be perpendicular"):
        mb.simulate(m, 0.1, sensitivities=["u.axis_i.y"])
    twice = mb.Model(gravity=(0.0, -G))
    rod = twice.add_body("rod", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    twice.add_revolute("a", twice.ground, rod, at=(0.0, 0.0))
    twice.add_revolute("b", twice.ground, rod, at=(0.0, 0.0))  # the same pin again: a redundant pair
    with pytest.raises(mb.ModelError, match=r"'b\.at\.y' = 0 has no sensitivity: which equations of 'b' are "
                                            r"redundant at the start differs"):
        mb.simulate(twice, 0.1, sensitivities=["b.at.y"])


def test_a_stop_never_reached_leaves_the_sensitivities_and_one_reached_ends_the_run_there():
    """A stop is open rows until an event: with a stop the pendulum never
    reaches (lower limit -3.5 rad: it swings between 0 and -pi), the sensitivities are those of the model
    without it (equal to differences of whole runs, 1e-6); with one it
    reaches at -pi/4, the run stops at that impact with SimulationError (its
    sensitivities would jump there) and keeps the outputs before it."""
    model = compound_pendulum()
    model.add_stop("stop", "pin", lower=-3.5)
    r = mb.simulate(model, 1.0, n_out=11, rtol=1e-10, atol=1e-12, sensitivities=["rod.mass"])
    assert r.events == []
    assert_close(r.sensitivity("rod.mass").q, finite_difference(model, "rod.mass", 1.0, lambda x: x.q, n_out=11))
    reached = compound_pendulum()
    reached.add_stop("stop", "pin", lower=-math.pi / 4)
    with pytest.raises(mb.SimulationError, match="sensitivities cannot follow the motion through an event") as info:
        mb.simulate(reached, 1.0, n_out=11, rtol=1e-10, atol=1e-12, sensitivities=["rod.mass"])
    assert info.value.result is not None and info.value.result.t[-1] < info.value.t
