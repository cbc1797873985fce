"""Two builds of lagmb side by side: is a change within noise?

Runs the 100-link chain (bench/performance/chain.py's model, 1 s, rtol 1e-6; GGL and the
explicit method), the 100-link spatial chain (tests/elements/test_spatial.py's, 0.1 s,
the same two methods) and the work-precision set (bench/accuracy/work_precision.py's problems, every method of
lagmb.accuracy.METHODS at rtol 1e-6, atol 1e-8) with each build in turn,
each in a fresh interpreter, alternating builds round by round so that the
machine's load falls on both alike. Each build is a directory holding a
`lagmb` package (e.g. `pip install --target DIR .` of a checkout).

Prints, per case, the fastest wall time of each build, their ratio
(new / base) and whether the deterministic counts (steps, residual
evaluations, LU factorizations) agree; writes bench/results/ab.json.

    python bench/performance/ab.py BASE_DIR NEW_DIR [--rounds 5] [--out FILE]
"""

import argparse
import json
import math
import os
import subprocess
import sys

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.paths import RESULTS  # noqa: E402  (lagmb is imported by the worker only)

COUNTS = ("steps", "residual_evals", "lu_factorizations")


def worker():
    """One round in this interpreter: every case once; JSON on stdout."""
    # an editable install's finder comes before PYTHONPATH: drop it, so that
    # the build under test is the one imported (checked below)
    sys.meta_path[:] = [f for f in sys.meta_path if "editable" not in type(f).__module__.lower()]
    from bench.common.chain import chain
    from bench.common.repo import spatial_chain
    from bench.accuracy import work_precision as wp_bench
    import lagmb as mb
    if not os.path.abspath(mb.__file__).startswith(os.environ["PYTHONPATH"]):
        raise SystemExit(f"imported {mb.__file__}, not the build in {os.environ['PYTHONPATH']}")
    from lagmb.accuracy import METHODS

    out = {}

    def record(case, model, t_end, **options):
        try:
            r = mb.simulate(model, t_end=t_end, rtol=1e-6, atol=1e-8, n_out=2, **options)
        except mb.SimulationError as e:  # the same failure in both builds is still a match
            out[case] = {"failed": str(e).splitlines()[0]}
            return
        out[case] = {"wall_time": r.stats["wall_time"], **{k: r.stats[k] for k in COUNTS}}

    erk = dict(formulation="projection", integrator="erk")
    record("chain100", chain(100), 1.0)
    record("chain100/erk", chain(100), 1.0, **erk)
    record("spatial_chain100", spatial_chain(100), 0.1)
    record("spatial_chain100/erk", spatial_chain(100), 0.1, **erk)
    for name, make in wp_bench.problems().items():
        model, t_end = make()
        for method, options in METHODS.items():
            record(f"{name}/{method}", model, t_end, **options)
    json.dump(out, sys.stdout)


def run_round(build):
    env = dict(os.environ, PYTHONPATH=os.path.abspath(build))
    p = subprocess.run([sys.executable, __file__, "--worker"], env=env, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"the worker with {build} failed:\n{p.stderr}")
    return json.loads(p.stdout)


def main():
    if "--worker" in sys.argv:
        return worker()
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("base")
    p.add_argument("new")
    p.add_argument("--rounds", type=int, default=5, help="runs of every case per build; the fastest is kept")
    p.add_argument("--out", default=os.path.join(RESULTS, "ab.json"))
    args = p.parse_args()

    best = {"base": {}, "new": {}}
    for k in range(args.rounds):
        for label, build in (("base", args.base), ("new", args.new)):
            print(f"round {k + 1}/{args.rounds}: {label}", file=sys.stderr, flush=True)
            for case, row in run_round(build).items():
                kept = best[label].get(case)
                if kept is None or row.get("wall_time", math.inf) < kept.get("wall_time", math.inf):
                    best[label][case] = row

    rows, ratios = [], []
    print(f"{'case':<36} {'base ms':>9} {'new ms':>9} {'new/base':>9}  counts")
    for case, b in best["base"].items():
        n = best["new"].get(case, {})
        if "failed" in b or "failed" in n:
            same = b.get("failed") == n.get("failed")
            rows.append({"case": case, "base": b, "new": n, "counts_equal": same})
            print(f"{case:<36} {'failed in ' + ('both' if same else 'one'):>30}")
            continue
        ratio = n["wall_time"] / b["wall_time"]
        ratios.append(ratio)
        same = all(b[c] == n[c] for c in COUNTS)
        rows.append({"case": case, "base": b, "new": n, "ratio": ratio, "counts_equal": same})
        print(f"{case:<36} {1e3 * b['wall_time']:>9.2f} {1e3 * n['wall_time']:>9.2f} {ratio:>9.3f}  "
              f"{'equal' if same else 'DIFFER'}")
    geo = math.exp(sum(map(math.log, ratios)) / len(ratios))
    print(f"geometric mean new/base over {len(ratios)} cases: {geo:.3f} "
          f"(min {min(ratios):.3f}, max {max(ratios):.3f})")
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump({"base": os.path.abspath(args.base), "new": os.path.abspath(args.new), "rounds": args.rounds,
                   "geometric_mean_ratio": geo, "cases": rows}, f, indent=1)


if __name__ == "__main__":
    main()
