"""What one right-hand side of the spatial projection formulation costs:
the revolute chains of bench/peers/spatial_peers.py (N = 32, 128) and the
Franka Panda of bench/robots/robots.py (example-robot-data's URDF, limits,
damping and mimic off: 9 bodies, 63 coordinates), each integrated for 1 s
by projection-erk at rtol 1e-8 (atol 1e-10), from rest in its built pose
(the Panda with the rates of robots.py: uniform in [-1, 1] rad/s, seed 1);
beside them the planar chain of bench/common/chain.py (N = 32, 128: the
plane's side of the same code, which must not get slower).

Per case: the wall time of the run (median of --repeat), its right-hand
sides (residual_evals), projections and steps, and the wall time per
right-hand side (all of the run's time divided by its right-hand sides:
the projections' and the stepper's share included; `perf record` on
--perf splits it). --dump writes the final q, v and lam of each case (for
comparing two builds to rounding).

    python bench/performance/spatial_rhs.py [--cases chain32 chain128 panda planar32 planar128] [--repeat 5]
        [--dump FILE.npz] [--json]

Run it under two builds in turn (PYTHONPATH=<a copy of the other build's
installed lagmb>) to compare them in one session (docs/benchmarks.md,
"Where the time goes").
"""

import argparse
import json
import os
import statistics
import sys
import time

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.chain import chain  # noqa: E402
from bench.common.paths import robots_dir  # noqa: E402
from bench.peers.spatial_engines import lagmb_chain  # noqa: E402

METHOD = dict(formulation="projection", integrator="erk")
RTOL, ATOL = 1e-8, 1e-10


def panda():
    model = mb.load_urdf(os.path.join(robots_dir(), "panda_description/urdf/panda.urdf"), limits=False,
                         dynamics=False, mimic=False)
    js = mb.JointSpace(model)
    rng = np.random.default_rng(1)
    return js.with_rates({name: rng.uniform(-1.0, 1.0) for name in js.joints})


def cases(names):
    make = {"chain8": lambda: lagmb_chain(8), "chain32": lambda: lagmb_chain(32),
            "chain128": lambda: lagmb_chain(128), "panda": panda,
            "planar32": lambda: chain(32), "planar128": lambda: chain(128)}
    return {name: make[name]() for name in names}


def run(model):
    t0 = time.perf_counter()
    r = mb.simulate(model, 1.0, rtol=RTOL, atol=ATOL, n_out=2, **METHOD)
    return time.perf_counter() - t0, r


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", nargs="+", default=["chain32", "chain128", "panda"])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--dump", help="write the final q, v, lam of each case to this .npz")
    parser.add_argument("--json", action="store_true", help="print one JSON line instead of a table")
    args = parser.parse_args(argv)
    models = cases(args.cases)
    for m in models.values():
        m.compiled()
    walls = {name: [] for name in models}
    last = {}
    for k in range(args.repeat):  # interleaved: every case once per round
        for name, m in models.items():
            wall, last[name] = run(m)
            walls[name].append(wall)
    out = {}
    for name, r in last.items():
        s = r.stats
        wall = statistics.median(walls[name])
        out[name] = {"wall_s": wall, "walls_s": walls[name], "residual_evals": int(s["residual_evals"]),
                     "projections": int(s["projections"]), "steps": int(s["steps"]),
                     "us_per_rhs": 1e6 * wall / int(s["residual_evals"]), "n": int(r.q.shape[1])}
    if args.dump:
        np.savez(args.dump, **{f"{name}_{key}": getattr(r, key)[-1] for name, r in last.items()
                               for key in ("q", "v", "lam")})
    if args.json:
        print(json.dumps(out))
        return
    print("| case | n | wall (ms) | right-hand sides | projections | steps | microseconds / right-hand side |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name, o in out.items():
        print(f"| {name} | {o['n']} | {1e3 * o['wall_s']:.2f} | {o['residual_evals']} | {o['projections']} | "
              f"{o['steps']} | {o['us_per_rhs']:.1f} |")


if __name__ == "__main__":
    main()
