"""The integration methods are declared once (cpp/src/integrators/methods.cpp) and every
user-facing list is that table: lagmb.methods(), `lagmb info --methods`,
the scene reader's formulation/integrator/max_order checks, simulate's
validation and the work-precision presets (mb.METHODS)."""

import inspect
import os
import re

import numpy as np
import pytest

import lagmb as mb
from builders import lagmb_command, pendulum
import paths  # noqa: E402  (tests/paths.py)


def options_of(method):
    options = dict(formulation=method["formulation"], integrator=method["integrator"])
    if method["fixed_step"]:
        options["step"] = 1e-3
    if method["baumgarte"]:
        options["baumgarte"] = (10.0, 10.0)
    return options


def test_the_table_lists_each_method_once_with_what_it_supports():
    table = mb.methods()
    assert table[0]["name"] == "ggl"                          # GGL first ("auto" chooses)
    names = [m["name"] for m in table]
    assert len(set(names)) == len(names)
    pairs = [(m["formulation"], m["integrator"]) for m in table]
    assert len(set(pairs)) == len(pairs)
    assert {"ggl", "index3", "index1", "projection-bdf", "projection-adams", "ali3p"} <= set(names)
    for m in table:
        assert m["description"] and m["solver"] and m["max_order"] >= 1
    ali3p = next(m for m in table if m["name"] == "ali3p")
    assert ali3p["fixed_step"] and ali3p["events"] and not ali3p["contact"] and not ali3p["friction"]


@pytest.mark.parametrize("method", mb.methods(), ids=lambda m: m["name"])
def test_every_method_swings_the_pendulum_to_the_same_place(method):
    """Each method, as listed, runs the rod pendulum for 0.5 s; its stats
    name the method and its angle agrees with ggl's tight run to 1e-3 rad."""
    reference = mb.simulate(pendulum(), t_end=0.5, rtol=1e-10, atol=1e-12)
    # (a fixed-step method has no error control: no rtol, atol)
    tolerances = {} if method["fixed_step"] else dict(rtol=1e-8, atol=1e-10)
    r = mb.simulate(pendulum(), t_end=0.5, **tolerances, **options_of(method))
    assert (r.stats["formulation"], r.stats["integrator"]) == (method["formulation"], method["integrator"])
    assert abs(r.q[-1, 2] - reference.q[-1, 2]) < 1e-3


def test_the_integrator_defaults_to_the_formulations_first():
    for formulation in dict.fromkeys(m["formulation"] for m in mb.methods()):
        first = next(m for m in mb.methods() if m["formulation"] == formulation)
        options = options_of(first)
        del options["integrator"]
        assert mb.simulate(pendulum(), t_end=0.05, **options).stats["integrator"] == first["integrator"]


def test_names_outside_the_table_are_refused_listing_it():
    with pytest.raises(mb.ModelError, match=r"unknown formulation 'rk4' \(the choices are auto, ggl, index3, "
                                            r"index1, projection, ali3p\)"):
        mb.simulate(pendulum(), t_end=0.1, formulation="rk4")
    with pytest.raises(mb.ModelError, match="integrated by 'bdf', not by 'adams'"):
        mb.simulate(pendulum(), t_end=0.1, formulation="ggl", integrator="adams")
    with pytest.raises(mb.ModelError, match=r"max_order must be in 1\.\.5 for projection-bdf"):
        mb.simulate(pendulum(), t_end=0.1, formulation="projection", max_order=6)
    with pytest.raises(mb.ModelError, match="Baumgarte terms apply to the methods index1, projection-adams"):
        mb.simulate(pendulum(), t_end=0.1, formulation="ggl", baumgarte=(1.0, 1.0))
    with pytest.raises(mb.ModelError, match="Baumgarte terms need the formulation.*'auto' does not choose"):
        mb.simulate(pendulum(), t_end=0.1, baumgarte=(1.0, 1.0))
    with pytest.raises(mb.ModelError, match="integrator 'adams' needs its formulation: formulation 'auto'"):
        mb.simulate(pendulum(), t_end=0.1, integrator="adams")
    with pytest.raises(mb.ModelError, match=r"unknown start 'rest' \(the choices are given, equilibrium\)"):
        mb.Simulator(pendulum(), start="rest")
    with pytest.raises(mb.ModelError, match=r"unknown integrator 'rk4' \(the choices are bdf, adams, erk, "
                                            r"trapezoidal\)"):
        mb.simulate(pendulum(), t_end=0.1, integrator="rk4")


def test_the_choices_and_defaults_come_from_the_core():
    """One table names each choice, one struct holds the defaults: Python's
    signatures read them (lagmb/options.hpp)."""
    from lagmb import _core

    choices = _core.choices()
    assert choices["analysis"] == ("auto", "dynamic", "kinematic", "inverse_dynamics")
    assert choices["start"] == ("given", "equilibrium")
    # every formulation has its methods; "auto" (the default) chooses one of them
    assert {m["formulation"] for m in mb.methods()} | {"auto"} == set(choices["formulation"])
    assert choices["formulation"][0] == "auto" == _core.default_options()["formulation"]
    defaults = _core.default_options()
    for function in (mb.simulate, mb.Simulator):
        params = inspect.signature(function).parameters
        for key in ("rtol", "atol", "max_steps", "formulation", "start", "newton_rtol", "newton_atol"):
            assert params[key].default == defaults[key], (function, key)
    assert inspect.signature(mb.simulate).parameters["analysis"].default == defaults["analysis"] == "auto"


def test_ali3p_takes_its_newton_tolerance_not_rtol():
    """ali3p has no error control: rtol and atol are refused, its Newton
    iteration has its own tolerances; a looser one moves the result by
    about that much."""
    ali3p = options_of(next(x for x in mb.methods() if x["name"] == "ali3p"))
    for tolerance in (dict(rtol=1e-10), dict(atol=1e-12)):
        with pytest.raises(mb.ModelError, match="'ali3p' takes fixed steps without error control.*newton_rtol"):
            mb.simulate(pendulum(), t_end=0.1, **tolerance, **ali3p)
    tight = mb.simulate(pendulum(), t_end=0.5, **ali3p)
    loose = mb.simulate(pendulum(), t_end=0.5, newton_rtol=1e-4, newton_atol=1e-6, **ali3p)
    assert 0.0 < np.abs(tight.q - loose.q).max() < 1e-3
    with pytest.raises(mb.ModelError, match="newton_rtol must be positive"):
        mb.simulate(pendulum(), t_end=0.1, newton_rtol=0.0, **ali3p)


def test_what_a_method_does_not_model_is_refused_naming_the_methods_that_do():
    m = pendulum()
    m.add_joint_friction("pin_friction", "pin", mu=0.2, pin_radius=0.01)
    ali3p = next(x for x in mb.methods() if x["name"] == "ali3p")
    with pytest.raises(mb.ModelError, match="does not include joint friction.*'pin_friction'.*the methods that do: ggl"):
        mb.simulate(m, t_end=0.1, **options_of(ali3p))


def test_a_scene_is_checked_against_the_table(tmp_path):
    def scene(settings):
        path = tmp_path / "s.toml"
        path.write_text('[[bodies]]\nname = "b"\nmass = 1.0\ninertia = 1.0\n'
                        f'[simulation]\nt_end = 0.1\n{settings}\n')
        return path

    assert mb.load_scene(scene('formulation = "projection"\nintegrator = "adams"\nmax_order = 12'))
    projection = ", ".join(f"'{m['integrator']}'" for m in mb.methods() if m["formulation"] == "projection")
    with pytest.raises(mb.SceneError, match=f"integrator.*{re.escape(projection)} for formulation 'projection'"):
        mb.load_scene(scene('formulation = "projection"\nintegrator = "rk4"'))
    with pytest.raises(mb.SceneError, match="max_order.*1..5 for method 'ggl'"):
        mb.load_scene(scene('method = "ggl"\nmax_order = 6'))
    with pytest.raises(mb.SceneError, match="formulation.*'ggl', 'index3'"):
        mb.load_scene(scene('formulation = "rk4"'))


def test_the_work_precision_presets_are_the_variable_step_methods():
    variable = {m["name"] for m in mb.methods() if not m["fixed_step"]}
    assert set(mb.METHODS) == variable | {"index1-baumgarte"}


def test_lagmb_info_lists_the_methods():
    out = lagmb_command("info", "--methods", timeout=60)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    for m in mb.methods():
        line = next(x for x in lines if x.split()[0] == m["name"])
        assert m["formulation"] in line and m["integrator"] in line and m["description"] in line


def test_auto_chooses_from_the_model_and_says_why():
    """formulation="auto" (the default): the explicit method for a pendulum
    (no stiff forces), GGL for a stiff spring (its rate sqrt(k/m) times the
    span above 1000) and for a contact; r.stats["method_choice"] says so."""
    free = mb.simulate(pendulum(), t_end=0.5, n_out=3)
    assert (free.stats["formulation"], free.stats["integrator"]) == ("projection", "erk")
    assert free.stats["method_choice"].startswith("auto: projection-erk, the forces' fastest rate 0 1/s")
    stiff = mb.Model(gravity=(0.0, -9.81))
    block = stiff.add_body("block", 1.0, 0.1, position=(1.0, 0.0))
    stiff.add_translational("rail", stiff.ground, block, at=(1.0, 0.0), axis=(1.0, 0.0))
    stiff.add_spring_damper("spring", stiff.ground, (0.0, 0.0), block, (1.0, 0.0), stiffness=1e8, free_length=0.9)
    r = mb.simulate(stiff, t_end=0.5, n_out=3)
    assert r.stats["formulation"] == "ggl"
    rate = float(r.stats["method_choice"].split("fastest rate ")[1].split()[0])
    assert rate == pytest.approx(1e4, rel=1e-2)  # sqrt(k / m)
    assert mb.simulate(stiff, t_end=0.5, n_out=3, formulation="projection", integrator="erk").stats["method_choice"] \
        == "given"
    ball = mb.Model(gravity=(0.0, -9.81))
    b = ball.add_body("ball", 1.0, 0.004, position=(0.0, 1.0))
    ball.add_contact("floor", b, (0.0, 1.0), 0.1, "ground", (0.0, 0.0), (1.0, 0.0), stiffness=1e7, restitution=0.8)
    assert "contact ('floor')" in mb.simulate(ball, t_end=0.5, n_out=3).stats["method_choice"]


def test_auto_hands_a_stiff_run_over_to_ggl(tmp_path):
    """A top of 9.2e18 kg on 0.002 kg m^2 (a fuzzed scene) is stiff in a way
    its forces do not show at the start: the explicit method gives up (its
    error test fails; or it would take 5,000 steps between two outputs) and
    GGL takes over from its last step (here to meet max_steps too: the model
    is beyond both)."""
    text = open(os.path.join(paths.EXAMPLES, "heavy_top.toml")).read()
    path = tmp_path / "heavy.toml"
    # (the scene as fuzzed: examples/heavy_top.toml when it spun at 10 rad/s)
    text = text.replace("[47.94255386, 0.0, 87.75825619]", "[4.794255386, 0.0, 8.775825619]")
    path.write_text(text.replace("mass = 1.0", "mass = 9223372036854775808"))
    with pytest.raises(mb.SimulationError, match="IDA took max_steps = 20000") as failure:
        mb.simulate(mb.load_scene(path).model, 2.0, n_out=11, max_steps=20000)
    stats = failure.value.result.stats
    assert stats["formulation"] == "ggl"
    assert re.search(r"GGL took over: (ERKStep failed|ARKODE ERKStep took 5000 steps)", stats["method_choice"])


def test_the_explicit_method_refuses_a_contact_it_cannot_place():
    """projection-erk passed a whole bounce of the bouncing ball inside one
    step, placed the onset on its interpolant and ran on 1 km off with no
    error; a model with a contact (an event that switches a force) is now
    refused by name, listing the methods that place it."""
    ball = mb.Model(gravity=(0.0, -9.81))
    b = ball.add_body("ball", 1.0, 0.004, position=(0.0, 1.0))
    ball.add_contact("floor", b, (0.0, 1.0), 0.1, "ground", (0.0, 0.0), (1.0, 0.0), stiffness=1e7, restitution=0.8)
    with pytest.raises(mb.ModelError, match="projection-erk cannot place the onset of contact 'floor'.*ggl"):
        mb.simulate(ball, t_end=1.0, formulation="projection", integrator="erk")
    assert not next(m for m in mb.methods() if m["name"] == "projection-erk")["contact"]


def test_a_method_is_named_the_same_way_everywhere(tmp_path):
    """One name per method, the one lagmb.methods() lists: simulate(method=),
    in any case, runs exactly what its formulation and integrator run, and
    r.stats["method"] names the method that ran; a listed name is taken as a
    formulation too; the Simulator and a scene's [simulation] take it alike."""
    model = pendulum()
    for m in mb.methods():
        if m["fixed_step"]:
            continue
        by_parts = mb.simulate(model, 0.2, n_out=3, formulation=m["formulation"], integrator=m["integrator"])
        by_name = mb.simulate(model, 0.2, n_out=3, method=m["name"].upper())
        assert np.array_equal(by_name.q, by_parts.q)
        assert by_name.stats["method"] == by_parts.stats["method"] == m["name"]
        as_formulation = mb.simulate(model, 0.2, n_out=3, formulation=m["name"])
        assert np.array_equal(as_formulation.q, by_parts.q)
    assert mb.simulate(model, 0.2, n_out=3).stats["method"] == "projection-erk"  # "auto" chose it
    simulator = mb.Simulator(model, method="Projection-BDF")
    simulator.advance(0.1)
    assert simulator.result().stats["method"] == "projection-bdf"
    scene = tmp_path / "s.toml"
    mb.save_scene(model, scene)
    scene.write_text(scene.read_text() + '\n[simulation]\nt_end = 0.2\nmethod = "index3"\n')
    assert mb.load_scene(scene).run().stats["method"] == "index3"


@pytest.mark.parametrize("options, message", [
    (dict(method="rk4"), "method 'rk4' is not one of: auto, ggl"),
    (dict(method="ggl", formulation="index3"), "give method, or formulation and integrator, not both"),
    (dict(method="ggl", integrator="bdf"), "not both"),
    (dict(formulation="projection-erk", integrator="bdf"), "names integrator 'erk', got integrator 'bdf'"),
    (dict(method=3), "method must be a string"),
])
def test_a_method_name_that_does_not_fit_is_refused_by_name(options, message):
    with pytest.raises(mb.ModelError, match=re.escape(message)):
        mb.simulate(pendulum(), 0.1, **options)


def test_a_scene_refuses_a_method_beside_a_formulation_at_its_line(tmp_path):
    scene = tmp_path / "s.toml"
    mb.save_scene(pendulum(), scene)
    scene.write_text(scene.read_text() + '\n[simulation]\nmethod = "ggl"\nformulation = "index1"\n')
    with pytest.raises(mb.SceneError, match=r"method.*not both"):
        mb.load_scene(scene)
