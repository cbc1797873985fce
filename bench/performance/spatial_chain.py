"""The spatial N-link chain: how the cost grows with N, and what space costs
against the plane.

N uniform rods (L = 0.1 m, m = 0.1 kg), a spherical joint at the ground and
universal joints between them (the spatial chain of tests/elements/test_spatial.py),
released from horizontal under gravity; 0.1 s at rtol 1e-6 (atol 1e-8) with
GGL and with the explicit method. Beside each, the same N as a planar chain
(revolutes; bench/performance/chain.py's geometry scaled alike), so the ratio is
measured in one run on the same machine. Prints a table and writes
bench/results/spatial_chain.json. The claim to check: time per step per
body stays flat in N (linear cost) up to N = 1,000 and beyond.

    python bench/performance/spatial_chain.py [--n 10 100 1000 ...] [--repeat 3]
"""

import argparse
import json
import os
import platform
import sys
import time

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.paths import RESULTS  # noqa: E402
from bench.common.repo import spatial_chain  # noqa: E402 - the chain the tests check

METHODS = {"ggl": dict(formulation="ggl"), "projection-erk": dict(formulation="projection", integrator="erk")}


def planar_chain(n, link=0.1):
    m = mb.Model(gravity=(0.0, -9.81))
    previous = m.ground
    for k in range(n):
        rod = m.add_body(f"l{k}", 0.1, 0.1 * link**2 / 12, ((k + 0.5) * link, 0.0))
        m.add_revolute(f"j{k}", previous, rod, at=(k * link, 0.0))
        previous = rod
    return m


def measure(model, n, method, repeat, t_end=0.1):
    best = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = mb.simulate(model, t_end, rtol=1e-6, atol=1e-8, n_out=2, **METHODS[method])
        wall = time.perf_counter() - t0
        if best is None or wall < best[0]:
            best = (wall, r)
    wall, r = best
    return {"wall_time": wall, "steps": r.stats["steps"], "residual_evals": r.stats["residual_evals"],
            "us_per_step_per_body": 1e6 * wall / max(r.stats["steps"], 1) / n,
            "max_residual": float(np.max(r.residual))}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=[10, 100, 1000, 10000])
    p.add_argument("--repeat", type=int, default=3, help="runs per case; the fastest is kept")
    p.add_argument("--out", default=os.path.join(RESULTS, "spatial_chain.json"))
    args = p.parse_args()
    rows = []
    print(f"{'N':>6} {'method':>15} {'spatial s':>10} {'steps':>6} {'us/step/body':>13} "
          f"{'planar s':>9} {'us/step/body':>13} {'ratio':>6}")
    for n in args.n:
        t0 = time.perf_counter()
        spatial, planar = spatial_chain(n), planar_chain(n)
        spatial.compiled(), planar.compiled()
        build = time.perf_counter() - t0
        for method in METHODS:
            repeat = args.repeat if n <= 1000 else 1
            s, q = measure(spatial, n, method, repeat), measure(planar, n, method, repeat)
            ratio = s["us_per_step_per_body"] / q["us_per_step_per_body"]
            rows.append({"n": n, "method": method, "build_and_compile_s": build, "spatial": s, "planar": q,
                         "ratio_per_step_per_body": ratio})
            print(f"{n:>6} {method:>15} {s['wall_time']:>10.3f} {s['steps']:>6} {s['us_per_step_per_body']:>13.2f} "
                  f"{q['wall_time']:>9.3f} {q['us_per_step_per_body']:>13.2f} {ratio:>6.1f}", flush=True)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as fh:
        json.dump({"machine": platform.platform(), "python": platform.python_version(), "rows": rows}, fh, indent=1)
    print(f"written {args.out}")


if __name__ == "__main__":
    main()
