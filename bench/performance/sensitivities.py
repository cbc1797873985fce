"""Forward sensitivities (simulate(..., sensitivities=[...]), issue 28)
against what a user would do without them: central finite differences,
2k extra whole runs for k parameters.

Two models, each run with method="ggl" at rtol 1e-8 (atol 1e-10), 101
outputs:

    slider_crank  examples/slider_crank.toml, 0.5 s. It is fully driven:
                  simulate runs a dynamic analysis when sensitivities are
                  asked (checked here), so the plain and the finite-difference
                  runs are given analysis="dynamic" to be the same run (the
                  default for this model, a kinematic analysis, is timed
                  beside them and recorded too)
    chain32       32 uniform rods (1 m, 1 kg, J = 1/12 kg m^2) pinned end to
                  end from the origin, released at rest along a straight
                  line tilted 1 rad from hanging, gravity 9.81, 1 s

For k = 1, 4, 16 (the first k names of the case's PARAMETERS list):

    plain   one run without sensitivities
    sens    the run with k sensitivities (IDAS, staggered corrector)
    FD      the 2k runs of central differences a user would run instead, at
            the same rtol/atol, parameters={name: p +- 1e-4 |p|} (1e-4 if
            p = 0); the sum over the first k names of each repeat's per-run
            times

and the ratios sens / plain, sens / (plain + FD) (below 1: the
sensitivities are cheaper than the differences) and the cost per extra
sensitivity in plain runs, (sens - plain) / k / plain (central differences
cost 2 plain runs per parameter), each of the min times and of the median
times. Wall time is time.perf_counter() around
mb.simulate (what a caller pays, the Result built); the core's own
stats["wall_time"] is recorded too. Each variant is timed in --repeats
rounds, interleaved within a round (the order reversed every other round),
after one untimed call of each; a run shorter than 50 ms is called
repeatedly in each sample (inner calls, the mean kept) so that the clock
and scheduling noise stay small. Min and median over rounds are reported:
the machine is shared (2 cores, other jobs compiling).

Accuracy, for one parameter per model (CHECK): the max over the history of
|dq/dp - FD(q)| / max |FD(q)|, where FD is the central difference of runs at
rtol 1e-12 (step 1e-4 |p|: its own error about 1e-8), for the sensitivity
run at rtol 1e-12 and for the timed one at rtol 1e-8; beside them the same
for the finite difference a user would take at the timed rtol 1e-8 (whose
error is about rtol / step = 1e-4), and the timed sensitivity against the
rtol-1e-12 one. The reference FD's own noise, about 1e-12 |q| / step
(|q| up to 32 m in the chain), bounds what the first two columns can show.
atol is 1e-12 in the rtol-1e-12 runs:
at atol 1e-14 (tests/analyses/test_sensitivities.py's) the 32-rod chain fails at
t = 0 with or without sensitivities (the floor the error message names is
1.1e-12 there) and the slider-crank's sensitivity run fails (its F_p, a
difference of the residual, is good to about 1e-12 of its scale); that
sensitivity run at atol 1e-14 is tried and its outcome recorded.

    python bench/performance/sensitivities.py [--repeats 7] [--quick] [--cases slider_crank chain32] [--out FILE]

Prints a markdown table and writes bench/results/sensitivities.json (with
the git commit and date); --quick (2 repeats, k = 1 and 4) writes nothing
unless --out is given. A failed run is recorded with its message, not
skipped silently. BLAS on one thread (set unless already set).
"""

import argparse
import math
import os
import sys
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.record import one_blas_thread  # noqa: E402

one_blas_thread()

import numpy as np  # noqa: E402

import lagmb as mb  # noqa: E402
from bench.common.paths import EXAMPLES, RESULTS  # noqa: E402
from bench.common.record import changed, load_average, stamp, stamp_line, write_json  # noqa: E402

RTOL, ATOL, N_OUT = 1e-8, 1e-10, 101
REF_RTOL, REF_ATOL = 1e-12, 1e-12
PROBE_ATOL = 1e-14  # the sensitivity run is also tried at this atol, its failure recorded
REL_STEP = 1e-4
KS = [1, 4, 16]
MIN_SAMPLE = 0.05  # s: shorter runs are called repeatedly per sample


def chain(n, tilt=1.0):
    """n uniform rods (1 m, 1 kg) pinned end to end from the origin, along a
    straight line tilt rad from hanging, at rest."""
    m = mb.Model(gravity=(0.0, -9.81))
    down = np.array([math.sin(tilt), -math.cos(tilt)])
    previous = m.ground
    for k in range(n):
        rod = m.add_body(f"rod{k}", 1.0, 1.0 / 12.0, position=tuple((k + 0.5) * down), angle=-math.pi / 2 + tilt)
        m.add_revolute(f"pin{k}", previous, rod, at=tuple(k * down))
        previous = rod
    return m


def slider_crank():
    return mb.load_scene(os.path.join(EXAMPLES, "slider_crank.toml")).model


CASES = {
    "slider_crank": dict(
        make=slider_crank, t_end=0.5, run=dict(analysis="dynamic"), check="B.at.y",
        # masses and inertias move only the reactions and the motor torque
        # (the drivers prescribe the motion); joint points move everything
        params=["B.at.y", "rod.mass", "crank.mass", "slider.mass",
                "crank.inertia", "rod.inertia", "slider.inertia", "B.at.x",
                "C.at.x", "C.at.y", "O.at.x", "O.at.y",
                "guide.at.x", "guide.at.y", "guide.axis.y", "rod.angle.start"]),
    "chain32": dict(
        make=lambda: chain(32), t_end=1.0, run={}, check="rod0.mass",
        params=["rod0.mass", "rod31.mass", "rod16.inertia", "rod8.angle.start",
                "rod4.mass", "rod12.mass", "rod20.mass", "rod28.mass",
                "rod0.inertia", "rod8.inertia", "rod24.inertia", "rod31.inertia",
                "rod0.angle.start", "rod16.angle.start", "rod24.angle.start", "rod31.angle.start"]),
}
STATS = ("steps", "residual_evals", "jacobian_evals", "lu_factorizations", "newton_iterations",
         "error_test_failures", "convergence_failures", "element_evaluations", "wall_time")


def step_of(p):
    return REL_STEP * abs(p) if p else REL_STEP


def settings(case, rtol=RTOL, atol=ATOL, **extra):
    s = dict(rtol=rtol, atol=atol, n_out=N_OUT, method="ggl")
    s.update(case["run"])
    s.update(extra)
    return s


def fd_q(model, case, name, rtol, atol):
    """Central difference of q over two whole runs."""
    p = model.parameters[name]
    h = step_of(p)
    run = settings(case, rtol, atol)
    plus = mb.simulate(model, case["t_end"], parameters={name: p + h}, **run)
    minus = mb.simulate(model, case["t_end"], parameters={name: p - h}, **run)
    return (plus.q - minus.q) / (2 * h)


def relative(actual, expected):
    scale = float(np.abs(expected).max())
    return float(np.abs(actual - expected).max() / scale) if scale > 0 else None


def measure(name, case, ks, repeats):
    model = case["make"]()
    model.compiled()
    values = model.parameters
    params = case["params"][:max(ks)]
    assert len(set(params)) == len(params) and all(p in values for p in params), params
    t_end = case["t_end"]
    plain_run = settings(case)
    sens_run = settings(case)
    sens_run.pop("analysis", None)  # simulate chooses the dynamic analysis itself

    # the variants: a label and a call returning a Result
    variants = {"plain": lambda: mb.simulate(model, t_end, **plain_run)}
    if case["run"].get("analysis"):  # the model's default analysis (kinematic for the slider-crank)
        default_run = dict(plain_run)
        default_run.pop("analysis")
        variants["plain_default_analysis"] = lambda: mb.simulate(model, t_end, **default_run)
    for k in ks:
        variants[f"sens{k}"] = (lambda names: lambda: mb.simulate(model, t_end, sensitivities=names, **sens_run))(
            params[:k])
    for p in params:
        for sign in (+1, -1):
            value = values[p] + sign * step_of(values[p])
            variants[f"fd {p} {sign:+d}"] = (lambda p, value: lambda: mb.simulate(
                model, t_end, parameters={p: value}, **plain_run))(p, value)

    failures, results = {}, {}
    for label, call in variants.items():  # untimed: the first call of each
        try:
            results[label] = call()
        except (mb.SimulationError, mb.ModelError) as e:
            failures[label] = f"{type(e).__name__}: {e}"
    first = time.perf_counter()
    variants["plain"]()
    inner = max(1, math.ceil(MIN_SAMPLE / (time.perf_counter() - first)))

    times = {label: [] for label in variants if label not in failures}
    core = {label: [] for label in times}
    for round_ in range(repeats):
        order = list(times) if round_ % 2 == 0 else list(reversed(times))
        for label in order:
            t0 = time.perf_counter()
            for _ in range(inner):
                r = variants[label]()
            times[label].append((time.perf_counter() - t0) / inner)
            core[label].append(r.stats["wall_time"])
            results[label] = r

    def summary(samples):
        return dict(min=float(np.min(samples)), median=float(np.median(samples)))

    def ratios(f, *samples):
        return dict(min=float(f(*(np.min(x) for x in samples))), median=float(f(*(np.median(x) for x in samples))))

    plain = np.array(times["plain"])
    row = dict(case=name, t_end=t_end, inner_calls=inner, parameters=params, failures=failures,
               plain=dict(summary(plain), core_wall_time_min=float(np.min(core["plain"])),
                          stats={s: results["plain"].stats[s] for s in STATS},
                          analysis=results["plain"].stats["analysis"]),
               ks=[])
    if "plain_default_analysis" in times:
        r = results["plain_default_analysis"]
        row["plain_default_analysis"] = dict(summary(times["plain_default_analysis"]), analysis=r.stats["analysis"],
                                             formulation=r.stats["formulation"])
    for k in ks:
        label = f"sens{k}"
        fd_labels = [f"fd {p} {s:+d}" for p in params[:k] for s in (+1, -1)]
        entry = dict(k=k, parameters=params[:k])
        if label in failures or any(f in failures for f in fd_labels):
            entry["failed"] = {x: failures[x] for x in [label] + fd_labels if x in failures}
            row["ks"].append(entry)
            continue
        sens = np.array(times[label])
        fd = np.sum([times[f] for f in fd_labels], axis=0)  # per round
        r = results[label]
        entry.update(
            sens=dict(summary(sens), core_wall_time_min=float(np.min(core[label])),
                      stats={s: r.stats[s] for s in STATS}, analysis=r.stats["analysis"],
                      method_choice=r.stats["method_choice"]),
            fd=dict(summary(fd), runs=2 * k),
            # of the mins, and of the medians
            sens_over_plain=ratios(lambda s, p, f: s / p, sens, plain, fd),
            sens_over_plain_plus_fd=ratios(lambda s, p, f: s / (p + f), sens, plain, fd),
            extra_per_sensitivity_in_plain_runs=ratios(lambda s, p, f: (s - p) / k / p, sens, plain, fd),
            fd_over_plain=ratios(lambda s, p, f: f / p, sens, plain, fd),
        )
        assert r.stats["analysis"] == "dynamic", r.stats["analysis"]
        row["ks"].append(entry)

    # accuracy of one parameter's dq/dp
    check = case["check"]
    acc = dict(parameter=check, rel_step=REL_STEP, reference_rtol=REF_RTOL, reference_atol=REF_ATOL)
    try:
        reference = fd_q(model, case, check, REF_RTOL, REF_ATOL)
        tight = mb.simulate(model, t_end, sensitivities=[check], **settings(case, REF_RTOL, REF_ATOL, analysis="auto"))
        acc["sens_at_reference_rtol"] = relative(tight.sensitivity(check).q, reference)
        timed = results.get(f"sens{ks[0]}")
        if timed is not None and check in timed.sensitivity_names:
            acc["sens_at_timed_rtol"] = relative(timed.sensitivity(check).q, reference)
            acc["sens_timed_against_sens_at_reference_rtol"] = relative(timed.sensitivity(check).q,
                                                                        tight.sensitivity(check).q)
        acc["fd_at_timed_rtol"] = relative(fd_q(model, case, check, RTOL, ATOL), reference)
        acc["scale"] = float(np.abs(reference).max())
    except (mb.SimulationError, mb.ModelError) as e:
        acc["failed"] = f"{type(e).__name__}: {e}"
    try:
        mb.simulate(model, t_end, sensitivities=[check], **settings(case, REF_RTOL, PROBE_ATOL, analysis="auto"))
        acc[f"sens_at_atol_{PROBE_ATOL:g}"] = "ok"
    except (mb.SimulationError, mb.ModelError) as e:
        acc[f"sens_at_atol_{PROBE_ATOL:g}"] = f"{type(e).__name__}: {e}"
    row["accuracy"] = acc
    return row


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    p.add_argument("--repeats", type=int, default=None, help="timed rounds (default 7, --quick 2)")
    p.add_argument("--quick", action="store_true", help="2 rounds, k = 1 and 4; writes nothing unless --out")
    p.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    p.add_argument("--out", default=None, help="the JSON written (default bench/results/sensitivities.json)")
    args = p.parse_args()
    repeats = args.repeats or (2 if args.quick else 7)
    ks = [1, 4] if args.quick else KS
    load_start = load_average()
    started = time.perf_counter()
    out = {**stamp("sensitivities", bool(changed("cpp", "python/lagmb"))),
           "numpy": np.__version__, "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS"),
           "repeats": repeats, "rtol": RTOL, "atol": ATOL, "n_out": N_OUT, "method": "ggl",
           "fd_rel_step": REL_STEP, "cases": []}

    rows = []
    for name in args.cases:
        row = measure(name, CASES[name], ks, repeats)
        out["cases"].append(row)
        rows.append(row)
        for label, why in row["failures"].items():
            print(f"FAILED {name} {label}: {why}", flush=True)

    print(f"\nrtol {RTOL:g}, atol {ATOL:g}, method ggl, {N_OUT} outputs; seconds, min (median) of {repeats} rounds; "
          f"FD = the 2k central-difference runs at the same rtol\n")
    print("| case | k | plain (s) | sens (s) | 2k FD runs (s) | sens / plain | sens / (plain + FD) "
          "| extra per sensitivity (plain runs) | steps plain / sens | residual evals plain / sens "
          "| Jacobians plain / sens |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        pl = row["plain"]
        for e in row["ks"]:
            if "failed" in e:
                print(f"| {row['case']} | {e['k']} | failed: {'; '.join(f'{a}: {b}' for a, b in e['failed'].items())} |")
                continue
            s, f = e["sens"], e["fd"]
            print(f"| {row['case']} | {e['k']} | {pl['min']:.4f} ({pl['median']:.4f}) | {s['min']:.4f} ({s['median']:.4f}) "
                  f"| {f['min']:.4f} ({f['median']:.4f}) | {e['sens_over_plain']['min']:.2f} "
                  f"({e['sens_over_plain']['median']:.2f}) | {e['sens_over_plain_plus_fd']['min']:.2f} "
                  f"({e['sens_over_plain_plus_fd']['median']:.2f}) "
                  f"| {e['extra_per_sensitivity_in_plain_runs']['min']:.2f} "
                  f"({e['extra_per_sensitivity_in_plain_runs']['median']:.2f}) "
                  f"| {pl['stats']['steps']} / {s['stats']['steps']} "
                  f"| {pl['stats']['residual_evals']} / {s['stats']['residual_evals']} "
                  f"| {pl['stats']['jacobian_evals']} / {s['stats']['jacobian_evals']} |")
    for row in rows:
        if "plain_default_analysis" in row:
            d = row["plain_default_analysis"]
            print(f"\n{row['case']}: the plain run with the model's default analysis ({d['analysis']}, "
                  f"{d['formulation']}): {d['min']:.4f} s ({d['median']:.4f}); with analysis='dynamic' "
                  f"{row['plain']['min']:.4f} s ({row['plain']['median']:.4f})")

    print(f"\nAccuracy of dq/dp against central differences of runs at rtol {REF_RTOL:g}, atol {REF_ATOL:g} "
          f"(step {REL_STEP:g} |p|): "
          "max |error| / max |FD|\n")
    print("| case | parameter | max abs FD(q) | sens at rtol 1e-12 | sens at rtol 1e-8 (timed) | FD at rtol 1e-8 "
          "| sens 1e-8 against sens 1e-12 |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for row in rows:
        a = row["accuracy"]
        if "failed" in a:
            print(f"| {row['case']} | {a['parameter']} | failed: {a['failed']} |")
            continue
        fmt = lambda x: "-" if x is None else f"{x:.1e}"  # noqa: E731
        print(f"| {row['case']} | {a['parameter']} | {a['scale']:.3g} | {fmt(a['sens_at_reference_rtol'])} "
              f"| {fmt(a.get('sens_at_timed_rtol'))} | {fmt(a['fd_at_timed_rtol'])} "
              f"| {fmt(a.get('sens_timed_against_sens_at_reference_rtol'))} |")
    for row in rows:
        probe = row["accuracy"].get(f"sens_at_atol_{PROBE_ATOL:g}")
        if probe != "ok":
            print(f"\n{row['case']}, the sensitivity run at rtol {REF_RTOL:g}, atol {PROBE_ATOL:g}: {probe}")

    out["load_average_1min"] = [load_start, load_average()]
    out["seconds"] = time.perf_counter() - started
    print(f"\n{stamp_line(out, out['load_average_1min'])}, BLAS threads {out['blas_threads']}, "
          f"{out['seconds']:.0f} s")
    write_json(args.out or (None if args.quick else os.path.join(RESULTS, "sensitivities.json")), out)


if __name__ == "__main__":
    sys.exit(main())
