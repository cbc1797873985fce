"""The default method, formulation="auto", against every variable-step
method it could have chosen, side by side in one run.

    python bench/accuracy/auto_method.py [--repeats 3] [--cases chain32 stiff8 ...]

Cases (the issue's list): the planar chain of N = 32 and 512 rods (1 s,
bench/performance/chain.py), the stiff 8-rod chain (the chain with a rotational
spring-damper at every inner joint, k and c of bench/peers/reference.py:
fastest mode 1e4 times the slowest, critically damped), the driven
slider-crank (examples/, a kinematic analysis whatever the method), the
bouncing ball (examples/, Hunt-Crossley contact), the heavy top
(examples/, spatial, 100 rad/s, 2 s). For each: a reference run (the
explicit method at rtol 1e-11, atol 1e-13, the 512-chain at 1e-10; GGL's
difference from it recorded; GGL where the explicit method refuses a
contact), then every method at rtol 1e-4 ..
1e-10 (half decades, atol = 1e-2 rtol), 11 outputs; the error is the
largest |q - q_ref| over the outputs. Runs are timed in --repeats rounds,
each round every method's every run once (the order reversed every other
round), fastest kept. The time to an error of 1e-6 and 1e-8 is
interpolated log-log (bench/common/time_to.py); "auto / best" is auto's time over
the fastest method's. Writes bench/results/auto_method.json and prints a
markdown table.
"""

import argparse
import json
import os
import sys
import time

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.chain import chain, stiff_chain as chain_with_dampers  # noqa: E402
from bench.common.paths import EXAMPLES, RESULTS  # noqa: E402
from bench.common.time_to import time_to  # noqa: E402

STIFF8 = (4302034.334948224, 634.4098641722912)  # bench/peers/reference.py stiff_parameters(8): k, c


def stiff_chain():
    return chain_with_dampers(8, *STIFF8)


def scene(name):
    return mb.load_scene(os.path.join(EXAMPLES, name + ".toml")).model


CASES = {
    "chain32": (lambda: chain(32), 1.0, 1e-11),
    "chain512": (lambda: chain(512), 1.0, 1e-10),
    "stiff8": (stiff_chain, 1.0, 1e-11),
    "slider_crank": (lambda: scene("slider_crank"), 1.0, 1e-11),
    "bouncing_ball": (lambda: scene("bouncing_ball"), 2.0, 1e-11),
    "heavy_top": (lambda: scene("heavy_top"), 2.0, 1e-11),
}
METHODS = {"auto": dict(formulation="auto"), "ggl": dict(formulation="ggl"),
           "projection-erk": dict(formulation="projection", integrator="erk"),
           "projection-bdf": dict(formulation="projection", integrator="bdf")}
RTOLS = [10.0 ** (-k / 2) for k in range(8, 21)]  # 1e-4 .. 1e-10
TARGETS = (1e-6, 1e-8)


def run(model, t_end, rtol, options):
    t0 = time.perf_counter()
    r = mb.simulate(model, t_end, rtol=rtol, atol=1e-2 * rtol, n_out=11, **options)
    return time.perf_counter() - t0, r


def reference_run(model, t_end, tol):
    """The reference: the explicit method at `tol` (eighth order: GGL's BDF
    at 1e-11 is 1.4e-7 off on the 100 rad/s heavy top), cross-checked
    against GGL at the same tol; GGL where the explicit method refuses the
    model (contact)."""
    def at(**options):
        return mb.simulate(model, t_end, rtol=tol, atol=1e-2 * tol, n_out=11, **options)

    ggl = at(formulation="ggl")
    try:
        erk = at(formulation="projection", integrator="erk")
    except (mb.SimulationError, mb.ModelError) as e:
        return ggl, {"method": "ggl", "rtol": tol, "why": f"projection-erk refused: {str(e)[:120]}"}
    return erk, {"method": "projection-erk", "rtol": tol, "ggl_difference": float(np.abs(erk.q - ggl.q).max())}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--cases", nargs="+", default=list(CASES))
    args = p.parse_args()
    out = {"benchmark": "auto_method", "targets": TARGETS, "cases": {}}
    print("| case | auto chose | best method at 1e-6 | auto / best at 1e-6 | best at 1e-8 | auto / best at 1e-8 |")
    print("|---|---|---|---:|---|---:|")
    for name in args.cases:
        make, t_end, ref_tol = CASES[name]
        model = make()
        ref, reference = reference_run(model, t_end, ref_tol)
        rows = {m: [dict(rtol=rt, status="?", time=float("inf"), error=None) for rt in RTOLS] for m in METHODS}
        choice = None
        for round_ in range(args.repeats):
            order = list(METHODS) if round_ % 2 == 0 else list(reversed(METHODS))
            for k, rtol in enumerate(RTOLS):
                for method in order:
                    row = rows[method][k]
                    if row["status"] == "failed":
                        continue
                    try:
                        dt, r = run(model, t_end, rtol, METHODS[method])
                    except (mb.SimulationError, mb.ModelError) as e:  # (ERK refuses a contact)
                        row.update(status="failed", why=str(e)[:160])
                        continue
                    err = float(np.abs(r.q - ref.q).max())
                    row.update(status="ok", error=err, time=min(row["time"], dt), steps=r.stats["steps"])
                    if method == "auto":
                        choice = r.stats["method_choice"]
        summary = {}
        for target in TARGETS:
            times = {m: time_to(rows[m], target) for m in METHODS}
            others = {m: t for m, t in times.items() if m != "auto" and t is not None}
            best = min(others, key=others.get) if others else None
            ratio = times["auto"] / others[best] if best and times["auto"] else None
            summary[target] = dict(times=times, best=best, auto_over_best=ratio)
        out["cases"][name] = dict(t_end=t_end, choice=choice, reference=reference, rows=rows,
                                  summary={str(k): v for k, v in summary.items()})

        def cell(target):
            s = summary[target]
            if s["best"] is None:
                return "none reached", ""
            ratio = f"{s['auto_over_best']:.2f}" if s["auto_over_best"] else "not reached"
            return f"{s['best']} ({s['times'][s['best']] * 1e3:.2f} ms)", ratio

        b6, r6 = cell(1e-6)
        b8, r8 = cell(1e-8)
        chose = (choice or "").split(",")[0].replace("auto: ", "")
        print(f"| {name} | {chose} | {b6} | {r6} | {b8} | {r8} |", flush=True)
    with open(os.path.join(RESULTS, "auto_method.json"), "w") as f:
        json.dump(out, f, indent=1, default=str)


if __name__ == "__main__":
    main()
