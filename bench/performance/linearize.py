"""Linearization, equilibrium and vibration modes of a hanging chain: how
the cost grows with the number of links N.

The chain: N uniform rods, 100 m long in all (rods of 100/N m, 1 kg/m,
inertia m l^2 / 12), planar, pinned to the ground at the origin and each
to the next by a revolute; gravity 9.81 m/s^2. It is built straight but
tilted 0.5 rad from the vertical, so that mb.equilibrium's Newton has to
find the hanging equilibrium (7 iterations at every N here).

    (a) mb.linearize(chain, at=eq) about the hanging equilibrium
        (N = 10, 25, 50, 100, 200): dense (numpy: the null space of Phi_q
        by an SVD, the augmented system solved dense, O(n^3) in the n = 3N
        coordinates); beside it the dense mb.modes(chain, at=eq) (every mode)
    (b) mb.equilibrium(chain, stability=False) (N = 10 ... 200, 500, 1000):
        sparse Newton from the tilted start
    (c) mb.modes(chain, at=eq, count=10) (N = 100, 250, 500, 1000): the
        sparse path (shift-invert Lanczos on a sparse LU of
        [[K - sigma M, Phi_q^T], [Phi_q, 0]]); the lowest two frequencies
        against the continuous hanging chain, omega_k = (j_{0,k} / 2)
        sqrt(g / L) (j_{0,k} the zeros of J0; Bernoulli, Rayleigh)
    (d) the dense mb.modes (every mode) of the N = 500 and 1000 chains, one
        run each (above 600 coordinates mb.modes takes the sparse path on
        its own: lagmb.linear.SPARSE_ABOVE is raised here to force the dense
        one), and how far its 10 lowest frequencies are from (c)'s

Each call is timed --repeats times (the model compiled and the equilibrium
found beforehand, SciPy imported by a first untimed call); min and median
are reported, as the machine is shared and noisy. BLAS runs on one thread
(OPENBLAS_NUM_THREADS etc. set to 1 unless already set, as in
bench/peers/spatial_peers.py): on the shared 2-core machine, busy with a
compilation, threaded OpenBLAS made dense calls up to 50 times slower (a
400 x 400 eigvals 5.2 s against 0.08 s on one thread).

    python bench/performance/linearize.py [--repeats 5] [--quick] [--dense-n 500 1000] [--out FILE]

Prints markdown tables and writes bench/results/linearize.json (with the
git commit and date); --quick (N up to 100 for (a) and (b), 100 and 250 for
(c), 2 repeats, no (d)) writes nothing unless --out is given.
"""

import argparse
import math
import os
import sys

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.record import one_blas_thread  # noqa: E402

one_blas_thread()

import numpy as np  # noqa: E402

import lagmb as mb  # noqa: E402
from bench.common.paths import RESULTS  # noqa: E402
from bench.common.record import changed, load_average, stamp, stamp_line, write_json  # noqa: E402
from bench.common.timing import wall_times  # noqa: E402

LENGTH, DENSITY, G, TILT = 100.0, 1.0, 9.81, 0.5
LINEARIZE_N = [10, 25, 50, 100, 200]
EQUILIBRIUM_N = LINEARIZE_N + [500, 1000]
MODES_N = [100, 250, 500, 1000]
COUNT = 10


def chain(n, length=LENGTH, tilt=TILT):
    """n uniform rods (length / n each, DENSITY kg/m) pinned end to end from
    the origin, built along a straight line tilt rad from hanging."""
    m = mb.Model(gravity=(0.0, -G))
    l, mass = length / n, DENSITY * length / n
    down = np.array([math.sin(tilt), -math.cos(tilt)])
    previous = m.ground
    for k in range(n):
        rod = m.add_body(f"rod{k}", mass, mass * l**2 / 12, position=tuple((k + 0.5) * l * down),
                         angle=-math.pi / 2 + tilt)
        m.add_revolute(f"pin{k}", previous, rod, at=tuple(k * l * down))
        previous = rod
    return m


def continuous_chain(count, length=LENGTH):
    """omega_k (rad/s) of the continuous hanging chain, k = 1 .. count."""
    from scipy.special import jn_zeros

    return jn_zeros(0, count) / 2 * math.sqrt(G / length)


def timed(call, repeats):
    """(min, median) wall seconds of `repeats` calls, and the last result."""
    times, result = wall_times(call, repeats)
    return float(np.min(times)), float(np.median(times)), result


def hanging(model):
    eq = mb.equilibrium(model, stability=False)
    angles = eq.q[2::3]
    assert np.abs(angles + math.pi / 2).max() < 1e-9, "the chain does not hang straight down"
    return eq


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    p.add_argument("--repeats", type=int, default=None, help="calls timed per case (default 5, --quick 2)")
    p.add_argument("--quick", action="store_true", help="small chains only; writes nothing unless --out")
    p.add_argument("--dense-n", type=int, nargs="*", default=None,
                   help="chains for (d), the dense modes timed once (default 500 1000; none with --quick)")
    p.add_argument("--out", default=None, help="the JSON written (default bench/results/linearize.json)")
    args = p.parse_args()
    repeats = args.repeats or (2 if args.quick else 5)
    small = lambda ns, top: [n for n in ns if n <= top] if args.quick else ns  # noqa: E731
    lin_n, eq_n, modes_n = small(LINEARIZE_N, 100), small(EQUILIBRIUM_N, 100), small(MODES_N, 250)
    load_start = load_average()
    out = {**stamp("linearize", bool(changed("python/lagmb/linear.py", "python/lagmb/statics.py"))),
           "numpy": np.__version__, "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS"),
           "repeats": repeats, "chain": dict(length=LENGTH, density=DENSITY, g=G, tilt=TILT),
           "linearize": [], "equilibrium": [], "modes": [], "dense_modes": []}
    import scipy

    out["scipy"] = scipy.__version__

    print(f"(a) mb.linearize about the hanging equilibrium (dense), and dense mb.modes; best of {repeats}\n")
    print("| N | coordinates | linearize min (s) | median (s) | dense modes min (s) | median (s) |")
    print("|---:|---:|---:|---:|---:|---:|")
    for n in lin_n:
        model = chain(n)
        eq = hanging(model)
        lmin, lmed, lin = timed(lambda: mb.linearize(model, at=eq), repeats)
        mmin, mmed, modes = timed(lambda: mb.modes(model, at=eq), repeats)
        assert lin.A.shape == (2 * n, 2 * n) and len(modes) == n
        out["linearize"].append(dict(n=n, coordinates=3 * n, min=lmin, median=lmed, dense_modes_min=mmin,
                                     dense_modes_median=mmed, lowest_omega=float(modes.omega[0])))
        print(f"| {n} | {3 * n} | {lmin:.4f} | {lmed:.4f} | {mmin:.4f} | {mmed:.4f} |", flush=True)

    print(f"\n(b) mb.equilibrium(stability=False) from the chain tilted {TILT} rad; best of {repeats}\n")
    print("| N | coordinates | Newton iterations | min (s) | median (s) |")
    print("|---:|---:|---:|---:|---:|")
    for n in eq_n:
        model = chain(n)
        model.compiled()
        emin, emed, eq = timed(lambda: mb.equilibrium(model, stability=False), repeats)
        out["equilibrium"].append(dict(n=n, coordinates=3 * n, iterations=eq.iterations, min=emin, median=emed,
                                       force_residual=eq.force_residual))
        print(f"| {n} | {3 * n} | {eq.iterations} | {emin:.4f} | {emed:.4f} |", flush=True)

    exact = continuous_chain(2)
    print(f"\n(c) mb.modes(count={COUNT}) (sparse) against the continuous chain: f1 = {exact[0] / (2 * math.pi):.6f} Hz, "
          f"f2 = {exact[1] / (2 * math.pi):.6f} Hz; best of {repeats}\n")
    print("| N | coordinates | min (s) | median (s) | f1 (Hz) | f1 / exact - 1 | f2 (Hz) | f2 / exact - 1 |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    mb.modes(chain(10), count=1)  # SciPy imported outside the timing
    for n in modes_n:
        model = chain(n)
        eq = hanging(model)
        smin, smed, modes = timed(lambda: mb.modes(model, at=eq, count=COUNT), repeats)
        error = modes.omega[:2] / exact - 1
        out["modes"].append(dict(n=n, coordinates=3 * n, count=COUNT, min=smin, median=smed,
                                 frequencies=modes.frequencies.tolist(), kinds=modes.kinds,
                                 relative_error_f1=float(error[0]), relative_error_f2=float(error[1])))
        print(f"| {n} | {3 * n} | {smin:.4f} | {smed:.4f} | {modes.frequencies[0]:.6f} | {error[0]:.2e} | "
              f"{modes.frequencies[1]:.6f} | {error[1]:.2e} |", flush=True)

    dense_n = args.dense_n if args.dense_n is not None else ([] if args.quick else [500, 1000])
    if dense_n:
        from lagmb import linear

        print("\n(d) the dense mb.modes (every mode), one run, against (c)'s sparse count=10\n")
        print("| N | coordinates | dense (s) | sparse count=10, min (s) | largest relative difference of the 10 lowest |")
        print("|---:|---:|---:|---:|---:|")
        sparse_times = {row["n"]: row["min"] for row in out["modes"]}
        above, linear.SPARSE_ABOVE = linear.SPARSE_ABOVE, 10**9
        try:
            for n in dense_n:
                model = chain(n)
                eq = hanging(model)
                seconds, _, dense = timed(lambda: mb.modes(model, at=eq), 1)
                sparse = mb.modes(model, at=eq, count=COUNT)
                difference = float(np.abs(sparse.omega / dense.omega[:COUNT] - 1).max())
                out["dense_modes"].append(dict(n=n, coordinates=3 * n, seconds=seconds, modes=len(dense),
                                               sparse_min=sparse_times.get(n), largest_relative_difference=difference))
                shown = f"{sparse_times[n]:.4f}" if n in sparse_times else "-"
                print(f"| {n} | {3 * n} | {seconds:.2f} | {shown} | {difference:.1e} |", flush=True)
        finally:
            linear.SPARSE_ABOVE = above

    out["load_average_1min"] = [load_start, load_average()]
    print(f"\n{stamp_line(out, out['load_average_1min'])}, BLAS threads {out['blas_threads']}")
    write_json(args.out or (None if args.quick else os.path.join(RESULTS, "linearize.json")), out)


if __name__ == "__main__":
    sys.exit(main())
