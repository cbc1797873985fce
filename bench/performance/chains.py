"""Many-link chains: how set-up and runs grow with the number of links.

The chain of bench/performance/chain.py (uniform rods, L = 1 m, m = 1 kg, J = 1/12 kg m^2,
pinned at the origin, released horizontal at rest, gravity 9.81 m/s^2). For
each N, in a fresh interpreter (so that its peak memory is its own):

- build: the add_body / add_revolute calls of the Python API;
- compile: the immutable Model (numbering, patterns, slots);
- assemble: consistent initial values (positions, velocities, accelerations
  and multipliers, with the redundancy check of a run's start);
- run: a simulation of --t-end seconds (default 0.1 s) at rtol 1e-6, atol
  1e-8 with the default method (left out above --run-max links);
- peak: the interpreter's peak resident memory (MiB).

Prints a table, fits the exponent p of time ~ N^p over N >= 1,000 for each
phase, and writes bench/results/chains_setup.json (and chains_setup.png with
matplotlib).

    python bench/performance/chains.py [--n 1000 2000 ...] [--t-end 0.1] [--run-max 100000]

What accuracy costs with each method on the same chain (N = 8 to 512) is
bench/accuracy/chains_accuracy.py.
"""

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.chain import chain  # noqa: E402  (the chain of bench/performance/chain.py)
from bench.common.paths import RESULTS  # noqa: E402

PHASES = ("build", "compile", "assemble", "run")


def measure(n, t_end, run):
    """One N in this interpreter: seconds per phase, steps, peak memory."""
    import resource

    import lagmb as mb

    out = {"n": n}
    t0 = time.perf_counter()
    m = chain(n)
    t1 = time.perf_counter()
    m.compiled()
    t2 = time.perf_counter()
    q, v, qdd, lam = m.assemble()
    t3 = time.perf_counter()
    out.update(build=t1 - t0, compile=t2 - t1, assemble=t3 - t2)
    if run:
        r = mb.simulate(m, t_end=t_end, rtol=1e-6, atol=1e-8, n_out=2)
        out.update(run=time.perf_counter() - t3, steps=r.stats["steps"],
                   max_residual=float(r.residual.max()), tip_y=float(r.q[-1, 3 * n - 2]))
    out["peak_mib"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return out


def fit_exponent(rows, phase):
    """Least-squares slope of log(time) against log(N) over N >= 1,000."""
    pts = [(math.log(r["n"]), math.log(r[phase])) for r in rows if r["n"] >= 1000 and r.get(phase, 0) > 0]
    if len(pts) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx


def plot(rows, path, t_end):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for phase in PHASES:
        pts = [(r["n"], r[phase]) for r in rows if phase in r]
        if pts:
            ax.loglog(*zip(*pts), "o-", label=phase)
    ns = [r["n"] for r in rows]
    ref = rows[-1]["build"] / ns[-1]
    ax.loglog(ns, [ref * x for x in ns], "k:", label="linear")
    ax.set_xlabel("links N")
    ax.set_ylabel("wall time (s)")
    ax.set_title(f"N-link chain: set-up, and a run of {t_end:g} s")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=[1000, 2000, 5000, 10000, 20000, 50000, 100000])
    p.add_argument("--t-end", type=float, default=0.1, help="simulated seconds of the run phase")
    p.add_argument("--run-max", type=int, default=100000, help="no run phase above this many links")
    p.add_argument("--out", default=os.path.join(RESULTS, "chains_setup.json"))
    p.add_argument("--worker", nargs=2, type=float, help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.worker:
        n, run = int(args.worker[0]), bool(args.worker[1])
        json.dump(measure(n, args.t_end, run), sys.stdout)
        return

    rows = []
    print(f"{'N':>7} {'build s':>8} {'compile s':>9} {'assemble s':>10} {'run s':>8} {'steps':>6} {'peak MiB':>9}")
    for n in args.n:
        cmd = [sys.executable, __file__, "--worker", str(n), str(int(n <= args.run_max)), "--t-end", str(args.t_end)]
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            raise SystemExit(f"N = {n} failed:\n{res.stderr}")
        r = json.loads(res.stdout)
        rows.append(r)
        run = f"{r['run']:8.2f} {r['steps']:6d}" if "run" in r else f"{'-':>8} {'-':>6}"
        print(f"{n:7d} {r['build']:8.2f} {r['compile']:9.3f} {r['assemble']:10.2f} {run} {r['peak_mib']:9.0f}",
              flush=True)
    exponents = {phase: fit_exponent(rows, phase) for phase in PHASES}
    print("time ~ N^p over N >= 1000: " + ", ".join(
        f"{phase} p = {e:.2f}" for phase, e in exponents.items() if e is not None))
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump({"machine": platform.platform(), "processor": platform.processor(), "t_end": args.t_end,
                   "rtol": 1e-6, "atol": 1e-8, "exponents": exponents, "rows": rows}, f, indent=1)
    try:
        plot(rows, os.path.splitext(args.out)[0] + ".png", args.t_end)
    except ImportError:
        pass


if __name__ == "__main__":
    main()
