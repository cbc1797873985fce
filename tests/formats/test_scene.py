"""Scene files (lagmb.scene): reading, writing, the examples, and errors.

- Round trip: a model built in Python with bodies, a particle, five joint
  kinds, a time-function driver and four force kinds is written with
  save_scene, read back with load_scene, and both are simulated with the
  same settings: t, q, v, a and lam must be identical to the last bit, and
  writing the loaded model again must give the same text.
- Every examples/*.toml loads and runs (to a short t_end) with max |Phi| <
  1e-8, and shows the number its comment promises (pin force m g / 4 at
  release, crank angle = pi/2 + 10 t, gear speed 4 x the motor's, ...).
- Every error names the file, the line, the table and the key: the lines are
  marked in the scene texts below with "# <-" and found from the marks.
"""

import glob
import math
import os

import numpy as np
import pytest

import lagmb as mb
from lagmb.scene import Scene, SceneError, load_scene, save_scene

import builders
from builders import pendulum_scene
from paths import EXAMPLES

G = 9.81

PENDULUM = "# the seed pendulum\n" + pendulum_scene() + """
[simulation]
t_end = 1.0
rtol = 1e-8
atol = 1e-10
n_out = 101

[output]
reactions = ["pin"]
"""


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def marked_line(text, mark="# <-"):
    """1-based number of the line carrying the mark."""
    lines = [i for i, line in enumerate(text.splitlines(), 1) if mark in line]
    assert len(lines) == 1, f"mark {mark!r} on lines {lines}"
    return lines[0]


def require(*methods):
    missing = [m for m in methods if not hasattr(mb.Model, m)]
    if missing:
        pytest.skip(f"mb.Model has no {', '.join(missing)} yet")


# --- reading ---------------------------------------------------------------------

def test_pendulum_scene_loads_and_runs(tmp_path):
    scene = load_scene(write(tmp_path, PENDULUM))
    assert isinstance(scene, Scene)
    assert scene.settings == {"t_end": 1.0, "rtol": 1e-8, "atol": 1e-10, "n_out": 101}
    assert scene.output == {"reactions": ["pin"]}
    assert [(e.table, e.type, e.name, e.line) for e in scene.elements] == [
        ("bodies", None, "rod", 5), ("joints", "revolute", "pin", 11)]
    model, settings = scene  # DESIGN: load_scene(path) -> Model (+ simulation settings)
    assert model is scene.model and settings is scene.settings
    assert model.n_coordinates == 3 and model.n_constraints == 2
    r = scene.run()
    assert r.t.shape == (101,) and r.t[-1] == 1.0
    # pin force on the rod at release: m g / 4 upward (closed form)
    assert r.reaction("pin")[0, 1] == pytest.approx(G / 4, rel=1e-9)
    assert r.residual.max() < 1e-8
    # the same model built in Python gives the same run, bit for bit
    m = builders.pendulum(g=G)
    ref = mb.simulate(m, t_end=1.0, rtol=1e-8, atol=1e-10, n_out=101)
    assert np.array_equal(r.q, ref.q) and np.array_equal(r.lam, ref.lam)


def test_run_overrides(tmp_path):
    scene = load_scene(write(tmp_path, PENDULUM))
    r = scene.run(t_end=0.25, n_out=11)
    assert r.t.shape == (11,) and r.t[-1] == 0.25
    assert scene.settings["t_end"] == 1.0  # the scene keeps its own settings


def test_t_out_and_multiline_values(tmp_path):
    text = PENDULUM.replace("n_out = 101\n", "t_out = [\n  0.0, 0.1,  # a comment [ {\n"
                                             "  0.2, 0.4,\n]\nmax_order = 4\n")
    text = text.replace('name = "rod"', 'name = """rod"""')
    scene = load_scene(write(tmp_path, text))
    assert scene.settings["t_out"] == [0.0, 0.1, 0.2, 0.4]
    assert scene.settings["max_order"] == 4
    r = scene.run()
    assert np.array_equal(r.t, [0.0, 0.1, 0.2, 0.4])
    # line numbers stay right after a value spanning lines
    bad = text.replace("max_order = 4", "max_order = 4.5  # <-")
    with pytest.raises(SceneError) as e:
        load_scene(write(tmp_path, bad))
    assert e.value.line == marked_line(bad) and e.value.key == "max_order"


def test_gravity_from_model_table(tmp_path):
    scene = load_scene(write(tmp_path, PENDULUM))
    if not hasattr(scene.model, "gravity"):
        pytest.skip("mb.Model has no .gravity yet")
    assert tuple(scene.model.gravity) == (0.0, -9.81)
    no_gravity = load_scene(write(tmp_path, PENDULUM.replace("[model]\ngravity = [0.0, -9.81]\n", "")))
    assert no_gravity.model.gravity is None


# --- round trip ------------------------------------------------------------------

def mechanism():
    """A slider-crank with a pendulum particle, springs and loads: bodies, a
    particle, revolute (global and local points), translational, distance,
    weld, a Linear driver on the crank, and four force kinds with time
    functions."""
    require("elements", "add_translational", "add_distance", "add_weld", "drive_joint",
            "add_spring_damper", "add_rotational_spring_damper", "add_force", "add_torque")
    xc = math.sqrt(0.3**2 - 0.1**2)
    m = mb.Model(gravity=(0.0, -9.81))
    crank = m.add_body("crank", mass=1.0, inertia=0.1**2 / 12, position=(0.0, 0.05),
                       angle=math.pi / 2, angular_velocity=10.0)
    rod = m.add_body("rod", mass=2.0, inertia=2 * 0.09 / 12, position=(xc / 2, 0.05),
                     angle=math.atan2(-0.1, xc))
    slider = m.add_body("slider", mass=0.5, inertia=1e-4, position=(xc, 0.0))
    bob = m.add_particle("bob", mass=0.1, position=(xc, -0.2), velocity=(0.1, 0.0))
    cap = m.add_body("cap", mass=0.05, inertia=1e-5, position=(xc + 0.02, 0.01), angle=0.3)
    m.add_revolute("O", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, rod, local_i=(0.05, 0.0), local_j=(-0.15, 0.0))
    m.add_revolute("C", rod, slider, at=(xc, 0.0))
    m.add_translational("guide", m.ground, slider, at=(xc, 0.0), axis=(1.0, 0.0))
    m.drive_joint("motor", "O", mb.Linear(10.0, start=math.pi / 2))
    m.add_distance("string", slider, (xc, 0.0), bob, (xc, -0.2))
    m.add_weld("cap_weld", slider, cap)
    m.add_spring_damper("spring", m.ground, (0.5, 0.0), slider, (xc, 0.0), stiffness=200.0,
                        damping=1.5, free_length=0.25,
                        force=mb.Harmonic(2.0, 7.0, phase=0.1, offset=0.5))
    m.add_rotational_spring_damper("twist", m.ground, rod, stiffness=3.0, damping=0.01,
                                   torque=mb.SmoothStep(0.1, 0.3, 0.0, 0.5))
    m.add_force("push", bob, (mb.Polynomial([0.1, -0.2, 0.05]), 0.3))
    m.add_torque("brake", crank, mb.Spline([0.0, 0.2, 0.5], [0.0, -0.1, 0.2]))
    m.add_force("wind", rod, (0.25, mb.Constant(-0.125)), point=(xc / 2 + 0.1, 0.05), local=True)
    return m


def test_round_trip_bit_for_bit(tmp_path):
    m = mechanism()
    settings = {"t_end": 0.3, "rtol": 1e-7, "atol": 1e-9, "n_out": 31}
    output = {"reactions": ["guide", "motor"], "efforts": ["motor"], "energy": True}
    path = str(tmp_path / "mechanism.toml")
    save_scene(m, path, settings=settings, output=output)
    scene = load_scene(path)
    assert scene.settings == settings and scene.output == output
    assert [method for method, _ in scene.model.elements] == [method for method, _ in m.elements]
    assert scene.model.n_coordinates == m.n_coordinates == 14
    assert scene.model.n_constraints == m.n_constraints == 13

    r0 = mb.simulate(m, **settings)
    r1 = scene.run()
    for name in ("t", "q", "v", "a", "lam"):
        assert np.array_equal(getattr(r0, name), getattr(r1, name)), name
    assert np.array_equal(r0.effort("motor"), r1.effort("motor"))
    assert r1.residual.max() < 1e-8
    # the crank follows its driver: angle = pi/2 + 10 t
    assert np.allclose(r1.body("crank").angle, math.pi / 2 + 10.0 * r1.t, atol=1e-9, rtol=0)

    # writing the loaded model again gives the same file
    again = str(tmp_path / "again.toml")
    save_scene(scene.model, again, settings=scene.settings, output=scene.output)
    assert open(again).read() == open(path).read()


def test_round_trip_exact_floats(tmp_path):
    require("elements")
    m = mb.Model(gravity=(0.1, -9.80665))
    values = [1 / 3, 2.0**-1074, 1e300, 0.1 + 0.2, -1e-5, 123456789.123456789]
    for k, v in enumerate(values):
        m.add_body(f"b{k}", mass=abs(v), inertia=abs(v) * 2.0, position=(v, -v), angle=v)
    path = str(tmp_path / "floats.toml")
    save_scene(m, path)
    back = dict((kw["name"], kw) for method, kw in load_scene(path).model.elements)
    for k, v in enumerate(values):
        kw = back[f"b{k}"]
        assert kw["mass"] == abs(v) and kw["inertia"] == abs(v) * 2.0
        assert tuple(kw["position"]) == (v, -v) and kw["angle"] == v
    assert tuple(load_scene(path).model.gravity) == (0.1, -9.80665)


def test_an_input_shared_by_two_elements_stays_one_input_through_a_scene(tmp_path):
    """One unnamed mb.Input fed two torques: one input "t1" before the round
    trip, two ("t1", "t2") after it, so set_input("t1", 1) drove both bodies
    before and one after. The scene names a shared input in each place, and
    the reader joins inputs by name."""
    m = mb.Model(dimension=3)
    a = m.add_body("a", 1.0, (0.1, 0.1, 0.1))
    b = m.add_body("b", 1.0, (0.1, 0.1, 0.1), position=(1.0, 0.0, 0.0))
    push = mb.Input(0.0)
    m.add_torque("t1", a, (push, 0.0, 0.0))
    m.add_torque("t2", b, (0.0, 0.0, push))
    path = tmp_path / "shared.toml"
    save_scene(m, path)
    back = load_scene(path).model
    assert [d["name"] for d in back.compiled().inputs] == [d["name"] for d in m.compiled().inputs] == ["t1"]
    for model in (m, back):
        sim = mb.Simulator(model)
        sim.set_input("t1", 1.0)
        sim.advance(0.1)
        assert sim.body("a").angular_velocity[0] > 0.9 and sim.body("b").angular_velocity[2] > 0.9
    text = path.read_text()
    assert text.count('{ type = "input", initial = 0.0, name = "t1" }') == 2
    path.write_text(text.replace("initial = 0.0", "initial = 2.0", 1))
    with pytest.raises(SceneError, match="input 't1' is given again with another initial value"):
        load_scene(path)


def test_writing_a_callable_names_the_element(tmp_path):
    require("elements", "add_torque")
    m = mb.Model()
    wheel = m.add_body("wheel", mass=1.0, inertia=0.5)
    m.add_revolute("axle", m.ground, wheel, at=(0.0, 0.0))
    m.add_torque("pedal", wheel, lambda t: (math.sin(t), math.cos(t), -math.sin(t)))
    path = tmp_path / "callable.toml"
    with pytest.raises(mb.ModelError) as e:
        save_scene(m, str(path))
    message = str(e.value)
    assert "'pedal'" in message and "'torque'" in message and "callable" in message
    assert not path.exists()


def test_written_settings_read_back(tmp_path):
    require("elements")
    m = mb.Model()
    m.add_body("disk", mass=1.0, inertia=0.5, angular_velocity=1.0)
    path = tmp_path / "settings.toml"
    # t_out wins over n_out in simulate: only t_out is written
    save_scene(m, str(path), settings={"t_out": np.array([0.0, 0.5, 1.0]), "n_out": 7,
                                       "rtol": 1e-9, "max_step": None})
    scene = load_scene(str(path))
    assert scene.settings == {"t_out": [0.0, 0.5, 1.0], "rtol": 1e-9}
    assert np.allclose(scene.run().body("disk").angle, [0.0, 0.5, 1.0], rtol=0, atol=1e-12)
    # what would not read back is not written
    bad = tmp_path / "bad.toml"
    for settings, output, key in (({"rtol": "tight"}, None, "rtol"),
                                  ({"t_end": 1.0, "steps": 3}, None, "steps"),
                                  (None, {"reactions": ["axle"]}, "reactions")):
        with pytest.raises(SceneError) as e:
            save_scene(m, str(bad), settings=settings, output=output)
        assert e.value.key == key and str(bad) in str(e.value)
        assert not bad.exists()


# --- the examples ------------------------------------------------------------------

def _slider_crank(r):
    # the motor imposes angle = pi/2 + 10 t; the slider stays between 0.2 and 0.4 m
    assert np.allclose(r.body("crank").angle, math.pi / 2 + 10.0 * r.t, atol=1e-8, rtol=0)
    x = r.body("slider").position[:, 0]
    assert x[0] == pytest.approx(math.sqrt(0.08), abs=1e-12)
    assert 0.2 - 1e-9 <= x.min() and x.max() <= 0.4 + 1e-9
    assert np.all(np.abs(r.body("slider").position[:, 1]) < 1e-9)


def _gear_train(r):
    # omega3 = (-2) (-2) omega1 = 20 rad/s; motor torque 4 N m against the -1 N m load
    assert np.allclose(r.body("g3").angular_velocity, 20.0, rtol=1e-7)
    assert np.allclose(r.body("g2").angular_velocity, -10.0, rtol=1e-7)
    assert np.allclose(r.effort("motor"), 4.0, rtol=1e-6)


def _spring_damper(r):
    # released with the spring unstretched: the block starts with a = -g
    assert r.body("block").acceleration[0, 1] == pytest.approx(-G, rel=1e-9)
    assert np.all(np.abs(r.body("block").position[:, 0]) < 1e-9)


def _seed_pendulum(r):
    assert r.reaction("pin")[0, 1] == pytest.approx(G / 4, rel=1e-9)


def _double_pendulum(r):
    assert np.ptp(r.energy) < 1e-5


def _four_bar(r):
    assert r.body("crank").angle[0] == pytest.approx(math.radians(60.0), abs=1e-12)
    assert np.ptp(r.energy) < 1e-5


def _quick_return(r):
    # the ram starts at sqrt(0.4^2 - 0.15^2) and keeps to its guide
    assert r.body("ram").position[0, 0] == pytest.approx(math.sqrt(0.4**2 - 0.15**2), abs=1e-12)
    assert np.all(np.abs(r.body("ram").position[:, 1] - 0.04) < 1e-9)


CHECKS = {
    "seed_pendulum": _seed_pendulum, "double_pendulum": _double_pendulum,
    "slider_crank": _slider_crank, "four_bar": _four_bar, "quick_return": _quick_return,
    "gear_train": _gear_train, "spring_damper": _spring_damper,
}


def test_all_examples_present():
    found = {os.path.basename(p)[:-5] for p in glob.glob(os.path.join(EXAMPLES, "*.toml"))}
    assert set(CHECKS) <= found


@pytest.mark.parametrize("name", sorted(os.path.basename(p)[:-5]
                                         for p in glob.glob(os.path.join(EXAMPLES, "*.toml"))))
def test_example_runs(name):
    path = os.path.join(EXAMPLES, name + ".toml")
    try:
        scene = load_scene(path)
    except SceneError as e:
        if "this lagmb has no" in str(e):
            pytest.skip(str(e))
        raise
    t_end = min(scene.settings["t_end"], 0.3)
    r = scene.run(t_end=t_end)
    assert r.t[0] == 0.0 and r.t[-1] == t_end
    assert r.residual.max() < 1e-8
    CHECKS.get(name, lambda r: None)(r)


def test_quick_return_time_ratio():
    """Whitworth: the ram's forward stroke takes 227.16 deg of crank turn, the
    return 132.84 deg (sin(theta) = 0.04 / 0.1): ratio 1.71."""
    try:
        scene = load_scene(os.path.join(EXAMPLES, "quick_return.toml"))
    except SceneError as e:
        if "this lagmb has no" in str(e):
            pytest.skip(str(e))
        raise
    r = scene.run(n_out=3601)  # one crank turn, every 0.1 degree
    x = r.body("ram").position[:, 0]
    v = r.body("ram").velocity[:, 0]
    turns = np.nonzero(np.sign(v[:-1]) * np.sign(v[1:]) < 0)[0]
    assert len(turns) == 2
    t_max, t_min = r.t[turns[np.argmax(x[turns])]], r.t[turns[np.argmin(x[turns])]]
    theta = math.degrees(math.asin(0.4))
    long_stroke = (180.0 + 2 * theta) / 360.0  # s: the crank turns once a second
    strokes = sorted([abs(t_max - t_min), 1.0 - abs(t_max - t_min)])
    assert strokes[1] == pytest.approx(long_stroke, abs=2e-3)
    assert strokes[1] / strokes[0] == pytest.approx(1.70995, abs=0.01)
    assert np.ptp(x) == pytest.approx(0.3, abs=1e-6)  # stroke = 2 x 0.15


# --- errors: file, line, table and key ------------------------------------------

def check_error(tmp_path, text, key, table, *words, mark="# <-"):
    path = write(tmp_path, text, "bad.toml")
    with pytest.raises(SceneError) as e:
        load_scene(path)
    err = e.value
    message = str(err)
    line = marked_line(text, mark)
    assert isinstance(err, mb.ModelError) and isinstance(err, ValueError)
    assert err.line == line, message
    assert err.key == key, message
    assert message.startswith(f"{path}, line {line}: "), message
    if table is not None:
        assert table in message, message
    assert f"'{key}'" in message, message
    for w in words:
        assert w in message, message
    assert err.path == path
    return err


def test_unknown_key(tmp_path):
    text = PENDULUM.replace("at = [0.0, 0.0]", "att = [0.0, 0.0]  # <-")
    check_error(tmp_path, text, "att", "joints[0] 'pin'", "unknown key", "at, local_i")


def test_unknown_table(tmp_path):
    text = PENDULUM.replace("[output]", "[outputs]  # <-")
    check_error(tmp_path, text, "outputs", None, "unknown table [outputs]")


def test_unknown_array_of_tables(tmp_path):
    text = PENDULUM + '\n[[springs]]  # <-\nname = "s"\n'
    check_error(tmp_path, text, "springs", None, "unknown table [[springs]]")


def test_missing_required_key(tmp_path):
    text = PENDULUM.replace("inertia = 0.08333333333333333\n", "").replace(
        "[[bodies]]", "[[bodies]]  # <-")
    check_error(tmp_path, text, "inertia", "bodies[0] 'rod'", "missing required key")


def test_missing_type(tmp_path):
    text = PENDULUM.replace('type = "revolute"\n', "").replace("[[joints]]", "[[joints]]  # <-")
    check_error(tmp_path, text, "type", "joints[0] 'pin'", "missing required key", "revolute")


def test_wrong_type(tmp_path):
    text = PENDULUM.replace("mass = 1.0", 'mass = "heavy"  # <-')
    check_error(tmp_path, text, "mass", "bodies[0] 'rod'", "must be a number", "string")


def test_wrong_point(tmp_path):
    text = PENDULUM.replace("position = [0.5, 0.0]", "position = [0.5, 0.0, 1.0]  # <-")
    check_error(tmp_path, text, "position", "bodies[0] 'rod'", "pair of numbers")


def test_value_rejected_by_the_model(tmp_path):
    text = PENDULUM.replace("mass = 1.0", "mass = -1.0  # <-")
    check_error(tmp_path, text, "mass", "bodies[0] 'rod'", "mass must be positive", "-1")


def test_non_finite_value_rejected_by_the_model(tmp_path):
    text = PENDULUM.replace("at = [0.0, 0.0]", "at = [0.0, nan]  # <-")
    check_error(tmp_path, text, "at", "joints[0] 'pin'", "not finite")


def test_unknown_body(tmp_path):
    text = PENDULUM.replace('body_j = "rod"', 'body_j = "rdo"  # <-')
    check_error(tmp_path, text, "body_j", "joints[0] 'pin'", "no body named 'rdo'")


def test_body_defined_after_its_joint(tmp_path):
    text = PENDULUM.replace('body_j = "rod"', 'body_j = "tip"  # <-') + (
        '\n[[bodies]]\nname = "tip"\nmass = 1.0\ninertia = 1.0\n')
    err = check_error(tmp_path, text, "body_j", "joints[0] 'pin'", "defined later")
    assert "bodies[1]" in str(err)


def test_unknown_joint_type(tmp_path):
    text = PENDULUM.replace('type = "revolute"', 'type = "hinge"  # <-')
    check_error(tmp_path, text, "type", "joints[0] 'pin'", "unknown joint type 'hinge'",
                "revolute, translational")


def test_duplicate_name(tmp_path):
    text = PENDULUM.replace('name = "pin"', 'name = "rod"  # <-')
    check_error(tmp_path, text, "name", "joints[0] 'rod'", "duplicate name", "bodies[0]", "line 5")


def test_joint_between_a_body_and_itself(tmp_path):
    text = PENDULUM.replace('body_i = "ground"', 'body_i = "rod"').replace(
        "[[joints]]", "[[joints]]  # <-")
    path = write(tmp_path, text)
    with pytest.raises(SceneError) as e:
        load_scene(path)
    assert e.value.line == marked_line(text) and "joints[0] 'pin'" in str(e.value)
    assert "itself" in str(e.value)


def test_bad_simulation_settings(tmp_path):
    check_error(tmp_path, PENDULUM.replace("rtol = 1e-8", 'rtol = "tight"  # <-'), "rtol",
                "[simulation]", "must be a number")
    check_error(tmp_path, PENDULUM.replace("n_out = 101", "n_out = 100.5  # <-"), "n_out",
                "[simulation]", "must be an integer")
    check_error(tmp_path, PENDULUM.replace("t_end = 1.0", "t_end = -1.0  # <-"), "t_end",
                "[simulation]", "greater than t0")
    check_error(tmp_path, PENDULUM.replace("atol = 1e-10", "tolerance = 1e-10  # <-"),
                "tolerance", "[simulation]", "unknown key")


def test_simulation_setting_rejected_at_run_time(tmp_path):
    text = PENDULUM.replace("rtol = 1e-8", "rtol = 1e-16  # <-")
    scene = load_scene(write(tmp_path, text))
    with pytest.raises(SceneError) as e:
        scene.run()
    assert e.value.line == marked_line(text) and e.value.key == "rtol"
    assert "[simulation]" in str(e.value)
    text = PENDULUM.replace("rtol = 1e-8", 'formulation = "fastest"  # <-')
    with pytest.raises(SceneError) as e:
        load_scene(write(tmp_path, text)).run()
    assert e.value.line == marked_line(text) and e.value.key == "formulation"
    assert "fastest" in str(e.value)
    # an override that is wrong is the caller's, not the file's
    scene = load_scene(write(tmp_path, PENDULUM))
    with pytest.raises(mb.ModelError) as e:
        scene.run(rtol=1e-16)
    assert not isinstance(e.value, SceneError)


def test_bad_output(tmp_path):
    check_error(tmp_path, PENDULUM.replace('reactions = ["pin"]', 'reactions = ["pen"]  # <-'),
                "reactions", "[output]", "no joint or driver named 'pen'")
    check_error(tmp_path, PENDULUM.replace('reactions = ["pin"]', 'file = "out.txt"  # <-'),
                "file", "[output]", ".npz or .csv")
    check_error(tmp_path, PENDULUM.replace('reactions = ["pin"]', "energy = 1  # <-"),
                "energy", "[output]", "true or false")


def test_element_table_must_be_an_array(tmp_path):
    text = PENDULUM.replace("[[joints]]", "[joints]  # <-")
    check_error(tmp_path, text, "joints", None, "array of tables [[joints]]")


def test_not_toml(tmp_path):
    text = PENDULUM.replace("mass = 1.0", "mass = = 1.0  # <-")
    path = write(tmp_path, text)
    with pytest.raises(SceneError) as e:
        load_scene(path)
    assert e.value.line == marked_line(text)
    assert str(e.value).startswith(f"{path}, line {marked_line(text)}: not valid TOML")


def test_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError):
        load_scene(str(tmp_path / "nowhere.toml"))


DRIVEN = PENDULUM.replace("[simulation]", """\
[[drivers]]
type = "joint"
name = "motor"
joint = "pin"
function = { type = "linear", rate = 2.0, start = 0.0 }

[simulation]""")


def test_driver_function_inline_table(tmp_path):
    require("drive_joint", "elements")
    scene = load_scene(write(tmp_path, DRIVEN))
    r = scene.run(t_end=0.5)
    assert np.allclose(r.body("rod").angle, 2.0 * r.t, atol=1e-9, rtol=0)
    # a plain number is a constant
    scene = load_scene(write(tmp_path, DRIVEN.replace(
        "function = { type = \"linear\", rate = 2.0, start = 0.0 }", "function = 0.0")))
    r = scene.run(t_end=0.5)
    assert np.all(np.abs(r.body("rod").angle) < 1e-9)
    assert np.allclose(r.effort("motor"), 0.5 * G, rtol=1e-8)  # holds the rod up: m g L / 2


def test_driver_errors(tmp_path):
    require("drive_joint")
    check_error(tmp_path, DRIVEN.replace('joint = "pin"', 'joint = "pn"  # <-'), "joint",
                "drivers[0] 'motor'", "no joint named 'pn'")
    check_error(tmp_path, DRIVEN.replace("function = {", "function = \"fast\"  # <-\n#{"),
                "function", "drivers[0] 'motor'", "number or a time function")
    check_error(tmp_path, DRIVEN.replace("type = \"linear\", rate", "type = \"linear\", rat")
                .replace("start = 0.0 }", "start = 0.0 }  # <-"),
                "function", "drivers[0] 'motor'")
    check_error(tmp_path, DRIVEN.replace('type = "joint"', 'type = "crank"  # <-'), "type",
                "drivers[0] 'motor'", "unknown driver type 'crank'", "joint, body")
    check_error(tmp_path, DRIVEN.replace("function = {", "# function = {").replace(
        "[[drivers]]", "[[drivers]]  # <-"), "function", "drivers[0] 'motor'",
        "missing required key")


def test_schema_gives_every_model_method_and_argument_a_kind():
    """lagmb.scene.schema.ELEMENTS lists every add_* / drive_* method of the
    Model (as handles.KINDS does) with exactly its arguments: the reader
    takes the keys from the signature and their kinds of value from the
    schema, so an argument missing there would be passed on unchecked."""
    import inspect

    from lagmb.handles import KINDS
    from lagmb.scene.schema import ELEMENTS

    assert set(ELEMENTS) == set(KINDS)
    for method, element in ELEMENTS.items():
        params = list(inspect.signature(getattr(mb.Model, method)).parameters)[1:]
        assert list(element.arguments) == params, method
        assert set(element.renamed) <= set(params), method
