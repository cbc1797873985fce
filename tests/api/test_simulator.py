"""The stepping simulator (mb.Simulator): a run advanced in chunks, its
inputs set from outside between them, saved and restored."""

import importlib.util
import math
import os
import re

import numpy as np
import pytest

import lagmb as mb
from builders import pendulum, rod_chain

from paths import EXAMPLES  # noqa: E402


def example(name):
    """examples/<name>.py as a module (its functions, not its main)."""
    spec = importlib.util.spec_from_file_location(name, os.path.join(EXAMPLES, name + ".py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def motor_pendulum(torque=0.0):
    """The seed pendulum with an input torque "motor" on the rod."""
    model = pendulum()
    model.add_torque("motor", "rod", torque=mb.Input(torque))
    return model


def pushed_slider(force=0.0, mass=2.0):
    """A block of `mass` kg on a frictionless horizontal rail, no gravity,
    pushed along the rail by the input force "push"."""
    model = mb.Model()
    block = model.add_body("block", mass=mass, inertia=0.1, position=(0.0, 0.0))
    model.add_translational("rail", model.ground, block, at=(0.0, 0.0), axis=(1.0, 0.0))
    model.add_force("push", block, force=(mb.Input(force), 0.0))
    return model


# --- advancing in chunks --------------------------------------------------------


@pytest.mark.parametrize("chunks", [1, 10, 1000])
def test_advancing_in_chunks_ends_where_one_run_ends(chunks):
    """A double pendulum falling from the horizontal for 2 s: advanced in 1,
    10 or 1,000 chunks, it ends where simulate's one run ends (to the
    tolerance), with the integrator never restarted and barely more steps
    (GGL, whose interpolant is as accurate as its steps; the explicit method
    steps to every output, so 1,000 chunks cost it 1,000 steps)."""
    model = rod_chain(2)
    one_run = mb.simulate(model, t_end=2.0, rtol=1e-8, atol=1e-10, n_out=2, formulation="ggl")
    sim = mb.Simulator(model, rtol=1e-8, atol=1e-10, formulation="ggl")
    for k in range(chunks):
        sim.advance(2.0 * (k + 1) / chunks)
    assert sim.t == 2.0
    assert np.max(np.abs(sim.q - one_run.q[-1])) < 1e-6
    assert np.max(np.abs(sim.v - one_run.v[-1])) < 1e-5
    assert sim.stats["restarts"] == 0
    # the steps may pass the end of a chunk: as many as one run takes
    assert sim.stats["steps"] <= 1.05 * one_run.stats["steps"] + 5
    assert len(sim.result().t) == chunks + 1



def test_a_simulators_counts_are_its_runs():
    """A Simulator reports what simulate reports for the same run: with the
    explicit method on a 20-link chain, the Schur complement's pattern
    analysed once and the same factor size, elements evaluated at the start
    and at every output as well as in the steps, and the steps of one run
    (give or take the last one, which may pass the end)."""
    model = rod_chain(20)
    options = dict(formulation="projection", integrator="erk", rtol=1e-6, atol=1e-8)
    one_run = mb.simulate(model, t_end=0.5, n_out=2, **options)
    sim = mb.Simulator(model, **options)
    sim.advance(0.5)
    s = sim.stats
    assert s["symbolic_analyses"] == one_run.stats["symbolic_analyses"] == 1
    assert s["factor_nonzeros"] == one_run.stats["factor_nonzeros"] > 0
    assert abs(s["steps"] - one_run.stats["steps"]) <= 1
    per_step = one_run.stats["element_evaluations"] / one_run.stats["residual_evals"]
    assert s["element_evaluations"] / s["residual_evals"] == pytest.approx(per_step, rel=0.05)


@pytest.mark.parametrize("method", [m["name"] for m in mb.methods()])
def test_every_method_advances_in_chunks(method):
    """Each integration method, advanced in 20 chunks over 1 s, follows the
    pendulum as simulate does with the same method."""
    entry = next(m for m in mb.methods() if m["name"] == method)
    options = dict(formulation=entry["formulation"], integrator=entry["integrator"])
    if entry["fixed_step"]:  # no error control: a step, no tolerances
        options["step"] = 1e-3
    else:
        options.update(rtol=1e-8, atol=1e-10)
    model = pendulum()
    reference = mb.simulate(model, t_end=1.0, n_out=21, **options)
    sim = mb.Simulator(model, **options)
    for t in reference.t[1:]:
        sim.advance(t)
    r = sim.result()
    np.testing.assert_array_equal(r.t, reference.t)
    tolerance = 1e-3 if entry["drifts"] or entry["formulation"] == "index3" else 1e-5
    assert np.max(np.abs(r.q - reference.q)) < tolerance


def test_output_interval_records_between_the_ends_of_advances():
    """output_interval = 0.1 s with advances of 0.25 s: the outputs are the
    multiples of 0.1 and the ends of the advances, each as simulate has it."""
    model = rod_chain(2)
    sim = mb.Simulator(model, rtol=1e-9, atol=1e-11, output_interval=0.1)
    for k in range(4):
        sim.advance(0.25 * (k + 1))
    r = sim.result()
    expected = np.array([0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.7, 0.75, 0.8, 0.9, 1.0])
    np.testing.assert_allclose(r.t, expected, rtol=0, atol=1e-12)
    reference = mb.simulate(model, t_out=r.t, rtol=1e-9, atol=1e-11)
    assert np.max(np.abs(r.q - reference.q)) < 1e-6
    assert np.max(np.abs(r.lam - reference.lam)) < 1e-4


# --- inputs -------------------------------------------------------------------


def test_a_force_input_acts_from_the_time_it_is_set():
    """A 2 kg block at rest, pushed with 4 N from t = 0.5 s: it stays put
    until then, and at t = 1.5 s it has moved a t^2 / 2 = 1 m (a = 2 m/s^2,
    for 1 s) at 2 m/s."""
    for formulation in ("ggl", "projection"):
        sim = mb.Simulator(pushed_slider(), formulation=formulation, rtol=1e-10, atol=1e-12)
        sim.advance(0.5)
        assert sim.body("block").position[0] == pytest.approx(0.0, abs=1e-12)
        sim.set_input("push", 4.0)
        assert sim.input("push") == 4.0
        sim.advance(1.5)
        block = sim.body("block")
        assert block.position[0] == pytest.approx(1.0, abs=1e-8)
        assert block.velocity[0] == pytest.approx(2.0, abs=1e-8)
        assert block.acceleration[0] == pytest.approx(2.0, abs=1e-8)


def test_restarts_are_the_input_changes():
    """The integrator restarts once per change of an input, and only then: a
    value set again unchanged, or set twice before an advance, is not a
    change (a model without breakpoints or events restarts for nothing else)."""
    sim = mb.Simulator(motor_pendulum(), rtol=1e-8)
    sim.advance(0.1)
    for k, torque in enumerate([1.0, 1.0, -2.0, 0.5, 0.5, 3.0]):
        sim.set_input("motor", torque)
        if k == 3:
            sim.set_input("motor", 7.0)  # overridden before the advance: one change
            sim.set_input("motor", torque)
        sim.advance(0.1 * (k + 2))
    assert sim.stats["input_changes"] == 4  # 1.0, -2.0, 0.5, 3.0
    assert sim.stats["restarts"] == sim.stats["input_changes"]


def test_a_driver_input_moves_the_driven_joint():
    """A crank driven through an input angle: setting 0.3 rad turns it there
    (the positions are assembled anew), where it stays at rest."""
    model = pendulum(g=0.0)
    model.drive_joint("motor", "pin", f=mb.Input(0.0))
    sim = mb.Simulator(model)
    sim.advance(0.2)
    sim.set_input("motor", 0.3)
    sim.advance(0.5)
    rod = sim.body("rod")
    r = sim.result()
    np.testing.assert_array_equal(r.input("motor"), [0.0, 0.0, 0.3])  # at t = 0, 0.2, 0.5
    assert np.max(r.residual) < 1e-9  # each output against the driver value it had then
    assert rod.angle == pytest.approx(0.3, abs=1e-9)
    assert rod.position == pytest.approx([0.5 * math.cos(0.3), 0.5 * math.sin(0.3)], abs=1e-9)
    assert rod.angular_velocity == pytest.approx(0.0, abs=1e-9)


def test_simulate_runs_an_input_at_its_initial_value():
    """Outside a simulator an input holds its initial value: simulate gives
    the run of the same model with that constant."""
    with_input = mb.simulate(motor_pendulum(torque=2.0), t_end=1.0, rtol=1e-8)
    constant = pendulum()
    constant.add_torque("motor", "rod", torque=2.0)
    np.testing.assert_array_equal(with_input.q, mb.simulate(constant, t_end=1.0, rtol=1e-8).q)
    assert np.all(with_input.input("motor") == 2.0)
    with pytest.raises(mb.ModelError, match="no input called 'torque'; the inputs are 'motor'"):
        with_input.input("torque")


def test_two_simulators_of_one_model_keep_their_own_inputs():
    """Two simulators of one model, advanced in turn with different torques,
    each end where it would alone: the input values belong to the run."""
    model = motor_pendulum()
    a, b = mb.Simulator(model, rtol=1e-8), mb.Simulator(model, rtol=1e-8)
    a.set_input("motor", 1.0)
    b.set_input("motor", -1.0)
    for k in range(10):
        a.advance(0.1 * (k + 1))
        b.advance(0.1 * (k + 1))
    alone = mb.Simulator(model, rtol=1e-8)
    alone.set_input("motor", 1.0)
    for k in range(10):
        alone.advance(0.1 * (k + 1))
    np.testing.assert_array_equal(a.q, alone.q)
    assert b.body("rod").angle < a.body("rod").angle - 0.1  # -1 N m turns it the other way


def test_inputs_are_named_after_their_elements():
    """An element's one input takes its name; several in one element are
    named by parameter and component; an explicit name wins; two inputs of
    one name are refused."""
    model = mb.Model()
    block = model.add_body("block", mass=1.0, inertia=1.0)
    model.add_force("push", block, force=(mb.Input(1.0), mb.Input(2.0)))
    model.add_torque("twist", block, torque=mb.Input(3.0))
    model.add_torque("spin", block, torque=mb.Input(0.0, name="u"))
    inputs = {d["name"]: d for d in model.compiled().inputs}
    assert set(inputs) == {"push.force.x", "push.force.y", "twist", "u"}
    assert inputs["twist"]["unit"] == "N m" and inputs["push.force.x"]["unit"] == "N"
    assert inputs["u"]["element"] == "spin" and inputs["twist"]["initial"] == 3.0
    sim = mb.Simulator(model)
    assert sim.inputs == {"push.force.x": 1.0, "push.force.y": 2.0, "twist": 3.0, "u": 0.0}
    with pytest.raises(mb.ModelError, match="another input has that name"):
        model.add_torque("spin2", block, torque=mb.Input(0.0, name="u"))


# --- the cart-pole controller (examples/cart_pole.py) -----------------------------


def test_a_pd_controller_holds_the_pole_upright():
    """The PD controller of examples/cart_pole.py, sampling every 10 ms,
    rights the pole from 0.1 rad: it never leans further, is within 0.05 rad
    after 1 s and stays so to 10 s, with the cart back near x = 0."""
    cp = example("cart_pole")
    sim = cp.balance(cp.cart_pole(theta0=0.1), t_end=10.0, rtol=1e-6)
    r = sim.result()
    theta = r.body("pole").angle - math.pi / 2
    assert r.t[-1] == pytest.approx(10.0)
    assert np.max(np.abs(theta)) <= 0.1 + 1e-9
    assert np.max(np.abs(theta[r.t >= 1.0])) < 0.05
    assert abs(sim.body("cart").position[0]) < 0.1
    assert sim.stats["input_changes"] >= 990  # a new force nearly every sample


def test_without_control_the_pole_falls():
    """The same cart-pole with the force held at 0: the pole falls (past
    1 rad within 3 s)."""
    cp = example("cart_pole")
    sim = cp.balance(cp.cart_pole(theta0=0.1), t_end=3.0, control=False)
    theta = sim.result().body("pole").angle - math.pi / 2
    assert np.max(np.abs(theta)) > 1.0
    assert sim.stats["input_changes"] == 0


# --- saving and restoring ---------------------------------------------------------


def test_a_restored_state_continues_bit_for_bit():
    """The cart-pole under control for 1 s, saved; the next second run twice
    (the second time from the restored state) gives the same numbers, bit
    for bit, and the same outputs."""
    cp = example("cart_pole")
    sim = mb.Simulator(cp.cart_pole(), rtol=1e-8)

    def control_to(t_end):
        path = []
        while sim.t < t_end - 1e-12:
            theta, rate = cp.tilt(sim)
            sim.set_input("push", -(40 * theta + 8 * rate))
            sim.advance(round(sim.t + 0.01, 12))
            path.append(np.concatenate([sim.q, sim.v, sim.lam]))
        return np.array(path)

    control_to(1.0)
    saved = sim.state()
    first = control_to(2.0)
    first_result = sim.result()
    sim.set_state(saved)
    assert sim.t == saved.t and np.array_equal(sim.q, saved.q)
    assert sim.result().t[-1] == saved.t  # the outputs after it are gone
    second = control_to(2.0)
    assert np.array_equal(first, second)
    np.testing.assert_array_equal(sim.result().q, first_result.q)
    np.testing.assert_array_equal(sim.result().t, first_result.t)


def test_state_can_go_back_for_what_if_runs():
    """From one saved state, a push one way and a push the other way: each
    branch's result holds the common past and its own future."""
    sim = mb.Simulator(pushed_slider(), rtol=1e-10, atol=1e-12)
    sim.advance(1.0)
    fork = sim.state()
    sim.set_input("push", 2.0)
    sim.advance(2.0)
    right = sim.body("block").position[0]
    sim.set_state(fork)
    sim.set_input("push", -2.0)
    sim.advance(2.0)
    assert right == pytest.approx(0.5, abs=1e-9) and sim.body("block").position[0] == pytest.approx(-0.5, abs=1e-9)
    np.testing.assert_array_equal(sim.result().t, [0.0, 1.0, 2.0])


# --- bad input ----------------------------------------------------------------------


def test_bad_inputs_are_named():
    sim = mb.Simulator(pushed_slider())
    with pytest.raises(mb.ModelError, match=r"no input called 'pull'; the inputs are 'push'"):
        sim.set_input("pull", 1.0)
    with pytest.raises(mb.ModelError, match=r"'rail' is a translational.*not an input; the inputs are 'push'"):
        sim.set_input("rail", 1.0)
    for bad in (float("nan"), float("inf")):
        with pytest.raises(mb.ModelError, match="input 'push' must be finite"):
            sim.set_input("push", bad)
    with pytest.raises(mb.ModelError, match="must be a number"):
        sim.set_input("push", "fast")
    assert sim.input("push") == 0.0  # unchanged
    with pytest.raises(mb.ModelError, match="the model has no inputs"):
        mb.Simulator(pendulum()).set_input("motor", 1.0)


def test_an_input_beyond_what_a_run_can_hold_is_named_where_it_is_set():
    """Issue 56: set_input("push", 1e300) was taken, then the next advance
    failed at t = 0 with IDA_REP_RES_ERR naming neither the input nor the
    value. Past 1e150 (the largest lagmb takes for a gain or an input: the
    squares of what it makes overflow a double) it is refused at once; a
    value within it that the model cannot take (1e150 N on 2 kg) fails the
    first step, and the failure names the input, the value and what it
    feeds."""
    sim = mb.Simulator(pushed_slider())
    for bad in (1e300, -1e151):
        with pytest.raises(mb.ModelError, match=rf"input 'push' = {re.escape(f'{bad:g}')} is beyond 1e\+150, the largest lagmb takes "
                                                r"for a gain or an input: the integrator's error norms square"):
            sim.set_input("push", bad)
    with pytest.raises(mb.ModelError, match=r"input 'push' = 1e\+200 is beyond 1e\+150"):
        sim.set_inputs({"push": 1e200})
    assert sim.input("push") == 0.0
    with pytest.raises(mb.ModelError, match=r"an input's initial value 1e\+300 is beyond 1e\+150"):
        mb.Input(1e300)
    sim.set_input("push", 1e150)  # (the largest is taken)
    with pytest.raises(mb.SimulationError, match=r"It failed at once where inputs were set \(t = 0 s: 'push' = "
                                                 r"1e\+150 \(push\.force\.x\)\); an input too large for this model"):
        sim.advance(0.01)


@pytest.mark.parametrize("given, message", [
    (None, r"set_inputs takes a dict \{name: value\} or 1 numbers in the order of Simulator.inputs \(push\), got None"),
    ([None], r"input 'push' must be a number, got None"),
    (["fast"], r"input 'push' must be a number, got 'fast'"),
    ([1.0, 2.0], r"set_inputs takes .* 1 numbers"),
])
def test_set_inputs_names_what_is_not_a_number(given, message):
    """set_inputs(None) and set_inputs([None]) said "input 'push' must be
    finite, got nan" (numpy had made None a nan)."""
    sim = mb.Simulator(pushed_slider())
    with pytest.raises(mb.ModelError, match=message):
        sim.set_inputs(given)
    sim.set_inputs(np.array([2.0]))
    assert sim.input("push") == 2.0


def test_set_inputs_of_a_float_array_is_checked_and_runs_as_a_dict():
    """A controller's array of every input (its fast path: the core checks
    each value) names a value that is not finite or too large, and moves
    the model as the same values given by name."""
    sim = mb.Simulator(pushed_slider())
    with pytest.raises(mb.ModelError, match=r"input 'push' must be finite, got nan"):
        sim.set_inputs(np.array([np.nan]))
    with pytest.raises(mb.ModelError, match=r"input 'push' = 1e\+200 is beyond 1e\+150"):
        sim.set_inputs(np.array([1e200]))
    by_name = mb.Simulator(pushed_slider())
    for k in range(5):
        sim.set_inputs(np.array([float(k)]))
        by_name.set_inputs({"push": float(k)})
        sim.advance(0.01 * (k + 1))
        by_name.advance(0.01 * (k + 1))
    assert np.array_equal(sim.q, by_name.q) and np.array_equal(sim.v, by_name.v)


def test_simulator_joint_names_itself_for_an_element_that_is_no_joint():
    """Simulator.joint(stop) said "Result.joint: ..."."""
    model = pendulum()
    model.add_stop("limit", "pin", lower=-1.0, upper=1.0)
    sim = mb.Simulator(model)
    with pytest.raises(mb.ModelError, match=r"^Simulator.joint: 'limit' is a stop, not a revolute"):
        sim.joint("limit")


def test_an_unstable_loop_driving_the_pandas_fingers_through_their_limits_names_what_holds_them():
    """Issue 56: an unstable PD loop at 1 kHz on the Panda (gains 2000 N m/rad
    and 100 N m s/rad on every joint, the fingers' too: the arm whirls at
    up to 1.8e3 rad/s) ended with "stop 'panda_finger_joint2_limit' is
    reached along a motion the joints and drivers prescribe (a driver
    pushing through the limit, or a gimbal lock)", neither of which it was:
    the finger's joint and its mimic are both on their limits, the first
    held by its stop, the second tied to it by the coupling, and the state
    at the event had drifted off them. The message names both stops and the
    coupling, and says the motion drifted off what holds it. (Should the run
    get through, the fingers must stay within their limits.)"""
    import warnings

    path = example("panda").panda_urdf()
    if path is None:
        pytest.skip("the Panda's URDF is example-robot-data's (the robots extra), not installed")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        m = mb.load_urdf(path)
    joints = [f"panda_joint{k}" for k in range(1, 8)] + ["panda_finger_joint1"]
    for j in joints:  # a torque (force) input on each joint
        m.add_servo(f"{j}_drive", j, target=0.0, kp=0.0, kd=0.0, feedforward=mb.Input(0.0, name=f"{j}_tau"))
    sim = mb.Simulator(m)
    target = sim.joints(joints)[0] + 0.3
    try:
        while sim.t < 0.05:
            q, rate = sim.joints(joints)
            sim.set_inputs({f"{j}_tau": 2000.0 * (a - b) - 100.0 * c for j, a, b, c in zip(joints, target, q, rate)})
            sim.advance(sim.t + 1e-3)
    except mb.SimulationError as e:
        said = " ".join(str(e).split())
        assert said.startswith("at an event: stop 'panda_finger_joint2_limit' is reached at t = ")
        assert ("where its joint is held by 'panda_finger_joint1_limit' (a spatial stop), to which "
                "'panda_finger_joint2_mimic' (a joint coupling) ties it: both joints are at their limits") in said
        assert "the motion has drifted off them" in said and "gimbal lock" not in said
    fingers, _ = sim.joints(["panda_finger_joint1", "panda_finger_joint2"])
    assert np.all(fingers <= 0.04 + 1e-8) and np.all(fingers >= -1e-8)


def test_time_only_goes_forward():
    sim = mb.Simulator(pendulum())
    sim.advance(0.5)
    with pytest.raises(mb.ModelError, match=r"t = 0.2 is before the simulator's time 0.5"):
        sim.advance(0.2)
    with pytest.raises(mb.ModelError, match="t must be finite"):
        sim.advance(float("nan"))
    sim.advance(0.5)  # no time to go: nothing happens
    assert sim.t == 0.5 and len(sim.result().t) == 2


def test_options_of_simulate_alone_are_refused():
    for bad in (dict(t_end=1.0), dict(n_out=5), dict(analysis="kinematic"), dict(progress=print)):
        with pytest.raises(TypeError):
            mb.Simulator(pendulum(), **bad)
    with pytest.raises(mb.ModelError, match="rtol"):
        mb.Simulator(pendulum(), rtol=-1.0)
    with pytest.raises(mb.ModelError, match="output_interval"):
        mb.Simulator(pendulum(), output_interval=-0.1)
    with pytest.raises(mb.ModelError, match="set_state takes what state"):
        mb.Simulator(pendulum()).set_state((0.0, [0.0]))
    other = mb.Simulator(rod_chain(2)).state()
    with pytest.raises(mb.ModelError, match="another model"):
        mb.Simulator(pendulum()).set_state(other)


def test_after_a_failure_the_outputs_stay_and_the_simulator_stops():
    """A torque that fails at t > 0.3 s (a user function raising): the advance
    raises SimulationError, the outputs reached are kept, the simulator
    refuses to go on, and a saved state brings it back."""

    def torque(t):
        if t > 0.3:
            raise RuntimeError("sensor lost")
        return 0.0

    model = pendulum()
    model.add_torque("motor", "rod", torque=torque)
    sim = mb.Simulator(model, output_interval=0.05)
    sim.advance(0.2)
    saved = sim.state()
    with pytest.raises(mb.SimulationError, match="sensor lost") as failure:
        sim.advance(1.0)
    assert isinstance(failure.value.__cause__, RuntimeError)
    kept = sim.result()
    assert 0.25 <= kept.t[-1] <= 0.3 and np.all(np.diff(kept.t) > 0)  # the step across 0.3 s failed
    assert failure.value.result is not None and failure.value.result.t[-1] == kept.t[-1]
    assert sim.t == kept.t[-1]
    with pytest.raises(mb.SimulationError, match="cannot go on.*set_state"):
        sim.advance(1.0)
    with pytest.raises(mb.SimulationError, match="cannot go on"):
        sim.set_input("motor", 1.0)
    sim.set_state(saved)
    sim.advance(0.25)
    assert sim.t == 0.25


def test_a_scene_declares_inputs(tmp_path, capsys):
    """A scene gives an input as { type = "input", initial = ... }: its run
    holds the initial value, a simulator sets it, and the scene is written
    back with it."""
    path = tmp_path / "pushed.toml"
    path.write_text("""
[[bodies]]
name = "block"
mass = 2.0
inertia = 0.1

[[joints]]
type = "translational"
name = "rail"
body_i = "ground"
body_j = "block"
at = [0.0, 0.0]
axis = [1.0, 0.0]

[[forces]]
type = "force"
name = "push"
body = "block"
force = [{ type = "input", initial = 4.0 }, 0.0]

[simulation]
t_end = 1.0
""")
    scene = mb.load_scene(str(path))
    assert scene.run().body("block").position[-1, 0] == pytest.approx(1.0, abs=1e-6)  # 2 m/s^2 for 1 s
    from lagmb.cli import main as cli

    assert cli(["info", str(path)]) == 0
    assert "inputs: 1 (push 4 N)" in capsys.readouterr().out
    sim = mb.Simulator(scene.model)
    sim.set_input("push", -4.0)
    sim.advance(1.0)
    assert sim.body("block").position[0] == pytest.approx(-1.0, abs=1e-6)
    mb.save_scene(scene.model, str(tmp_path / "again.toml"))
    again = mb.load_scene(str(tmp_path / "again.toml")).model.compiled().inputs
    assert [(d["name"], d["initial"]) for d in again] == [("push", 4.0)]


def test_events_and_breakpoints_in_chunks():
    """The bouncing ball of examples/bouncing_ball.toml (impacts found as
    roots) advanced in 100 chunks has the impacts simulate has, at the same
    times; a smooth-step torque on the pendulum restarts the integrator at
    its two ends, and nowhere else."""
    scene = mb.load_scene(os.path.join(EXAMPLES, "bouncing_ball.toml"))
    t_end = scene.settings["t_end"]
    one_run = mb.simulate(scene.model, t_end=t_end, rtol=1e-8, atol=1e-10)
    sim = mb.Simulator(scene.model, rtol=1e-8, atol=1e-10)
    for k in range(100):
        sim.advance(t_end * (k + 1) / 100)
    impacts = [e["t"] for e in sim.result().events]
    assert len(impacts) == len(one_run.events) > 0
    np.testing.assert_allclose(impacts, [e["t"] for e in one_run.events], atol=1e-6)
    assert sim.stats["events"] == one_run.stats["events"]

    model = pendulum()
    model.add_torque("kick", "rod", torque=mb.SmoothStep(0.2, 0.4, 0.0, 1.0))
    sim = mb.Simulator(model, rtol=1e-8)
    for k in range(10):
        sim.advance(0.1 * (k + 1))
    assert sim.stats["restarts"] == 2 and sim.stats["input_changes"] == 0


@pytest.mark.parametrize("method", mb.methods(), ids=[m["name"] for m in mb.methods()])
def test_advances_ending_just_before_a_breakpoint_are_inside_the_last_step(method):
    """A step that ends on a breakpoint past the time asked for restarted the
    integrator at once, discarding the step; the next advance, still before
    the breakpoint, then asked for a time the integrator no longer held:
    CVodeGetDky / IDAGetDky "Illegal value for t" (a RuntimeError), and
    ali3p gave outputs 0.075 off the constraints. The restart now waits until
    a run steps past the breakpoint, and the outputs are those of simulate
    at the same times."""
    m = mb.Model(dimension=3)
    arm = m.add_body("arm", 1.0, (0.1, 0.1, 0.1), position=(0.5, 0.0, 0.0))
    m.add_revolute("hinge", m.ground, arm, at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    m.add_spherical("tip", arm, m.add_body("bob", 1.0, (0.1, 0.1, 0.1), position=(1.0, 0.0, -0.5)),
                    at=(1.0, 0.0, 0.0))
    m.drive_joint("motor", "hinge", mb.Spline([0.0, 0.02, 0.04], [0.0, 0.5, 0.0]))
    options = dict(formulation=method["formulation"], integrator=method["integrator"])
    if method["fixed_step"]:
        options["step"] = 0.005
    sim = mb.Simulator(m, **options)
    for k in range(1, 41):
        sim.advance(k * 0.001)
    chunks = sim.result()
    one_run = mb.simulate(m, t_out=chunks.t, analysis="dynamic", **options)
    assert chunks.residual.max() < 10 * max(one_run.residual.max(), 1e-9)
    assert np.abs(chunks.q - one_run.q).max() < 1e-4


def test_an_output_interval_that_cannot_fit_is_refused():
    """1e-12 s between outputs over 1 s would be 1e12 outputs: refused with
    the count, before any is made; a shorter advance goes."""
    sim = mb.Simulator(pendulum(), output_interval=1e-12)
    with pytest.raises(mb.ModelError, match=r"asks for 1e\+12 outputs"):
        sim.advance(1.0)
    sim.advance(1e-11)
    assert len(sim.result().t) == 11


def test_simulators_on_two_threads_keep_their_inputs():
    """Two simulators of one model on two threads at once (the GIL is
    released while they integrate), pushed opposite ways: each ends where
    it ends alone. The input values are bound per thread and run."""
    import threading

    model = motor_pendulum()
    ends = {}

    def run(torque):
        sim = mb.Simulator(model, rtol=1e-8)
        sim.set_input("motor", torque)
        for k in range(200):
            sim.advance(0.005 * (k + 1))
        ends[torque] = sim.q

    threads = [threading.Thread(target=run, args=(t,)) for t in (1.0, -1.0)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for torque in (1.0, -1.0):
        alone = mb.Simulator(model, rtol=1e-8)
        alone.set_input("motor", torque)
        for k in range(200):
            alone.advance(0.005 * (k + 1))
        np.testing.assert_array_equal(ends[torque], alone.q)


def test_a_simulator_does_not_pickle_and_says_what_to_send_instead():
    """Its integrator's state lives in this process (issue 39): pickling or
    copying it is a ModelError naming what travels (the model, the result,
    the state's numbers), and those do."""
    import copy
    import pickle

    sim = mb.Simulator(motor_pendulum(torque=1.0))
    sim.advance(0.2)
    for send in (pickle.dumps, copy.copy):
        with pytest.raises(mb.ModelError, match=r"a Simulator cannot be pickled or copied.*the model \(it pickles\)"
                                                r".*sim\.result\(\) \(it pickles\).*\(sim\.t, sim\.q, sim\.v, "
                                                r"sim\.inputs\)"):
            send(sim)
    r = pickle.loads(pickle.dumps(sim.result()))
    assert np.array_equal(r.q[-1], sim.q) and r.t[-1] == sim.t
    assert pickle.loads(pickle.dumps(sim.model)).parameters == sim.model.parameters


def test_the_wall_time_is_the_time_spent_advancing():
    """stats["wall_time"] (and a result's, which the viewer's header shows):
    the seconds spent in advance, summed; it grows with each advance and is
    not the 0 it was (nothing measured it)."""
    import time

    sim = mb.Simulator(pendulum())
    assert sim.stats["wall_time"] == 0.0
    start = time.perf_counter()
    sim.advance(0.5)
    spent = time.perf_counter() - start
    first = sim.stats["wall_time"]
    assert 0.0 < first <= spent
    sim.advance(1.0)
    assert sim.stats["wall_time"] > first
    assert sim.result().stats["wall_time"] == sim.stats["wall_time"]
