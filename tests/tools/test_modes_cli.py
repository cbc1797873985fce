"""`lagmb modes SCENE` and lagmb.plotting.animate_mode (issue 28, item 2).

- The table of a uniform rod (L = 1.3 m) pinned at one end: one vibration
  mode at sqrt(3 g / 2 L) / (2 pi) Hz, undamped, moving the pin's angle
  most (a joint named where the model has joints); a body hanging on a
  ball joint (spatial): a free spin about the vertical (rigid-body: no
  frequency) and two swings at sqrt(m g l / (I + m l^2)) about the two
  horizontal axes, named as the body's turns about the global axes; an
  inverted pendulum's mode grows at a rate, printed as a growth rate, not a
  frequency. Frequencies are printed to 6 digits.
- Bad options exit 2 before the analysis, naming the option and the value
  (--mode and --view need --gif); a scene with no equilibrium exits 1.
- animate_mode writes a GIF of `frames` frames (default cycles x 2 s at
  fps: 100) that differ, for a planar and a spatial model; its default
  amplitude moves the drawn points by a tenth of the mechanism's size (the
  pendulum: 0.1 rad, its tip moving L per radian); spatial bodies' Euler
  parameters stay unit length; a bad index is a ModelError naming the index
  and the number of modes.

What a frame shows was judged by eye while writing it (the rod at its
turning point, the mode's title).
"""

import importlib.util
import io
import math

import numpy as np
import pytest

import lagmb as mb
from builders import gif_durations, pendulum_scene
from builders import lagmb_main as lagmb

G = 9.81
L = 1.3
MASS = 2.0

PENDULUM = pendulum_scene(L=L, m=MASS, g=G, angle=-1.0)  # 1 rad below horizontal

BALL_MASS, BALL_L, BALL_INERTIA = 3.0, 0.4, (0.05, 0.06, 0.08)

BALL = f"""
[model]
dimension = 3
gravity = [0.0, 0.0, -{G}]

[[bodies]]
name = "bob"
mass = {BALL_MASS}
inertia = {list(BALL_INERTIA)}
position = [0.0, 0.0, -{BALL_L}]

[[joints]]
type = "spherical"
name = "ball"
body_i = "ground"
body_j = "bob"
at = [0.0, 0.0, 0.0]
"""


@pytest.fixture
def pendulum(tmp_path):
    path = tmp_path / "pendulum.toml"
    path.write_text(PENDULUM)
    return path


@pytest.fixture
def mpl():
    """Skip where the plot extra is not installed."""
    pytest.importorskip("PIL")
    return pytest.importorskip("matplotlib")


def rows(out):
    """The table's rows: {mode number: its fields}, the last ("moves most")
    whole: the columns are mode, kind, frequency, omega, growth, damping
    ratio, moves most."""
    return {int(line.split()[0]): line.split(maxsplit=6) for line in out.splitlines() if line.split()[:1]
            and line.split()[0].isdigit()}


def test_the_table_of_a_pinned_rod_gives_the_compound_pendulum_frequency(capsys, pendulum):
    code, out, err = lagmb(capsys, "modes", pendulum)
    assert code == 0, err
    assert out.splitlines()[0] == f"{pendulum}: 1 mode about the stable equilibrium at t = 0 s"
    assert "frequency (Hz)" in out and "omega (rad/s)" in out and "growth (1/s)" in out and "damping ratio" in out \
        and "moves most" in out
    table = rows(out)
    assert list(table) == [0]
    fields = table[0]
    omega_exact = math.sqrt(3 * G / (2 * L))
    assert fields[1] == "vibration" and fields[-1] == "joint 'pin' (angle)" and fields[4] == "-"
    assert float(fields[5]) == 0.0
    assert float(fields[2]) == pytest.approx(omega_exact / (2 * math.pi), rel=1e-5)  # 6 digits printed
    assert float(fields[3]) == pytest.approx(omega_exact, rel=1e-5)


def test_a_body_on_a_ball_joint_spins_freely_and_swings_about_both_horizontal_axes(capsys, tmp_path):
    scene = tmp_path / "ball.toml"
    scene.write_text(BALL)
    code, out, err = lagmb(capsys, "modes", scene)
    assert code == 0, err
    table = rows(out)
    assert [table[i][1] for i in range(3)] == ["rigid-body", "vibration", "vibration"]
    assert table[0][2] == table[0][3] == table[0][4] == table[0][5] == "-"
    expected = sorted(math.sqrt(BALL_MASS * G * BALL_L / (I + BALL_MASS * BALL_L**2)) for I in BALL_INERTIA[:2])
    for i, omega in zip((1, 2), expected):
        assert float(table[i][2]) == pytest.approx(omega / (2 * math.pi), rel=1e-5)
        assert float(table[i][3]) == pytest.approx(omega, rel=1e-5)
    # no revolute joint: the body's turn about the global axes (a spherical joint has no angle)
    assert table[0][-1] == "bob turns about z" and {table[1][-1], table[2][-1]} == {"bob turns about x",
                                                                                  "bob turns about y"}
    assert "rigid-body: a motion nothing resists (no frequency, no growth)" in out


def test_an_unstable_mode_is_a_growth_rate_not_a_frequency(capsys, tmp_path):
    """A rod pinned at its lower end, standing up: one unstable mode growing
    as exp(sqrt(3 g / 2 L) t), printed under growth (1/s) with no frequency."""
    scene = tmp_path / "inverted.toml"
    scene.write_text(pendulum_scene(L=L, m=MASS, g=G, angle=math.pi / 2))
    code, out, err = lagmb(capsys, "modes", scene)
    assert code == 0, err
    fields = rows(out)[0]
    assert fields[1] == "unstable" and fields[2] == fields[3] == fields[5] == "-"
    assert float(fields[4]) == pytest.approx(math.sqrt(3 * G / (2 * L)), rel=1e-5)
    assert "it grows as exp(growth t), it does not vibrate" in out


def test_count_lists_the_lowest_and_at_time_is_the_equilibrium_s_time(capsys, tmp_path):
    scene = tmp_path / "ball.toml"
    scene.write_text(BALL)
    code, out, err = lagmb(capsys, "modes", scene, "--count", "2", "--at-time", "2.5")
    assert code == 0, err
    assert sorted(rows(out)) == [0, 1] and "the 2 lowest of 3 modes (--count)" in out
    assert "at t = 2.5 s" in out.splitlines()[0]


@pytest.mark.parametrize("options, message", [
    (["--count", "0"], "--count 0: must be at least 1"),
    (["--count", "two"], "--count: 'two' is not a whole number"),
    (["--mode", "-1", "--gif", "x.gif"], "--mode -1: must be the number of a mode"),
    (["--mode", "0"], "--mode 0: there is no animation to apply it to; give --gif"),
    (["--view", "10,20"], "--view 10,20: there is no animation to apply it to; give --gif"),
    (["--at-time", "nan"], "--at-time nan: must be a finite time"),
    (["--gif", "x.mp4"], "--gif x.mp4: must end in one of the animation formats"),
    (["--gif", "x.gif", "--mode", "3"], "--mode 3: the scene has 1 mode (0 .. 0)"),
    (["--gif", "x.gif", "--view", "10"], "--view 10: must be two numbers ELEV,AZIM"),
])
def test_bad_options_exit_2_naming_the_option(capsys, pendulum, tmp_path, monkeypatch, options, message):
    monkeypatch.chdir(tmp_path)
    if "--gif" in options:
        pytest.importorskip("matplotlib")
    code, out, err = lagmb(capsys, "modes", pendulum, *options)
    assert code == 2 and message in err, err
    assert "Traceback" not in err and not (tmp_path / "x.gif").exists()


def test_no_equilibrium_exits_1_and_no_modes_are_said(capsys, tmp_path):
    free = tmp_path / "free.toml"
    free.write_text(PENDULUM.split("[[joints]]")[0])  # the rod alone: it falls
    code, out, err = lagmb(capsys, "modes", free)
    assert code == 1 and "no static equilibrium" in err and "body 'rod'" in err
    driven = tmp_path / "driven.toml"
    driven.write_text(PENDULUM + '\n[[drivers]]\ntype = "joint"\nname = "motor"\njoint = "pin"\n'
                      'function = { type = "constant", c = 0.0 }\n')
    code, out, err = lagmb(capsys, "modes", driven)
    assert code == 0, err
    assert "0 modes" in out and "no modes: every degree of freedom is driven" in out
    code, out, err = lagmb(capsys, "modes", driven, "--gif", tmp_path / "x.gif")
    if importlib.util.find_spec("matplotlib") is None:  # (checked first: before a long equilibrium search)
        assert code == 2 and "--gif needs matplotlib" in err
    else:
        assert code == 2 and "no modes to animate" in err


def test_gif_animates_the_first_vibration_mode(capsys, pendulum, tmp_path, mpl):
    from PIL import Image

    gif = tmp_path / "mode.gif"
    code, out, err = lagmb(capsys, "modes", pendulum, "--gif", gif)
    assert code == 0, err
    assert f"mode 0 (vibration) animated in {gif}" in out
    with Image.open(gif) as im:
        assert im.n_frames == 100  # 2 cycles of 2 s at 25 frames/s
    assert gif_durations(gif) == [40] * 100


def hanging_rod():
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", MASS, MASS * L**2 / 12, position=(0.0, -L / 2), angle=-math.pi / 2)
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m


def ball_joint():
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    bob = m.add_body("bob", BALL_MASS, BALL_INERTIA, position=(0.0, 0.0, -BALL_L))
    m.add_spherical("ball", m.ground, bob, at=(0.0, 0.0, 0.0))
    return m


def frames_of(path):
    from PIL import Image

    with Image.open(path) as im:
        pictures = []
        for k in range(im.n_frames):
            im.seek(k)
            pictures.append(np.asarray(im.convert("RGB"), dtype=int))
    return pictures


@pytest.mark.parametrize("build, index", [(hanging_rod, 0), (ball_joint, 1)], ids=["planar", "spatial"])
def test_animate_mode_writes_the_frames_asked_for_and_they_move(tmp_path, mpl, build, index):
    from PIL import Image

    from lagmb.plotting import animate_mode

    modes = mb.modes(build())
    path = animate_mode(modes, index, tmp_path / "mode.gif", frames=24, cycles=1, fps=20)
    assert path == str(tmp_path / "mode.gif")
    pictures = frames_of(path)
    assert len(pictures) == 24 and gif_durations(path) == [50] * 24
    # the mechanism at its equilibrium, then a quarter of a cycle on at the turning point
    assert np.count_nonzero(np.abs(pictures[0] - pictures[6]).sum(axis=2)) > 200
    # the default: 2 cycles of 2 s at 25 frames/s; without a path, the GIF's bytes
    data = animate_mode(modes, index)
    assert data[:6] == b"GIF89a"
    with Image.open(io.BytesIO(data)) as im:
        assert im.n_frames == 100 and im.size == (640, 480)


def test_an_unstable_mode_is_shown_back_and_forth_in_the_time_asked(tmp_path, mpl):
    """An upright rod falls (omega is its growth rate): drawn as a loop all
    the same; frames that come out the same (the turning points) are merged
    by Pillow into one longer frame, the loop's length stays frames / fps."""
    from lagmb.plotting import animate_mode

    upright = mb.Model(gravity=(0.0, -G))
    rod = upright.add_body("rod", MASS, MASS * L**2 / 12, position=(0.0, L / 2), angle=math.pi / 2)
    upright.add_revolute("pin", upright.ground, rod, at=(0.0, 0.0))
    modes = mb.modes(upright)
    assert modes.kinds == ["unstable"]
    path = animate_mode(modes, 0, tmp_path / "falling.gif", frames=40, fps=10, cycles=2)
    assert sum(gif_durations(path)) == 4000
    pictures = frames_of(path)
    assert max(np.count_nonzero(np.abs(pictures[0] - p).sum(axis=2)) for p in pictures) > 200


def test_the_default_amplitude_moves_the_rod_s_tip_a_tenth_of_its_length():
    from lagmb._drawing import mode_amplitude as _mode_amplitude

    modes = mb.modes(hanging_rod())
    # the shape is 1 rad of turn (its largest entry, the angle); the tip moves L per radian,
    # and the drawing spans L (pin to tip)
    assert _mode_amplitude(modes.equilibrium, modes.shapes[0]) == pytest.approx(0.1, rel=1e-6)


def test_spatial_bodies_keep_unit_euler_parameters_along_a_shape():
    from lagmb._drawing import posed as _posed

    modes = mb.modes(ball_joint())
    eq = modes.equilibrium
    shown = _posed(eq, eq.q + np.outer([-0.5, 0.0, 0.3, 0.8], modes.shapes[1]))
    p = shown.body("bob").orientation
    np.testing.assert_allclose(np.linalg.norm(p, axis=1), 1.0, rtol=1e-14)
    np.testing.assert_array_equal(shown.q[1], eq.q)


def test_a_bad_index_names_it_and_the_number_of_modes(mpl, tmp_path):
    from lagmb.plotting import animate_mode

    modes = mb.modes(ball_joint())
    for index in (3, -1, 1.0, True):
        with pytest.raises(mb.ModelError, match=rf"index {index!r}: there are 3 modes \(0 \.\. 2\)"):
            animate_mode(modes, index, tmp_path / "x.gif")
    driven = hanging_rod()
    driven.drive_joint("motor", "pin", 0.0)
    with pytest.raises(mb.ModelError, match=r"index 0: there are 0 modes \(none: nothing can move\)"):
        animate_mode(mb.modes(driven), 0, tmp_path / "x.gif")
    with pytest.raises(mb.ModelError, match="animate_mode: frames 1: must be a whole number, at least 2"):
        animate_mode(modes, 1, tmp_path / "x.gif", frames=1)
    with pytest.raises(mb.ModelError, match="modes must be what mb.modes"):
        animate_mode(modes.shapes, 0, tmp_path / "x.gif")
    assert not (tmp_path / "x.gif").exists()
