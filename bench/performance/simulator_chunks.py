"""What driving a run from outside costs: one run against the same run
advanced in many chunks, and a controller loop that changes an input at
every chunk.

1. A 10-link chain (rods of 0.1 m, 0.1 kg, released from horizontal) for
   1 s, rtol 1e-8, GGL and the explicit method: simulate once, then a
   Simulator advanced in 1, 10, 100, 1,000 and 10,000 chunks. Each ends
   where simulate ends (the largest coordinate difference is printed); the
   steps and the time per run show what the chunks cost.
2. The cart-pole PD loop of examples/cart_pole.py for 10 s: an input change
   (an integrator restart) every 10, 5 or 1 ms; steps, restarts and time
   per sample.

Prints tables and writes bench/results/simulator_chunks.json.

    python bench/performance/simulator_chunks.py [--repeat 3]
"""

import argparse
import json
import os
import platform
import sys

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.paths import RESULTS  # noqa: E402
from bench.common.repo import cart_pole  # noqa: E402  (examples/cart_pole.py)
from bench.common.timing import best_of  # noqa: E402
from bench.performance.spatial_chain import planar_chain  # noqa: E402 - the chain of spatial_chain.py

METHODS = {"ggl": dict(formulation="ggl"), "projection-erk": dict(formulation="projection", integrator="erk")}


def chunks(repeat):
    model, rows = planar_chain(10), []
    for method, options in METHODS.items():
        options = dict(options, rtol=1e-8, atol=1e-10)
        wall, one = best_of(lambda: mb.simulate(model, t_end=1.0, n_out=2, **options), repeat)
        rows.append(dict(method=method, chunks="simulate", steps=one.stats["steps"], seconds=wall, difference=0.0))
        for n in (1, 10, 100, 1000, 10000):
            def run():
                sim = mb.Simulator(model, **options)
                for k in range(n):
                    sim.advance((k + 1) / n)
                return sim
            wall, sim = best_of(run, repeat)
            rows.append(dict(method=method, chunks=n, steps=sim.stats["steps"], seconds=wall,
                             difference=float(np.max(np.abs(sim.q - one.q[-1])))))
    return rows


def controller(repeat):
    rows = []
    for period in (0.01, 0.005, 0.001):
        def run():
            cart_pole.PERIOD = period
            return cart_pole.balance(cart_pole.cart_pole(), t_end=10.0, rtol=1e-6)
        wall, sim = best_of(run, repeat)
        samples = round(10.0 / period)
        rows.append(dict(period=period, samples=samples, steps=sim.stats["steps"], restarts=sim.stats["restarts"],
                         seconds=wall, us_per_sample=1e6 * wall / samples))
    cart_pole.PERIOD = 0.01
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per case; the fastest counts")
    args = parser.parse_args()
    a = chunks(args.repeat)
    print("10-link chain, 1 s, rtol 1e-8: one run against chunks")
    print(f"{'method':16} {'chunks':>9} {'steps':>7} {'time (s)':>9} {'|q - q_simulate|':>17}")
    for r in a:
        print(f"{r['method']:16} {r['chunks']!s:>9} {r['steps']:7d} {r['seconds']:9.4f} {r['difference']:17.2e}")
    b = controller(args.repeat)
    print("\ncart-pole PD loop, 10 s, rtol 1e-6: an input change every period")
    print(f"{'period (s)':>10} {'samples':>8} {'steps':>7} {'restarts':>9} {'time (s)':>9} {'us/sample':>10}")
    for r in b:
        print(f"{r['period']:10.3f} {r['samples']:8d} {r['steps']:7d} {r['restarts']:9d} {r['seconds']:9.3f} "
              f"{r['us_per_sample']:10.1f}")
    os.makedirs(RESULTS, exist_ok=True)
    with open(os.path.join(RESULTS, "simulator_chunks.json"), "w") as f:
        json.dump(dict(machine=platform.platform(), python=platform.python_version(), chunks=a, controller=b),
                  f, indent=1)


if __name__ == "__main__":
    main()
