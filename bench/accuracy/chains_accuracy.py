"""Many-link chains: what accuracy costs with each method, N = 8 .. 512.

The chain of bench/common/chain.py over 1 s. For each N, every variable-step
method of lagmb.METHODS runs at rtol 1e-2 .. 1e-11 (atol = 1e-2 rtol); its
error is the tip rod's centre at t = 1 s against the minimal-coordinate
reference of tests/references.py (RodChain: Lagrange's equations in
absolute angles, DOP853 at rtol = atol = 1e-12). Wall times are the fastest
of --repeat runs. For each method and target error (1e-6, 1e-8) the time to
reach it is interpolated log-log between the two runs around it, as in a
work-precision diagram.

Prints a table, writes bench/results/chains_accuracy.json and, with
matplotlib, chains_accuracy.png (error against time, one panel per N).

    python bench/accuracy/chains_accuracy.py [--n 8 32 128 512] [--repeat 3]
"""

import argparse
import json
import math
import os
import platform
import sys
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.chain import chain  # noqa: E402
from bench.common.paths import RESULTS  # noqa: E402
from bench.common.repo import RodChain  # noqa: E402
from bench.common.time_to import time_to  # noqa: E402

TARGETS = (1e-6, 1e-8)
RTOLS = tuple(10.0 ** -k for k in range(2, 12))


def tip_reference(n):
    """The tip rod's centre at t = 1 s from the minimal-coordinate reference."""
    ref = RodChain(n)
    theta, _ = ref.solve([0.0, 1.0])
    return ref.centres(theta[1])[0, -1]


def sweep(n, method, options, tip, repeat):
    model = chain(n)
    model.compiled()
    rows = []
    for rtol in RTOLS:
        best = None
        for _ in range(repeat):
            t0 = time.perf_counter()
            try:
                r = mb.simulate(model, t_end=1.0, rtol=rtol, atol=1e-2 * rtol, n_out=2, **options)
            except mb.SimulationError as e:
                best = {"rtol": rtol, "status": "failed", "message": str(e).splitlines()[0][:200]}
                break
            wall = time.perf_counter() - t0
            if best is None or wall < best["time"]:
                err = float(max(abs(r.q[-1, 3 * n - 3] - tip[0]), abs(r.q[-1, 3 * n - 2] - tip[1])))
                best = {"rtol": rtol, "status": "ok", "time": wall, "error": err, "steps": r.stats["steps"],
                        "residual_evals": r.stats["residual_evals"]}
        rows.append(best)
    return rows


def plot(results, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ns = sorted({r["n"] for r in results})
    fig, axes = plt.subplots(1, len(ns), figsize=(4.2 * len(ns), 4.0), squeeze=False)
    for ax, n in zip(axes[0], ns):
        for r in results:
            if r["n"] != n:
                continue
            pts = [(row["time"], row["error"]) for row in r["runs"] if row["status"] == "ok"]
            if pts:
                ax.loglog(*zip(*pts), "o-", ms=3, label=r["method"])
        for target in TARGETS:
            ax.axhline(target, color="k", lw=0.5, ls=":")
        ax.set_title(f"N = {n}")
        ax.set_xlabel("wall time (s)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("tip error at t = 1 s (m)")
    axes[0][-1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=[8, 32, 128, 512])
    p.add_argument("--repeat", type=int, default=3, help="runs per tolerance; the fastest is kept")
    p.add_argument("--out", default=os.path.join(RESULTS, "chains_accuracy.json"))
    args = p.parse_args()
    methods = {m["name"]: mb.METHODS[m["name"]] for m in mb.methods() if not m["fixed_step"]}
    results = []
    print(f"{'N':>4} {'method':<18} " + " ".join(f"{'t(' + format(t, 'g') + ') s':>12}" for t in TARGETS))
    for n in args.n:
        tip = tip_reference(n)
        for name, options in methods.items():
            rows = sweep(n, name, options, tip, args.repeat)
            reach = {f"{t:g}": time_to(rows, t) for t in TARGETS}
            results.append({"n": n, "method": name, "time_to": reach, "runs": rows})
            print(f"{n:4d} {name:<18} " + " ".join(
                f"{v:12.4f}" if v is not None else f"{'-':>12}" for v in reach.values()), flush=True)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump({"machine": platform.platform(), "targets": TARGETS, "rtols": RTOLS, "repeat": args.repeat,
                   "results": results}, f, indent=1)
    try:
        plot(results, os.path.splitext(args.out)[0] + ".png")
    except ImportError:
        pass


if __name__ == "__main__":
    main()
