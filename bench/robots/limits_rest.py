"""Robots resting on their limits against the same robots in free motion:
steps per simulated second (issue 41's target: at rest within 2 times free
motion).

For each arm of example-robot-data (its URDF read by mb.load_urdf with its
limits, damping and mimic couplings), three runs of --t-end seconds (default
5) with default options ("auto"), and again with formulation="ggl":

- rest: the arm with a viscous damper of 2 N m s/rad (N s/m) on every
  joint, built at rest in the pose where it rests on its limits (found
  beforehand: the same damped arm let fall onto its limits for 10 s, its
  final joint values given to load_urdf's positions; the followers of a
  mimic left to their leaders). The stops that held it close at t = 0 and
  hold it again; the other joints hang near their equilibrium (the light
  wrists still creep under the dampers: the rate at the end says how much).
- free: the same file with limits=False from its zero configuration: the
  arm falls and swings freely (no stop, no event); "free damped" with the
  dampers of the rest run.
- falling: the file with its limits from its zero configuration (load_urdf
  starts a joint whose limits exclude 0 at their middle): it falls onto its
  limits, impacts, captures and releases included.

Each row: steps, steps per simulated second, wall time (best of
--repeats), captures and releases, the largest joint rate at the end and
the largest excursion beyond a limit (rad or m, every output). Writes
bench/results/limits_rest.json and prints a table.

    python bench/robots/limits_rest.py [--robots panda,kinova,z1] [--t-end 5] [--repeats 3]
"""

import argparse
import json
import os
import platform
import sys
import time
import warnings

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.paths import RESULTS, robots_dir  # noqa: E402
from bench.common.timing import best_of  # noqa: E402
from bench.robots.robot_survey import limit_excursion  # noqa: E402

ARMS = {
    "panda": "panda_description/urdf/panda.urdf",
    "kinova": "kinova_description/robots/kinova.urdf",
    "z1": "z1_description/urdf/z1.urdf",
}
SETTLE_TIME = 10.0     # s of the damped fall that finds the resting pose
SETTLE_DAMPING = 2.0   # N m s/rad (N s/m) on every joint while settling


def load(path, **options):
    import lagmb as mb

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        return mb.load_urdf(path, **options)


def coordinate(result, joint):
    path = result.joint(joint)
    return path.angle if hasattr(path, "angle") else path.slide


def stops_of(model):
    return [kw for kind, kw in model.elements if kind == "add_stop"]


def with_dampers(model):
    """The model with a viscous damper of SETTLE_DAMPING on every joint."""
    import lagmb as mb

    for joint in mb.JointSpace(model).joints:
        model.add_joint_friction(f"{joint}_settling", joint=joint, viscous=SETTLE_DAMPING)
    return model


def resting_pose(path):
    """{joint: value} where the damped arm (with_dampers) rests on its limits
    after falling onto them for SETTLE_TIME, and the stops that hold it
    there. Followers of a mimic are left to their leaders."""
    import lagmb as mb

    model = with_dampers(load(path))
    r = mb.simulate(model, SETTLE_TIME)
    followers = {kw["joint"] for kind, kw in model.elements if kind == "add_joint_coupling"}
    pose = {joint: float(coordinate(r, joint)[-1]) for joint in mb.JointSpace(model).joints if joint not in followers}
    held = sorted(stop["name"] for stop in stops_of(model) if r.effort(stop["name"])[-1] != 0.0)
    return pose, held


def run(model, t_end, repeats, **options):
    import lagmb as mb

    wall, r = best_of(lambda: mb.simulate(model, t_end, **options), repeats)
    joints = mb.JointSpace(model).joints
    return {"steps": int(r.stats["steps"]), "steps_per_second": r.stats["steps"] / t_end, "wall_time": wall,
            "method": r.stats.get("method", r.stats.get("formulation")),
            "captures": int(r.stats.get("captures", 0)), "releases": int(r.stats.get("releases", 0)),
            "final_rate": max(float(abs(r.joint(joint).rate[-1])) for joint in joints),
            "limit_excursion": limit_excursion(model, r)}


def main(argv=None):
    import lagmb as mb

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default=",".join(ARMS))
    parser.add_argument("--t-end", type=float, default=5.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(RESULTS, "limits_rest.json"))
    args = parser.parse_args(argv)
    out = {"machine": platform.platform(), "lagmb": mb.__version__, "date": time.strftime("%Y-%m-%d"),
           "t_end": args.t_end, "robots": {}}
    print(f"{'robot':8s} {'formulation':11s} {'run':11s} {'method':15s} {'steps':>6s} {'steps/s':>8s} "
          f"{'wall s':>7s} {'capt.':>5s} {'rel.':>5s} {'rate end':>9s} {'excursion':>9s}")
    for name in args.robots.split(","):
        path = os.path.join(robots_dir(), ARMS[name])
        pose, held = resting_pose(path)
        models = {"rest": with_dampers(load(path, positions=pose)), "free": load(path, limits=False),
                  "free damped": with_dampers(load(path, limits=False)), "falling": load(path)}
        rows = {}
        for formulation in ("auto", "ggl"):
            for kind, model in models.items():
                row = run(model, args.t_end, args.repeats, formulation=formulation)
                rows[f"{formulation} {kind}"] = row
                print(f"{name:8s} {formulation:11s} {kind:11s} {row['method']:15s} {row['steps']:6d} "
                      f"{row['steps_per_second']:8.1f} {row['wall_time']:7.3f} {row['captures']:5d} "
                      f"{row['releases']:5d} {row['final_rate']:9.1e} {row['limit_excursion']:9.1e}", flush=True)
            ratio = rows[f"{formulation} rest"]["steps"] / rows[f"{formulation} free"]["steps"]
            print(f"{name:8s} {formulation:11s} rest / free steps = {ratio:.2f}")
        out["robots"][name] = {"file": ARMS[name], "pose": pose, "stops_holding": held, "runs": rows}
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
