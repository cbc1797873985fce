"""lagmb against other engines on many-link chains, side by side, one run.

The problem (the same in every engine): N uniform rods (L = 1 m, m = 1 kg,
J = 1/12 kg m^2 about the centre) pinned to the ground at the origin,
released horizontal at rest, gravity 9.81 m/s^2 in -y, 1 s. The error of a
run is the tip rod's centre at t = 1 s (max of |x|, |y| error) against the
minimal-coordinate reference of bench/peers/reference.py (non-stiff:
tests/references.py RodChain, DOP853 at 1e-12; --stiff: the same chain
with a rotational spring-damper at every joint between rods, k set so that
the fastest linearised mode is 1e4 times the slowest, c so that the fastest
mode has damping ratio 1; Radau at 1e-11).

Engines (each in its own bench/peers/peer_*.py, with the model, its
conversions, what its time covers, and a self-check):
  lagmb      projection-erk, ggl (+ projection-bdf with --stiff); rtol swept
  pinocchio  ABA + SciPy solve_ivp: DOP853 (+ Radau, BDF, LSODA); rtol swept
  mujoco     RK4 (+ implicitfast, implicit, discrete); step swept
  exudyn     redundant coordinates: TrapezoidalIndex2, GeneralizedAlpha
             (RK44 recorded as refused); kinematic tree (N <= 128): RK67
             (step swept), DOPRI5 (tolerance swept)
An engine that is not installed is reported as skipped with the reason.
Everything runs on one thread (BLAS/OpenMP limited to 1, set below).

Sweeps: each engine-method goes from coarse to fine; the sweeps run
interleaved (level 1 of every sweep, then level 2, ..., the order reversed
every other level) so that machine noise hits all engines alike. A sweep
stops at the first run with error <= 1e-8, when the next run would take
longer than --max-run seconds (estimated from the last two), after a run
(or a failing run) longer than --max-run, or when the error has not
improved by 2x over five step doublings or seven half decades of rtol.
Then --repeat - 1 more rounds rerun the runs the results rest on (for each
target the run that first reaches it and the one before, or the slowest
run if it is never reached), again interleaved; the fastest time is kept.
Within a round, a run shorter than --min-time (0.2 s) is repeated until its
runs add up to that (at most 20), fastest kept: a busy machine distorts the
millisecond runs of the short chains most. The first level of every sweep
is run once untimed first (warm-up). Times are those of the integration
call only; models are built beforehand. The JSON lists every time of every
run.

Table: for each engine-method and target error (1e-6, 1e-8) the time to
reach it, interpolated log-log between the run that first reaches it and
the run before (bench/common/time_to.py); a sweep that never
reaches a target gets a lower bound ">" = its slowest run. Ratios are
engine time / lagmb's best time at the same target and N. "err min" is the
sweep's smallest error; "conv" "yes" if its error came down with
refinement (finest run 4x below the coarsest), "flat" if every run was
already below 1e-8 (explicit methods on the stiff chain, whose step is set
by stability), "no" otherwise; "stop" why the sweep ended.

    /tmp/peers-venv/bin/python bench/peers/compare.py [--n 8 32 128 512] [--stiff]
        [--repeat 2] [--max-run 10] [--min-time 0.2] [--engines lagmb mujoco ...]
        [--quick] [--out FILE] [--append] [--from-json]

Default N: 8 32 128 512; with --stiff 8 32 128 (add 512 with --n 512
--append: its reference takes about 20 min to compute once). Writes
bench/results/peers.json (peers_stiff.json with --stiff) and, with
matplotlib, the .png next to it (error against time, one panel per N).
The references are cached in bench/results/peers_reference.json
(bench/peers/reference.py computes and checks them; compare.py computes a
missing one).
"""

import argparse
import importlib
import json
import math
import os
import platform
import signal
import sys
import time
import warnings

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.record import one_blas_thread  # noqa: E402

# one thread everywhere (BLAS/LAPACK behind SciPy and NumPy, OpenMP): every
# engine integrates on one core, as lagmb, MuJoCo's mj_step and Exudyn
# (numberOfThreads = 1) do; set before NumPy is imported
one_blas_thread()

from bench.common.paths import RESULTS  # noqa: E402
from bench.common.time_to import decisive as shared_decisive, time_to  # noqa: E402
from bench.peers import reference  # noqa: E402

TARGETS = (1e-6, 1e-8)
MAX_INNER = 20  # repetitions of one short run at most
ENGINE_MODULES = ("peer_lagmb", "peer_pinocchio", "peer_mujoco", "peer_exudyn")  # in bench/peers/


def lower_bound(rows, target):
    """Slowest ok run of a sweep that never reached `target`."""
    ok = [r for r in rows if r["status"] == "ok"]
    if not ok or min(r["error"] for r in ok) <= target:
        return None
    return max(r["time"] for r in ok)


class Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise Timeout("run exceeded the hard time limit")


def load_engines(names, log):
    engines, skipped = [], []
    for mod_name in ENGINE_MODULES:
        mod = importlib.import_module(f"bench.peers.{mod_name}")
        if names and mod.NAME not in names:
            continue
        try:
            ok, info = mod.available()
        except Exception as e:  # noqa: BLE001 - a broken install is a skip, not a crash
            ok, info = False, f"{type(e).__name__}: {e}"
        if ok:
            engines.append(mod)
            log(f"  {mod.NAME:<10} {info}")
        else:
            skipped.append({"engine": mod.NAME, "reason": info})
            log(f"  {mod.NAME:<10} skipped: {info}")
    return engines, skipped


class Sweep:
    def __init__(self, engine, spec):
        self.engine = engine
        self.ename = engine.name
        self.method = spec["method"]
        self.kind = spec["kind"]
        self.levels = list(spec["levels"])
        self.rows = []
        self.active = True
        self.stop_reason = "levels exhausted"

    @property
    def label(self):
        return f"{self.ename} {self.method}"


def run_once(sweep, level, tip, hard_limit, min_time=0.0):
    """One measurement; a row with status ok (error, time, counters) or
    failed. A run shorter than min_time is repeated until the runs add up
    to min_time (at most MAX_INNER times) and the fastest is kept: short
    runs are the ones a busy machine distorts most."""
    row = {"level": level, "kind": sweep.kind}
    if hard_limit:
        signal.signal(signal.SIGALRM, _alarm)
        signal.alarm(int(math.ceil(hard_limit)))
    times = []
    t_call = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            while True:
                t_call = time.perf_counter()
                r = sweep.engine.run(sweep.method, level)
                times.append(float(r["time"]))
                if sum(times) >= min_time or len(times) >= MAX_INNER:
                    break
    except Exception as e:  # noqa: BLE001 - any engine failure is recorded, not fatal
        row.update(status="failed", message=(str(e).strip().splitlines() or [type(e).__name__])[0][:200],
                   wall=time.perf_counter() - t_call)  # until it failed, with the call's overheads
        return row
    finally:
        if hard_limit:
            signal.alarm(0)
    err = max(abs(r["tip"][0] - tip[0]), abs(r["tip"][1] - tip[1]))
    if not math.isfinite(err):
        row.update(status="failed", message="non-finite result")
        return row
    row.update(status="ok", error=float(err), time=min(times), times=times,
               **{k: v for k, v in r.items() if k not in ("tip", "time")})
    row["tip"] = r["tip"]
    return row


def should_stop(sweep, max_run):
    rows = sweep.rows
    last = rows[-1]
    ok = [r for r in rows if r["status"] == "ok"]
    if last["status"] == "ok":
        if last["error"] <= min(TARGETS):
            return f"reached {min(TARGETS):g}"
        if last["time"] > max_run:
            return f"run took {last['time']:.1f} s > --max-run"
        if len(ok) >= 2 and ok[-2] is rows[-2]:
            growth = max(1.2, last["time"] / max(ok[-2]["time"], 1e-9))
            if last["time"] * growth > max_run:
                return f"next run estimated {last['time'] * growth:.1f} s > --max-run"
        m = 5 if sweep.kind == "steps" else 7  # doublings of the step count / half decades of rtol
        if len(ok) > m and min(r["error"] for r in ok[-m:]) > 0.5 * min(r["error"] for r in ok[:-m]):
            return "error stopped improving"
    else:
        if last["message"].startswith("run exceeded"):
            return "hard time limit"
        if last["wall"] > max_run:
            return f"failed run took {last['wall']:.1f} s > --max-run"
        prev = rows[-2] if len(rows) >= 2 else None
        if prev is not None and prev["status"] == "failed":
            growth = max(1.2, last["wall"] / max(prev["wall"], 1e-9))
            if last["wall"] * growth > max_run:
                return f"next (failing) run estimated {last['wall'] * growth:.1f} s > --max-run"
        fails = 0
        for r in reversed(rows):
            if r["status"] == "ok":
                break
            fails += 1
        if ok and fails >= 3:
            return "three failures after a success"
        if "refuse" in last["message"] or "cannot be solved" in last["message"]:
            return "refused"
    return None


def decisive(rows):
    """The rows a sweep's times rest on (time_to.decisive)."""
    return shared_decisive(rows, TARGETS, "time")


def order(items, k):
    """Alternate the order of the sweeps from one level to the next."""
    return items if k % 2 == 0 else items[::-1]


def measure(n, engines, stiff, params, tip, args, log):
    k, c = (params["stiffness"], params["damping"]) if stiff else (0.0, 0.0)
    sweeps, notes = [], []
    for mod in engines:
        t0 = time.perf_counter()
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                eng = mod.Engine(n, k, c)
        except Exception as e:  # noqa: BLE001
            notes.append({"engine": mod.NAME, "reason": f"model not built: {type(e).__name__}: {e}"})
            log(f"  {mod.NAME}: model not built: {e}")
            continue
        log(f"  {mod.NAME}: model built in {time.perf_counter() - t0:.2f} s (not timed)")
        for spec in eng.methods(stiff):
            if n > spec.get("max_n", math.inf):
                notes.append({"engine": mod.NAME, "method": spec["method"],
                              "reason": f"not run above N = {spec['max_n']}"})
                continue
            sweeps.append(Sweep(eng, spec))
    hard = 6 * args.max_run
    # warm-up (not recorded): the first level of every sweep once, so that no
    # timed run pays for first-call costs (imports, caches, allocations)
    for s in sweeps:
        run_once(s, s.levels[0], tip, hard)
    # round 1: the sweeps, interleaved level by level
    depth = max(len(s.levels) for s in sweeps) if sweeps else 0
    for i in range(depth):
        for s in order([s for s in sweeps if s.active and i < len(s.levels)], i):
            row = run_once(s, s.levels[i], tip, hard, args.min_time)
            s.rows.append(row)
            why = should_stop(s, args.max_run)
            if why:
                s.active, s.stop_reason = False, why
        for s in sweeps:
            if s.active and i + 1 >= len(s.levels):
                s.active = False
    # rounds 2..repeat: the runs the results rest on again, interleaved; keep the fastest
    needed = {id(s): decisive(s.rows) for s in sweeps}
    for rep in range(1, args.repeat):
        for i in range(depth):
            todo = [s for s in sweeps if i in needed[id(s)]]
            for s in order(todo, i + rep):
                again = run_once(s, s.levels[i], tip, hard, args.min_time)
                row = s.rows[i]
                if again["status"] == "ok":
                    row["times"] += again["times"]
                    row["time"] = min(row["times"])
                    if abs(again["error"] - row["error"]) > 1e-3 * row["error"] + 1e-15:
                        row["repeat_error_differs"] = again["error"]
    results = [summarize(n, s.ename, s.method, s.kind, s.rows, s.stop_reason) for s in sweeps]
    return results, notes


def converges(ok):
    """"yes" if the error came down with refinement (the finest run 4x below
    the coarsest), "flat" if every run is already below the finest target
    (an explicit method on the stiff chain: the step is set by stability,
    the error is tiny from the loosest setting on), else "no"."""
    if len(ok) >= 2 and ok[-1]["error"] <= 0.25 * ok[0]["error"]:
        return "yes"
    if ok and max(r["error"] for r in ok) <= min(TARGETS):
        return "flat"
    return "no"


def summarize(n, engine, method, kind, rows, stop):
    ok = [r for r in rows if r["status"] == "ok"]
    return {"n": n, "engine": engine, "method": method, "kind": kind,
            "time_to": {f"{t:g}": time_to(rows, t) for t in TARGETS},
            "lower_bound": {f"{t:g}": lower_bound(rows, t) for t in TARGETS},
            "min_error": min((r["error"] for r in ok), default=None),
            "converges": converges(ok), "stop": stop, "runs": rows}


def fmt_t(v, bound=None):
    if v is not None:
        return f"{v:.4f}" if v < 10 else f"{v:.2f}"
    if bound is not None:
        return f">{bound:.3f}" if bound < 10 else f">{bound:.1f}"
    return "-"


def fmt_ratio(v, best, bound=None):
    if best is None:
        return "-"
    if v is not None:
        return f"{v / best:.2f}" if v / best < 100 else f"{v / best:.0f}"
    if bound is not None:
        return f">{bound / best:.1f}"
    return "-"


def table(results, log):
    head = (f"{'N':>4}  {'engine':<10} {'method':<28} {'t(1e-6) s':>10} {'ratio':>6} "
            f"{'t(1e-8) s':>10} {'ratio':>6} {'err min':>8} {'conv':>4}  stop")
    log(head)
    log("-" * len(head))
    for n in sorted({r["n"] for r in results}):
        rs = [r for r in results if r["n"] == n]
        best = {}
        for t in TARGETS:
            key = f"{t:g}"
            vals = [r["time_to"][key] for r in rs if r["engine"] == "lagmb" and r["time_to"][key] is not None]
            best[key] = min(vals) if vals else None
        for r in rs:
            cells = []
            for t in TARGETS:
                key = f"{t:g}"
                cells += [fmt_t(r["time_to"][key], r["lower_bound"][key]),
                          fmt_ratio(r["time_to"][key], best[key], r["lower_bound"][key])]
            me = f"{r['min_error']:.1e}" if r["min_error"] is not None else "-"
            log(f"{n:>4}  {r['engine']:<10} {r['method']:<28} {cells[0]:>10} {cells[1]:>6} {cells[2]:>10} "
                f"{cells[3]:>6} {me:>8} {r['converges']:>4}  {r['stop']}")
        log("")


def plot(results, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ns = sorted({r["n"] for r in results})
    colors = {"lagmb": "tab:blue", "pinocchio": "tab:orange", "mujoco": "tab:green", "exudyn": "tab:red"}
    styles = ["o-", "s--", "^-.", "v:", "d-", "x--"]
    fig, axes = plt.subplots(1, len(ns), figsize=(4.6 * len(ns) + 2.2, 4.4), squeeze=False)
    for ax, n in zip(axes[0], ns):
        seen = {}
        for r in results:
            if r["n"] != n:
                continue
            pts = [(row["time"], max(row["error"], 1e-14)) for row in r["runs"] if row["status"] == "ok"]
            if not pts:
                continue
            j = seen.setdefault(r["engine"], 0)
            seen[r["engine"]] = j + 1
            ax.loglog(*zip(*pts), styles[j % len(styles)], ms=3, color=colors.get(r["engine"], "k"),
                      label=f"{r['engine']} {r['method']}")
        for target in TARGETS:
            ax.axhline(target, color="k", lw=0.5, ls=":")
        ax.set_title(f"{title}, N = {n}")
        ax.set_xlabel("wall time (s)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("tip error at t = 1 s (m)")
    labels = {}
    for ax in axes[0]:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            labels.setdefault(lab, h)
    fig.legend(list(labels.values()), list(labels.keys()), loc="center right", fontsize=7)
    fig.tight_layout(rect=(0, 0, 1 - 2.2 / fig.get_figwidth(), 1))
    fig.savefig(path, dpi=100)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=None,
                   help="chain lengths (default 8 32 128 512; with --stiff 8 32 128)")
    p.add_argument("--stiff", action="store_true", help="the chain with joint spring-dampers")
    p.add_argument("--repeat", type=int, default=None, help="rounds; the fastest time of each run is kept (2)")
    p.add_argument("--max-run", type=float, default=None,
                   help="a sweep stops after a run this long or when its next run is estimated longer (s; 10)")
    p.add_argument("--min-time", type=float, default=0.2,
                   help="a run shorter than this is repeated until the runs add up to it; fastest kept (s)")
    p.add_argument("--engines", nargs="+", default=None, help="only these (lagmb pinocchio mujoco exudyn)")
    p.add_argument("--quick", action="store_true", help="N = 8 32, one round, --max-run 1")
    p.add_argument("--out", default=None)
    p.add_argument("--from-json", action="store_true",
                   help="no runs: recompute the summaries, table and plot from the runs in the --out file")
    p.add_argument("--append", action="store_true",
                   help="keep the other N of an existing --out file (same --stiff); replace these N")
    args = p.parse_args()
    if args.quick:
        args.n = args.n or [8, 32]
        args.repeat = args.repeat or 1
        args.max_run = args.max_run or 1.0
    args.n = args.n or ([8, 32, 128] if args.stiff else [8, 32, 128, 512])
    args.repeat = args.repeat or 2
    args.max_run = args.max_run or 10.0
    name = "peers_stiff" if args.stiff else "peers"
    out = args.out or os.path.join(RESULTS, name + ".json")

    def log(msg=""):
        print(msg, flush=True)

    if args.from_json:
        with open(out) as f:
            doc = json.load(f)
        doc["results"] = [summarize(r["n"], r["engine"], r["method"], r["kind"], r["runs"], r["stop"])
                          for r in doc["results"]]
        with open(out, "w") as f:
            json.dump(doc, f, indent=1)
        table(doc["results"], log)
        plot(doc["results"], os.path.splitext(out)[0] + ".png", "stiff" if doc["stiff"] else "non-stiff")
        log(f"rewritten {out} and its .png")
        return

    t_start = time.perf_counter()
    log(f"{'stiff' if args.stiff else 'non-stiff'} chain, N = {args.n}, repeat {args.repeat}, "
        f"max-run {args.max_run} s; engines:")
    engines, skipped = load_engines(args.engines, log)
    cache = reference.load_cache()
    results, notes, refs, invocations = [], [], {}, []
    if args.append and os.path.exists(out):
        with open(out) as f:
            old = json.load(f)
        if old.get("stiff") != args.stiff:
            sys.exit(f"{out} holds {'stiff' if old.get('stiff') else 'non-stiff'} results; not appending")
        results = [r for r in old["results"] if r["n"] not in args.n]
        notes = [x for x in old.get("notes", []) if x["n"] not in args.n]
        refs = {k: v for k, v in old.get("references", {}).items() if int(k) not in args.n}
        invocations = old.get("invocations", [])
        log(f"appending to {out} (keeping N = {sorted({r['n'] for r in results})})")
    doc = {"benchmark": "peers", "stiff": args.stiff, "targets": TARGETS, "machine": platform.platform(),
           "processor": platform.processor(), "python": sys.version.split()[0], "args": vars(args),
           "engines": {m.NAME: m.available()[1] for m in engines}, "skipped": skipped}
    invocations.append({"args": vars(args), "started": time.strftime("%Y-%m-%d %H:%M:%S"),
                        "engines": doc["engines"]})
    for n in args.n:
        log(f"N = {n}:")
        cached = str(n) in cache["stiff" if args.stiff else "nonstiff"]
        if args.stiff:
            params, tip = reference.stiff_reference(n, cache, log=log)
            refs[str(n)] = {"tip": list(tip), "params": params, "how": cache["stiff"][str(n)]["how"]}
            log(f"  reference: k = {params['stiffness']:.6g} N m/rad, c = {params['damping']:.6g} N m s/rad, "
                f"omega {params['omega_min']:.4g} .. {params['omega_max']:.4g} rad/s")
        else:
            params, tip = None, reference.nonstiff_reference(n, cache, log=log)
            refs[str(n)] = {"tip": list(tip), "how": cache["nonstiff"][str(n)]["how"]}
        if not cached:
            reference.save_cache(cache)
        t0 = time.perf_counter()
        res, nts = measure(n, engines, args.stiff, params, tip, args, log)
        log(f"  measured in {time.perf_counter() - t0:.0f} s")
        results += res
        notes += [dict(x, n=n) for x in nts]
        table(res, log)
        results.sort(key=lambda r: r["n"])
        invocations[-1]["elapsed"] = time.perf_counter() - t_start
        doc.update(references=dict(sorted(refs.items(), key=lambda kv: int(kv[0]))), notes=notes,
                   results=results, invocations=invocations)
        os.makedirs(os.path.dirname(out), exist_ok=True)
        with open(out, "w") as f:
            json.dump(doc, f, indent=1)
    log(f"all N ({time.perf_counter() - t_start:.0f} s in all):")
    table(results, log)
    for x in notes:
        log(f"note: N = {x['n']} {x['engine']} {x.get('method', '')}: {x['reason']}")
    for x in skipped:
        log(f"skipped: {x['engine']}: {x['reason']}")
    log(f"written {out}")
    try:
        plot(results, os.path.splitext(out)[0] + ".png", "stiff" if args.stiff else "non-stiff")
        log(f"written {os.path.splitext(out)[0]}.png")
    except ImportError:
        pass


if __name__ == "__main__":
    main()
