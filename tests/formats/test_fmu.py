"""A scene as an FMI 3.0 co-simulation FMU (`lagmb fmu`), checked with FMPy
as the importer: the model description validates, FMPy runs the FMU, its
outputs match lagmb.simulate of the same scene, parameters change before
initialization, and a controller closes the loop through the FMU's input.
The co-simulation the FMU wraps (lagmb._core.CoSimulation) is tested here
too, without FMPy."""

import contextlib
import math
import os
import re
import shutil
import sys
import zipfile
from types import SimpleNamespace

import numpy as np
import pytest

import lagmb as mb
from lagmb.cli import main as cli

from paths import ROOT  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "examples"))
import cart_pole as cp  # noqa: E402

try:
    import fmpy
    from fmpy import read_model_description, simulate_fmu
    from fmpy.fmi3 import FMU3Slave
    from fmpy.validation import validate_fmu
except ImportError:
    fmpy = None
needs_fmpy = pytest.mark.skipif(fmpy is None, reason="FMPy is not installed (pip install 'lagmb[fmu]'): "
                                                      "it provides the FMI headers and is the test importer")
needs_cc = pytest.mark.skipif(not any(shutil.which(c) for c in ("cc", "gcc", "clang")), reason="needs a C compiler")


@pytest.fixture(scope="module")
def cart_pole_scene():
    """examples/cart_pole.toml: examples/cart_pole.py's model as a scene
    (tests/tools/test_examples.py checks they are one model), with the hinge's
    reaction as an output and tight tolerances."""
    return os.path.join(ROOT, "examples", "cart_pole.toml")


@pytest.fixture(scope="module")
def cart_pole_fmu(cart_pole_scene, tmp_path_factory):
    if fmpy is None:
        pytest.skip("FMPy is not installed")
    path = str(tmp_path_factory.mktemp("fmu") / "cart_pole.fmu")
    assert cli(["fmu", cart_pole_scene, "-o", path, "-q"]) == 0
    return path


# --- the co-simulation behind the FMU (no FMPy needed) --------------------------


def cosimulation(scene_path):
    from lagmb.fmu import setup_text

    return mb._core.CoSimulation(setup_text(mb.load_scene(scene_path)))


def test_the_variables_of_a_cosimulation(cart_pole_scene):
    """Time, the input, each number given to an element as a parameter (a
    body's initial angle as "<body>.angle.start"), the coordinates and
    their rates, the reaction asked for: each with its unit."""
    variables = {v["name"]: v for v in cosimulation(cart_pole_scene).variables}
    assert variables["time"]["causality"] == "independent" and variables["time"]["unit"] == "s"
    assert variables["push"]["causality"] == "input" and variables["push"]["unit"] == "N"
    assert variables["pole.mass"]["causality"] == "parameter" and variables["pole.mass"]["unit"] == "kg"
    assert variables["pole.mass"]["start"] == 0.1
    assert variables["pole.angle.start"]["start"] == pytest.approx(math.pi / 2 + 0.1)
    assert variables["pole.angle"]["causality"] == "output" and variables["pole.angle"]["unit"] == "rad"
    assert variables["der(pole.angle)"]["unit"] == "rad/s" and variables["der(cart.x)"]["unit"] == "m/s"
    assert [variables[f"hinge.reaction.{c}"]["unit"] for c in ("x", "y", "torque")] == ["N", "N", "N m"]


def test_a_driver_effort_has_the_unit_of_what_it_drives():
    """examples/slider_crank.toml: the motor drives an angle, its effort is a
    torque (N m); the guide's reaction a force."""
    variables = {v["name"]: v for v in cosimulation(os.path.join(ROOT, "examples", "slider_crank.toml")).variables}
    assert variables["motor.effort"]["unit"] == "N m"
    assert variables["guide.reaction.y"]["unit"] == "N"


def test_a_cosimulation_refuses_what_it_cannot_do(cart_pole_scene):
    c = cosimulation(cart_pole_scene)
    names = [v["name"] for v in c.variables]
    with pytest.raises(mb.ModelError, match="from initialization on"):
        c.get(names.index("pole.angle"))
    with pytest.raises(mb.ModelError, match="'pole.angle' is an output"):
        c.set(names.index("pole.angle"), 1.0)
    with pytest.raises(mb.ModelError, match="must be finite"):
        c.set(names.index("push"), float("nan"))
    with pytest.raises(mb.ModelError, match="no variable with value reference 999"):
        c.get(999)
    c.enter_initialization(0.0)
    c.exit_initialization()
    with pytest.raises(mb.ModelError, match="'pole.mass' is fixed once initialization has ended"):
        c.set(names.index("pole.mass"), 0.2)
    with pytest.raises(mb.ModelError, match="a step from t = 1"):
        c.do_step(1.0, 0.01)
    with pytest.raises(mb.ModelError, match="a step from t = nan"):
        c.do_step(float("nan"), 0.01)  # was taken, and reported lastSuccessfulTime NaN
    c.do_step(0.0, 0.01)
    assert c.get(0) == pytest.approx(0.01)


@pytest.mark.parametrize("input_name, other", [
    ("pole.x", "the output (coordinate of body pole)"),
    ("pole.mass", "the parameter (mass"),
    ("der(cart.x)", "the output (its rate)"),
    ("time", "the independent (simulation time)"),
])
def test_names_that_would_collide_in_an_fmu_are_refused_naming_both(input_name, other):
    """An input named like another variable gave an FMU with two variables
    of one name, which FMPy rejects."""
    from lagmb.fmu import setup_text

    m = mb.Model(gravity=(0.0, -9.81))
    cart = m.add_body("cart", 1.0, 0.01)
    pole = m.add_body("pole", 0.1, 1e-3, position=(0.0, 0.5))
    m.add_revolute("hinge", cart, pole, at=(0.0, 0.0))
    m.add_force("push", cart, force=(mb.Input(0.0, name=input_name), 0.0))
    with pytest.raises(mb.ModelError, match=f"two variables would be called '{re.escape(input_name)}'") as e:
        mb._core.CoSimulation(setup_text(SimpleNamespace(model=m, settings={}, output={})))
    assert other in str(e.value) and "input to push" in str(e.value)


def test_a_python_callable_cannot_go_in_an_fmu():
    from lagmb.fmu import setup_text

    model = cp.cart_pole()
    model.add_torque("wobble", "pole", torque=lambda t: 0.0)
    with pytest.raises(mb.ModelError, match="'wobble'.*Python callable"):
        setup_text(SimpleNamespace(model=model, settings={}, output={}))


def test_an_fmu_integrates_the_dynamics():
    from lagmb.fmu import setup_text

    with pytest.raises(mb.ModelError, match="analysis 'kinematic' is not for an FMU"):
        setup_text(SimpleNamespace(model=cp.cart_pole(), settings=dict(analysis="kinematic"), output={}))


def test_the_model_text_reads_back_to_the_same_run():
    """Every example scene written as text (what an FMU carries) and read
    back runs bit for bit as the original."""
    for name in ("slider_crank", "four_bar", "double_pendulum", "spring_damper", "heavy_top", "bouncing_ball"):
        scene = mb.load_scene(os.path.join(ROOT, "examples", name + ".toml"))
        text = scene.model._spec.to_text()
        again = mb._core.ModelSpec.from_text(text)
        assert again.to_text() == text
        options = dict(t_end=0.2, n_out=5)
        a = mb._core.simulate(scene.model.compiled(), options)
        b = mb._core.simulate(again.compile(), options)
        np.testing.assert_array_equal(a["q"], b["q"])


def test_a_wrong_model_text_names_its_line():
    with pytest.raises(mb.ModelError, match="not lagmb's"):
        mb._core.ModelSpec.from_text("hello")
    with pytest.raises(mb.ModelError, match="line 3: .*mass"):
        mb._core.ModelSpec.from_text('lagmb-spec 1\nelement body "b"\nmass r oops\nend\n')


# --- the FMU through FMPy ---------------------------------------------------------


# what every Linux machine has: the C and C++ runtimes and the loader
SYSTEM_RUNTIME = re.compile(r"^(linux-vdso|ld-linux-x86-64|libc|libm|libdl|libpthread|librt|libstdc\+\+|libgcc_s)\.so")


@needs_fmpy
@needs_cc
@pytest.mark.skipif(not sys.platform.startswith("linux") or not shutil.which("ldd"), reason="needs Linux's ldd")
def test_the_fmu_carries_every_library_it_loads_but_the_system_runtime(cart_pole_fmu, tmp_path):
    """The shared libraries the runtime needs (SuiteSparse's, where lagmb
    links the system's) travel in the FMU next to its binaries, and are the
    copies that load with the FMU's binary, all the way down (ldd lists the
    whole tree: an RPATH of $ORIGIN is searched before the system's folders,
    for the libraries' own dependencies too): the FMU runs where none of
    them is installed. Nothing GPL and no BLAS goes with it (the rank tests'
    QR is lagmb's own)."""
    import subprocess

    with zipfile.ZipFile(cart_pole_fmu) as z:
        z.extractall(tmp_path)
    binaries = tmp_path / "binaries" / "x86_64-linux"
    names = sorted(p.name for p in binaries.iterdir())
    assert {"cart_pole.so", "liblagmb_fmu.so"} <= set(names)
    assert not any(n.startswith(("libspqr", "libcholmod", "libblas", "liblapack", "libopenblas")) for n in names)
    # under make test-asan the FMU runtime is sanitized and the compiler's
    # sanitizer runtimes are preloaded: those are the build's, not the FMU's
    preloaded = set(os.environ.get("LD_PRELOAD", "").split())
    for name in ("cart_pole.so", "liblagmb_fmu.so"):  # what an importer loads, and what that loads
        out = subprocess.run(["ldd", str(binaries / name)], capture_output=True, text=True, check=True).stdout
        for line in out.strip().splitlines():
            lib = line.split()[0]
            if not SYSTEM_RUNTIME.match(os.path.basename(lib)) and lib not in preloaded:
                assert f"=> {binaries}/{lib} " in line, f"{name} loads {line.strip()} from outside the FMU"


@needs_fmpy
@needs_cc
def test_fmpy_finds_no_problem_in_the_fmu(cart_pole_fmu):
    assert validate_fmu(cart_pole_fmu) == []
    md = read_model_description(cart_pole_fmu)
    assert md.fmiVersion == "3.0" and md.coSimulation is not None
    units = {v.name: v.declaredType or v.unit for v in md.modelVariables}
    assert units["pole.angle"] == "rad" and units["hinge.reaction.torque"] == "N m"


@needs_fmpy
@needs_cc
def test_the_fmu_runs_as_lagmb_simulate_does(cart_pole_fmu, cart_pole_scene):
    """FMPy runs the FMU for 2 s (one co-simulation step per 20 ms output):
    coordinates, rates and the hinge reaction equal lagmb.simulate's on the
    same scene to 1e-6."""
    r = simulate_fmu(cart_pole_fmu, stop_time=2.0, output_interval=0.02)
    scene = mb.load_scene(cart_pole_scene)
    ref = mb.simulate(scene.model, t_out=r["time"], rtol=1e-9, atol=1e-11)
    pole, cart = ref.body("pole"), ref.body("cart")
    assert np.max(np.abs(r["pole.angle"] - pole.angle)) < 1e-6
    assert np.max(np.abs(r["der(pole.angle)"] - pole.angular_velocity)) < 1e-6
    assert np.max(np.abs(r["cart.x"] - cart.position[:, 0])) < 1e-6
    reaction = ref.reaction("hinge")
    for k, c in enumerate(("x", "y", "torque")):
        assert np.max(np.abs(r[f"hinge.reaction.{c}"] - reaction[:, k])) < 1e-6
    assert abs(r["pole.angle"][-1] - math.pi / 2) > 1.0  # with no force the pole has fallen


@needs_fmpy
@needs_cc
def test_parameters_change_before_initialization(cart_pole_fmu, cart_pole_scene, tmp_path):
    """A heavier pole (0.3 kg) set as a start value runs as the scene with
    that mass does."""
    r = simulate_fmu(cart_pole_fmu, stop_time=1.0, output_interval=0.05, start_values={"pole.mass": 0.3})
    ref = mb.simulate(_with_pole_mass(cart_pole_scene, 0.3, tmp_path), t_out=r["time"], rtol=1e-9, atol=1e-11)
    assert np.max(np.abs(r["cart.x"] - ref.body("cart").position[:, 0])) < 1e-6
    light = simulate_fmu(cart_pole_fmu, stop_time=1.0, output_interval=0.05)
    assert np.max(np.abs(r["cart.x"] - light["cart.x"])) > 1e-3  # the mass mattered


def _with_pole_mass(scene_path, mass, directory):
    """The scene's model with the pole's mass changed in a copy of the file
    (in directory)."""
    text = open(scene_path).read()
    text = re.sub(r'(name = "pole"\nmass = )[0-9.e-]+', lambda m: m.group(1) + repr(mass), text)
    path = os.path.join(str(directory), f"cart_pole_{mass}.toml")
    open(path, "w").write(text)
    return mb.load_scene(path).model


@needs_fmpy
@needs_cc
def test_an_input_signal_drives_the_fmu(cart_pole_fmu, cart_pole_scene):
    """A force of 2 N from t = 0.5 s on (a step in FMPy's input table): the
    FMU ends where a lagmb Simulator ends with that input."""
    signal = np.array([(0.0, 0.0), (0.5, 0.0), (0.5, 2.0), (1.0, 2.0)],
                      dtype=[("time", np.float64), ("push", np.float64)])
    r = simulate_fmu(cart_pole_fmu, stop_time=1.0, output_interval=0.05, input=signal)
    sim = mb.Simulator(mb.load_scene(cart_pole_scene).model, rtol=1e-9, atol=1e-11)
    sim.advance(0.5)
    sim.set_input("push", 2.0)
    sim.advance(1.0)
    assert r["cart.x"][-1] == pytest.approx(sim.body("cart").position[0], abs=1e-6)
    assert r["pole.angle"][-1] == pytest.approx(sim.body("pole").angle, abs=1e-6)


@contextlib.contextmanager
def initialized(path, name):
    """The FMU at `path` instantiated by FMPy and initialized at t = 0:
    (the FMU3Slave, {variable name: value reference}); freed afterwards."""
    md = read_model_description(path)
    unzipped = fmpy.extract(path)
    fmu = FMU3Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier,
                    instanceName=name)
    try:
        fmu.instantiate()
        fmu.enterInitializationMode(startTime=0.0)
        fmu.exitInitializationMode()
        yield fmu, {v.name: v.valueReference for v in md.modelVariables}
        fmu.terminate()
    finally:
        fmu.freeInstance()
        shutil.rmtree(unzipped, ignore_errors=True)


@needs_fmpy
@needs_cc
def test_a_controller_balances_the_pole_through_fmpy(cart_pole_fmu):
    """The PD controller of examples/cart_pole.py, on the other side of the
    FMI: FMPy instantiates the FMU, the loop reads its outputs and sets its
    input every 10 ms; the pole stays within 0.05 rad after 1 s. Setting a
    parameter after initialization is refused (fmi3Error)."""
    with initialized(cart_pole_fmu, "controller") as (fmu, vr):
        g = cp.GAINS
        t, worst_after_1s = 0.0, 0.0
        for k in range(1000):
            angle, rate, x, xdot = fmu.getFloat64([vr["pole.angle"], vr["der(pole.angle)"], vr["cart.x"],
                                                   vr["der(cart.x)"]])
            theta = angle - math.pi / 2
            if t >= 1.0:
                worst_after_1s = max(worst_after_1s, abs(theta))
            force = -(g["k_p"] * theta + g["k_d"] * rate) + g["k_x"] * x + g["k_v"] * xdot
            fmu.setFloat64([vr["push"]], [force])
            fmu.doStep(currentCommunicationPoint=t, communicationStepSize=0.01)
            t = (k + 1) * 0.01
        assert worst_after_1s < 0.05
        with pytest.raises(fmpy.fmi1.FMICallException):
            fmu.setFloat64([vr["pole.mass"]], [1.0])


def test_without_fmpy_the_fmu_command_says_what_is_missing(cart_pole_scene, tmp_path, monkeypatch, capsys):
    """`lagmb fmu` without FMPy: exit 1 and the pip command that brings it."""
    monkeypatch.setitem(sys.modules, "fmpy", None)  # import fmpy raises ImportError
    assert cli(["fmu", cart_pole_scene, "-o", str(tmp_path / "x.fmu")]) == 1
    assert "pip install 'lagmb[fmu]'" in capsys.readouterr().err
    assert not (tmp_path / "x.fmu").exists()


@needs_fmpy
@needs_cc
def test_a_spatial_scene_as_an_fmu(tmp_path):
    """examples/heavy_top.toml as an FMU: positions and Euler parameters
    (e0..e3, no unit) of the top over 0.5 s, as lagmb.simulate has them, and
    the spherical joint's reaction in six components."""
    scene = os.path.join(ROOT, "examples", "heavy_top.toml")
    path = str(tmp_path / "top.fmu")
    assert cli(["fmu", scene, "-o", path, "-q"]) == 0
    assert validate_fmu(path) == []
    units = {v.name: v.unit for v in read_model_description(path).modelVariables}
    assert units["top.e0"] is None and units["top.z"] == "m" and units["der(top.e1)"] == "1/s"
    assert units["tip.reaction.z"] == "N" and units["tip.reaction.torque.z"] == "N m"
    r = simulate_fmu(path, stop_time=0.5, output_interval=0.05)
    s = mb.load_scene(scene)
    settings = {k: v for k, v in s.settings.items() if k not in ("t_end", "n_out", "t_out")}
    ref = mb.simulate(s.model, t_out=r["time"], **settings)
    top = ref.body("top")
    for k, c in enumerate("xyz"):
        assert np.max(np.abs(r[f"top.{c}"] - top.position[:, k])) < 1e-6
    for k in range(4):
        assert np.max(np.abs(r[f"top.e{k}"] - top.orientation[:, k])) < 1e-6


@needs_fmpy
@needs_cc
def test_an_fmu_state_saved_and_restored_steps_on_bit_for_bit(cart_pole_fmu):
    """fmi3GetFMUState after 0.5 s, 50 steps of 10 ms with a push, back to
    the state, the same 50 steps: the same outputs, bit for bit."""
    with zipfile.ZipFile(cart_pole_fmu) as z:
        assert 'canGetAndSetFMUState="true"' in z.read("modelDescription.xml").decode()
    with initialized(cart_pole_fmu, "what-if") as (fmu, vr):
        for k in range(50):
            fmu.doStep(currentCommunicationPoint=0.01 * k, communicationStepSize=0.01)
        saved = fmu.getFMUState()

        def branch():
            path = []
            for k in range(50, 100):
                fmu.setFloat64([vr["push"]], [2.0 if k < 75 else -1.0])
                fmu.doStep(currentCommunicationPoint=0.01 * k, communicationStepSize=0.01)
                path.append(fmu.getFloat64([vr["pole.angle"], vr["cart.x"], vr["hinge.reaction.y"]]))
            return np.array(path)

        first = branch()
        fmu.setFMUState(saved)
        assert fmu.getFloat64([vr["time"]])[0] == pytest.approx(0.5)
        assert np.array_equal(branch(), first)
        fmu.freeFMUState(saved)
