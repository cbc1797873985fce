"""lagmb.view: one self-contained HTML page per run, opened from disk in a
real headless Chromium with the network off. The page's test hook
(window.lagmbViewer) says how many bodies it drew and where playback is;
pressing play moves time on, the slider and a click on a plot move it
where asked; a screenshot shows the bodies (pixels that differ from the
white background where the view is). Skipped with the reason where no
Chromium is installed (scripts/setup.sh installs chromium-headless-shell)."""

import base64
import math
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("trimesh", reason="lagmb.view takes three.js from the trimesh wheel: the 'view' extra")

import lagmb as mb  # noqa: E402
from lagmb.viewer import view

import browser
from builders import hinged_rod_with_mesh, lagmb_command, pendulum
import paths  # noqa: E402  (tests/paths.py)

EXAMPLES = Path(paths.EXAMPLES)


def test_the_page_is_self_contained_and_bad_input_is_named(tmp_path):
    r = mb.load_scene(EXAMPLES / "slider_crank.toml").run(t_end=0.5, n_out=51)
    v = view(r, tmp_path / "sc.html", outputs=["motor.effort", "C.reaction.y", "slider.x"], title="slider-crank")
    page = (tmp_path / "sc.html").read_text()
    assert v.size == len(page.encode()) and v.path == str(tmp_path / "sc.html")
    # nothing fetched: no http(s) source, no CDN; three.js inside
    assert "src=\"http" not in page and "https://" not in page.split("<script>")[0]
    assert "WebGLRenderer" in page and "TrackballControls" in page
    assert "<iframe" in v._repr_html_() and "srcdoc=" in view(r, None)._repr_html_()
    with pytest.raises(mb.ModelError, match=r"no output 'slider\.z'.*slider\.x"):
        view(r, tmp_path / "x.html", outputs=["slider.z"])
    with pytest.raises(mb.ModelError, match="cannot write"):
        view(r, tmp_path / "missing" / "dir" / "x.html")
    with pytest.raises(mb.ModelError, match="give a Result"):
        view(r.q, tmp_path / "x.html")
    r.model = None
    with pytest.raises(mb.ModelError, match="has no model"):
        view(r, tmp_path / "x.html")


def chain(n):
    """n uniform rods hanging from a pin, tilted 0.5 rad, 0.1 m each."""
    m = mb.Model(gravity=(0.0, -9.81))
    previous, joint = m.ground, (0.0, 0.0)
    a = -math.pi / 2 + 0.5
    e = np.array([math.cos(a), math.sin(a)])
    for i in range(n):
        rod = m.add_body(f"rod{i}", 0.1, 0.1 * 0.01 / 12, position=tuple(joint + 0.05 * e), angle=a)
        m.add_revolute(f"pin{i}", previous, rod, at=tuple(joint))
        previous, joint = rod, joint + 0.1 * e
    return m


@pytest.fixture(scope="module")
def chromium():
    binary = browser.find()
    if binary is None:
        pytest.skip("no headless Chromium (install Debian's chromium-headless-shell: scripts/setup.sh does)")
    b = browser.Browser(binary)
    yield b
    b.close()


def pixels_in_view(page, shot, renders):
    """After two more renders than `renders`, the page's screenshot (to the
    path `shot`): its drawn pixels in the 3D view (drawn_pixels)."""
    page.wait_for(f"lagmbViewer.state().renders > {renders + 2}")
    page.screenshot(shot)
    box = page.evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect(); "
                        "return [r.left, r.top, r.right, r.bottom]; })()")
    return drawn_pixels(shot, [int(x) for x in box])


def drawn_pixels(png, region):
    """Pixels in region (x0, y0, x1, y1) that are not the white background."""
    from PIL import Image

    im = np.asarray(Image.open(png).convert("RGB"), dtype=int)
    x0, y0, x1, y1 = region
    patch = im[y0:y1, x0:x1]
    return int(np.sum(np.abs(patch - 255).sum(axis=2) > 60))


def open_page(chromium, path):
    # the network off: a page that reached for it would fail to load
    page = chromium.open("about:blank")
    page.command("Network.enable")
    page.command("Network.emulateNetworkConditions", {"offline": True, "latency": 0, "downloadThroughput": -1,
                                                      "uploadThroughput": -1})
    start = time.monotonic()
    page.command("Page.navigate", {"url": Path(path).resolve().as_uri()})
    page.wait_for("window.lagmbViewer && window.lagmbViewer.state().ready")
    return page, time.monotonic() - start


@pytest.mark.parametrize("case", ["slider_crank", "four_bar", "heavy_top"])
def test_a_run_plays_in_a_browser(chromium, tmp_path, case):
    scene = mb.load_scene(EXAMPLES / f"{case}.toml")
    r = scene.run(t_end=2.0, n_out=201)
    path = tmp_path / f"{case}.html"
    outputs = {"slider_crank": ["motor.effort", "slider.x"], "four_bar": ["energy", "crank.angle"],
               "heavy_top": ["energy"]}[case]
    view(r, path, outputs=outputs, title=f"{case}.toml")
    page, load = open_page(chromium, path)
    state = page.evaluate("lagmbViewer.state()")
    assert state["bodies"] == len(scene.model.bodies) and state["drawn"] >= state["bodies"]
    assert state["frames"] == 201 and state["frame"] == 0 and state["plots"] == outputs
    # play for about a second: time moves on (software rendering: at its own pace)
    page.evaluate("lagmbViewer.play()")
    time.sleep(1.0)
    played = page.evaluate("lagmbViewer.state()")
    assert played["playing"] and played["time"] > 0.1, played
    page.evaluate("lagmbViewer.pause()")
    # the slider: to frame 150 (t = 1.5 s)
    page.evaluate("(() => { const s = document.getElementById('slider'); s.value = '150'; "
                  "s.dispatchEvent(new Event('input')); })()")
    moved = page.evaluate("lagmbViewer.state()")
    assert moved["frame"] == 150 and moved["time"] == pytest.approx(1.5, abs=1e-6) and not moved["playing"]
    # a click at the middle of the first plot: t = 1 s
    box = page.evaluate("(() => { const r = document.querySelector('.plot').getBoundingClientRect(); "
                        "return [r.left, r.top, r.width, r.height]; })()")
    page.click(box[0] + 0.5 * box[2], box[1] + 0.5 * box[3])
    clicked = page.evaluate("lagmbViewer.state()")
    assert clicked["time"] == pytest.approx(1.0, abs=0.011)
    # the bodies and the grid, not a blank canvas
    assert pixels_in_view(page, tmp_path / f"{case}.png", clicked["renders"]) > 2000
    page.close()


def test_a_thousand_link_chain_is_sent_as_poses_and_loads(chromium, tmp_path):
    model = chain(1000)
    r = mb.simulate(model, 0.2, n_out=21, method="ggl", rtol=1e-4, atol=1e-6)
    path = tmp_path / "chain.html"
    v = view(r, path)
    # geometry once, then 7 float32 per body per frame (base64: 4/3)
    poses = 21 * 1000 * 7 * 4 * 4 / 3
    assert poses < v.size < poses + 4e6
    page, load = open_page(chromium, path)
    state = page.evaluate("lagmbViewer.state()")
    assert state["bodies"] == 1000 and state["frames"] == 21
    page.evaluate("lagmbViewer.setFrame(20)")
    assert page.evaluate("lagmbViewer.state().frame") == 20
    page.close()


def test_lagmb_run_writes_the_page_with_html(tmp_path):
    page = tmp_path / "out" / "four_bar.html"
    done = lagmb_command("run", EXAMPLES / "four_bar.toml", "--t-end", "0.5", "--html", page)
    assert done.returncode == 0, done.stderr
    assert "interactive view written to" in done.stdout and page.is_file()
    assert "WebGLRenderer" in page.read_text() and "four_bar.toml" in page.read_text()
    bad = lagmb_command("run", EXAMPLES / "four_bar.toml", "--html", tmp_path / "four_bar.txt")
    assert bad.returncode == 2 and "--html" in bad.stderr and "must end in .html" in bad.stderr


def test_a_vibration_mode_loops_in_the_browser(chromium, tmp_path):
    scene = mb.load_scene(EXAMPLES / "double_pendulum.toml")
    modes = mb.modes(scene.model)
    path = tmp_path / "mode.html"
    v = mb.view_mode(modes, 1, path)
    assert v.path == str(path)
    page, _ = open_page(chromium, path)
    state = page.evaluate("lagmbViewer.state()")
    assert state["loop"] and state["frames"] == 101 and state["bodies"] == 2
    period = 1.0 / modes.frequencies[1]
    assert page.evaluate("lagmbViewer.state().time") == 0.0
    page.evaluate(f"lagmbViewer.seek({0.9 * period})")
    page.evaluate("lagmbViewer.play()")
    time.sleep(1.0)  # past the period's end: it starts again instead of stopping
    state = page.evaluate("lagmbViewer.state()")
    assert state["playing"] and state["time"] < 0.9 * period
    page.close()
    with pytest.raises(mb.ModelError, match="index 5: there are 2 modes"):
        mb.view_mode(modes, 5, tmp_path / "x.html")


def test_a_sweep_s_cases_are_selectable_each_drawn_with_its_own_parameters(chromium, tmp_path):
    scene = mb.load_scene(EXAMPLES / "slider_crank.toml")
    grid = {"B.at.y": [0.08, 0.12], "rod.mass": [1.0, 2.0]}
    ds = mb.sweep(scene, grid, t_end=0.3, histories=np.linspace(0.0, 0.3, 31), progress=False)
    index = mb.view_sweep(ds, scene.model, tmp_path / "study")
    page, _ = open_page_of_sweep(chromium, index)
    assert page.evaluate("lagmbSweep.cases()") == 4 and page.evaluate("lagmbSweep.page()") == "case_0000.html"
    page.evaluate("lagmbSweep.choose(3)")
    assert page.evaluate("lagmbSweep.page()") == "case_0003.html"
    page.close()
    # each case's page: the crank as long as its B.at.y says (the bar from O to B)
    short = (tmp_path / "study" / "case_0000.html").read_text()
    long = (tmp_path / "study" / "case_0002.html").read_text()
    assert "B.at.y = 0.08" in short and "B.at.y = 0.12" in long and short != long
    with pytest.raises(mb.ModelError, match="no time histories"):
        mb.view_sweep(mb.sweep(scene, grid, t_end=0.1, progress=False), scene.model, tmp_path / "x")


def open_page_of_sweep(chromium, path):
    page = chromium.open("about:blank")
    page.command("Page.navigate", {"url": Path(path).resolve().as_uri()})
    page.wait_for("window.lagmbSweep && window.lagmbSweep.selected() !== null")
    return page, None


def test_an_imported_robot_plays_with_its_meshes(chromium, tmp_path):
    import sys

    sys.path.insert(0, str(EXAMPLES))
    try:
        import panda
    finally:
        sys.path.remove(str(EXAMPLES))
    urdf = panda.panda_urdf()
    if urdf is None:
        pytest.skip("example-robot-data is not installed (the robots extra)")
    model = panda.build(urdf)
    r = mb.simulate(model, 0.3, n_out=31, method="projection-erk", rtol=1e-6, atol=1e-8)
    path = tmp_path / "panda.html"
    view(r, path, outputs=["energy", "panda_joint2.angle"])
    assert '"type": "mesh"' in path.read_text()  # its STL meshes, sent once
    page, _ = open_page(chromium, path)
    state = page.evaluate("lagmbViewer.state()")
    assert state["bodies"] == len(model.bodies) and state["drawn"] > state["bodies"]
    page.evaluate("lagmbViewer.setFrame(30)")
    assert page.evaluate("lagmbViewer.state().time") == pytest.approx(0.3)
    assert pixels_in_view(page, tmp_path / "panda.png", state["renders"]) > 2000
    page.close()


# --- hostile names, bad arguments, what a page cannot draw (issue 39) ------

HOSTILE = ["<!--<script>", "</script><script>alert(1)</script>", "%%POSES%%", "%%THREE%%"]


def hostile_chain():
    """A chain of rods named HOSTILE, each pinned by a joint named 'pin'
    plus its rod's name."""
    m = mb.Model(gravity=(0.0, -9.81))
    previous = m.ground
    for i, name in enumerate(HOSTILE):
        rod = m.add_body(name, 1.0, 0.1 / 12, position=(0.1 * i + 0.05, 0.0))
        m.add_revolute("pin" + name, previous, rod, at=(0.1 * i, 0.0))
        previous = rod
    return m


def test_hostile_names_start_the_page_and_show_as_text(chromium, tmp_path):
    """A name holding "<!--<script>" once made the HTML tokenizer swallow the
    data's </script> (the viewer never started), and placeholders in names
    or the title were substituted (three.js copied into the title)."""
    r = mb.simulate(hostile_chain(), 0.1, n_out=11)
    outputs = [f"pin{name}.reaction.x" for name in HOSTILE]
    path = tmp_path / "hostile.html"
    v = view(r, path, outputs=outputs, title=" ".join(HOSTILE))
    assert v.size < 1.2 * view(r, None, outputs=outputs).size  # three.js once, not again in the title
    page, _ = open_page(chromium, path)
    state = page.evaluate("lagmbViewer.state()")
    assert state["bodies"] == 4 and state["plots"] == outputs
    assert page.evaluate("document.title") == " ".join(HOSTILE)
    assert page.evaluate("document.querySelector('#info .title').textContent") == " ".join(HOSTILE)
    shown = page.evaluate("[...document.querySelectorAll('.plot .name')].map((d) => d.textContent)")
    assert shown == [f"{name} (N)" for name in outputs]
    assert page.evaluate("document.scripts.length") == 4  # three.js, the data, the poses, the viewer: none added
    page.close()


def test_a_sweep_of_a_hostile_parameter_lists_its_cases(chromium, tmp_path):
    model = hostile_chain()
    ds = mb.sweep(model, {"<!--<script>.mass": [1.0, 2.0]}, t_end=0.05,
                  histories=np.linspace(0.0, 0.05, 6), progress=False)
    index = mb.view_sweep(ds, model, tmp_path / "study")
    page, _ = open_page_of_sweep(chromium, index)
    assert page.evaluate("lagmbSweep.cases()") == 2
    labels = page.evaluate("[...document.querySelectorAll('#cases div')].map((d) => d.textContent)")
    assert labels == ["case 0: <!--<script>.mass = 1", "case 1: <!--<script>.mass = 2"]
    page.close()
    for kwargs, message in (({"cases": "0"}, "cases must be a list of case numbers, got '0'"),
                            ({"cases": [1.5]}, r"cases\[0\] must be an integer, got 1\.5"),
                            ({"folder": 5}, r"folder must be a file name \(str or os\.PathLike\), got 5")):
        with pytest.raises(mb.ModelError, match="lagmb.view_sweep: " + message):
            mb.view_sweep(ds, model, **{"folder": tmp_path / "x", **kwargs})


def short_pendulum():
    """A 0.1 m rod of 1 kg (J = 0.1/12 kg m^2) pinned at the origin, level."""
    return pendulum(L=0.1, inertia=0.1 / 12)


@pytest.mark.parametrize("argument, value, message", [
    ("max_frames", 0, r"max_frames must be in 1\.\.\d+, got 0"),
    ("max_frames", -1, r"max_frames must be in 1\.\.\d+, got -1"),
    ("max_frames", math.nan, "max_frames must be an integer, got nan"),
    ("max_frames", True, "max_frames must be an integer, got True"),
    ("outputs", [None], r"outputs\[0\] must be a string, got None"),
    ("outputs", 5, "outputs must be a list of strings, got 5"),
    ("title", 5, "title must be a string, got 5"),
    ("lines", ["ok", 7], r"lines\[1\] must be a string, got 7"),
    ("loop", "yes", "loop must be True or False, got 'yes'"),
    ("trace", 5, "trace: expected a body.*got 5"),
    ("trace", [("rod", (0.0, "a"))], r"trace point \(0\.0, 'a'\): must be 2 numbers"),
    ("trace", "rod:1_0,0", "trace 'rod:1_0,0': '1_0' is not a decimal number"),
    ("path", 5, r"path must be a file name \(str or os\.PathLike\), got 5"),
])
def test_a_bad_argument_of_view_is_named_with_its_value(argument, value, message):
    r = mb.simulate(short_pendulum(), 0.1, n_out=3)
    kwargs = {"path": None, argument: value}
    with pytest.raises(mb.ModelError, match="lagmb.view: " + message):
        view(r, **kwargs)


@pytest.mark.parametrize("argument, value, message", [
    ("amplitude", math.nan, "amplitude must be finite, got nan"),
    ("amplitude", math.inf, "amplitude must be finite, got inf"),
    ("amplitude", "big", "amplitude must be a number, got 'big'"),
    ("frames", 0, r"frames must be in 1\.\.100000, got 0"),
    ("frames", 2.5, "frames must be an integer, got 2.5"),
])
def test_a_bad_argument_of_view_mode_is_named_with_its_value(argument, value, message):
    modes = mb.modes(short_pendulum())
    with pytest.raises(mb.ModelError, match="lagmb.view_mode: " + message):
        mb.view_mode(modes, 0, None, **{argument: value})


def test_what_a_page_cannot_draw_is_refused_and_named(tmp_path):
    """NaN or Infinity once went into the page's JSON (which JSON.parse
    refuses: a blank page) or its float32 poses, without a word."""
    m = mb.Model(gravity=(0.0, 0.0))
    m.add_body("near", 1.0, 0.1, position=(0.0, 0.0))
    m.add_body("far", 1.0, 0.1, position=(2e160, 0.0))
    r = mb.simulate(m, 0.1, n_out=3)
    with pytest.raises(mb.ModelError, match=r"the position of body 'far' at t = 0 is too large to draw .*float32.*"
                                            r"\(2e\+160, 0\)"):
        view(r, tmp_path / "far.html")
    assert not (tmp_path / "far.html").exists()
    from lagmb.result import Result

    model = short_pendulum()
    q = np.tile([0.05, 0.0, 0.0], (3, 1))
    q[1:, 2] = math.nan  # the rod's angle, from the second output on
    zero = np.zeros_like(q)
    r = Result(model, model.compiled(), {"t": np.array([0.0, 0.1, 0.2]), "q": q, "v": zero, "a": zero,
                                         "lam": np.zeros((3, 2)), "stats": {}})
    with pytest.raises(mb.ModelError, match=r"the angle of body 'rod' at t = 0\.1 is not finite: nan"):
        view(r, None)
    with pytest.raises(mb.ModelError, match=r"the traced point \(1e\+300, 0\.0\) of body 'rod' at t = 0 is too large"):
        view(mb.simulate(short_pendulum(), 0.1, n_out=3), None, trace=[("rod", (1e300, 0.0))])


def test_the_page_embeds_its_json_safely():
    from lagmb.viewer import _fill, _script_json

    text = _script_json({"name": "</script><!--<script>&\u2028\u2029"})
    assert not set("<>&\u2028\u2029") & set(text)
    import json
    assert json.loads(text) == {"name": "</script><!--<script>&\u2028\u2029"}
    assert _fill("%%A%%|%%B%%", {"A": "%%B%%", "B": "%%A%%"}) == "%%B%%|%%A%%"


def test_a_broken_stl_mesh_is_named_by_view(tmp_path):
    (tmp_path / "cut.stl").write_text("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0")
    r = hinged_rod_with_mesh(tmp_path / "cut.stl", "visual")
    with pytest.raises(mb.ModelError, match=r"STL file '.*cut\.stl': ends \(line 5\) where a number belongs"):
        view(r, None)
    # a mesh scaled past float32 (the page's numbers)
    (tmp_path / "cut.stl").write_text("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                      "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n")
    r = hinged_rod_with_mesh(tmp_path / "cut.stl", "visual", size=(1e39, 1.0, 1.0))
    with pytest.raises(mb.ModelError, match=r"the mesh shape of body 'rod' \('.*cut\.stl'\) reaches past what the "
                                            r"page draws \(float32.*size \(1e\+39, 1\.0, 1\.0\)"):
        view(r, None)


def test_a_planar_contact_is_drawn_as_a_disc_and_a_bar(chromium, tmp_path):
    """A ball on a sprung seesaw whose plank nothing else outlines: the page
    draws the contact's circle as a disc (radius 0.1 m) on the ball and its
    line as a long bar on the plank (through the plank's pivot, along it),
    and shows them in Chromium."""
    import json
    import re

    m = mb.Model(gravity=(0.0, -9.81))
    plank = m.add_body("plank", mass=2.0, inertia=2.0 * 4.0 / 12.0, position=(0.0, 0.0), angle=0.1)
    m.add_revolute("pivot", m.ground, plank, at=(0.0, 0.0))
    m.add_rotational_spring_damper("spring", m.ground, plank, stiffness=40.0, damping=1.0, free_angle=0.1)
    ball = m.add_body("ball", mass=0.5, inertia=0.002, position=(0.6, 0.4))
    m.add_contact("hit", ball, (0.6, 0.4), 0.1, plank, (0.0, 0.0), (math.cos(0.1), math.sin(0.1)),
                  stiffness=1e6, restitution=0.6, friction=0.4)
    r = mb.simulate(m, t_end=1.0, n_out=51)
    path = tmp_path / "seesaw.html"
    view(r, path)
    data = json.loads(re.search(r'id="lagmb-data">(.*?)</script>', path.read_text(), re.S).group(1))
    parts = {b["name"]: b["parts"] for b in data["bodies"]}
    discs = [p for p in parts["ball"] if p["type"] == "cylinder"]
    assert len(discs) == 1 and discs[0]["radius"] == 0.1 and discs[0]["position"][:2] == [0.0, 0.0]
    bars = [p for p in parts["plank"] if p["type"] == "box" and p["size"][0] > 1.0]
    assert len(bars) == 1 and abs(bars[0]["quaternion"][2]) <= 1e-12  # along the plank's own x axis
    assert np.allclose(bars[0]["position"][:2], [0.0, 0.0], atol=1e-12)
    page, _ = open_page(chromium, path)
    state = page.evaluate("lagmbViewer.state()")
    assert state["bodies"] == 2 and state["drawn"] > state["bodies"]
    assert pixels_in_view(page, tmp_path / "seesaw.png", state["renders"]) > 2000
    page.close()


def test_spatial_shapes_and_a_floor_are_drawn(chromium, tmp_path):
    """Shapes resting on a plane: the page draws each body's shape as a
    mesh (a capsule's side and two ends, a box's six faces), the plane as a
    floor on the ground (a square of twice the scene's size, under its
    middle), and Chromium shows them."""
    import json
    import re

    from tools import test_plotting

    r = mb.simulate(test_plotting._shapes_on_a_floor(), 0.5, n_out=11)
    path = tmp_path / "floor.html"
    view(r, path)
    data = json.loads(re.search(r'id="lagmb-data">(.*?)</script>', path.read_text(), re.S).group(1))
    for body in data["bodies"]:
        assert [p["type"] for p in body["parts"]] == ["mesh"]
    (floor,) = [p for p in data["ground_parts"] if p["type"] == "mesh"]
    corners = np.frombuffer(base64.b64decode(floor["vertices"]), "<f4").reshape(-1, 3)
    assert np.all(corners[:, 2] == 0.0)  # on the plane z = 0
    assert np.allclose(np.ptp(corners[:, :2], axis=0), 2 * data["size"], rtol=1e-6)
    assert np.allclose(corners[:, :2].mean(axis=0), data["camera"]["target"][:2], atol=1e-6)  # under the middle
    page, _ = open_page(chromium, path)
    state = page.evaluate("lagmbViewer.state()")
    assert state["bodies"] == 4 and state["drawn"] == 4
    assert pixels_in_view(page, tmp_path / "floor.png", state["renders"]) > 20000
    page.close()


def test_contact_forces_are_drawn_as_arrows(chromium, tmp_path):
    """view(..., forces=True): one arrow per contact at its point along the
    force on its first shape (r.contact: normal and friction), the largest
    over the run a tenth of the scene long, the scale written under the
    title; Chromium shows the arrows of the contacts pressing at a frame."""
    import json
    import re

    from tools import test_plotting

    r = mb.simulate(test_plotting._shapes_on_a_floor(), 0.5, n_out=11)
    path = tmp_path / "forces.html"
    view(r, path, forces=True)
    data = json.loads(re.search(r'id="lagmb-data">(.*?)</script>', path.read_text(), re.S).group(1))
    assert len(data["arrows"]) == 4
    vectors = [np.frombuffer(base64.b64decode(a["vectors"]), "<f4").reshape(-1, 3) for a in data["arrows"]]
    longest = max(np.linalg.norm(v, axis=1).max() for v in vectors)
    assert abs(longest - 0.1 * data["size"]) <= 1e-6 * data["size"]
    pressing_at_end = 0
    for i, v in enumerate(vectors):  # (the box, bouncing, is in the air at the end)
        c = r.contact(f"c{i}")
        if c.normal_force[-1] > 0.0:
            force = c.normal_force[-1] * c.normal[-1] + c.friction_force[-1]
            assert np.allclose(v[-1] / np.linalg.norm(v[-1]), force / np.linalg.norm(force), atol=1e-6)
            pressing_at_end += 1
    assert pressing_at_end >= 2
    assert any(line.startswith("contact forces: ") for line in data["lines"])
    page, _ = open_page(chromium, path)
    page.evaluate(f"lagmbViewer.setFrame({len(r.t) - 1})")
    pressing = sum(r.contact(f"c{i}").normal_force[-1] > 0 for i in range(4))
    page.wait_for(f"lagmbViewer.state().arrows == {pressing}")
    page.close()
    with pytest.raises(mb.ModelError, match="lagmb.view: forces"):
        view(r, tmp_path / "x.html", forces="yes")


def _page_data(path):
    """The JSON the page draws from (its title, plots and their units)."""
    import json
    import re

    text = Path(path).read_text()
    return json.loads(re.search(r'<script type="application/json" id="lagmb-data">(.*?)</script>', text, re.S)[1])


def test_a_page_is_titled_by_its_model_and_an_effort_by_its_unit(tmp_path):
    """The page's title: the model's name (a scene file's, a robot's,
    Model(name=...)), else what the model is made of, never a bare "lagmb";
    an effort's plot is labelled N m for a driven angle and N for a driven
    slide (from what the driver drives), not "N or N m"."""
    r = mb.load_scene(EXAMPLES / "slider_crank.toml").run(t_end=0.2, n_out=11)
    view(r, tmp_path / "sc.html", outputs=["motor.effort"])
    data = _page_data(tmp_path / "sc.html")
    assert data["title"] == "slider_crank" and "<title>slider_crank</title>" in (tmp_path / "sc.html").read_text()
    assert data["plots"][0]["unit"] == "N m"
    unnamed = mb.simulate(pendulum(), 0.2, n_out=5)
    view(unnamed, tmp_path / "p.html")
    assert _page_data(tmp_path / "p.html")["title"] == "lagmb: 1 body, 1 joint"
    m = mb.Model(gravity=(0.0, -9.81), name="lift")
    block = m.add_body("block", 1.0, 0.1)
    m.add_translational("guide", m.ground, block, at=(0.0, 0.0), axis=(0.0, 1.0))
    m.drive_joint("jack", "guide", mb.Linear(0.1))
    view(mb.simulate(m, 0.2, n_out=5), tmp_path / "lift.html", outputs=["jack.effort"])
    data = _page_data(tmp_path / "lift.html")
    assert data["title"] == "lift" and data["plots"][0]["unit"] == "N"
    # the header says what the camera frames (every body over the whole run)
    assert data["lines"][-1] == f"framed: the whole motion, {data['size']:.2g} m across (drag to turn, scroll to zoom)"
    assert m.copy().name == "lift"


def test_a_conserved_energy_is_drawn_as_its_change_and_flat_to_round_off(chromium, tmp_path):
    """The energy's plot: E - E(t0), with a note giving E(t0) and the drift;
    a run that conserves energy to round-off (the explicit method on a
    pendulum: |E - E(t0)| ~ 1e-14 J) spans at least 1e-9 of the largest
    kinetic energy, so it is drawn flat, not as round-off steps across the
    whole plot (the UR5's "14.69 ... 14.69" staircase)."""
    r = mb.simulate(pendulum(), 1.0, n_out=101, method="projection-erk", rtol=1e-10, atol=1e-12)
    path = tmp_path / "energy.html"
    view(r, path, outputs=["energy"])
    plot = _page_data(path)["plots"][0]
    drift = float(np.max(np.abs(r.energy - r.energy[0])))
    assert plot["name"] == "energy" and plot["label"] == "energy change E - E(t0)" and plot["unit"] == "J"
    assert plot["note"].startswith(f"E(t0) = {r.energy[0]:.6g} J; drift max |E - E(t0)| = {drift:.2g} J")
    kinetic = 0.5 * 1.0 / 3.0 * np.max(r.body("rod").angular_velocity ** 2)  # J_pin w^2 / 2, J_pin = m L^2 / 3
    assert plot["scale"] == pytest.approx(kinetic, rel=1e-3)
    page, _ = open_page(chromium, path)
    lo, hi = page.evaluate("lagmbViewer.state().ranges")[0]
    assert hi - lo == pytest.approx(1e-9 * plot["scale"], rel=1e-6) and drift < 1e-3 * (hi - lo)
    assert "drift max |E - E(t0)|" in page.evaluate("document.querySelector('.plot .note').textContent")
    page.close()


def test_a_body_drawn_as_its_shapes_is_framed_by_them_not_by_its_inertia(tmp_path):
    """A body the page draws as its shapes (a robot link's mesh; here a
    0.2 m box) is framed by how far they reach, not by the box of its
    inertia (a URDF's inflated inertias made robots small in a large
    frame): the page's size follows the shape."""
    def model(inertia):
        m = mb.Model(dimension=3)
        b = m.add_body("b", 1.0, inertia, position=(0.0, 0.0, 0.0))
        m.add_shape(b, "box", (0.2, 0.2, 0.2), position=(0.0, 0.0, 0.0), role="visual")
        return m

    sizes = []
    for inertia in ((0.01, 0.01, 0.01), (10.0, 10.0, 10.0)):  # the second: a 9.5 m inertia box
        view(mb.simulate(model(inertia), 0.1, n_out=3), tmp_path / "b.html")
        sizes.append(_page_data(tmp_path / "b.html")["size"])
    # the centre widened by the box's reach (its half-diagonal r) along each axis: a cube of
    # side 2 r, whose diagonal the page's size is
    r = 0.5 * np.linalg.norm([0.2, 0.2, 0.2])
    assert sizes[0] == sizes[1] == pytest.approx(2.0 * r * math.sqrt(3.0))
