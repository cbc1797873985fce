"""Every robot of example-robot-data as a new user meets it: loaded with
mb.load_urdf's defaults (limits, damping, mimic couplings on; fixed base)
and left to fall under gravity from its zero configuration.

For each URDF file (69 in example-robot-data 4.x), in a worker process of
its own (a time limit, so a hang is a row, not a stuck survey):

- load: "ok" or the exception's class and first line;
- run: mb.simulate(model, t_end) with the default options: "ok", or the
  exception's class and first line and the time it reached;
- the largest excursion of a joint beyond its limit over the outputs
  (rad or m; 0 when every limit held), from each stop's joint reading;
- wall time, steps, the events the run logged (impacts, captures,
  releases) and the counts of captures and releases.

Prints a table and the counts; writes bench/results/robot_survey.json and
robot_survey.md. Not a timing benchmark: the times only show where a run
is slow.

    python bench/robots/robot_survey.py [--t-end 2] [--timeout 300] [--robots a1,panda]
"""

import argparse
import glob
import json
import multiprocessing
import os
import sys
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.paths import RESULTS, robots_dir  # noqa: E402


def first_line(e, path=""):
    """The exception's class and first line (the file's folder left out)."""
    text = str(e).strip().splitlines()
    line = text[0] if text else ""
    if path:
        line = line.replace(os.path.dirname(path) + os.sep, "")
    return f"{type(e).__name__}: {line}"


def cell(text, width=160):
    text = str(text or "").replace("|", "/")
    return text if len(text) <= width else text[:width - 1] + "…"


def limit_excursion(model, result):
    """The largest distance (rad or m) any stop's joint went beyond its limit
    over the outputs. An angle is r.joint's, continuous from output to
    output, put by whole turns onto the joint's initial angle in the model
    (r.joint starts within pi of 0, so a joint built at 3.96 rad would read
    a turn lower)."""
    import numpy as np

    initial = {kw["name"]: kw.get("angle", 0.0) for kind, kw in model.elements}
    worst = 0.0
    for kind, stop in model.elements:
        if kind != "add_stop":
            continue
        reading = result.joint(stop["joint"])
        if hasattr(reading, "angle"):
            turns = np.round((initial[stop["joint"]] - reading.angle[0]) / (2 * np.pi))
            s = reading.angle + 2 * np.pi * turns
        else:
            s = reading.slide
        worst = max(worst, float((stop["lower"] - s).max()), float((s - stop["upper"]).max()))
    return worst


def survey_one(path, t_end, out):
    """In the worker: one robot's row, put on `out` (a queue)."""
    import warnings

    import lagmb as mb

    row = {"load": "ok", "run": None}
    warnings.simplefilter("ignore")
    try:
        model = mb.load_urdf(path)
    except Exception as e:  # noqa: BLE001 - every failure is a row of the survey
        row["load"] = first_line(e, path)
        out.put(row)
        return
    stops = [kw for kind, kw in model.elements if kind == "add_stop"]
    row["stops"] = len(stops)
    start = time.perf_counter()
    result = None
    try:
        result = mb.simulate(model, t_end=t_end)
        row["run"] = "ok"
        row["t_reached"] = t_end
    except mb.SimulationError as e:
        row["run"] = first_line(e, path)
        row["t_reached"] = e.t
        result = e.result
    except Exception as e:  # noqa: BLE001
        row["run"] = first_line(e, path)
    row["wall_time"] = time.perf_counter() - start
    if result is not None:
        row["steps"] = int(result.stats.get("steps", 0))
        row["events"] = len(result.events)
        row["captures"] = int(result.stats.get("captures", 0))
        row["releases"] = int(result.stats.get("releases", 0))
        try:
            row["limit_excursion"] = limit_excursion(model, result)
        except Exception as e:  # noqa: BLE001
            row["limit_excursion"] = first_line(e)
    out.put(row)


def survey(path, t_end, timeout):
    ctx = multiprocessing.get_context("spawn")
    out = ctx.Queue()
    worker = ctx.Process(target=survey_one, args=(path, t_end, out))
    worker.start()
    worker.join(timeout)
    if worker.is_alive():
        worker.kill()
        worker.join()
        return {"load": "?", "run": f"no answer within {timeout} s (killed)"}
    if out.empty():
        return {"load": "?", "run": f"the worker died (exit code {worker.exitcode})"}
    return out.get()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--t-end", type=float, default=2.0)
    parser.add_argument("--timeout", type=float, default=300.0)
    parser.add_argument("--robots", help="comma-separated parts of the file names to keep (default: all)")
    parser.add_argument("--out", default=os.path.join(RESULTS, "robot_survey"))
    args = parser.parse_args(argv)
    root = robots_dir()
    paths = sorted(glob.glob(os.path.join(root, "**", "*.urdf"), recursive=True))
    if args.robots:
        keep = args.robots.split(",")
        paths = [p for p in paths if any(k in os.path.relpath(p, root) for k in keep)]
    rows = {}
    for path in paths:
        name = os.path.relpath(path, root)
        rows[name] = row = survey(path, args.t_end, args.timeout)
        print(f"{name:60s} load {row['load'][:40]:40s} run {str(row['run'])[:70]}", flush=True)
    loaded = sum(r["load"] == "ok" for r in rows.values())
    ran = sum(r["run"] == "ok" for r in rows.values())
    held = sum(r["run"] == "ok" and isinstance(r.get("limit_excursion"), float) and r["limit_excursion"] <= 1e-8
               for r in rows.values())
    summary = {"files": len(rows), "loaded": loaded, "ran": ran, "ran_with_limits_held_to_1e-8": held,
               "t_end": args.t_end}
    print(f"{len(rows)} files: {loaded} load, {ran} run {args.t_end:g} s, {held} of those with every "
          f"limit held to 1e-8")
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out + ".json", "w") as f:
        json.dump({"summary": summary, "robots": rows}, f, indent=1)
    with open(args.out + ".md", "w") as f:
        f.write(f"# example-robot-data with mb.load_urdf's defaults, {args.t_end:g} s under gravity\n\n")
        f.write(f"{summary['files']} files: {loaded} load, {ran} run, {held} with every limit held to 1e-8 "
                "(bench/robots/robot_survey.py)\n\n| robot | load | run | excursion | steps | events | captures | releases | wall s |\n"
                "|---|---|---|---|---|---|---|---|---|\n")
        for name, r in rows.items():
            exc = r.get("limit_excursion")
            exc = f"{exc:.1e}" if isinstance(exc, float) else (exc or "")
            wall = f"{r['wall_time']:.2f}" if "wall_time" in r else ""
            f.write(f"| {name} | {cell(r['load'])} | {cell(r.get('run'))} | {exc} | {r.get('steps', '')} | "
                    f"{r.get('events', '')} | {r.get('captures', '')} | {r.get('releases', '')} | {wall} |\n")


if __name__ == "__main__":
    main()
