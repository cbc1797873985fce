"""Robots from example-robot-data: lagmb against Pinocchio and MuJoCo, side by side.

For each robot (fixed base, its URDF read by mb.load_urdf with limits,
damping and mimic couplings left out, as Pinocchio builds it): the zero
configuration with random joint rates in [-1, 1] rad/s (seed 1, as
tests/formats/test_urdf.py), 1 s of free motion.

- Reference: Pinocchio's ABA integrated by SciPy's DOP853 at rtol = atol =
  1e-13; every run below is measured against it (the largest joint-angle
  error at t = 1 s, mod 2 pi).
- MuJoCo (bench/robots/mujoco_urdf.py): the same URDF read by MuJoCo's URDF
  reader without its <visual>/<collision> elements (fixed joints fused),
  damping, friction, armature, limits and mimic equalities taken out,
  contacts and constraints disabled, gravity (0, 0, -9.81); joints matched
  to Pinocchio's by name. Checked before it is timed: mj_forward's qacc at
  the start state and at the evaluation state below equals pin.aba to 1e-8
  of the largest acceleration, and its RK4 runs converge to the reference
  (the doubling sweep gets below 1e-8; each of its last two halvings of the
  step cuts the error at least 4 times, as long as it is above 1e-11; one
  more halving beyond the sweep cuts it again). A robot that fails a check
  has no MuJoCo numbers, and the output says why. lagmb is checked too: its
  joint accelerations at the start state (mb.solve_accelerations, read back
  by JointSpace.motion) equal pin.aba to 1e-8 relative.
- Forward dynamics: the time of one evaluation of the joint accelerations
  through Python (pin.aba; lagmb's mb.solve_accelerations on the Cartesian
  state; MuJoCo's qpos/qvel written, then mj_forward), best of 5 rounds of
  200.
- Time to error: each engine at a sweep of tolerances (lagmb's explicit
  method, projection-erk, and GGL; Pinocchio + DOP853) or of steps
  (MuJoCo's RK4, fixed steps of 1 s / n: n = 25, 50, 100, ... doubled until
  the error is below 1e-8, then for each target the fewest steps reaching
  it, by bisection on n between the doubling levels, to 1 %); the time to
  reach a joint-angle error of 1e-6 and 1e-8 is the fastest run whose error
  is below it. Runs are timed in --repeats rounds, each round every engine's
  every run once (the engines' order reversed every other round; a run
  shorter than 20 ms repeated within its round until 20 ms, at most 10
  times), the fastest time of all rounds kept. A MuJoCo run is
  mj_resetData, the start state written, mj_step(nstep = n) and the joint
  angles read; the model is built beforehand, as lagmb's and Pinocchio's.

    python bench/robots/robots.py [--robots ur5,panda,solo12,go1,talos] [--repeats 3] [--out bench/results/robots.json]
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

from bench.common.paths import RESULTS, robots_dir  # noqa: E402
from bench.common.timing import best_of  # noqa: E402

ROBOTS = {
    "ur5": "ur_description/urdf/ur5_robot.urdf",
    "panda": "panda_description/urdf/panda.urdf",
    "solo12": "solo_description/robots/solo12.urdf",
    "go1": "go1_description/urdf/go1.urdf",
    "talos": "talos_data/robots/talos_reduced.urdf",
}
TARGETS = (1e-6, 1e-8)
RTOLS = tuple(10.0 ** (-k / 2) for k in range(10, 25))


def angle_error(a, b):
    return float(np.max(np.abs(np.remainder(np.asarray(a) - np.asarray(b) + np.pi, 2 * np.pi) - np.pi)))


def timed(f, min_time=0.02, max_calls=10):
    """(fastest wall time, last value): f called until the calls add up to
    min_time seconds (at most max_calls times)."""
    fastest, total, calls, value = np.inf, 0.0, 0, None
    while total < min_time and calls < max_calls:
        t0 = time.perf_counter()
        value = f()
        seconds = time.perf_counter() - t0
        fastest, total, calls = min(fastest, seconds), total + seconds, calls + 1
    return fastest, value


MUJOCO = "mujoco rk4"
PINOCCHIO = "pinocchio aba + dop853"


def check_mujoco(path, names, pm, pd, start, state, reference, rtol=1e-8):
    """MuJoCo's model of the robot, checked against the bench's reference:
    (Rk4 runner, sweep points, check record), or (None, None, check record
    with "excluded": why)."""
    import pinocchio as pin

    from bench.robots import mujoco_urdf as mjb

    check = {}
    try:
        model, jmap = mjb.load(path, names)
        check["joints_mapped"] = True
        for label, (q, v) in (("start", start), ("evaluation", state)):
            aba = pin.aba(pm, pd, q, v, np.zeros(pm.nv))
            qacc = mjb.accelerations(model, jmap, q, v)
            check[f"qacc_vs_aba_{label}"] = float(np.max(np.abs(qacc - aba)) / np.max(np.abs(aba)))
            if not check[f"qacc_vs_aba_{label}"] <= rtol:
                raise mjb.Unmatched(f"mj_forward's qacc at the {label} state differs from pin.aba by "
                                    f"{check[f'qacc_vs_aba_{label}']:.1e} of the largest acceleration")
        rk4 = mjb.Rk4(model, jmap, *start)
        error_of = lambda end: angle_error(end, reference)
        points, doubling = mjb.search(rk4, error_of, TARGETS)
        check["rk4_doubling"] = doubling
        errors = [p.get("error", np.inf) for p in doubling]
        if not errors[-1] <= min(TARGETS):
            raise mjb.Unmatched(f"RK4 does not get below {min(TARGETS):g} of the reference by {doubling[-1]['steps']} "
                                f"steps (error {errors[-1]:.1e})")
        for a, b in zip(errors[-3:-1], errors[-2:]):
            if a > 1e-11 and not b <= a / 4:
                raise mjb.Unmatched(f"RK4 errors do not converge to the reference as the step halves: {errors}")
        finer = 2 * doubling[-1]["steps"]
        check["rk4_one_halving_more"] = {"steps": finer, "error": error_of(rk4.run(finer))}
        if not (check["rk4_one_halving_more"]["error"] <= errors[-1] / 4 or
                check["rk4_one_halving_more"]["error"] <= 1e-11):
            raise mjb.Unmatched(f"RK4 error does not fall further at {finer} steps "
                                f"({check['rk4_one_halving_more']['error']:.1e} after {errors[-1]:.1e})")
        check["rk4_orders"] = [float(np.log2(a / b)) for a, b in zip(errors, errors[1:]) if np.isfinite(a) and b > 0]
        return rk4, points, check
    except (mjb.Unmatched, mjb.Unstable, ValueError) as e:
        check["excluded"] = f"{type(e).__name__}: {e}"[:500]
        return None, None, check


def case(relpath, repeats):
    import pinocchio as pin
    from scipy.integrate import solve_ivp

    import lagmb as mb

    path = os.path.join(robots_dir(), relpath)
    model = mb.load_urdf(path, limits=False, dynamics=False, mimic=False)
    js = mb.JointSpace(model)
    pm = pin.buildModelFromUrdf(path)
    pm.gravity.linear[:] = (0.0, 0.0, -9.81)
    pd = pm.createData()
    names = [pm.names[j] for j in range(1, pm.njoints)]
    lagmb_names = [n if n in js.joints else f"{n}_joint" for n in names]
    rng = np.random.default_rng(1)
    rates = {name: rng.uniform(-1.0, 1.0) for name in js.joints}
    v0 = np.array([rates[n] for n in lagmb_names])
    assert pm.nq == pm.nv == len(names)

    def pinocchio_run(rtol):
        f = lambda t, y: np.concatenate([y[pm.nq:], pin.aba(pm, pd, y[:pm.nq], y[pm.nq:], np.zeros(pm.nv))])
        sol = solve_ivp(f, (0.0, 1.0), np.concatenate([pin.neutral(pm), v0]), method="DOP853", rtol=rtol,
                        atol=rtol)
        return sol.y[:pm.nq, -1]

    reference = pinocchio_run(1e-13)

    moving = js.with_rates(rates)  # from the zero configuration

    def lagmb_run(rtol, **method):
        r = mb.simulate(moving, 1.0, n_out=2, rtol=rtol, atol=1e-2 * rtol, **method)
        return np.array([js.motion(n, r.q[-1], r.v[-1])[0] for n in lagmb_names])

    # forward dynamics, one evaluation through Python
    x, xd = rng.uniform(-1, 1, pm.nq), rng.uniform(-1, 1, pm.nv)
    qc, vc, _ = js.coordinates(dict(zip(lagmb_names, x)), dict(zip(lagmb_names, xd)))

    # the checks against the reference, before timing
    checks = {}
    q0c, v0c, _ = js.coordinates({}, rates)
    qdd = mb.solve_accelerations(model, q0c, v0c)[0]
    aba0 = pin.aba(pm, pd, pin.neutral(pm), v0, np.zeros(pm.nv))
    ours = np.array([js.motion(n, q0c, v0c, qdd)[2] for n in lagmb_names])
    checks["lagmb"] = {"accelerations_vs_aba_start": float(np.max(np.abs(ours - aba0)) / np.max(np.abs(aba0)))}
    if not checks["lagmb"]["accelerations_vs_aba_start"] <= 1e-8:
        print(f"  {relpath}: lagmb's accelerations differ from pin.aba by "
              f"{checks['lagmb']['accelerations_vs_aba_start']:.1e} (relative)", file=sys.stderr)
    rk4, mujoco_points, checks["mujoco"] = check_mujoco(path, names, pm, pd, (pin.neutral(pm), v0), (x, xd),
                                                        reference)

    per_call = {}
    per_call["pinocchio"] = min(best_of(lambda: [pin.aba(pm, pd, x, xd, np.zeros(pm.nv)) for _ in range(200)], 5)[0]
                                for _ in range(1)) / 200
    per_call["lagmb"] = best_of(lambda: [mb.solve_accelerations(model, qc, vc) for _ in range(200)], 5)[0] / 200
    if rk4 is not None:
        per_call["mujoco"] = rk4.per_call(x, xd)

    engines = {
        "lagmb projection-erk": lambda rtol: lagmb_run(rtol, formulation="projection", integrator="erk"),
        "lagmb ggl": lambda rtol: lagmb_run(rtol),
        PINOCCHIO: pinocchio_run,
    }
    # each engine's runs: (level, run); a level's error is that of its first run
    levels = {engine: [("rtol", rtol) for rtol in RTOLS if not (engine == "lagmb ggl" and rtol < 1e-11)]
              for engine in engines}  # (GGL's BDF steps shrink to rounding below 1e-11)
    if rk4 is not None:
        engines[MUJOCO] = rk4.run
        levels[MUJOCO] = [("steps", p["steps"]) for p in mujoco_points if "error" in p]
    sweeps = {engine: [None] * len(levels[engine]) for engine in engines}
    if rk4 is not None:
        sweeps[MUJOCO] += [dict(p) for p in mujoco_points if "failed" in p]  # kept, not timed
    order = list(engines)
    for round_ in range(repeats):
        for engine in (order if round_ % 2 == 0 else order[::-1]):
            run = engines[engine]
            for i, (kind, level) in enumerate(levels[engine]):
                point = sweeps[engine][i]
                if point is not None and "failed" in point:
                    continue
                try:
                    seconds, end = timed(lambda: run(level))
                except mb.SimulationError as e:  # a failed run is a result too: kept, with why
                    sweeps[engine][i] = {kind: level, "failed": str(e)[:300]}
                    print(f"  {relpath} {engine} {kind} {level:.1e}: failed ({str(e)[:100]}...)", file=sys.stderr)
                    continue
                if point is None:
                    point = sweeps[engine][i] = {kind: level, "seconds": seconds, "error": angle_error(end, reference)}
                    if engine == MUJOCO:
                        point["step"] = 1.0 / level
                point["seconds"] = min(point["seconds"], seconds)
    if rk4 is not None:
        sweeps[MUJOCO].sort(key=lambda p: p["steps"])
    time_to = {engine: {str(target): min((p["seconds"] for p in points if p.get("error", np.inf) <= target),
                                         default=None)
                        for target in TARGETS} for engine, points in sweeps.items()}
    row = {"urdf": relpath, "joints": len(names), "bodies": len(model.bodies), "checks": checks,
           "evaluation_seconds": per_call, "sweeps": sweeps, "time_to_error": time_to}
    if rk4 is not None:
        row["mujoco_steps_to_error"] = {  # the steps of the run that gives the time
            str(target): min(((p["seconds"], p["steps"]) for p in sweeps[MUJOCO] if p.get("error", np.inf) <= target),
                             default=(None, None))[1] for target in TARGETS}
    return row


def fmt(seconds):
    return "-" if seconds is None else f"{seconds:.2g}" if seconds < 0.01 else f"{seconds:.3g}"


def ratio(a, b):
    return "-" if not (a and b) else f"{a / b:.2f}" if a / b < 1 else f"{a / b:.1f}" if a / b < 10 else f"{a / b:.0f}"


def lagmb_best(times, target):
    ours = [times[e][str(target)] for e in times if e.startswith("lagmb") and times[e][str(target)]]
    return min(ours) if ours else None


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default=",".join(ROBOTS))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(RESULTS, "robots.json"))
    args = parser.parse_args(argv)
    import mujoco
    import pinocchio as pin

    import lagmb as mb

    results = {"machine": platform.platform(), "lagmb": mb.__version__, "pinocchio": pin.__version__,
               "mujoco": mujoco.__version__, "date": time.strftime("%Y-%m-%d"), "robots": {}}
    header = f"{'robot':8} {'joints':>6} {'eval lagmb':>11} {'eval pin':>9} {'ratio':>6} {'eval mj':>9} {'ratio':>6}"
    for target in TARGETS:
        header += f" | to {target:g}: {'lagmb best':>11} {'pin+dop853':>10} {'ratio':>6} {'mujoco rk4':>10} " \
                  f"{'ratio':>6}"
    print(header)
    for key in args.robots.split(","):
        row = case(ROBOTS[key], args.repeats)
        results["robots"][key] = row
        ev = row["evaluation_seconds"]
        mj = ev.get("mujoco")
        line = f"{key:8} {row['joints']:6d} {ev['lagmb'] * 1e6:9.1f}us {ev['pinocchio'] * 1e6:7.1f}us " \
               f"{ev['lagmb'] / ev['pinocchio']:6.1f} " + \
               (f"{mj * 1e6:7.1f}us {ev['lagmb'] / mj:6.1f}" if mj else f"{'-':>9} {'-':>6}")
        for target in TARGETS:
            times = row["time_to_error"]
            mine = lagmb_best(times, target)
            theirs = times[PINOCCHIO][str(target)]
            mjt = times.get(MUJOCO, {}).get(str(target))
            r_pin = f"{mine / theirs:6.1f}" if mine and theirs else "     -"
            r_mj = f"{mine / mjt:6.1f}" if mine and mjt else "     -"
            line += f" | {'':>8} {mine if mine is None else round(mine, 4)!s:>11} " \
                    f"{theirs if theirs is None else round(theirs, 4)!s:>10} {r_pin} " \
                    f"{mjt if mjt is None else round(mjt, 4)!s:>10} {r_mj}"
        print(line, flush=True)
        if "excluded" in row["checks"]["mujoco"]:
            print(f"  {key}: MuJoCo left out: {row['checks']['mujoco']['excluded']}", flush=True)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as fh:
        json.dump(results, fh, indent=1)
    print(f"written {args.out}")

    # the same as markdown: seconds to each error; ratio = lagmb's best / the other's
    print()
    print("| robot | joints | eval lagmb / Pinocchio / MuJoCo (us) | "
          + " | ".join(f"to {t:g}: lagmb | Pinocchio | lagmb/Pin. | MuJoCo RK4 (steps) | lagmb/MuJoCo" for t in TARGETS)
          + " |")
    print("|---|---:|---:|" + "---:|" * (5 * len(TARGETS)))
    for key, row in results["robots"].items():
        ev, times = row["evaluation_seconds"], row["time_to_error"]
        evs = " / ".join(f"{ev[e] * 1e6:.1f}" if e in ev else "-" for e in ("lagmb", "pinocchio", "mujoco"))
        cells = []
        for target in TARGETS:
            mine, theirs = lagmb_best(times, target), times[PINOCCHIO][str(target)]
            mjt = times.get(MUJOCO, {}).get(str(target))
            steps = row.get("mujoco_steps_to_error", {}).get(str(target))
            cells += [fmt(mine), fmt(theirs), ratio(mine, theirs),
                      f"{fmt(mjt)} ({steps})" if mjt else "-", ratio(mine, mjt)]
        print(f"| {key} | {row['joints']} | {evs} | " + " | ".join(cells) + " |")
    for key, row in results["robots"].items():
        c = row["checks"]["mujoco"]
        if "excluded" in c:
            print(f"{key}: MuJoCo left out: {c['excluded']}")
        else:
            d, ours = c["rk4_doubling"], row["checks"]["lagmb"]["accelerations_vs_aba_start"]
            print(f"{key}: checks: lagmb accelerations vs pin.aba {ours:.1e}; "
                  f"MuJoCo qacc vs pin.aba {c['qacc_vs_aba_start']:.1e} (start), {c['qacc_vs_aba_evaluation']:.1e} "
                  f"(evaluation state); RK4 error by steps: " +
                  ", ".join(f"{p['steps']}: {p['error']:.1e}" if "error" in p else f"{p['steps']}: unstable" for p in d)
                  + f", {c['rk4_one_halving_more']['steps']}: {c['rk4_one_halving_more']['error']:.1e}")


if __name__ == "__main__":
    main()
