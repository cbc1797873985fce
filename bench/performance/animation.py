"""What a 300-frame GIF of lagmb.plotting.animate costs to draw, before and
after a change of plotting.py.

Two runs, each drawn into 300 frames at the default size (640 x 480):
- planar: examples/double_pendulum.toml run for 12 s (1201 outputs);
- spatial: examples/heavy_top.toml (2 s, spinning at 100 rad/s), 301 outputs.

The plotting module is lagmb.plotting as imported (the installed lagmb:
install this tree, or put a copy of it first on PYTHONPATH), and with
``--before REV`` also the plotting.py of that git revision, loaded beside it
(its relative imports read the imported lagmb; a revision from before issue
40, which made lagmb.plotting a package). A revision whose animate
has no ``speed`` is asked for max_frames=300 (its frames were outputs); one
with ``speed`` for 300 frames at 25 frames/s (the planar run in real time,
the spatial one at 1/6 speed). The runs themselves are not timed.

Then, with the drawing of the imported plotting.py, what each part of its
way of writing frames buys (``--no-stages`` leaves this out): every frame
redrawn whole and grabbed by matplotlib's PillowWriter (the old way); redrawn
whole but Agg's buffer handed to Pillow on one palette; only the moving
artists drawn over a copy of the fixed part (blitting) with Pillow making a
palette for each frame; blitting on one palette (what animate does).

Prints tables and writes bench/results/animation.json and animation.md.

    python bench/performance/animation.py [--before REV] [--repeat 1] [--keep DIR] [--no-stages]
"""

import argparse
import datetime
import importlib.util
import inspect
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.paths import EXAMPLES, RESULTS, ROOT  # noqa: E402
from bench.common.record import changed, git, load_average  # noqa: E402

FRAMES = 300


def runs():
    """{case: Result}: the planar and the spatial run."""
    planar = mb.load_scene(os.path.join(EXAMPLES, "double_pendulum.toml")).run(t_end=12.0, n_out=1201)
    spatial = mb.load_scene(os.path.join(EXAMPLES, "heavy_top.toml")).run(n_out=301)
    return {"planar (double pendulum, 12 s)": planar, "spatial (heavy top, 2 s)": spatial}


def plotting_of(rev):
    """The plotting module of a git revision, loaded as lagmb._plotting_<rev>."""
    source = subprocess.run(["git", "show", f"{rev}:python/lagmb/plotting.py"], cwd=ROOT, check=True,
                            capture_output=True, text=True).stdout
    folder = tempfile.mkdtemp(prefix="lagmb-bench-")
    path = os.path.join(folder, "plotting.py")
    with open(path, "w", encoding="utf-8") as f:
        f.write(source)
    name = f"lagmb._plotting_{rev.replace('~', '_').replace('^', '_')}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def gif_facts(path):
    from PIL import Image

    with Image.open(path) as im:
        durations = []
        for k in range(im.n_frames):
            im.seek(k)
            durations.append(im.info.get("duration", 0))
    return {"frames": len(durations), "gif_seconds": sum(durations) / 1000.0,
            "kilobytes": round(os.path.getsize(path) / 1024.0, 1)}


def time_animate(plotting, r, path, repeat):
    """(best wall seconds, GIF facts) for FRAMES frames of r."""
    span = float(r.t[-1] - r.t[0])
    if "speed" in inspect.signature(plotting.animate).parameters:
        kwargs = dict(fps=25, speed=span * 25 / FRAMES, progress=False)
    else:
        kwargs = dict(max_frames=FRAMES)
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        plotting.animate(r, path, **kwargs)
        best = min(best, time.perf_counter() - start)
    return best, gif_facts(path), kwargs


def _drawing(plotting, r):
    """(drawing, durations) of FRAMES frames of r by the imported lagmb.plotting
    (a package since issue 40: its frames, planar and spatial modules)."""
    from lagmb._drawing import Scene
    from lagmb.plotting import frames, planar, spatial

    span = float(r.t[-1] - r.t[0])
    speed = span * 25 / FRAMES
    times, durations = frames._frame_plan(r.t, 25, speed, FRAMES)
    shown = frames._resample(r, times)
    scene = Scene(r)
    if scene.dimension == 3:
        return spatial._spatial_drawing(scene, shown, [], (640, 480), 100, (20.0, -70.0), speed), durations
    return planar._planar_drawing(scene, shown, [], (640, 480), 100, speed), durations


def _redrawn_pillowwriter(drawing, durations, path):
    from matplotlib.animation import PillowWriter

    writer = PillowWriter(fps=25)
    with writer.saving(drawing.fig, path, 100):
        for k in range(len(durations)):
            drawing.update(k)
            writer.grab_frame()


def _pictures(drawing, n, blit):
    """Frame k's RGB image, for k < n: the whole figure drawn, or blitted."""
    from PIL import Image

    fig, canvas = drawing.fig, drawing.fig.canvas
    if blit:
        for art in drawing.animated:
            art.set_animated(True)
        canvas.draw()
        background = canvas.copy_from_bbox(fig.bbox)
    for k in range(n):
        drawing.update(k)
        if blit:
            canvas.restore_region(background)
            for art in drawing.animated:
                fig.draw_artist(art)
        else:
            canvas.draw()
        width, height = canvas.get_width_height(physical=True)
        yield Image.frombuffer("RGBA", (width, height), canvas.buffer_rgba(), "raw", "RGBA", 0, 1).convert("RGB")


def _on_one_palette(pictures, durations, path):
    from PIL import Image

    pictures = list(pictures)
    palette = pictures[0].quantize(colors=255, method=Image.Quantize.MEDIANCUT)
    frames = [p.quantize(palette=palette, dither=Image.Dither.NONE) for p in pictures]
    frames[0].save(path, save_all=True, append_images=frames[1:], duration=list(durations), loop=0)


def _redrawn_one_palette(drawing, durations, path):
    _on_one_palette(_pictures(drawing, len(durations), blit=False), durations, path)


def _blitted_palette_each(drawing, durations, path):
    pictures = list(_pictures(drawing, len(durations), blit=True))  # Pillow quantizes each (adaptive)
    pictures[0].save(path, save_all=True, append_images=pictures[1:], duration=list(durations), loop=0)


def _blitted_one_palette(drawing, durations, path):
    from lagmb.plotting import frames

    frames._write_gif(drawing, path, durations)


STAGES = {"redrawn, PillowWriter (the old way)": _redrawn_pillowwriter,
          "redrawn, Agg buffer to Pillow, one palette": _redrawn_one_palette,
          "blitted, Agg buffer to Pillow, a palette per frame": _blitted_palette_each,
          "blitted, Agg buffer to Pillow, one palette (animate)": _blitted_one_palette}


def stages(plotting, results, folder):
    rows = []
    for case, r in results.items():
        for label, write in STAGES.items():
            path = os.path.join(folder, f"stage-{case.split()[0]}-{len(rows) % len(STAGES)}.gif")
            start = time.perf_counter()
            drawing, durations = _drawing(plotting, r)  # a fresh figure each time, its making timed too
            write(drawing, durations, path)
            seconds = time.perf_counter() - start
            facts = gif_facts(path)
            rows.append({"case": case, "writing": label, "seconds": round(seconds, 2),
                         "ms_per_frame": round(1e3 * seconds / facts["frames"], 1), **facts})
            print(f"{case:32s} {label:52s} {seconds:7.2f} s  {rows[-1]['ms_per_frame']:6.1f} ms/frame  "
                  f"{facts['kilobytes']:.0f} kB", flush=True)
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", metavar="REV", help="also time the plotting.py of this git revision")
    parser.add_argument("--repeat", type=int, default=1, help="best of this many (default 1)")
    parser.add_argument("--keep", metavar="DIR", help="keep the GIFs in this folder")
    parser.add_argument("--no-write", action="store_true", help="print only")
    parser.add_argument("--no-stages", action="store_true", help="leave out the parts of the way of writing")
    args = parser.parse_args()

    from lagmb import plotting

    load_start = load_average()
    versions = []
    if args.before:
        versions.append((f"before ({args.before})", plotting_of(args.before)))
    head = git("rev-parse", "--short", "HEAD")
    dirty = changed("python/lagmb/plotting")
    versions.append((f"now ({head}{' + changes' if dirty else ''})", plotting))
    folder = args.keep or tempfile.mkdtemp(prefix="lagmb-gifs-")
    os.makedirs(folder, exist_ok=True)
    rows = []
    results = runs()
    for case, r in results.items():
        for label, module in versions:
            path = os.path.join(folder, f"{case.split()[0]}-{label.split()[0]}.gif")
            seconds, facts, kwargs = time_animate(module, r, path, args.repeat)
            row = {"case": case, "plotting": label, "seconds": round(seconds, 2),
                   "ms_per_frame": round(1e3 * seconds / facts["frames"], 1),
                   "call": ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                                     for k, v in kwargs.items()), **facts}
            rows.append(row)
            print(f"{case:32s} {label:28s} {row['seconds']:7.2f} s  {row['ms_per_frame']:6.1f} ms/frame  "
                  f"{facts['frames']} frames, plays {facts['gif_seconds']:.2f} s, {facts['kilobytes']:.0f} kB",
                  flush=True)
    stage_rows = [] if args.no_stages else stages(plotting, results, folder)
    print(f"GIFs in {folder}")
    if args.no_write:
        return
    load = load_average()
    out = {"date": datetime.date.today().isoformat(), "machine": platform.platform(),
           "python": platform.python_version(), "cpus": os.cpu_count(),
           "load_average_1min_at_start": load_start, "load_average_1min_at_end": load, "repeat": args.repeat, "rows": rows, "stages": stage_rows}
    os.makedirs(RESULTS, exist_ok=True)
    with open(os.path.join(RESULTS, "animation.json"), "w", encoding="utf-8") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    lines = [f"# Drawing a {FRAMES}-frame GIF (bench/performance/animation.py)", "",
             f"{out['date']}, {out['machine']}, Python {out['python']}, {out['cpus']} CPUs, "
             f"load average {load_start:.2f} at the start, {load:.2f} at the end; best of {args.repeat} "
             "(the parts below: one run each).", "",
             "| run | plotting.py | call | wall (s) | ms/frame | frames | plays (s) | kB |",
             "|---|---|---|---:|---:|---:|---:|---:|"]
    lines += [f"| {r['case']} | {r['plotting']} | {r['call']} | {r['seconds']:.2f} | {r['ms_per_frame']:.1f} | "
              f"{r['frames']} | {r['gif_seconds']:.2f} | {r['kilobytes']:.0f} |" for r in rows]
    if stage_rows:
        lines += ["", "What each part of the way of writing frames buys (the drawing of the imported plotting.py, "
                  "made and written; one run each):", "",
                  "| run | frames written | wall (s) | ms/frame | kB |", "|---|---|---:|---:|---:|"]
        lines += [f"| {r['case']} | {r['writing']} | {r['seconds']:.2f} | {r['ms_per_frame']:.1f} | "
                  f"{r['kilobytes']:.0f} |" for r in stage_rows]
    with open(os.path.join(RESULTS, "animation.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print(f"written: {os.path.join(RESULTS, 'animation.json')}, animation.md")


if __name__ == "__main__":
    main()
