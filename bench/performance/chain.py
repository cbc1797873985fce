"""The planar N-link pendulum chain: how the cost grows with N.

Uniform rods (L = 1 m, m = 1 kg, J = 1/12 kg m^2), pivot at the origin,
released from horizontal, gravity 9.81 m/s^2, 1 s of simulated time at
rtol 1e-6 (atol 1e-8). Prints a table and writes bench/results/chain.json.
The claim to check: time per step per body stays flat in N (no quadratic
term up to N = 1000).

    python bench/performance/chain.py [--n 1 2 4 ...] [--repeat 3] [--out FILE]
"""

import argparse
import json
import os
import platform
import sys
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.chain import chain  # noqa: E402
from bench.common.paths import RESULTS  # noqa: E402


def measure(n, repeat, rtol=1e-6, atol=1e-8, t_end=1.0):
    model = chain(n)
    best = None
    for _ in range(repeat):
        r = mb.simulate(model, t_end=t_end, rtol=rtol, atol=atol, n_out=2)
        if best is None or r.stats["wall_time"] < best.stats["wall_time"]:
            best = r
    s = best.stats
    return {
        "n": n,
        "coordinates": 3 * n,
        "unknowns": 10 * n,
        "wall_time": s["wall_time"],
        "steps": s["steps"],
        "residual_evals": s["residual_evals"],
        "jacobian_evals": s["jacobian_evals"],
        "lu_factorizations": s["lu_factorizations"],
        "error_test_failures": s["error_test_failures"],
        "convergence_failures": s["convergence_failures"],
        "time_per_step_per_body": s["wall_time"] / s["steps"] / n,
        "max_residual": float(best.residual.max()),
    }


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=[1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1000])
    p.add_argument("--repeat", type=int, default=3, help="runs per N; the fastest is kept")
    p.add_argument("--out", default=os.path.join(RESULTS, "chain.json"))
    args = p.parse_args()

    rows = []
    print(f"{'N':>5} {'wall (s)':>9} {'steps':>6} {'res.ev':>7} {'jac':>5} {'LU':>5} "
          f"{'us/step/body':>13} {'max|Phi|':>9}")
    for n in args.n:
        t0 = time.perf_counter()
        row = measure(n, args.repeat if n < 500 else 1)
        rows.append(row)
        print(f"{n:>5} {row['wall_time']:>9.4f} {row['steps']:>6} {row['residual_evals']:>7} "
              f"{row['jacobian_evals']:>5} {row['lu_factorizations']:>5} "
              f"{1e6 * row['time_per_step_per_body']:>13.2f} {row['max_residual']:>9.1e}", flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump({"benchmark": "chain", "rtol": 1e-6, "atol": 1e-8, "t_end": 1.0,
                   "machine": platform.platform(), "processor": platform.processor(),
                   "lagmb": mb.__version__, "sundials": mb.SUNDIALS_VERSION, "rows": rows}, f, indent=1)
    print(f"written {args.out}")


if __name__ == "__main__":
    main()
