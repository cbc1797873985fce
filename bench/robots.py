"""Robots from example-robot-data: lagmb against Pinocchio, side by side.

For each robot (fixed base, its URDF read by mb.load_urdf with limits,
damping and mimic couplings left out, as Pinocchio builds it): the zero
configuration with random joint rates in [-1, 1] rad/s (seed 1, as
tests/test_urdf.py), 1 s of free motion.

- Reference: Pinocchio's ABA integrated by SciPy's DOP853 at rtol = atol =
  1e-13; every run below is measured against it (the largest joint-angle
  error at t = 1 s, mod 2 pi).
- Forward dynamics: the time of one evaluation of the joint accelerations
  through Python (pin.aba; lagmb's mb.solve_accelerations on the Cartesian
  state), best of 5 rounds of 200.
- Time to error: each engine at a sweep of tolerances (lagmb's explicit
  method, projection-erk, and GGL; Pinocchio + DOP853); the time to reach a
  joint-angle error of 1e-6 and 1e-8 is the fastest run whose error is
  below it (best of --repeats runs each).

MuJoCo is not in this table yet: its URDF import needs the meshes beside
the file (package:// names are not resolved).

    python bench/robots.py [--robots ur5,panda,solo12,talos] [--repeats 3] [--out bench/results/robots.json]
"""

import argparse
import json
import os
import platform
import site
import sys
import sysconfig
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROBOTS = {
    "ur5": "ur_description/urdf/ur5_robot.urdf",
    "panda": "panda_description/urdf/panda.urdf",
    "solo12": "solo_description/robots/solo12.urdf",
    "talos": "talos_data/robots/talos_reduced.urdf",
}
TARGETS = (1e-6, 1e-8)
RTOLS = tuple(10.0 ** (-k / 2) for k in range(10, 25))


def robots_dir():
    for base in sorted({sysconfig.get_paths()["purelib"], *site.getsitepackages()}):
        path = os.path.join(base, "cmeel.prefix", "share", "example-robot-data", "robots")
        if os.path.isdir(path):
            return path
    sys.exit("example-robot-data is not installed (pip install 'lagmb[robots]')")


def angle_error(a, b):
    return float(np.max(np.abs(np.remainder(np.asarray(a) - np.asarray(b) + np.pi, 2 * np.pi) - np.pi)))


def best(f, repeats):
    """(fastest wall time, last value) of `repeats` calls."""
    fastest, value = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        value = f()
        fastest = min(fastest, time.perf_counter() - t0)
    return fastest, value


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
    per_call = {}
    per_call["pinocchio"] = min(best(lambda: [pin.aba(pm, pd, x, xd, np.zeros(pm.nv)) for _ in range(200)], 5)[0]
                                for _ in range(1)) / 200
    per_call["lagmb"] = best(lambda: [mb.solve_accelerations(model, qc, vc) for _ in range(200)], 5)[0] / 200

    engines = {
        "lagmb projection-erk": lambda rtol: lagmb_run(rtol, formulation="projection", integrator="erk"),
        "lagmb ggl": lambda rtol: lagmb_run(rtol),
        "pinocchio aba + dop853": pinocchio_run,
    }
    sweeps = {}
    for engine, run in engines.items():
        points = []
        for rtol in RTOLS:
            if engine == "lagmb ggl" and rtol < 1e-11:
                continue  # (GGL's BDF steps shrink to rounding there)
            try:
                seconds, end = best(lambda: run(rtol), repeats)
            except mb.SimulationError as e:  # a failed run is a result too: kept, with why
                points.append({"rtol": rtol, "failed": str(e)[:300]})
                print(f"  {relpath} {engine} rtol {rtol:.1e}: failed ({str(e)[:100]}...)", file=sys.stderr)
                continue
            points.append({"rtol": rtol, "seconds": seconds, "error": angle_error(end, reference)})
        sweeps[engine] = points
    time_to = {engine: {str(target): min((p["seconds"] for p in points if p.get("error", np.inf) <= target),
                                         default=None)
                        for target in TARGETS} for engine, points in sweeps.items()}
    return {"urdf": relpath, "joints": len(names), "bodies": len(model.bodies),
            "evaluation_seconds": per_call, "sweeps": sweeps, "time_to_error": time_to}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", default=",".join(ROBOTS))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=os.path.join(HERE, "results", "robots.json"))
    args = parser.parse_args(argv)
    import lagmb as mb
    import pinocchio as pin

    results = {"machine": platform.platform(), "lagmb": mb.__version__, "pinocchio": pin.__version__,
               "date": time.strftime("%Y-%m-%d"), "robots": {}}
    header = f"{'robot':8} {'joints':>6} {'eval lagmb':>11} {'eval pin':>9} {'ratio':>6}"
    for target in TARGETS:
        header += f" | to {target:g}: {'lagmb best':>11} {'pin+dop853':>10} {'ratio':>6}"
    print(header)
    for key in args.robots.split(","):
        row = case(ROBOTS[key], args.repeats)
        results["robots"][key] = row
        ev = row["evaluation_seconds"]
        line = f"{key:8} {row['joints']:6d} {ev['lagmb'] * 1e6:9.1f}us {ev['pinocchio'] * 1e6:7.1f}us " \
               f"{ev['lagmb'] / ev['pinocchio']:6.1f}"
        for target in TARGETS:
            times = row["time_to_error"]
            ours = [times[e][str(target)] for e in times if e.startswith("lagmb") and times[e][str(target)]]
            theirs = times["pinocchio aba + dop853"][str(target)]
            mine = min(ours) if ours else None
            ratio = f"{mine / theirs:6.1f}" if mine and theirs else "     -"
            line += f" | {'':>8} {mine if mine is None else round(mine, 4)!s:>11} " \
                    f"{theirs if theirs is None else round(theirs, 4)!s:>10} {ratio}"
        print(line, flush=True)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as fh:
        json.dump(results, fh, indent=1)
    print(f"written {args.out}")


if __name__ == "__main__":
    main()
