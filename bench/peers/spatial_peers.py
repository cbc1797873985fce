"""lagmb against Pinocchio and MuJoCo on a spatial chain, side by side, one run.

The spatial counterpart of bench/peers/compare.py (the planar chain). The
problem, the same in every engine: N uniform rods (L = 1 m, m = 1 kg,
principal moments (1e-4, 1/12, 1/12) kg m^2 about the centre, the rod along
its body x axis); revolute joints whose axes alternate between y and z:
joint 0 pins rod 0 to the ground at the origin about y, joint k (k >= 1)
sits at the far end of rod k-1 with its axis along rod k-1's y (k even) or
z (k odd) axis. Every joint starts at 0.1 rad (so the initial poses are the
composed rotations R_k = R_{k-1} Rot(a_k, 0.1)), at rest; gravity 9.81 m/s^2
in -z; 1 s. The error of a run is the tip (the far end of rod N-1) at
t = 1 s: max of |x|, |y|, |z| error against the reference.

Engines:
  lagmb      Model(dimension=3): bodies in the posed configuration, each
             add_revolute at the joint point with the axis in world axes and
             angle=0.1 (so its joint coordinate reads as Pinocchio's q);
             mb.simulate(t_end=1, rtol, atol=1e-2 rtol, n_out=2) with
             "auto" (the default formulation; r.stats["method_choice"] is
             recorded), "projection-erk" and "ggl"; rtol in half decades from
             1e-2 (to 1e-11 at most).
  pinocchio  pin.Model built in code (JointModelRY / RZ alternating,
             placements (1, 0, 0) after the first, pin.Inertia of the rod),
             q0 = 0.1, ABA integrated by SciPy solve_ivp DOP853 (Python
             right-hand side), rtol in half decades, atol = 1e-2 rtol.
  mujoco     MJCF written in code (nested bodies, hinge joints, explicit
             <inertial>, contacts and constraints disabled, no damping or
             armature, a site at the tip), qpos = 0.1 after mj_resetData,
             RK4 with fixed steps h = 1/steps: doubling from 25 steps until
             below 1e-8, then for each target the fewest steps reaching it by
             bisection to 1 % (bench/robots/mujoco_urdf.py search, as
             bench/robots/robots.py).

Reference: Pinocchio ABA + DOP853 at rtol = atol = 1e-13, cross-checked
against lagmb GGL at rtol 1e-11 and lagmb projection-erk at rtol 1e-13
(independent formulation, coordinates and integrators) and against DOP853
at 1e-12; cached in bench/results/spatial_peers_reference.json.

Checks, before anything is timed: (1) the three models are the same: at the
initial configuration and at a random state (seed 1) the joint
accelerations of mj_forward and of lagmb (mb.solve_accelerations read back
through mb.JointSpace) equal pin.aba to 1e-8 relative; (2) every
engine-method's sweep converges to the reference (its errors fall as the
tolerance or step tightens and reach 1e-8) and a tight run of it (lagmb and
DOP853 at rtol 1e-12, GGL at 1e-11; RK4 at 2x and 4x the doubling level that
first reached 1e-8) agrees with the reference to ~1e-10. An engine that
fails (1) is left out of the timing; (2) is reported.

Timing: the search (coarse to fine, one untimed-for-results run per level;
its wall times are recorded) finds each sweep's decisive runs (for each
target the first that reaches it and the one before; the slowest run if it
is never reached). Those are then timed in --repeat rounds, interleaved:
slot j of every sweep, then slot j + 1, the order of the sweeps reversed
every other slot and round; a run under --min-time (20 ms) is repeated
until its runs add up to that (at most 20), and the fastest time of all
rounds is kept. Times are those of the integration call only (models built
and compiled beforehand). The time to a target is interpolated log-log
between the run that first reaches it and the one before (bench/common/time_to.py);
a sweep that never reaches it gives a lower bound ">" (its slowest run); one
whose loosest run already reaches it an upper bound "<=" (that run). A
sweep stops after a run longer than --max-run seconds or when its next run
is estimated longer (from the last two).

    python bench/peers/spatial_peers.py [--n 8 32 128] [--repeat 3] [--max-run 30]
        [--min-time 0.02] [--engines lagmb pinocchio mujoco] [--out FILE]

Writes bench/results/spatial_peers.json and prints a markdown table.
"""

import argparse
import json
import math
import os
import platform
import sys
import time
import warnings

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.record import one_blas_thread  # noqa: E402

one_blas_thread()

import numpy as np  # noqa: E402

from bench.common.paths import RESULTS  # noqa: E402
from bench.common.record import build_id  # noqa: E402
from bench.common.time_to import decisive as shared_decisive, time_to  # noqa: E402
from bench.peers.spatial_engines import ANGLE0, ENGINES, LagmbEngine, PinocchioEngine  # noqa: E402

TARGETS = (1e-6, 1e-8)
MAX_INNER = 20
CACHE = os.path.join(RESULTS, "spatial_peers_reference.json")


# --------------------------------------------------------------------------
# reference
# --------------------------------------------------------------------------

def load_cache():
    if os.path.exists(CACHE):
        with open(CACHE) as f:
            return json.load(f)
    return {}


def reference(n, cache, log):
    """Tip at 1 s: Pinocchio ABA + DOP853 at rtol = atol = 1e-13, with its
    cross-checks. Cached by N."""
    key = str(n)
    if key in cache:
        return np.array(cache[key]["tip"]), cache[key]
    pe = PinocchioEngine(n)
    t0 = time.perf_counter()
    r = pe.run("DOP853", 1e-13, 1e-13)
    entry = {"tip": r["tip"], "how": "Pinocchio ABA + SciPy DOP853, rtol = atol = 1e-13",
             "seconds": time.perf_counter() - t0, "steps": r["steps"], "evals": r["evals"]}
    tip = np.array(r["tip"])
    log(f"  reference N = {n}: tip {tip} ({entry['seconds']:.1f} s, {r['steps']} steps)")
    checks = entry["cross_checks"] = {}
    r2 = pe.run("DOP853", 1e-12, 1e-12)
    checks["pinocchio_DOP853_1e-12"] = float(np.max(np.abs(np.array(r2["tip"]) - tip)))
    le = LagmbEngine(n)
    for method, rtol in (("ggl", 1e-11), ("projection-erk", 1e-13)):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                rr = le.run(method, rtol, 1e-2 * rtol)
            checks[f"lagmb_{method}_rtol{rtol:g}"] = float(np.max(np.abs(np.array(rr["tip"]) - tip)))
        except Exception as e:  # noqa: BLE001
            checks[f"lagmb_{method}_rtol{rtol:g}"] = f"failed: {str(e).splitlines()[0][:160]}"
    log("  reference cross-checks: " + ", ".join(f"{k} {v:.1e}" if isinstance(v, float) else f"{k} {v}"
                                                 for k, v in checks.items()))
    cache[key] = entry
    os.makedirs(os.path.dirname(CACHE), exist_ok=True)
    with open(CACHE, "w") as f:
        json.dump(cache, f, indent=1)
    return tip, entry


# --------------------------------------------------------------------------
# sweeps
# --------------------------------------------------------------------------

class Sweep:
    def __init__(self, engine, spec):
        self.engine, self.ename = engine, engine.name
        self.method, self.kind = spec["method"], spec["kind"]
        self.levels = spec["levels"]
        self.rows = []  # the search, coarse to fine
        self.stop = "levels exhausted"
        self.checks = {}

    @property
    def label(self):
        return f"{self.ename} {self.method}"


def one_run(sweep, level, tip):
    """One run (not repeated): a row with error and the run's time."""
    row = {"level": level}
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = sweep.engine.run(sweep.method, level)
    except Exception as e:  # noqa: BLE001 - a failed run is a result
        row.update(status="failed", message=(str(e).strip().splitlines() or [type(e).__name__])[0][:200],
                   wall=time.perf_counter() - t0)
        return row
    err = float(np.max(np.abs(np.array(r["tip"]) - tip)))
    if not math.isfinite(err):
        row.update(status="failed", message="non-finite result", wall=time.perf_counter() - t0)
        return row
    row.update(status="ok", error=err, search_time=float(r["time"]),
               **{k: v for k, v in r.items() if k not in ("time",)})
    return row


def too_long(rows, max_run):
    """Why the next (finer) run should not be made, or None."""
    last = rows[-1]
    t = last.get("search_time", last.get("wall", 0.0))
    if t > max_run:
        return f"run took {t:.1f} s > --max-run"
    if len(rows) >= 2:
        prev = rows[-2]
        tp = prev.get("search_time", prev.get("wall", 0.0))
        growth = max(1.2, t / max(tp, 1e-9))
        if t * growth > max_run:
            return f"next run estimated {t * growth:.1f} s > --max-run"
    return None


def search_rtol(sweep, tip, max_run, log):
    for level in sweep.levels:
        row = one_run(sweep, level, tip)
        sweep.rows.append(row)
        ok = [r for r in sweep.rows if r["status"] == "ok"]
        if row["status"] == "ok" and row["error"] <= min(TARGETS):
            sweep.stop = f"reached {min(TARGETS):g}"
            break
        fails = 0
        for r in reversed(sweep.rows):
            if r["status"] == "ok":
                break
            fails += 1
        if ok and fails >= 3:
            sweep.stop = "three failures after a success"
            break
        if len(ok) > 7 and min(r["error"] for r in ok[-7:]) > 0.5 * min(r["error"] for r in ok[:-7]):
            sweep.stop = "error stopped improving"
            break
        why = too_long(sweep.rows, max_run)
        if why:
            sweep.stop = why
            break
    log(f"    {sweep.label:<26} " + " ".join(
        f"{r['level']:.0e}:{r['error']:.1e}" if r["status"] == "ok" else f"{r['level']:.0e}:failed"
        for r in sweep.rows) + f"  ({sweep.stop})")


def search_steps(sweep, tip, max_run, log, first=25, max_steps=25 * 2 ** 16):
    """Doubling from `first` until below every target, then bisection on the
    number of steps for each target to 1 % (bench/robots/mujoco_urdf.py search)."""
    cache = {}

    def point(steps):
        if steps not in cache:
            cache[steps] = one_run(sweep, steps, tip)
        return cache[steps]

    err = lambda p: p.get("error", math.inf)
    doubling, steps = [], first
    while steps <= max_steps:
        doubling.append(point(steps))
        if err(doubling[-1]) <= min(TARGETS):
            sweep.stop = f"reached {min(TARGETS):g}"
            break
        why = too_long(doubling, max_run)
        if why:
            sweep.stop = why
            break
        steps *= 2
    for target in TARGETS:
        below = [p["level"] for p in doubling if err(p) <= target]
        if not below:
            continue
        hi = min(below)
        lo = max([p["level"] for p in doubling if err(p) > target and p["level"] < hi], default=0)
        while hi - lo > max(1, hi // 100):
            mid = (lo + hi) // 2
            if err(point(mid)) <= target:
                hi = mid
            else:
                lo = mid
    sweep.rows = sorted(cache.values(), key=lambda p: p["level"])
    sweep.doubling = [p["level"] for p in doubling]
    log(f"    {sweep.label:<26} doubling " + " ".join(
        f"{p['level']}:{p['error']:.1e}" if p["status"] == "ok" else f"{p['level']}:failed" for p in doubling)
        + f"; {len(cache) - len(doubling)} bisection runs ({sweep.stop})")


def decisive(rows):
    """The rows a sweep's times rest on (time_to.decisive)."""
    return sorted(shared_decisive(rows, TARGETS, "search_time"))


def check_sweep(sweep, tip, max_run):
    """Convergence to the reference: the sweep's errors come down and reach
    1e-8, and tight runs agree with the reference."""
    ok = [r for r in sweep.rows if r["status"] == "ok"]
    c = sweep.checks
    c["errors_fall"] = bool(len(ok) >= 2 and ok[-1]["error"] <= 0.25 * ok[0]["error"])
    c["reaches_1e-8"] = bool(ok and min(r["error"] for r in ok) <= min(TARGETS))
    if sweep.kind == "rtol":
        tight = [1e-11] if sweep.method == "ggl" else [1e-12]
    else:
        base = next((s for s in getattr(sweep, "doubling", []) if any(
            r["level"] == s and r["status"] == "ok" and r["error"] <= min(TARGETS) for r in sweep.rows)), None)
        tight = [2 * base, 4 * base] if base else []
    slowest = max((r.get("search_time", 0.0) for r in ok), default=0.0)
    runs = {}
    for level in tight:
        # a tight run costs ~3x the loosest reaching 1e-8 (rtol) or 2x / 4x (steps)
        est = slowest * (3.0 if sweep.kind == "rtol" else level / max(r["level"] for r in ok))
        if est > 3 * max_run:
            runs[f"{level:g}"] = f"not run (estimated {est:.0f} s)"
            continue
        row = one_run(sweep, level, tip)
        runs[f"{level:g}"] = row["error"] if row["status"] == "ok" else f"failed: {row['message']}"
        if "method_choice" in row:
            c["method_choice_tight"] = row["method_choice"]
    c["tight_runs_error"] = runs
    errs = [v for v in runs.values() if isinstance(v, float)]
    c["tight_agrees_1e-9"] = bool(errs and min(errs) <= 1e-9)
    return c


def timed(sweep, level, min_time):
    times = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        while True:
            r = sweep.engine.run(sweep.method, level)
            times.append(float(r["time"]))
            if sum(times) >= min_time or len(times) >= MAX_INNER:
                break
    return times


def measure(n, names, tip, args, log):
    engines, notes = [], []
    for name in names:
        t0 = time.perf_counter()
        try:
            engines.append(ENGINES[name](n))
            log(f"  {name}: model built in {time.perf_counter() - t0:.2f} s")
        except Exception as e:  # noqa: BLE001
            notes.append(f"{name}: model not built: {type(e).__name__}: {e}")
            log(f"  {name}: model not built: {e}")
    # check 1: the same dynamics (joint accelerations against pin.aba)
    model_check = {}
    pin_e = next((e for e in engines if e.name == "pinocchio"), None)
    if pin_e is not None:
        rng = np.random.default_rng(1)
        states = {"initial": (np.full(n, ANGLE0), np.zeros(n)),
                  "random": (rng.uniform(-1, 1, n), rng.uniform(-1, 1, n))}
        for e in list(engines):
            if e is pin_e:
                continue
            rel = {}
            for label, (q, v) in states.items():
                aba = pin_e.accelerations(q, v)
                rel[label] = float(np.max(np.abs(e.accelerations(q, v) - aba)) / np.max(np.abs(aba)))
            model_check[e.name] = rel
            log(f"  {e.name} joint accelerations vs pin.aba: " + ", ".join(f"{k} {v:.1e}" for k, v in rel.items()))
            if not max(rel.values()) <= 1e-8:
                notes.append(f"{e.name}: left out: its accelerations differ from pin.aba ({rel})")
                engines.remove(e)
    sweeps = [Sweep(e, spec) for e in engines for spec in e.methods()]
    # warm-up (first-call costs), then the search, then check 2
    for s in sweeps:
        if s.kind == "rtol":
            one_run(s, s.levels[0], tip)
        else:
            one_run(s, 25, tip)
    log("  search (error by rtol / steps):")
    for s in sweeps:
        (search_rtol if s.kind == "rtol" else search_steps)(s, tip, args.max_run, log)
    log("  checks against the reference (tight runs):")
    for s in sweeps:
        c = check_sweep(s, tip, args.max_run)
        log(f"    {s.label:<26} errors fall {c['errors_fall']}, reaches 1e-8 {c['reaches_1e-8']}, tight: "
            + ", ".join(f"{k}: {v:.1e}" if isinstance(v, float) else f"{k}: {v}"
                        for k, v in c["tight_runs_error"].items()))
    # timing rounds, interleaved
    slots = {id(s): decisive(s.rows) for s in sweeps}
    depth = max((len(v) for v in slots.values()), default=0)
    for rep in range(args.repeat):
        for j in range(depth):
            todo = [s for s in sweeps if j < len(slots[id(s)])]
            if (j + rep) % 2:
                todo = todo[::-1]
            for s in todo:
                row = s.rows[slots[id(s)][j]]
                try:
                    times = timed(s, row["level"], args.min_time)
                except Exception as e:  # noqa: BLE001
                    row.setdefault("timing_failures", []).append(str(e)[:200])
                    continue
                row.setdefault("times", []).extend(times)
                row["time"] = min(row["times"])
        log(f"  round {rep + 1} of {args.repeat} done")
    results = []
    for s in sweeps:
        timed_rows = [r for r in s.rows if r["status"] == "ok" and "time" in r]
        tt, lb = {}, {}
        for t in TARGETS:
            key = f"{t:g}"
            tt[key] = time_to(timed_rows, t)
            lb[key] = (max(r["time"] for r in timed_rows)
                       if timed_rows and tt[key] is None else None)
        ok = [r for r in s.rows if r["status"] == "ok"]
        res = {"n": n, "engine": s.ename, "method": s.method, "kind": s.kind, "time_to": tt, "lower_bound": lb,
               "min_error": min((r["error"] for r in ok), default=None), "stop": s.stop, "checks": s.checks,
               "runs": s.rows}
        if s.kind == "steps":
            res["steps_to"] = {f"{t:g}": min((r["level"] for r in ok if r["error"] <= t), default=None)
                               for t in TARGETS}
        # the loosest run already reaches the target: the time to it is at most that
        res["at_loosest"] = {f"{t:g}": bool(timed_rows and ok and ok[0] is timed_rows[0] and ok[0]["error"] <= t)
                             for t in TARGETS}
        choices = sorted({r["method_choice"] for r in s.rows if "method_choice" in r})
        if choices and choices != ["given"]:
            res["method_choices"] = choices
        results.append(res)
    return results, model_check, notes


# --------------------------------------------------------------------------
# output
# --------------------------------------------------------------------------

def fmt_t(v, bound=None, at_most=False):
    if v is not None:
        return f"<={v:.3g}" if at_most else f"{v:.3g}"
    if bound is not None:
        return f">{bound:.3g}"
    return "-"


def cell(r, key):
    if r is None:
        return None, None
    return r["time_to"][key], r["lower_bound"][key], r.get("at_loosest", {}).get(key, False)


def ratio(a, b):
    (va, _, _), (vb, bb, _) = a, b
    if va is not None and vb is not None:
        x = va / vb
        return f"{x:.2f}" if x < 10 else f"{x:.1f}"
    if va is not None and bb is not None:  # the other never got there: lagmb / (> bound) = < ratio
        return f"<{va / bb:.2g}"
    return "-"


def tables(results, log):
    log(f"{'N':>4}  {'engine method':<26} {'t(1e-6) s':>10} {'t(1e-8) s':>10} {'err min':>8}  stop")
    for r in results:
        log(f"{r['n']:>4}  {r['engine'] + ' ' + r['method']:<26} "
            f"{fmt_t(*cell(r, '1e-06')):>10} {fmt_t(*cell(r, '1e-08')):>10} "
            f"{r['min_error'] if r['min_error'] is None else format(r['min_error'], '.1e'):>8}  {r['stop']}")
    log("")
    log("| N | target | lagmb best (method) | Pinocchio ABA+DOP853 | MuJoCo RK4 (steps) | lagmb/Pinocchio | "
        "lagmb/MuJoCo |")
    log("|---:|---:|---:|---:|---:|---:|---:|")
    for n in sorted({r["n"] for r in results}):
        rs = [r for r in results if r["n"] == n]
        for t in TARGETS:
            key = f"{t:g}"
            ours = [r for r in rs if r["engine"] == "lagmb" and r["time_to"][key] is not None]
            best = min(ours, key=lambda r: r["time_to"][key]) if ours else None
            pin = next((r for r in rs if r["engine"] == "pinocchio"), None)
            mj = next((r for r in rs if r["engine"] == "mujoco"), None)
            b = cell(best, key)
            lag = f"{fmt_t(*b)} ({best['method']})" if best else "-"
            mjs = fmt_t(*cell(mj, key)) if mj else "-"
            if mj and mj.get("steps_to", {}).get(key):
                mjs += f" ({mj['steps_to'][key]})"
            log(f"| {n} | {key} | {lag} | {fmt_t(*cell(pin, key)) if pin else '-'} | {mjs} | "
                f"{ratio(b, cell(pin, key)) if best and pin else '-'} | {ratio(b, cell(mj, key)) if best and mj else '-'} |")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=[8, 32, 128])
    p.add_argument("--repeat", type=int, default=3, help="timing rounds; the fastest time of each run is kept")
    p.add_argument("--max-run", type=float, default=30.0,
                   help="a sweep stops after a run this long, or when its next run is estimated longer (s)")
    p.add_argument("--min-time", type=float, default=0.02,
                   help="a run shorter than this is repeated until its runs add up to it (s)")
    p.add_argument("--engines", nargs="+", default=list(ENGINES), choices=list(ENGINES))
    p.add_argument("--out", default=os.path.join(RESULTS, "spatial_peers.json"))
    args = p.parse_args()

    def log(msg=""):
        print(msg, flush=True)

    versions = {}
    for name, mod in (("lagmb", "lagmb"), ("pinocchio", "pinocchio"), ("mujoco", "mujoco"), ("scipy", "scipy")):
        try:
            versions[name] = __import__(mod).__version__
        except Exception as e:  # noqa: BLE001
            versions[name] = f"not importable: {e}"
    try:
        import lagmb as mb

        versions["lagmb_build"] = build_id(mb)
    except Exception:  # noqa: BLE001
        pass
    log(f"spatial chain, N = {args.n}, repeat {args.repeat}, max-run {args.max_run} s, min-time {args.min_time} s; "
        + ", ".join(f"{k} {v}" for k, v in versions.items()))
    doc = {"benchmark": "spatial_peers", "targets": TARGETS, "machine": platform.platform(),
           "python": sys.version.split()[0], "versions": versions, "args": vars(args),
           "started": time.strftime("%Y-%m-%d %H:%M:%S"), "references": {}, "model_checks": {}, "notes": [],
           "results": []}
    cache = load_cache()
    t_start = time.perf_counter()
    for n in args.n:
        log(f"N = {n}:")
        tip, entry = reference(n, cache, log)
        doc["references"][str(n)] = entry
        t0 = time.perf_counter()
        res, mc, notes = measure(n, args.engines, tip, args, log)
        log(f"  measured in {time.perf_counter() - t0:.0f} s")
        doc["results"] += res
        doc["model_checks"][str(n)] = mc
        doc["notes"] += [f"N = {n}: {x}" for x in notes]
        doc["elapsed"] = time.perf_counter() - t_start
        os.makedirs(os.path.dirname(args.out), exist_ok=True)
        with open(args.out, "w") as f:
            json.dump(doc, f, indent=1)
        tables(res, log)
    log(f"all N ({time.perf_counter() - t_start:.0f} s):")
    tables(doc["results"], log)
    for n, e in doc["references"].items():
        log(f"reference N = {n}: " + ", ".join(f"{k} {v:.1e}" if isinstance(v, float) else f"{k} {v}"
                                               for k, v in e["cross_checks"].items()))
    for r in doc["results"]:
        if r.get("method_choices"):
            log(f"N = {r['n']} lagmb {r['method']}: method_choice {r['method_choices']}")
    for x in doc["notes"]:
        log(f"note: {x}")
    log(f"written {args.out}")


if __name__ == "__main__":
    main()
