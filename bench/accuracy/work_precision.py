"""Work-precision diagrams: what each formulation and integrator pays for
accuracy, on five problems.

    python bench/accuracy/work_precision.py [--problems seed double ...] [--quick]

Problems: the seed pendulum (2 s), a double pendulum over a chaotic interval
(released from horizontal, 10 s), the slider-crank of examples/ (driven,
1 s), Andrews' squeezing mechanism (Hairer & Wanner's seven-body test, 0.03
s; needs examples/andrews.py), and a 32-link chain (1 s). Tolerances 1e-3
to 1e-11 (atol = 1e-2 rtol). For each problem: bench/results/wp_<name>.json
(the mb.work_precision table) and wp_<name>.png (error vs CPU time, drift vs
time), and a printed summary: for a target error, the cheapest method and
how much the others cost relative to it.
"""

import argparse
import json
import os
import sys

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.chain import chain as chain_model  # noqa: E402
from bench.common.paths import EXAMPLES, RESULTS  # noqa: E402


def chain(n, t_end):
    return chain_model(n), t_end


def problems():
    out = {
        "seed": lambda: (mb.load_scene(os.path.join(EXAMPLES, "seed_pendulum.toml")).model, 2.0),
        "double": lambda: chain(2, 10.0),
        "slider_crank": lambda: (mb.load_scene(os.path.join(EXAMPLES, "slider_crank.toml")).model, 1.0),
        "chain32": lambda: chain(32, 1.0),
    }
    try:
        from bench.common.repo import andrews_model

        out["andrews"] = lambda: (andrews_model(), 0.03)
    except ImportError:
        pass
    return out


def summarize(name, wp, target):
    best = wp.cheapest(target)
    reached = {m: t for m, t in best.items() if t is not None}
    if not reached:
        return f"{name}: no method reached {target:g}"
    fastest = min(reached, key=reached.get)
    parts = [f"{m} {t / reached[fastest]:.1f}x" for m, t in sorted(reached.items(), key=lambda kv: kv[1])]
    missing = [m for m, t in best.items() if t is None]
    s = f"{name}: error {target:g} cheapest with {fastest} ({1e3 * reached[fastest]:.1f} ms); " + ", ".join(parts)
    if missing:
        s += f"; not reached: {', '.join(missing)}"
    return s


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--problems", nargs="+", help="subset of: seed double slider_crank andrews chain32")
    p.add_argument("--quick", action="store_true", help="tolerances 1e-3..1e-7 only")
    p.add_argument("--targets", type=float, nargs="+", default=[1e-3, 1e-6],
                   help="errors for the summary (default 1e-3 1e-6)")
    args = p.parse_args()
    tols = [10.0 ** -k for k in range(3, 8 if args.quick else 12)]
    os.makedirs(RESULTS, exist_ok=True)
    summary = []
    for name, make in problems().items():
        if args.problems and name not in args.problems:
            continue
        model, t_end = make()
        print(f"== {name} (t_end = {t_end} s)", flush=True)
        wp = mb.work_precision(model, t_end, tolerances=tols,
                               progress=lambda i, n, r: print(f"  [{i}/{n}] {r['method']} {r['rtol']:.0e} "
                                                              f"{r['status']}", file=sys.stderr, flush=True))
        print(wp.table())
        wp.save(os.path.join(RESULTS, f"wp_{name}.json"))
        try:
            wp.plot(os.path.join(RESULTS, f"wp_{name}.png"), title=f"{name}: t = 0 .. {t_end:g} s")
        except ImportError:
            pass
        for target in args.targets:
            line = summarize(name, wp, target)
            summary.append(line)
            print(line, flush=True)
    with open(os.path.join(RESULTS, "wp_summary.json"), "w") as f:
        json.dump({"target_errors": args.targets, "tolerances": tols, "summary": summary}, f, indent=1)
    print("\n".join(["", "summary:"] + summary))


if __name__ == "__main__":
    main()
