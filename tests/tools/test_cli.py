"""The lagmb command, run as `python -m lagmb` in a subprocess.

- `run -o x.npz` writes t, q, v, a, lam, energy, residual, the coordinate
  names and reaction_<name> for the joints listed in [output] (all joints
  when none are listed), with the scene's output times.
- `run -o x.csv` writes a header (t, crank.x, ..., A.fx, A.fy, A.torque,
  energy) and one row per output time.
- `info` on the four-bar: 9 coordinates, 8 equations, rank 8, 1 degree of
  freedom; with a redundant fifth bar it names the redundant rows' joint.
- Exit 2 with the file and line on stderr (no traceback) for a bad scene;
  exit 1 for a failed run, with the partial results still written.
- `demo --quiet` exits 0 and prints nothing; --plot / --animate write files.
"""

import csv
import os
import re
import shutil

import numpy as np
import pytest

from lagmb.progress import Progress
from lagmb.scene import load_scene

from builders import ARM_URDF, gif_durations, pendulum_scene
from builders import lagmb_command as lagmb

from paths import EXAMPLES  # noqa: E402
FOUR_BAR_NAMES = ["crank", "coupler", "rocker"]


@pytest.fixture
def four_bar(tmp_path):
    """examples/four_bar.toml (reactions = ["A", "D"], energy = true), in tmp_path."""
    path = tmp_path / "four_bar.toml"
    shutil.copy(os.path.join(EXAMPLES, "four_bar.toml"), path)
    return path


def test_the_help_and_the_usage_name_every_subcommand_and_option():
    """lagmb --help lists each subcommand of lagmb.cli's table with its
    help; the usage in lagmb.cli's docstring shows each subcommand and
    every option each takes (short or long)."""
    import argparse

    from lagmb import cli

    p = lagmb("--help")
    assert p.returncode == 0, p.stderr
    listed = re.findall(r"^    (\w+)  +\S", p.stdout, re.M)
    assert listed == list(cli.COMMANDS)
    parsers = next(a for a in cli._parser()._actions if isinstance(a, argparse._SubParsersAction)).choices
    assert list(parsers) == list(cli.COMMANDS)
    for name, parser in parsers.items():
        assert f"lagmb {name} " in cli.__doc__, name
        for action in parser._actions:
            if action.option_strings and not isinstance(action, argparse._HelpAction):
                assert any(re.search(rf"(?<![\w-]){re.escape(o)}(?![\w-])", cli.__doc__) for o in
                           action.option_strings), f"lagmb {name} {action.option_strings[-1]}"


def test_run_npz(four_bar, tmp_path):
    out = tmp_path / "x.npz"
    p = lagmb("run", four_bar, "-o", out, "--t-end", "0.5", "--quiet")
    assert p.returncode == 0, p.stderr
    assert p.stdout == "" and p.stderr == ""
    with np.load(out) as d:
        assert sorted(d.files) == sorted(["t", "q", "v", "a", "lam", "energy", "residual",
                                          "coordinates", "reaction_A", "reaction_D"])
        # n_out = 401 from the scene, t_end from the command line
        assert d["t"][0] == 0.0 and d["t"][-1] == 0.5
        assert np.allclose(d["t"], np.linspace(0.0, 0.5, 401), rtol=0, atol=1e-15)
        for name in ("q", "v", "a"):
            assert d[name].shape == (401, 9)
        assert d["lam"].shape == (401, 8)
        assert d["energy"].shape == d["residual"].shape == (401,)
        assert d["reaction_A"].shape == (401, 3)
        assert list(d["coordinates"]) == [f"{b}.{c}" for b in FOUR_BAR_NAMES
                                          for c in ("x", "y", "angle")]
        assert d["residual"].max() < 1e-8
        assert d["q"][0, 2] == pytest.approx(np.radians(60.0), abs=1e-12)
        # the same numbers as the Python API gives
        r = load_scene(str(four_bar)).run(t_end=0.5)
        assert np.array_equal(d["t"], r.t) and np.array_equal(d["q"], r.q)
        assert np.array_equal(d["reaction_D"], r.reaction("D"))


def test_run_npz_all_joints_by_default(four_bar, tmp_path):
    text = four_bar.read_text().replace('reactions = ["A", "D"]\n', "")
    four_bar.write_text(text)
    out = tmp_path / "all.npz"
    p = lagmb("run", four_bar, "-o", out, "--t-end", "0.1", "--quiet")
    assert p.returncode == 0, p.stderr
    with np.load(out) as d:
        assert {f for f in d.files if f.startswith("reaction_")} == {
            "reaction_A", "reaction_B", "reaction_C", "reaction_D"}
        assert d["t"].shape == (401,) and d["t"][-1] == 0.1


def test_run_csv(four_bar, tmp_path):
    out = tmp_path / "x.csv"
    p = lagmb("run", four_bar, "-o", out, "--t-end", "0.2", "--n-out", "21")
    assert p.returncode == 0, p.stderr
    assert f"results written to {out}" in p.stdout
    with open(out, newline="") as fh:
        rows = list(csv.reader(fh))
    header = ["t"] + [f"{b}.{c}" for b in FOUR_BAR_NAMES for c in ("x", "y", "angle")] + [
        "A.fx", "A.fy", "A.torque", "D.fx", "D.fy", "D.torque", "energy"]
    assert rows[0] == header
    assert len(rows) == 1 + 21
    data = np.array(rows[1:], dtype=float)
    assert np.allclose(data[:, 0], np.linspace(0.0, 0.2, 21), rtol=0, atol=1e-15)
    assert data[0, 3] == pytest.approx(np.radians(60.0), abs=1e-12)  # crank.angle
    with np.load(_npz_of(four_bar, tmp_path)) as d:  # the csv carries the same bits
        assert np.array_equal(data[:, 0], d["t"]) and np.array_equal(data[:, 1:10], d["q"])
        assert np.array_equal(data[:, 10:13], d["reaction_A"])
        assert np.array_equal(data[:, -1], d["energy"])


def _npz_of(scene, tmp_path):
    out = tmp_path / "same.npz"
    p = lagmb("run", scene, "-o", out, "--t-end", "0.2", "--n-out", "21", "-q")
    assert p.returncode == 0, p.stderr
    return out


def test_output_file_from_scene(four_bar, tmp_path):
    four_bar.write_text(four_bar.read_text().replace("[output]", '[output]\nfile = "from_scene.csv"'))
    p = lagmb("run", four_bar, "--t-end", "0.05", "-q", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "from_scene.csv").exists()


def test_info_four_bar(four_bar):
    p = lagmb("info", four_bar)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert "bodies: 3 (crank, coupler, rocker)" in lines
    assert "joints: 4 (revolute 4)" in lines
    assert "coordinates: 9" in lines
    assert "constraint equations: 8" in lines
    assert "rank of the constraint Jacobian: 8" in lines
    assert "degrees of freedom: 1" in lines
    assert "redundant equations: none" in lines
    assert any(line.startswith("parameters: ") and "--parameters lists them" in line for line in lines)


def test_info_lists_the_parameters_a_run_takes(four_bar):
    """lagmb info --parameters: the names model.parameters and the FMU use,
    each with its value, unit and meaning."""
    import lagmb as mb
    from lagmb.scene import load_scene

    p = lagmb("info", four_bar, "--parameters")
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    expected = load_scene(four_bar).model.parameters
    assert f"parameters: {len(expected)}" in lines
    listed = {line.split()[0]: float(line.split()[1]) for line in lines if line.startswith("  ")}
    assert listed == pytest.approx(expected, rel=1e-9, abs=1e-12)  # (printed to 10 digits)
    crank = next(line for line in lines if line.split()[:1] == ["crank.mass"])
    assert " kg " in crank and "mass" in crank.split("kg", 1)[1]
    assert isinstance(mb.simulate(load_scene(four_bar).model, 0.01, n_out=2,
                                  parameters={"crank.mass": 2 * expected["crank.mass"]}), mb.Result)


PARALLELOGRAM = """\
# a parallelogram linkage with a third, parallel bar: one redundant equation
[[bodies]]
name = "left"
mass = 1.0
inertia = 0.1
position = [0.0, 0.5]
angle = 1.5707963267948966

[[bodies]]
name = "top"
mass = 2.0
inertia = 0.7
position = [1.0, 1.0]

[[bodies]]
name = "right"
mass = 1.0
inertia = 0.1
position = [2.0, 0.5]
angle = 1.5707963267948966

[[bodies]]
name = "middle"
mass = 1.0
inertia = 0.1
position = [1.0, 0.5]
angle = 1.5707963267948966

[[joints]]
type = "revolute"
name = "L0"
body_i = "ground"
body_j = "left"
at = [0.0, 0.0]

[[joints]]
type = "revolute"
name = "L1"
body_i = "left"
body_j = "top"
at = [0.0, 1.0]

[[joints]]
type = "revolute"
name = "R1"
body_i = "top"
body_j = "right"
at = [2.0, 1.0]

[[joints]]
type = "revolute"
name = "R0"
body_i = "right"
body_j = "ground"
at = [2.0, 0.0]

[[joints]]
type = "revolute"
name = "M1"
body_i = "top"
body_j = "middle"
at = [1.0, 1.0]

[[joints]]
type = "revolute"
name = "M0"
body_i = "middle"
body_j = "ground"
at = [1.0, 0.0]
"""


def test_info_redundant(tmp_path):
    path = tmp_path / "parallelogram.toml"
    path.write_text(PARALLELOGRAM)
    p = lagmb("info", path)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    # 4 bodies: 12 coordinates; 6 revolutes: 12 equations of rank 11: 1 DOF
    assert "coordinates: 12" in lines
    assert "constraint equations: 12" in lines
    assert "rank of the constraint Jacobian: 11" in lines
    assert "degrees of freedom: 1" in lines
    assert "redundant equations: 1" in lines
    row = [l for l in lines if l.startswith("  row ")]
    assert len(row) == 1 and "joint '" in row[0] and "(revolute, equation" in row[0]


def test_bad_scene_exits_2_naming_the_line(four_bar):
    text = four_bar.read_text()
    lines = text.splitlines()
    k = next(i for i, l in enumerate(lines) if l.startswith("inertia = 3.57"))
    lines[k] = "inertia = -3.57"
    four_bar.write_text("\n".join(lines) + "\n")
    p = lagmb("run", four_bar)
    assert p.returncode == 2
    assert f"{four_bar}, line {k + 1}: bodies[1] 'coupler', key 'inertia'" in p.stderr
    assert "Traceback" not in p.stderr and p.stdout == ""
    p = lagmb("info", four_bar)
    assert p.returncode == 2 and f"line {k + 1}" in p.stderr


def test_usage_errors_exit_2(four_bar, tmp_path):
    p = lagmb("run")
    assert p.returncode == 2 and "usage" in p.stderr
    p = lagmb("run", tmp_path / "nowhere.toml")
    assert p.returncode == 2 and "cannot read" in p.stderr and "Traceback" not in p.stderr
    p = lagmb("run", four_bar, "-o", tmp_path / "x.txt")
    assert p.returncode == 2 and ".npz or .csv" in p.stderr
    p = lagmb("run", four_bar, "--rtol", "1e-20")
    assert p.returncode == 2 and "rtol" in p.stderr and "Traceback" not in p.stderr
    four_bar.write_text(four_bar.read_text().replace("t_end = 2.0", ""))
    p = lagmb("run", four_bar)
    assert p.returncode == 2 and "--t-end" in p.stderr


@pytest.mark.parametrize("command, options, message", [
    ("run", ["--t-end", "1_0"], "argument --t-end: '1_0' is not a decimal number"),
    ("run", ["--n-out", "1_01"], "argument --n-out: '1_01' is not a whole number"),
    ("run", ["--n-out", "2.5"], "argument --n-out: '2.5' is not a whole number"),
    ("run", ["--rtol", "1e-6\u0661"], "argument --rtol: '1e-6\u0661' is not a decimal number"),
    ("accuracy", ["--tolerances", "1e-3", "1e-6_0"], "argument --tolerances: '1e-6_0' is not a decimal number"),
    ("modes", ["--at-time", "0_5"], "argument --at-time: '0_5' is not a decimal number"),
    ("run", ["--animate", "x.gif", "--view", "1_0,20"], "--view 1_0,20: must be two numbers ELEV,AZIM"),
    ("run", ["--animate", "x.gif", "--fps", "1_0"], "--fps 1_0: must be a number above 0 and at most 50"),
])
def test_numbers_are_read_as_toml_writes_them_not_as_float_does(four_bar, tmp_path, command, options, message):
    """float() and int() read '1_0' as 10 and other scripts' digits as
    digits: every number option refuses them, exit 2 naming it."""
    p = lagmb(command, four_bar, *options, cwd=tmp_path)
    assert p.returncode == 2 and message in p.stderr, p.stderr
    assert p.stdout == "" and "Traceback" not in p.stderr


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs Linux's /proc, where even root cannot write")
def test_an_output_that_cannot_be_written_is_refused_before_the_run(four_bar):
    for option, path in [("--html", "/proc/lagmb_view.html"), ("-o", "/proc/lagmb_results.npz")]:
        p = lagmb("run", four_bar, "--t-end", "0.1", option, path)
        assert p.returncode == 2 and p.stdout == "", p.stderr  # no run, no summary
        assert p.stderr.startswith(f"lagmb run: {option} {path}: cannot make a file in /proc: ")
        assert len(p.stderr.splitlines()) == 1


def test_failed_run_exits_1_and_writes_partial_results(four_bar, tmp_path):
    # 60 steps between outputs 0.5 s apart are too few at rtol 1e-8
    four_bar.write_text(four_bar.read_text().replace("n_out = 401", "n_out = 5\nmax_steps = 60\nformulation = \"ggl\""))
    out = tmp_path / "partial.npz"
    p = lagmb("run", four_bar, "-o", out)
    assert p.returncode == 1, p.stderr
    assert "simulation failed" in p.stderr and "partial results" in p.stderr
    assert str(out) in p.stderr and "Traceback" not in p.stderr
    with np.load(out) as d:
        k = len(d["t"])
        assert 1 <= k < 5 and d["t"][-1] < 2.0
        assert d["q"].shape == (k, 9) and d["reaction_A"].shape == (k, 3)
        assert np.allclose(d["t"], np.linspace(0.0, 2.0, 5)[:k], rtol=0, atol=1e-15)


def test_run_summary(four_bar):
    p = lagmb("run", four_bar, "--t-end", "0.1")
    assert p.returncode == 0, p.stderr
    assert "401 outputs, t = 0 .. 0.1 s" in p.stdout
    assert "steps" in p.stdout and "max |Phi|" in p.stdout
    # the method by its listed name, and a run that keeps nothing says so
    assert re.search(r"method (ggl|index3|index1|projection-bdf|projection-adams|projection-erk|ali3p): \d+ steps",
                     p.stdout)
    assert "nothing written: -o FILE (.npz or .csv), --plot, --animate or --html keep the outputs" in p.stdout


def test_run_option_numbers_in_messages_as_given(four_bar):
    p = lagmb("run", four_bar, "--rtol", "1e-16")
    assert p.returncode != 0
    assert "rtol = 1e-16 is below 1e-14" in p.stderr


def test_demo_quiet():
    p = lagmb("demo", "--quiet")
    assert p.returncode == 0, p.stderr
    assert p.stdout == ""


def test_plot_and_animate(four_bar, tmp_path):
    pytest.importorskip("matplotlib")
    pytest.importorskip("lagmb.plotting")
    png, gif = tmp_path / "out" / "fb.png", tmp_path / "fb.gif"
    p = lagmb("run", four_bar, "--t-end", "0.2", "--n-out", "6", "--plot", png,
              "--animate", gif, "-q")
    assert p.returncode == 0, p.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")


def test_animation_in_real_time_and_its_options(tmp_path):
    """The double pendulum for 1 s: --animate alone plays it in 1 s (25
    frames of 40 ms); --fps 20 --speed 0.5 in 2 s (40 frames of 50 ms),
    with the lower rod's tip and the elbow traced by name; --frames 10 in
    the same 2 s with 10 frames."""
    pytest.importorskip("matplotlib")
    pytest.importorskip("PIL")
    scene = os.path.join(EXAMPLES, "double_pendulum.toml")
    gif = tmp_path / "dp.gif"
    p = lagmb("run", scene, "--t-end", "1", "--n-out", "51", "--animate", gif, "-q")
    assert p.returncode == 0, p.stderr
    assert gif_durations(gif) == [40] * 25
    p = lagmb("run", scene, "--t-end", "1", "--n-out", "51", "--animate", gif, "--fps", "20", "--speed", "0.5",
              "--trace", "lower:0.5,0", "elbow", "-q")
    assert p.returncode == 0, p.stderr
    assert gif_durations(gif) == [50] * 40
    p = lagmb("run", scene, "--t-end", "1", "--n-out", "51", "--animate", gif, "--speed", "0.5", "--frames", "10",
              "-q")
    assert p.returncode == 0, p.stderr
    assert gif_durations(gif) == [200] * 10


@pytest.mark.parametrize("options, message", [
    (["--fps", "0"], "--fps 0: must be a number above 0 and at most 50 (GIF viewers show a frame shorter "
                     "than 20 ms for 100 ms)"),
    (["--fps", "60"], "--fps 60: must be a number above 0 and at most 50 (GIF viewers show a frame shorter "
                      "than 20 ms for 100 ms)"),
    (["--fps", "fast"], "--fps fast: must be a number above 0 and at most 50 (GIF viewers show a frame "
                        "shorter than 20 ms for 100 ms)"),
    (["--speed", "-2"], "--speed -2: must be a number above 0"),
    (["--speed", "inf"], "--speed inf: must be a number above 0"),
    (["--frames", "2.5"], "--frames 2.5: must be a whole number, at least 1"),
    (["--frames", "0"], "--frames 0: must be a whole number, at least 1"),
    (["--trace", "wrist"], "--trace wrist: no body or element of that name; the bodies are upper, lower"),
    (["--trace", "lower:1"], "--trace lower:1: a point on a body is body:x,y (m, in the body's own axes)"),
    (["--trace", "hand:0,1"], "--trace hand:0,1: no body named 'hand'; the bodies are upper, lower"),
])
def test_bad_animation_options_are_usage_errors_naming_option_and_value(tmp_path, options, message):
    """Checked before the run: exit 2 and one line naming the option and the
    value as typed; no GIF is written."""
    gif = tmp_path / "x.gif"
    p = lagmb("run", os.path.join(EXAMPLES, "double_pendulum.toml"), "--animate", gif, *options)
    assert p.returncode == 2
    assert p.stderr == f"lagmb run: {message}\n"
    assert p.stdout == "" and not gif.exists()


def test_animation_options_without_an_animation_are_refused(four_bar):
    p = lagmb("run", four_bar, "--fps", "30")
    assert p.returncode == 2
    assert p.stderr.startswith("lagmb run: --fps 30: there is no animation to apply it to; give --animate GIF")


# --- the progress bar --------------------------------------------------------------

class _Stream:
    def __init__(self, tty):
        self.tty, self.text = tty, ""

    def isatty(self):
        return self.tty

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def test_progress_shows_after_the_delay_on_a_terminal_only():
    tty = _Stream(True)
    p = Progress(0.0, 2.0, delay=0.0, stream=tty)
    p(0.5)
    p(1.0)
    p.close()
    assert "50%" in tty.text or "1/2" in tty.text or "25%" in tty.text
    quiet = _Stream(True)
    with Progress(0.0, 2.0, enabled=False, delay=0.0, stream=quiet) as p:
        p(1.0)
    pipe = _Stream(False)
    with Progress(0.0, 2.0, delay=0.0, stream=pipe) as p:
        p(1.0)
    late = _Stream(True)
    with Progress(0.0, 2.0, delay=60.0, stream=late) as p:
        p(1.0)
    assert quiet.text == pipe.text == late.text == ""


def test_the_progress_line_estimates_the_time_left_at_the_pace_so_far(monkeypatch):
    """Without tqdm: the line says the time reached, the percentage, the time
    elapsed and, from a tenth of the span on, about how long is left at the
    pace so far (elapsed x (span - done) / done); not before."""
    import builtins

    from lagmb import progress

    real_import = builtins.__import__
    monkeypatch.setattr(builtins, "__import__", lambda name, *a, **k: (_ for _ in ()).throw(ImportError(name))
                        if name == "tqdm" else real_import(name, *a, **k))
    clock = [100.0]
    monkeypatch.setattr(progress.time, "monotonic", lambda: clock[0])
    tty = _Stream(True)
    p = Progress(0.0, 10.0, delay=0.0, stream=tty)
    clock[0] = 102.0
    p(0.5)  # 5 %: too early to tell
    assert "t = 0.5 of 10 s (  5%), 2.0 s elapsed " in tty.text and "left" not in tty.text
    clock[0] = 104.0
    p(2.0)  # 20 % in 4 s: 16 s to go
    assert tty.text.endswith("t = 2 of 10 s ( 20%), 4.0 s elapsed, about 16 s left ")
    clock[0] = 400.0
    p(4.0)  # 40 % in 300 s: 450 s = 7.5 min to go
    assert "about 8 min left" in tty.text
    p.close()


KINEMATIC_SCENE = pendulum_scene(m=0.0) + """
[[drivers]]
type = "joint"
name = "motor"
joint = "pin"
function = { type = "linear", rate = 1.0 }
[simulation]
t_end = 0.5
n_out = 6
[output]
reactions = ["pin"]
efforts = ["motor"]
"""


@pytest.mark.parametrize("suffix", [".npz", ".csv"])
def test_run_kinematic_scene_writes_what_it_computed(tmp_path, suffix):
    """A massless driven rod runs as a kinematic analysis: no reactions or
    efforts exist, so the listed ones are skipped with a note on stderr and
    the motion is written (angle = t, to rounding)."""
    import numpy as np

    scene = tmp_path / "kin.toml"
    scene.write_text(KINEMATIC_SCENE)
    out = tmp_path / f"kin{suffix}"
    p = lagmb("run", scene, "-o", out)
    assert p.returncode == 0, p.stderr
    assert "computes no reactions" in p.stderr and "pin" in p.stderr
    if suffix == ".npz":
        data = np.load(out)
        assert "lam" not in data and "reaction_pin" not in data
        np.testing.assert_allclose(data["q"][:, 2], data["t"], atol=1e-12)
    else:
        rows = out.read_text().splitlines()
        assert rows[0] == "t,rod.x,rod.y,rod.angle"
        t, angle = (float(x) for x in rows[-1].split(",")[::3])
        assert abs(angle - t) < 1e-12


def test_run_a_spatial_scene_with_its_animation_seen_from_a_viewpoint(tmp_path):
    pytest.importorskip("matplotlib")
    pytest.importorskip("PIL")
    scene = os.path.join(EXAMPLES, "heavy_top.toml")
    out = tmp_path / "top.npz"
    p = lagmb("run", scene, "-o", out, "--animate", tmp_path / "top.gif", "--view", "10,30", "--n-out", "11")
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "top.gif").exists()
    with np.load(out) as data:
        assert data["q"].shape == (11, 7)
    info = lagmb("info", scene)
    assert "dimension: 3" in info.stdout and "joints: 1 (spherical 1)" in info.stdout
    bad = lagmb("run", scene, "--animate", tmp_path / "x.gif", "--view", "10")
    assert bad.returncode != 0 and "--view 10: must be two numbers ELEV,AZIM" in bad.stderr




def test_a_urdf_file_is_a_scene_for_info_and_run(tmp_path):
    """lagmb info and run take a .urdf (mb.load_urdf, its options as flags;
    the run settings from the command line): the one-link arm has one body,
    one joint and, with its limits, one stop; --no-limits leaves it out; a
    run needs --t-end, and writes what the same load and simulate give."""
    path = tmp_path / "arm.urdf"
    path.write_text(ARM_URDF)
    p = lagmb("info", path)
    assert p.returncode == 0, p.stderr
    assert "bodies: 1 (upper)" in p.stdout and "joints: 1 (revolute 1)" in p.stdout and "stops: 1" in p.stdout
    assert "degrees of freedom: 1" in p.stdout
    p = lagmb("info", path, "--no-limits")
    assert p.returncode == 0 and "stops: 0" in p.stdout
    p = lagmb("run", path, "--no-limits")
    assert p.returncode == 2 and "no end time" in p.stderr
    out = tmp_path / "arm.npz"
    p = lagmb("run", path, "--no-limits", "--t-end", "0.3", "--n-out", "4", "-o", out, "--quiet")
    assert p.returncode == 0, p.stderr
    import lagmb as mb

    r = mb.simulate(mb.load_urdf(path, limits=False), t_end=0.3, n_out=4)
    with np.load(out) as d:
        assert np.array_equal(d["q"], r.q)
    p = lagmb("info", tmp_path / "missing.urdf")
    assert p.returncode == 2 and "cannot read the file" in p.stderr


def test_cmake_prefix_names_the_wheels_cpp_package_or_says_there_is_none():
    """`lagmb --cmake-prefix`: the folder holding lib/cmake/lagmb of a wheel
    built with its C++ package (make wheel); exit 2 with the way to get the
    library where lagmb was built without it (make's build from a clone)."""
    from lagmb.cli import cmake_prefix

    out = lagmb("--cmake-prefix")
    prefix = cmake_prefix()
    if prefix is None:
        assert out.returncode == 2 and out.stdout == ""
        assert "has no C++ package" in out.stderr and "make wheel" in out.stderr
    else:
        assert out.returncode == 0 and out.stdout.strip() == prefix
        assert os.path.isfile(os.path.join(prefix, "lib", "cmake", "lagmb", "lagmbConfig.cmake"))
        assert os.path.isfile(os.path.join(prefix, "include", "lagmb", "lagmb.hpp"))
