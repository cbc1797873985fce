"""Cost of the singular passages of the N-four-bar (IFToMM A02) per method.

    python bench/accuracy/singular.py [N] [t_end]        (defaults 2, 10)

For each method: whether it reaches t_end, the time reached, steps, Newton
iterations, LU factorizations, wall time, the relative energy error, max
|Phi| and the B0 error against the one-coordinate SciPy reference
(examples/n_four_bar.py). Printed as a table and written to
bench/results/singular_N<N>.json; nothing is asserted.
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
from bench.common.repo import n_four_bar  # noqa: E402  (examples/n_four_bar.py: the model and its reference)

build, reference_b0 = n_four_bar.build, n_four_bar.reference_b0

METHODS = [
    ("ggl rtol 1e-6", dict(rtol=1e-6, atol=1e-8)),
    ("ggl rtol 1e-8", dict(rtol=1e-8, atol=1e-10)),
    ("projection rtol 1e-8", dict(formulation="projection", rtol=1e-8, atol=1e-10)),
    ("ali3p step 1e-3", dict(formulation="ali3p", step=1e-3)),
    ("ali3p step 2e-4", dict(formulation="ali3p", step=2e-4)),
    ("ali3p step 1e-4", dict(formulation="ali3p", step=1e-4)),
]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("n", type=int, nargs="?", default=2, help="four-bars in the chain")
    p.add_argument("t_end", type=float, nargs="?", default=10.0, help="simulated time (s)")
    args = p.parse_args()
    n, t_end = args.n, args.t_end
    print(f"N-four-bar (A02), N = {n}, t_end = {t_end} s")
    print(f"{'method':<22} {'t reached':>9} {'steps':>7} {'Newton':>7} {'LU':>7} {'wall s':>7} "
          f"{'dE/E':>9} {'max|Phi|':>9} {'B0 err':>9}")
    rows = []
    for label, kw in METHODS:
        t0 = time.perf_counter()
        try:
            r = mb.simulate(build(n), t_end=t_end, n_out=int(100 * t_end) + 1, **kw)
        except mb.SimulationError as e:
            r = e.result
        wall = time.perf_counter() - t0
        if r is None or len(r.t) < 2:
            print(f"{label:<22} failed at the start")
            rows.append({"method": label, "settings": kw, "t_reached": 0.0})
            continue
        b0 = r.point("crank0", (0.5, 0.0))
        de = np.abs(r.energy - r.energy[0]).max() / abs(r.energy[0])
        err = np.abs(b0 - reference_b0(n, r.t)).max()
        s = r.stats
        print(f"{label:<22} {r.t[-1]:>9.3f} {s['steps']:>7d} {s['newton_iterations']:>7d} "
              f"{s['lu_factorizations']:>7d} {wall:>7.2f} {de:>9.2e} {r.residual.max():>9.2e} {err:>9.2e}")
        rows.append({"method": label, "settings": kw, "t_reached": float(r.t[-1]), "steps": s["steps"],
                     "newton_iterations": s["newton_iterations"], "lu_factorizations": s["lu_factorizations"],
                     "wall_time_s": wall, "energy_error_relative": float(de),
                     "max_residual": float(r.residual.max()), "b0_error": float(err)})
    out = os.path.join(RESULTS, f"singular_N{n}.json")
    with open(out, "w") as f:
        json.dump({"problem": "IFToMM A02 N-four-bar", "N": n, "t_end": t_end, "rows": rows,
                   "machine": platform.machine(), "python": platform.python_version()}, f, indent=2)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
