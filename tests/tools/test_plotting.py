"""Pictures of a run: lagmb.plotting.plot_result and animate.

The pictures are checked by what can be counted: file type (magic bytes),
pixel size, number of subplots and GIF frames, axis labels with units,
legends that stay short. The points a body is drawn through are checked
against the joint positions of the four-bar (to 1e-12 m). Whether the
pictures look right was judged by eye while writing them.

The two models: a double pendulum (two uniform rods, L = 1 m, m = 1 kg,
the upper one horizontal, the lower one hanging from its tip) and the
four-bar of test_fourbar.py (crank 1 m, coupler 3.5 m, rocker 3 m, ground
4 m, crank at 60 degrees).
"""

import math
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import lagmb as mb
from lagmb import _drawing, _meshes, plotting
from lagmb.plotting import frames as gif_frames, planar as planar_drawing, spatial as spatial_drawing
from builders import gif_durations, hinged_rod_with_mesh, pendulum

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
from paths import EXAMPLES  # noqa: E402


@pytest.fixture
def mpl():
    """Skip where the plot extra is not installed."""
    pytest.importorskip("PIL")
    return pytest.importorskip("matplotlib")


def double_pendulum():
    """Rod "upper" from the origin to (1, 0), rod "lower" hanging from (1, 0)
    to (1, -1); revolutes "shoulder" (ground-upper at the origin) and "elbow"
    (upper-lower at (1, 0))."""
    m = mb.Model(gravity=(0.0, -9.81))
    upper = m.add_body("upper", mass=1.0, inertia=1 / 12, position=(0.5, 0.0))
    lower = m.add_body("lower", mass=1.0, inertia=1 / 12, position=(1.0, -0.5),
                       angle=-math.pi / 2)
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("elbow", upper, lower, at=(1.0, 0.0))
    return m


FOURBAR_A, FOURBAR_D = np.array([0.0, 0.0]), np.array([4.0, 0.0])


def fourbar(omega=5.0):
    """The crank-rocker of test_fourbar.py; returns (model, joint points A, B, C, D)."""
    A, D = FOURBAR_A, FOURBAR_D
    B = A + np.array([math.cos(math.pi / 3), math.sin(math.pi / 3)])
    b, c = 3.5, 3.0  # coupler and rocker: C is the upper intersection of two circles
    d = float(np.hypot(*(D - B)))
    along = (b * b - c * c + d * d) / (2 * d)
    u = (D - B) / d
    C = B + along * u + math.sqrt(b * b - along * along) * np.array([-u[1], u[0]])
    m = mb.Model(gravity=(0.0, -9.81))
    bars = []
    for name, (p, q) in zip(("crank", "coupler", "rocker"), ((A, B), (B, C), (D, C))):
        length = float(np.hypot(*(q - p)))
        bars.append(m.add_body(name, mass=length, inertia=length**3 / 12, position=0.5 * (p + q),
                               angle=math.atan2(q[1] - p[1], q[0] - p[0]),
                               angular_velocity=omega if name == "crank" else 0.0))
    m.add_revolute("A", m.ground, bars[0], at=A)
    m.add_revolute("B", bars[0], bars[1], at=B)
    m.add_revolute("C", bars[1], bars[2], at=C)
    m.add_revolute("D", m.ground, bars[2], at=D)
    return m, (A, B, C, D)


@pytest.fixture(scope="module")
def pendulum_run():
    return mb.simulate(double_pendulum(), t_end=2.0, n_out=201)


# --- plot_result ---------------------------------------------------------


def test_plot_result_writes_a_png_with_one_labelled_subplot_per_quantity(mpl, pendulum_run,
                                                                         tmp_path):
    path = tmp_path / "sub" / "run.png"
    fig = plotting.plot_result(pendulum_run, path)
    # a real PNG of the figure's size (8.5 in wide at 120 dpi), a tall column
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC
    assert 20_000 < len(data) < 2_000_000
    from PIL import Image

    with Image.open(path) as im:
        width, height = im.size
    assert width == 1020
    assert height > width
    # positions, angles, reactions, energy, residual (no drivers: no efforts)
    axes = fig.axes
    units = ["(m)", "(rad)", "(N)", "(J)", "(m)"]
    assert len(axes) == len(units)
    for ax, unit in zip(axes, units):
        assert ax.get_ylabel().strip()
        assert unit in ax.get_ylabel()
    # one time axis, labelled under the bottom subplot
    assert "time" in axes[-1].get_xlabel() and "(s)" in axes[-1].get_xlabel()
    for ax in axes[:-1]:
        assert ax.get_shared_x_axes().joined(ax, axes[-1])
    assert axes[-1].get_xlim() == pytest.approx((0.0, 2.0))
    assert axes[-1].get_yscale() == "log"
    # title: model and solver
    title = fig._suptitle.get_text()
    assert "2 bodies" in title and "2 joints" in title
    assert f"{pendulum_run.stats['steps']} steps" in title
    # legends name the bodies and joints
    legends = [[t.get_text() for t in ax.get_legend().get_texts()] for ax in axes[:3]]
    assert legends[0] == ["upper", "lower", "x", "y"]
    assert legends[1] == ["upper", "lower"]
    assert legends[2] == ["shoulder", "elbow"]


def test_plot_result_curves_are_the_result(mpl, pendulum_run):
    """The lines drawn are the result's numbers: x of "upper", |F| of "elbow",
    E - E(0) and max |Phi|."""
    r = pendulum_run
    fig = plotting.plot_result(r)
    pos, _, reac, energy, residual = fig.axes
    np.testing.assert_array_equal(pos.lines[0].get_ydata(), r.body("upper").position[:, 0])
    elbow = np.hypot(*r.reaction("elbow")[:, :2].T)
    np.testing.assert_array_equal(reac.lines[1].get_ydata(), elbow)
    np.testing.assert_allclose(energy.lines[0].get_ydata(), r.energy - r.energy[0], atol=1e-15)
    drawn = residual.lines[0].get_ydata()
    positive = r.residual > 0
    np.testing.assert_array_equal(drawn[positive], r.residual[positive])


@pytest.mark.parametrize("ext, magic", [("pdf", b"%PDF"), ("svg", b"<?xml")])
def test_plot_result_format_follows_the_extension(mpl, pendulum_run, tmp_path, ext, magic):
    path = tmp_path / f"run.{ext}"
    plotting.plot_result(pendulum_run, path, what=("energy",))
    assert path.read_bytes()[:len(magic)] == magic


def test_plot_result_limits_the_lines_and_says_so(mpl, rod_chain):
    """A 10-rod chain: 6 bodies and 8 joints are drawn, and the legend titles
    say how many there are."""
    r = mb.simulate(rod_chain(10), t_end=0.2, n_out=21)
    fig = plotting.plot_result(r, what=("coordinates", "reactions"))
    pos, ang, reac = fig.axes
    assert len(pos.lines) == 2 * 6 and len(ang.lines) == 6 and len(reac.lines) == 8
    assert pos.get_legend().get_title().get_text() == "first 6 of 10 bodies"
    assert ang.get_legend().get_title().get_text() == "first 6 of 10 bodies"
    assert reac.get_legend().get_title().get_text() == "first 8 of 10 joints"
    assert len(reac.get_legend().get_texts()) == 8
    assert "10 bodies, 10 joints" in fig._suptitle.get_text()


def test_plot_result_rejects_unknown_or_empty_selections(mpl, pendulum_run):
    with pytest.raises(ValueError, match="unknown panel"):
        plotting.plot_result(pendulum_run, what=("coordinates", "forces"))
    with pytest.raises(ValueError, match="nothing to plot"):
        plotting.plot_result(pendulum_run, what=("efforts",))  # no drivers in the model


@pytest.mark.skipif(not (hasattr(mb.Model, "drive_joint") and hasattr(mb, "Linear")),
                    reason="drivers are not in this build yet")
def test_plot_result_shows_driver_efforts(mpl, tmp_path):
    """The four-bar with its crank turned at 2 rad/s: an efforts subplot in N m."""
    m, _ = fourbar(omega=2.0)
    m.drive_joint("motor", "A", mb.Linear(2.0, start=math.pi / 3))
    r = mb.simulate(m, t_end=0.5, n_out=51)
    fig = plotting.plot_result(r, tmp_path / "driven.png")
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert len(fig.axes) == 6
    effort = next(ax for ax in fig.axes if "effort" in ax.get_ylabel())
    assert "(N m)" in effort.get_ylabel()
    np.testing.assert_allclose(effort.lines[0].get_ydata(), r.effort("motor"))
    assert labels.index(effort.get_ylabel()) == 3  # after the reactions
    assert "1 driver" in fig._suptitle.get_text()


def test_plot_result_shows_a_stops_torque(mpl, tmp_path):
    """A bar on a hinge, pushed by 2 N m onto a stop at 0 (restitution 0):
    the efforts subplot draws the stop's torque along the hinge, in N m,
    r.effort's values: 0 while open, the pushing 2 N m once captured."""
    m = mb.Model()
    bar = m.add_body("bar", mass=1.0, inertia=1.0 / 12.0, position=(0.5 * math.cos(0.3), 0.5 * math.sin(0.3)),
                     angle=0.3)
    hinge = m.add_revolute("hinge", m.ground, bar, at=(0.0, 0.0))
    m.add_torque("push", bar, -2.0)
    m.add_stop("stop", hinge, lower=0.0)
    r = mb.simulate(m, t_end=1.0, n_out=101)
    fig = plotting.plot_result(r, tmp_path / "stop.png", what=("efforts",))
    (effort,) = fig.axes
    assert effort.get_ylabel() == "effort (N m)"
    np.testing.assert_allclose(effort.lines[0].get_ydata(), r.effort("stop"))
    assert effort.lines[0].get_ydata()[0] == 0.0 and effort.lines[0].get_ydata()[-1] == pytest.approx(2.0)


# --- what the pictures know of the model ----------------------------------


def test_bodies_are_drawn_through_their_joints():
    """Four-bar: each bar's outline is its two joint points in its own axes
    (-l/2 and +l/2 on its x axis, to 1e-12 m), in the order the joints were
    added (the rocker: C, then D); along the run the drawn ends of
    neighbouring bars meet at the joints (to the constraint residual) and the
    ground joints stay at A and D."""
    m, (A, B, C, D) = fourbar()
    r = mb.simulate(m, t_end=0.5, n_out=11)
    scene = _drawing.Scene(r)
    assert scene.joints == ["A", "B", "C", "D"] and scene.drivers == []
    ends = {}
    for name, (p, q) in zip(("crank", "coupler", "rocker"), ((A, B), (B, C), (D, C))):
        half = 0.5 * float(np.hypot(*(q - p)))
        sign = -1.0 if name == "rocker" else 1.0
        np.testing.assert_allclose(scene.outlines[name], [[-sign * half, 0.0], [sign * half, 0.0]],
                                   atol=1e-12)
        ends[name] = [r.point(name, s) for s in scene.outlines[name]]
    tol = 10 * r.residual.max() + 1e-12
    np.testing.assert_allclose(ends["crank"][0], np.broadcast_to(A, (11, 2)), atol=tol)
    np.testing.assert_allclose(ends["crank"][1], ends["coupler"][0], atol=tol)
    np.testing.assert_allclose(ends["coupler"][1], ends["rocker"][0], atol=tol)
    np.testing.assert_allclose(ends["rocker"][1], np.broadcast_to(D, (11, 2)), atol=tol)


def test_drawing_uses_the_model_outline_and_attachments():
    """Bodies are drawn through the points where elements attach (the
    model's outline, computed by the core): a coupler with a force at a third
    point becomes a triangle (closed polygon); a revolute attaches to both
    its bodies at the joint point."""
    m, (A, B, C, D) = fourbar()
    apex = 0.5 * (B + C) + np.array([0.0, 0.8])
    m.add_force("load", "coupler", (0.0, -1.0), point=apex)
    r = mb.simulate(m, t_end=0.1, n_out=3)
    scene = _drawing.Scene(r)
    assert scene.joints == ["A", "B", "C", "D"] and scene.by_role["force"] == ["load"]
    assert len(scene.outlines["coupler"]) == 3
    local, closed = _drawing.outline_shape(scene.outlines["coupler"])
    assert closed and len(local) == 3
    (bi, pi), (bj, pj) = scene.attachments("B")
    assert (bi, bj) == ("crank", "coupler")
    np.testing.assert_allclose(r.point("crank", pi)[0], B, atol=1e-9)
    np.testing.assert_allclose(r.point("coupler", pj)[0], B, atol=1e-9)
    ground, support = scene.attachments("A")[0]
    assert ground == "ground"
    np.testing.assert_allclose(support, A)


@pytest.mark.parametrize("outline, n, closed", [
    ([], 0, False),                                        # a dot at the centre
    ([(0.0, 0.0)], 0, False),                              # only the centre: a dot
    ([(0.5, 0.0)], 2, False),                              # centre to the point
    ([(-0.5, 0.0), (0.5, 0.0)], 2, False),                 # a bar
    ([(-1.0, 0.0), (1.0, 0.0), (0.2, 0.0)], 2, False),     # collinear: the long segment
    ([(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.5)], 4, True),  # inner point left out
])
def test_body_shapes(outline, n, closed):
    local, is_closed = _drawing.outline_shape([np.array(p, float) for p in outline])
    assert len(local) == n and is_closed == closed
    if outline and not closed and len(outline) == 3:
        np.testing.assert_allclose(sorted(local[:, 0]), [-1.0, 1.0])


# --- animate: timing ------------------------------------------------------


def test_frame_plan_plays_the_span_in_span_over_speed():
    """2 s of outputs: 25 frames/s in real time is 50 frames of 40 ms; at
    30 frames/s (33.3 ms, not a whole number of a GIF's 10 ms ticks) 60
    frames of 30 or 40 ms that add up to 2 s; half speed doubles the frames;
    a cap of 20 frames makes each last 100 ms. Frame i shows t0 + i span/n."""
    t = np.linspace(1.0, 3.0, 401)
    times, durations = gif_frames.frame_plan(t, fps=25, speed=1.0)
    assert len(times) == 50 and set(durations) == {40}
    np.testing.assert_allclose(times, 1.0 + 0.04 * np.arange(50), rtol=0, atol=1e-12)
    times, durations = gif_frames.frame_plan(t, fps=30, speed=1.0)
    assert len(times) == 60 and set(durations) == {30, 40} and sum(durations) == 2000
    times, durations = gif_frames.frame_plan(t, fps=25, speed=0.5)
    assert len(times) == 100 and sum(durations) == 4000
    times, durations = gif_frames.frame_plan(t, fps=25, speed=1.0, frames=20)
    assert len(times) == 20 and set(durations) == {100}
    times, durations = gif_frames.frame_plan(t, fps=50, speed=100.0)  # 20 ms: one frame per 20 ms at most
    assert len(times) == 1


@pytest.mark.parametrize("kwargs, frames, duration_ms", [
    ({}, 25, 1000),                           # real time at 25 frames/s (40 ms each)
    ({"speed": 0.25}, 100, 4000),             # four times slower
    ({"fps": 20}, 20, 1000),                  # 50 ms each
    ({"frames": 10}, 10, 1000),               # fewer frames, 100 ms each, the same second
    ({"fps": 50, "speed": 2.0}, 25, 500),     # twice as fast at 50 frames/s
])
def test_a_gif_lasts_the_run_span_over_the_speed(mpl, tmp_path, kwargs, frames, duration_ms):
    """A 1 s run of the double pendulum: the GIF's frame durations (as Pillow
    reads them) add up to 1 s / speed, and there are span * fps / speed
    frames (or the number asked for)."""
    r = mb.simulate(double_pendulum(), t_end=1.0, n_out=51)
    path = tmp_path / "pendulum.gif"
    assert plotting.animate(r, path, size=(320, 240), **kwargs) == str(path)
    durations = gif_durations(path)
    assert len(durations) == frames
    assert sum(durations) == duration_ms
    assert len(set(durations)) == 1


def test_a_run_shorter_than_a_second_plays_in_one_by_default_and_says_so(mpl, tmp_path):
    """0.2 s of the double pendulum in real time would be 5 frames: unless a
    speed is given it is slowed down to last 1 s (25 frames), and the title
    says the speed; speed=1 keeps real time."""
    r = mb.simulate(double_pendulum(), t_end=0.2, n_out=21)
    times, _ = gif_frames.frame_plan(r.t, fps=25, speed=0.2)
    scene = _drawing.Scene(r)
    drawing = planar_drawing.planar_drawing(scene, gif_frames.resample(r, times), [], (320, 240), 100, 0.2)
    assert drawing.fig.axes[0].get_title() == "lagmb: 2 bodies, 2 joints, played at 0.2 × real time"
    plotting.animate(r, tmp_path / "slow.gif", size=(320, 240))
    assert len(gif_durations(tmp_path / "slow.gif")) == 25 and sum(gif_durations(tmp_path / "slow.gif")) == 1000
    plotting.animate(r, tmp_path / "real.gif", size=(320, 240), speed=1)
    assert gif_durations(tmp_path / "real.gif") == [40] * 5


def test_animate_writes_a_moving_gif_of_the_size_asked(mpl, tmp_path):
    from PIL import Image, ImageChops

    r = mb.simulate(double_pendulum(), t_end=1.0, n_out=11)
    path = tmp_path / "pendulum.gif"
    plotting.animate(r, path, size=(320, 240), trace=[("lower", (0.5, 0.0))])
    with Image.open(path) as im:
        assert im.format == "GIF" and im.size == (320, 240)
        assert im.n_frames == 25  # frames between the 11 outputs are interpolated
        first = im.convert("RGB")
        im.seek(im.n_frames - 1)
        last = im.convert("RGB")
    assert ImageChops.difference(first, last).getbbox() is not None  # it moves


def test_frames_between_outputs_are_interpolated_from_positions_and_velocities():
    """The frames of a run with 21 outputs in 1 s (every 50 ms), at 25
    frames/s, are within 2e-3 (m, rad) of a run with an output at each frame
    time (a tenth of what straight lines between the outputs give: 1.5e-2);
    at the outputs themselves they are the outputs."""
    coarse = mb.simulate(double_pendulum(), t_end=1.0, n_out=21)
    fine = mb.simulate(double_pendulum(), t_end=1.0, n_out=101)
    times, _ = gif_frames.frame_plan(coarse.t, fps=25, speed=1.0)
    shown = gif_frames.resample(coarse, times)
    np.testing.assert_allclose(shown.t, fine.t[:-1:4], rtol=0, atol=1e-12)
    error = np.max(np.abs(shown.q - fine.q[:-1:4]))
    straight = np.column_stack([np.interp(times, coarse.t, q) for q in coarse.q.T])
    assert error < 2e-3 and error < 0.1 * np.max(np.abs(straight - fine.q[:-1:4]))
    np.testing.assert_allclose(shown.q[::5], coarse.q[:-1:4], rtol=0, atol=1e-12)  # t = 0, 0.2, ... 0.8


def test_animate_reports_its_progress_in_run_time(mpl, tmp_path, monkeypatch):
    """animate counts the frames drawn on lagmb.progress.Progress, labelled
    "drawn", from the first frame's time to the run's end, and closes it."""
    import lagmb.progress

    calls = []

    class Recorder:
        def __init__(self, t0, t_end, enabled=True, label=None, **kwargs):
            calls.append(("open", t0, t_end, enabled, label))

        def __call__(self, t):
            calls.append(("at", t))

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            calls.append(("close",))

    monkeypatch.setattr(lagmb.progress, "Progress", Recorder)
    r = mb.simulate(double_pendulum(), t_end=0.4, n_out=5)
    plotting.animate(r, tmp_path / "p.gif", size=(160, 120), speed=1.0)
    assert calls[0] == ("open", 0.0, 0.4, True, "drawn") and calls[-1] == ("close",)
    seen = [c[1] for c in calls if c[0] == "at"]
    np.testing.assert_allclose(seen, 0.04 * np.arange(10), atol=1e-12)


# --- animate: what is drawn ------------------------------------------------


def test_a_rod_pinned_at_one_end_is_drawn_to_both_ends(mpl):
    """The double pendulum's lower rod (1 m, 1 kg, inertia 1/12: a uniform
    rod) has one joint, at its upper end: it is drawn from the elbow through
    its centre to its free end (1, -1), not to its centre only. A bob of
    little inertia (1 kg, 1e-6 kg m^2) on a joint 1 m away is drawn from the
    joint to its centre (and 1.7 mm on)."""
    m = double_pendulum()
    bob = m.add_body("bob", mass=1.0, inertia=1e-6, position=(2.0, -1.0))
    m.add_revolute("string", "lower", bob, at=(1.0, -1.0))
    r = mb.simulate(m, t_end=0.2, n_out=3)
    scene = _drawing.Scene(r)
    assert len(scene.outlines["upper"]) == 2  # two joints: drawn between them
    np.testing.assert_allclose(scene.drawn_outline("upper"), [[-0.5, 0.0], [0.5, 0.0]], atol=1e-12)
    np.testing.assert_allclose(scene.drawn_outline("bob"), [[-1.0, 0.0], [math.sqrt(3e-6), 0.0]], atol=1e-12)
    # the lower rod now has two joints (elbow and string); alone, one:
    m1 = double_pendulum()
    r1 = mb.simulate(m1, t_end=0.2, n_out=3)
    scene1 = _drawing.Scene(r1)
    assert len(scene1.outlines["lower"]) == 1
    np.testing.assert_allclose(scene1.drawn_outline("lower"), [[-0.5, 0.0], [0.5, 0.0]], atol=1e-12)
    # and the line drawn at the first frame runs from the elbow (1, 0) to the tip (1, -1)
    drawing = planar_drawing.planar_drawing(scene1, r1, [], (320, 240), 100, 1.0)
    drawing.update(0)
    x, y = drawing.artists["bodies"][1].get_data()
    np.testing.assert_allclose(sorted(zip(x, y), key=lambda p: -p[1]), [[1.0, 0.0], [1.0, -1.0]], atol=1e-9)
    # a body pinned at its centre with one more point (the cam of examples/cam_follower.toml, its
    # contact circle 0.02 m off the pivot) is not taken for a rod
    cam = _drawing.Scene(mb.load_scene(os.path.join(EXAMPLES, "cam_follower.toml")).run(t_end=0.01, n_out=2))
    np.testing.assert_allclose(cam.drawn_outline("cam"), cam.outlines["cam"])
    assert len(cam.outlines["cam"]) == 2


def test_a_contact_is_drawn_as_its_circle_and_its_line(mpl):
    """A ball on a sprung seesaw: the plank (pinned at its centre, nothing
    else attached) is seen through its contact line, which turns with it,
    and the ball through its contact circle (radius 0.1 m) round the
    circle's centre; at each frame where the contact's reading says so."""
    m = mb.Model(gravity=(0.0, -9.81))
    plank = m.add_body("plank", mass=2.0, inertia=2.0 * 4.0 / 12.0, position=(0.0, 0.0), angle=0.1)
    m.add_revolute("pivot", m.ground, plank, at=(0.0, 0.0))
    m.add_rotational_spring_damper("spring", m.ground, plank, stiffness=40.0, damping=1.0, free_angle=0.1)
    ball = m.add_body("ball", mass=0.5, inertia=0.002, position=(0.6, 0.4))
    m.add_contact("hit", ball, (0.6, 0.4), 0.1, plank, (0.0, 0.0), (math.cos(0.1), math.sin(0.1)), stiffness=1e6,
                  restitution=0.6, friction=0.4)
    r = mb.simulate(m, t_end=1.0, n_out=11)
    drawing = planar_drawing.planar_drawing(_drawing.Scene(r), r, [], (320, 240), 100, 1.0)
    (circle,), (line,) = drawing.artists["circles"], drawing.artists["lines"]
    plank_angle = r.body("plank").angle
    for k in (0, 5, 10):
        drawing.update(k)
        assert circle.get_radius() == 0.1
        np.testing.assert_allclose(circle.get_center(), r.body("ball").position[k], atol=1e-12)
        x, y = line.get_data()
        direction = np.array([x[1] - x[0], y[1] - y[0]])
        assert abs(math.atan2(direction[1], direction[0]) - plank_angle[k]) <= 1e-9
        assert abs(math.atan2(y[0], x[0]) - math.atan2(y[1], x[1])) == pytest.approx(math.pi, abs=1e-9)  # through the pivot
    c = r.contact("hit")
    assert c.state[0] == "open" and c.state[-1] == "slip"


def test_a_spatial_body_is_drawn_with_its_axes_turning_with_it(mpl):
    """The heavy top spinning at 100 rad/s, 201 outputs in 2 s: its frames at
    25 frames/s fall on every 4th output. At each frame the triad drawn at
    the centre of mass points along the columns of the body's rotation
    matrix there (x red, y green, z blue), so that its spin shows, and its
    inertia box (a flat square: the inertia (2, 2, 4) g m^2 of a disc) has
    its corners where the rotation puts them."""
    r = mb.load_scene(os.path.join(EXAMPLES, "heavy_top.toml")).run(n_out=201)
    times, _ = gif_frames.frame_plan(r.t, fps=25, speed=1.0)
    shown = gif_frames.resample(r, times)
    scene = _drawing.Scene(r)
    drawing = spatial_drawing.spatial_drawing(scene, shown, [], (320, 240), 100, (20.0, -70.0), 1.0)
    top = r.body("top")
    lengths = drawing.triad_lengths["top"]  # x and y a fifth past the square, z a 25th of the scene
    corners = scene.box("top")
    half = np.sqrt(3 * 0.002 / 1.0)  # a uniform square with S_xx = S_yy = 2 g m^2: half side sqrt(3 S / m)
    np.testing.assert_allclose(sorted(np.abs(corners).max(axis=0)), [0.0, half, half], atol=1e-12)
    np.testing.assert_allclose(drawing.triad_lengths["top"][:2], 1.2 * half, rtol=1e-12)
    directions = []
    for k in (0, 1, 17, 49):
        drawing.update(k)
        R, c = top.rotation[4 * k], top.position[4 * k]
        for axis, art in enumerate(drawing.artists["triad"]):
            x, y, z = (np.asarray(v, dtype=float) for v in art.get_data_3d())
            np.testing.assert_allclose([x[0], y[0], z[0]], c, atol=1e-9)
            np.testing.assert_allclose(np.array([x[1], y[1], z[1]]) - c, lengths[axis] * R[:, axis], atol=1e-9)
        x, y, z = (np.asarray(v, dtype=float) for v in drawing.artists["boxes"][0].get_data_3d())
        drawn = np.column_stack([x, y, z])
        drawn = drawn[np.isfinite(drawn).all(axis=1)]
        expected = c + corners @ R.T
        assert max(np.min(np.linalg.norm(expected - p, axis=1)) for p in drawn) < 1e-9
        directions.append(R[:, 0])
    assert np.linalg.norm(directions[1] - directions[0]) > 0.5  # it turned 4 rad in 40 ms


def test_trace_takes_bodies_elements_and_points_by_name():
    """What a trace names: a body (its centre of mass), a joint (where it
    attaches to its moving body), "body:x,y", a (body, point) pair; what it
    cannot trace is a ModelError naming it."""
    m = double_pendulum()
    got = plotting.trace_points(m, ["lower", "elbow", "lower:0.5,0", ("upper", (0.5, 0.0))])
    assert [b for b, _ in got] == ["lower", "lower", "lower", "upper"]
    np.testing.assert_allclose([p for _, p in got], [[0, 0], [-0.5, 0], [0.5, 0], [0.5, 0]], atol=1e-12)
    assert plotting.trace_points(m, "shoulder")[0][0] == "upper"
    with pytest.raises(mb.ModelError, match=r"animate: trace 'wrist': no body or element of that name; "
                                            r"the bodies are upper, lower"):
        plotting.trace_points(m, ["wrist"])
    with pytest.raises(mb.ModelError, match=r"animate: trace 'lower:0.5': a point on a body is body:x,y"):
        plotting.trace_points(m, "lower:0.5")
    with pytest.raises(mb.ModelError, match=r"--trace hand: no body or element"):
        plotting.trace_points(m, ["hand"], context="--trace")


@pytest.mark.parametrize("kwargs, message", [
    ({"fps": 0}, "animate: fps 0: must be a number above 0 and at most 50"),
    ({"fps": 100}, "animate: fps 100: must be a number above 0 and at most 50"),
    ({"speed": -1.0}, "animate: speed -1.0: must be a number above 0"),
    ({"speed": float("nan")}, "animate: speed nan: must be a number above 0"),
    ({"frames": 0}, "animate: frames 0: must be a whole number, at least 1"),
    ({"frames": 2.5}, "animate: frames 2.5: must be a whole number, at least 1"),
    ({"trace": "elbw"}, "animate: trace 'elbw': no body or element of that name"),
])
def test_animate_refuses_bad_settings_naming_them(mpl, pendulum_run, tmp_path, kwargs, message):
    with pytest.raises(mb.ModelError) as e:
        plotting.animate(pendulum_run, tmp_path / "x.gif", **kwargs)
    assert str(e.value).startswith(message)
    assert not (tmp_path / "x.gif").exists()


def test_animate_default_size_and_single_trace_pair(mpl, tmp_path):
    from PIL import Image

    m, (A, B, C, D) = fourbar()
    r = mb.simulate(m, t_end=0.5, n_out=26)
    path = tmp_path / "fourbar.gif"
    plotting.animate(r, path, frames=5, trace=("coupler", (0.0, 0.5)))
    with Image.open(path) as im:
        assert im.size == (640, 480) and im.n_frames == 5



# --- matplotlib is optional ------------------------------------------------


def test_lagmb_imports_without_matplotlib_and_plotting_says_what_to_install():
    """In a fresh interpreter where matplotlib cannot be imported, lagmb and
    lagmb.plotting import and run; plot_result and animate raise ImportError
    (mb.MissingExtraError) with the pip command."""
    script = textwrap.dedent("""
        import sys
        sys.modules["matplotlib"] = None   # import matplotlib now raises ImportError
        import lagmb as mb
        import lagmb.plotting as plotting
        m = mb.Model(gravity=(0.0, -9.81))
        rod = m.add_body("rod", mass=1.0, inertia=1 / 12, position=(0.5, 0.0))
        m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
        r = mb.simulate(m, t_end=0.1, n_out=3)
        for call in (lambda: plotting.plot_result(r), lambda: plotting.animate(r, "x.gif")):
            try:
                call()
            except ImportError as e:
                assert 'pip install "lagmb[plot]"' in str(e) and isinstance(e, mb.MissingExtraError), str(e)
            else:
                raise SystemExit("no ImportError")
        print("ok")
    """)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "ok"


# --- spatial runs ------------------------------------------------------------

def spatial_double_pendulum():
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
    m.add_body("upper", 1.0, (0.02, 0.02, 0.001), (0.0, 0.25, -0.25),
               orientation=(np.cos(np.pi / 8), np.sin(np.pi / 8), 0.0, 0.0))
    m.add_body("lower", 0.5, (0.01, 0.01, 0.001), (0.2, 0.5, -0.5))
    m.add_spherical("shoulder", m.ground, "upper", (0.0, 0.0, 0.0))
    m.add_revolute("elbow", "upper", "lower", (0.0, 0.5, -0.5), axis=(0.0, 1.0, 1.0))
    return m


def test_plot_result_of_a_spatial_run_draws_x_y_z_and_the_turn_of_each_body(mpl):
    r = mb.simulate(spatial_double_pendulum(), 1.0, n_out=51)
    fig = plotting.plot_result(r)
    pos, turn, reac = fig.axes[:3]
    assert [t.get_text() for t in pos.get_legend().get_texts()] == ["upper", "lower", "x", "y", "z"]
    np.testing.assert_array_equal(pos.lines[2].get_ydata(), r.body("upper").position[:, 2])
    angle = turn.lines[0].get_ydata()
    assert angle[0] == 0.0 and np.all((angle >= 0.0) & (angle <= np.pi))
    np.testing.assert_allclose(reac.lines[1].get_ydata(), np.linalg.norm(r.reaction("elbow")[:, :3], axis=1))


def test_animate_a_spatial_run_from_the_viewpoint_asked(mpl, tmp_path):
    from PIL import Image, ImageChops

    r = mb.simulate(spatial_double_pendulum(), 1.0, n_out=21)
    frames = {}
    for view in ((25.0, -60.0), (80.0, 0.0)):
        path = tmp_path / f"view{view[0]:.0f}.gif"
        assert plotting.animate(r, path, frames=10, size=(320, 240), view=view,
                                trace=("lower", (0.0, 0.0, 0.0))) == str(path)
        with Image.open(path) as im:
            assert im.n_frames == 10 and im.size == (320, 240)
            frames[view] = im.convert("RGB")
    assert ImageChops.difference(*frames.values()).getbbox() is not None  # seen from elsewhere


def _binary_stl(path, triangles):
    """An STL file (binary) of the given triangles (n, 3, 3)."""
    triangles = np.asarray(triangles, dtype="<f4")
    record = np.zeros(len(triangles), dtype=[("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])
    record["vertices"] = triangles
    with open(path, "wb") as f:
        f.write(b"lagmb test".ljust(80, b" "))
        f.write(np.uint32(len(triangles)).tobytes())
        f.write(record.tobytes())


def test_stl_files_are_read_binary_and_ascii(tmp_path):
    triangles = np.array([[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 1], [1, 0, 1], [0, 1, 1.5]]], dtype=float)
    _binary_stl(tmp_path / "b.stl", triangles)
    ascii_text = "solid t\n" + "".join(
        "facet normal 0 0 1\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in tri) +
        "endloop\nendfacet\n" for tri in triangles) + "endsolid t\n"
    (tmp_path / "a.stl").write_text(ascii_text)
    for name in ("b.stl", "a.stl"):
        assert _meshes.read_stl(tmp_path / name) == pytest.approx(triangles)


def _ascii_stl(*vertex_lines, end="endloop\nendfacet\nendsolid t\n"):
    return ("solid t\nfacet normal 0 0 1\nouter loop\n" + "".join(f"vertex {v}\n" for v in vertex_lines) + end).encode()


_HEADER = b"lagmb test".ljust(80, b" ")


@pytest.mark.parametrize("content, message", [
    (_ascii_stl("0 0 0", "1 0 0", "0 1 0", end=""), r"ends \(line 6\) where 'endloop' belongs \(cut short\?\)"),
    (_ascii_stl("0 0 0", "1 0"), r"line 6: 'endloop' is not a decimal number"),
    (_ascii_stl("0 0 0", "1 0 0", "0 1 0", end="endloop\nendfacet\n"),
     r"ends \(line 8\) where 'facet' or 'endsolid' belongs \(cut short\?\)"),
    (_ascii_stl("one two three", "1 0 0", "0 1 0"), r"line 4: 'one' is not a decimal number"),
    (_ascii_stl("1_0 0 0", "1 0 0", "0 1 0"), r"line 4: '1_0' is not a decimal number"),
    (_ascii_stl("0 0 0", "1 0 0", "0 1 0", "1 1 0"), r"line 7: 'vertex' where 'endloop' belongs"),
    (_ascii_stl("nan 0 0", "1 0 0", "0 1 0"), r"line 4: a vertex coordinate 'nan' is not finite"),
    (_ascii_stl("1e999 0 0", "1 0 0", "0 1 0"), r"line 4: '1e999' is too large for a float"),
    (b"", r"0 bytes: too short for a binary STL .* and not an ASCII one"),
    (_HEADER + np.uint32(5).tobytes() + bytes(120),
     r"a binary STL of 5 triangles .* is 84 \+ 50 x 5 = 334 bytes long; the file has 204 bytes \(cut short"),
    (_HEADER + np.uint32(4_000_000_000).tobytes() + bytes(50),
     r"a binary STL of 4000000000 triangles .* = 200000000084 bytes long; the file has 134 bytes"),
    (b"solid".ljust(80) + np.uint32(2).tobytes() + bytes(50), r"a binary STL of 2 triangles"),
    (_HEADER + np.uint32(1).tobytes() + np.array([0, 0, 1, np.inf, 0, 0, 1, 0, 0, 0, 1, 0], "<f4").tobytes() + bytes(2),
     r"triangle 1 of 1 has a vertex that is not finite: \[\[inf, 0\.0, 0\.0\]"),
])
def test_a_broken_stl_file_is_named_with_what_is_wrong(tmp_path, content, message):
    (tmp_path / "bad.stl").write_bytes(content)
    with pytest.raises(mb.ModelError, match=r"STL file '.*bad\.stl'(, |: )" + message):
        _meshes.read_stl(tmp_path / "bad.stl")


def test_an_ascii_stl_may_hold_several_solids_named_anything(tmp_path):
    text = ("solid my facet\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1E0 0 0\n"
            "   vertex 0 1 0\n  endloop\n endfacet\nendsolid my facet\nSOLID empty\nENDSOLID\n")
    (tmp_path / "s.stl").write_text(text)
    assert _meshes.read_stl(tmp_path / "s.stl") == pytest.approx(np.array([[[0, 0, 0], [1, 0, 0], [0, 1, 0]]]))


def test_picture_draws_the_shapes_at_their_bodies_poses(mpl, tmp_path):
    """plotting.picture: a box, a cylinder, a sphere and an STL mesh on a
    swinging rod are drawn (4), a COLLADA mesh is counted out; the PNG is
    written; a trace is refused (planar pictures only)."""
    _binary_stl(tmp_path / "tri.stl", [[[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0]]])
    m = mb.Model(dimension=3)
    rod = m.add_body("rod", 1.0, (1e-3, 1.0 / 12, 1.0 / 12), position=(0.5, 0.0, 0.0))
    m.add_revolute("hinge", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    for kind, size, mesh in (("box", (1.0, 0.05, 0.05), None), ("cylinder", (0.03, 0.2), None),
                             ("sphere", (0.06,), None), ("mesh", (2.0, 2.0, 2.0), str(tmp_path / "tri.stl")),
                             ("mesh", (1.0, 1.0, 1.0), str(tmp_path / "arm.dae"))):
        m.add_shape(rod, kind, size, position=(0.5, 0.0, 0.0), mesh=mesh, role="collision")
    r = mb.simulate(m, 0.5, n_out=6)
    assert plotting.picture(r, tmp_path / "rod.png", time=0.2) == 4
    assert (tmp_path / "rod.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert plotting.picture(r, tmp_path / "none.png", role="visual") == 0
    with pytest.raises(mb.ModelError, match="plotting.picture: trace draws paths in planar pictures"):
        plotting.picture(r, tmp_path / "t.png", trace="rod")


def test_a_planar_picture_is_animates_frame_with_the_paths_travelled(mpl, tmp_path):
    """plotting.picture of a planar run: animate's drawing at the output
    nearest ``time`` (its stamp says which), one body drawn per body, the
    traced path through the outputs up to then; a bad trace is named."""
    m = mb.Model(gravity=(0.0, -9.81))
    rod = m.add_body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    r = mb.simulate(m, t_end=1.0, n_out=11)
    path = tmp_path / "rod.png"
    captured = {}
    original = plotting.pictures.planar_drawing

    def spy(scene, shown, trace, size, dpi, speed):
        drawing = original(scene, shown, trace, size, dpi, speed)
        captured["drawing"], captured["shown"] = drawing, shown
        return drawing

    mp = pytest.MonkeyPatch()
    mp.setattr(plotting.pictures, "planar_drawing", spy)
    try:
        assert plotting.picture(r, path, time=0.52, trace=[("rod", (0.5, 0.0))], title="a rod") == 1
    finally:
        mp.undo()
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    drawing = captured["drawing"]
    assert captured["shown"].t.tolist() == [0.5]  # the output nearest 0.52
    assert drawing.artists["stamp"].get_text().strip().startswith("t = 0.5")
    assert drawing.fig.axes[0].get_title() == "a rod"
    (tip,) = drawing.artists["traces"]
    x, y = tip.get_data()
    assert len(x) == 7  # outputs 0, 0.1, ..., 0.5 and the frame's own point
    assert np.allclose(np.hypot(x, y), 1.0)  # the rod's tip stays 1 m from the pin
    with pytest.raises(mb.ModelError, match="plotting.picture: trace 'tip': no body or element"):
        plotting.picture(r, path, trace="tip")


def test_picture_names_a_bad_argument_and_draws_a_mesh_of_no_triangles(mpl, tmp_path):
    (tmp_path / "empty.stl").write_text("solid empty\nendsolid empty\n")
    r = hinged_rod_with_mesh(tmp_path / "empty.stl", "collision", t_end=0.2)
    assert plotting.picture(r, tmp_path / "empty.png") == 1
    for kwargs, message in (({"time": "late"}, "time must be a number, got 'late'"),
                            ({"time": math.nan}, "time must be finite, got nan"),
                            ({"role": "visible"}, "role must be 'visual' or 'collision', got 'visible'"),
                            ({"view": (20.0,)}, r"view \(elevation, azimuth in degrees\) must be a pair")):
        with pytest.raises(mb.ModelError, match="plotting.picture: " + message):
            plotting.picture(r, tmp_path / "bad.png", **kwargs)


def _shapes_on_a_floor():
    """A box, a sphere, a capsule and a cylinder dropped onto a plane."""
    m = mb.Model(gravity=(0.0, 0.0, -9.81), dimension=3)
    floor = m.add_shape("ground", "plane", (), role="collision")
    for i, (kind, size) in enumerate([("box", (0.2, 0.15, 0.1)), ("sphere", (0.08,)), ("capsule", (0.05, 0.2)),
                                      ("cylinder", (0.07, 0.15))]):
        centre = (0.3 * i - 0.45, 0.0, 0.2)
        m.add_body(f"b{i}", mass=1.0, inertia=(0.01, 0.012, 0.014), position=centre)
        shape = m.add_shape(f"b{i}", kind, size, centre, role="collision")
        m.add_contact(f"c{i}", shape, floor, stiffness=1e7, restitution=0.5, friction=0.5)
    return m


def test_a_picture_draws_a_plane_as_a_floor_under_the_shapes(mpl, tmp_path):
    """plotting.picture of shapes resting on a plane: all five drawn (the
    plane as a square floor spanning the bodies, drawn first, the axes'
    limits set by the bodies alone), the shapes' colours visible over it."""
    from PIL import Image

    r = mb.simulate(_shapes_on_a_floor(), 0.5, n_out=3)
    path = tmp_path / "floor.png"
    assert plotting.picture(r, path) == 5
    im = np.asarray(Image.open(path).convert("RGB"), dtype=int)
    grey = (np.ptp(im, axis=2) < 6) & (im[:, :, 0] > 150) & (im[:, :, 0] < 235)
    floor = np.sum(grey[300:450, 100:560])  # (the floor's grey, below the title, above the axis labels)
    blue = np.sum((im[:, :, 2] > 120) & (im[:, :, 0] < 80))  # (the box, body 0's colour)
    assert floor > 20000 and blue > 300


def test_an_animation_draws_a_plane_as_a_floor_under_the_bodies(mpl):
    """A spatial animation of bodies on a plane: one floor (a square in the
    plane z = 0 spanning 0.9 of the view) drawn under everything."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    r = mb.simulate(_shapes_on_a_floor(), 0.5, n_out=11)
    scene = _drawing.Scene(r)
    drawing = spatial_drawing.spatial_drawing(scene, r, [], (320, 240), 100, (20.0, -60.0), 1.0)
    ax = drawing.fig.axes[0]
    floor, solids = [c for c in ax.collections if isinstance(c, Poly3DCollection)]
    assert floor.get_zorder() == 0 and solids.get_zorder() > 0 and not ax.computed_zorder
    (square,) = drawing.floors
    assert np.allclose(square[:, 2], 0.0)
    view_width = ax.get_xlim()[1] - ax.get_xlim()[0]
    assert abs(np.ptp(square[:, 0]) - 0.9 * view_width) <= 1e-9 * view_width


def test_an_animation_draws_bodies_with_shapes_as_their_shapes(mpl):
    """Bodies that have shapes (a robot's meshes; here a box, a sphere, a
    capsule and a cylinder) are drawn as those shapes, placed by each
    frame's pose and shaded, in one collection; no inertia boxes or axes
    for them (a URDF's inflated inertias drew as large slabs)."""
    from lagmb.plotting.spatial import _body_shapes

    r = mb.simulate(_shapes_on_a_floor(), 0.5, n_out=11)
    scene = _drawing.Scene(r)
    drawing = spatial_drawing.spatial_drawing(scene, r, [], (320, 240), 100, (20.0, -60.0), 1.0)
    solids = _body_shapes(r.model, scene.bodies)
    assert set(solids) == {"b0", "b1", "b2", "b3"}
    assert drawing.artists["boxes"] == [] and drawing.artists["triad"] == []
    (collection,) = drawing.artists["solids"]
    for k in (0, 10):
        drawing.update(k)
        placed = np.concatenate([r.body(b).position[k] + solids[b] @ r.body(b).rotation[k].T
                                 for b in scene.bodies])
        assert np.array_equal(drawing.now["triangles"], placed)
        assert len(collection.get_facecolor()) == len(placed)


def test_a_robot_s_histories_are_its_joints(mpl, tmp_path):
    """plot_result of a spatial model with revolute joints (a URDF arm):
    the joint angles (rad) and rates (rad/s) as r.joint reads them, not the
    bodies' centres of mass and turns; the title names the robot. A planar
    model keeps its bodies' coordinates. A series constant to round-off is
    drawn flat in a span of 1e-9 of its size, not magnified."""
    from builders import ARM_URDF

    path = tmp_path / "arm.urdf"
    path.write_text(ARM_URDF)
    r = mb.simulate(mb.load_urdf(str(path)), 0.5, n_out=51)
    fig = plotting.plot_result(r, what=("coordinates",))
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert labels == ["joint angle (rad)", "joint rate (rad/s)"]
    for line in fig.axes[0].lines:
        assert np.array_equal(line.get_ydata(), r.joint(line.get_label()).angle)
    for line in fig.axes[1].lines:
        assert np.array_equal(line.get_ydata(), r.joint(line.get_label()).rate)
    assert fig._suptitle.get_text().startswith("lagmb: arm (")
    planar = plotting.plot_result(mb.simulate(pendulum(), 0.2, n_out=11), what=("coordinates",))
    assert planar.axes[0].get_ylabel().startswith("centre of mass")
    import matplotlib.figure

    from lagmb.plotting.history import _least_span

    ax = matplotlib.figure.Figure().add_subplot()
    ax.plot([0.0, 1.0], [3e-16, -2e-16])
    _least_span(ax, [np.array([3e-16, -2e-16])])
    assert ax.get_ylim() == pytest.approx((-1e-9, 1e-9), abs=1e-12)
