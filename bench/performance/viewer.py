"""What lagmb.view's pages cost: file size, the time headless Chromium
takes to load one (navigate -> the viewer's first frame drawn), and how
fast it plays with software WebGL (frames advanced in 2 s of play), for
the slider-crank, the four-bar, the heavy top, a 1,000-link chain over 10 s
at 100 frames per second, and the Panda arm from its URDF (meshes). Saves a
screenshot of each in bench/results/viewer_<case>.png.

    python bench/performance/viewer.py [--quick]
"""

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from datetime import datetime
from pathlib import Path

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.paths import RESULTS, ROOT  # noqa: E402
from bench.common.record import git  # noqa: E402
from bench.common.repo import browser  # noqa: E402  (the tests' DevTools driver)

ROOT, RESULTS = Path(ROOT), Path(RESULTS)


def chain(n, length=10.0, tilt=0.1):
    """n uniform rods (1 kg each, length / n long) hanging from a pin,
    released tilt rad from the vertical (0.5 rad made the free end whip and
    the 10 s run take minutes)."""
    m = mb.Model(gravity=(0.0, -9.81))
    previous, joint = m.ground, np.zeros(2)
    a = -math.pi / 2 + tilt
    e = np.array([math.cos(a), math.sin(a)])
    h = length / n
    for i in range(n):
        rod = m.add_body(f"rod{i}", 1.0, h**2 / 12, position=tuple(joint + 0.5 * h * e), angle=a)
        m.add_revolute(f"pin{i}", previous, rod, at=tuple(joint))
        previous, joint = rod, joint + h * e
    return m


def cases(quick):
    out = []
    for name in ("slider_crank", "four_bar", "heavy_top"):
        scene = mb.load_scene(ROOT / "examples" / f"{name}.toml")
        out.append((name, lambda scene=scene: scene.run(t_end=2.0, n_out=201), None))
    n, t_end = (100, 2.0) if quick else (1000, 10.0)
    out.append((f"chain{n}", lambda: mb.simulate(chain(n), t_end, n_out=int(100 * t_end) + 1, method="ggl",
                                                  rtol=1e-3, atol=1e-5), ["energy", "rod0.angle"]))
    from bench.common.repo import panda

    urdf = panda.panda_urdf()
    if urdf:
        out.append(("panda", lambda: mb.simulate(panda.build(urdf), 2.0, n_out=201, method="projection-erk",
                                                 rtol=1e-6, atol=1e-8), ["energy"]))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a 100-link chain over 2 s; nothing written")
    args = parser.parse_args()
    binary = browser.find()
    if binary is None:
        sys.exit("no headless Chromium: apt-get install chromium-headless-shell")
    results = []
    b = browser.Browser(binary, width=1100, height=640)
    try:
        with tempfile.TemporaryDirectory() as tmp:
            for name, run, outputs in cases(args.quick):
                t0 = time.perf_counter()
                r = run()
                simulated = time.perf_counter() - t0
                path = Path(tmp) / f"{name}.html"
                t0 = time.perf_counter()
                v = mb.view(r, path, outputs=outputs, title=name)
                written = time.perf_counter() - t0
                page = b.open("about:blank")
                t0 = time.perf_counter()
                page.command("Page.navigate", {"url": path.as_uri()})
                page.wait_for("window.lagmbViewer && window.lagmbViewer.state().ready", timeout=300)
                load = time.perf_counter() - t0
                state = page.evaluate("lagmbViewer.state()")
                page.evaluate("lagmbViewer.play()")
                renders0 = state["renders"]
                time.sleep(2.0)
                played = page.evaluate("lagmbViewer.state()")
                page.evaluate("lagmbViewer.pause()")
                page.evaluate(f"lagmbViewer.setFrame({state['frames'] // 2})")
                page.wait_for(f"lagmbViewer.state().renders > {played['renders'] + 2}")
                shot = RESULTS / f"viewer_{name}.png"
                if not args.quick:
                    page.screenshot(shot)
                page.close()
                row = dict(case=name, bodies=state["bodies"], frames=state["frames"], size_mb=v.size / 1e6,
                           simulate_s=simulated, write_s=written, load_s=load,
                           rendered_fps=(played["renders"] - renders0) / 2.0, played_time_s=played["time"])
                results.append(row)
                print(f"{name:14s} {row['bodies']:5d} bodies {row['frames']:5d} frames  {row['size_mb']:7.2f} MB  "
                      f"write {written:6.2f} s  load {load:6.2f} s  {row['rendered_fps']:5.1f} renders/s "
                      f"(software WebGL)", flush=True)
    finally:
        b.close()
    if args.quick:
        return
    commit = git("rev-parse", "--short", "HEAD")
    version = subprocess.run([binary, "--version"], capture_output=True, text=True).stdout.strip()
    out = dict(date=datetime.now().isoformat(timespec="minutes"), commit=commit, machine=platform.platform(),
               cpus=os.cpu_count(), load=os.getloadavg(), browser=version, results=results)
    (RESULTS / "viewer.json").write_text(json.dumps(out, indent=1))
    print("written: bench/results/viewer.json and the screenshots bench/results/viewer_*.png")


if __name__ == "__main__":
    main()
