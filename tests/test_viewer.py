"""lagmb.view: one self-contained HTML page per run, opened from disk in a
real headless Chromium with the network off. The page's test hook
(window.lagmbViewer) says how many bodies it drew and where playback is;
pressing play moves time on, the slider and a click on a plot move it
where asked; a screenshot shows the bodies (pixels that differ from the
white background where the view is). Skipped with the reason where no
Chromium is installed (scripts/setup.sh installs chromium-headless-shell)."""

import math
import time
from pathlib import Path

import numpy as np
import pytest

import lagmb as mb
from lagmb.viewer import view

import browser

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


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
    shot = tmp_path / f"{case}.png"
    page.wait_for(f"lagmbViewer.state().renders > {clicked['renders'] + 2}")
    page.screenshot(shot)
    view_box = page.evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect(); "
                             "return [r.left, r.top, r.right, r.bottom]; })()")
    assert drawn_pixels(shot, [int(x) for x in view_box]) > 2000  # the bodies and the grid, not a blank canvas
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
    import subprocess
    import sys

    def lagmb(*args):
        return subprocess.run([sys.executable, "-m", "lagmb", *map(str, args)], capture_output=True, text=True)

    page = tmp_path / "out" / "four_bar.html"
    done = lagmb("run", EXAMPLES / "four_bar.toml", "--t-end", "0.5", "--html", page)
    assert done.returncode == 0, done.stderr
    assert "interactive view written to" in done.stdout and page.is_file()
    assert "WebGLRenderer" in page.read_text() and "four_bar.toml" in page.read_text()
    bad = lagmb("run", EXAMPLES / "four_bar.toml", "--html", tmp_path / "four_bar.txt")
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
    shot = tmp_path / "panda.png"
    page.wait_for(f"lagmbViewer.state().renders > {state['renders'] + 2}")
    page.screenshot(shot)
    box = page.evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect(); "
                        "return [r.left, r.top, r.right, r.bottom]; })()")
    assert drawn_pixels(shot, [int(x) for x in box]) > 2000
    page.close()
