"""Go1 standing on servos: lagmb against MuJoCo at matched final error.

Unitree Go1 (example-robot-data's URDF, the model of contact_peers.py's go1
scene: contact_scenes.lagmb_go1 / mujoco_go1, its joint limits, damping and
friction on, 38 contacts with the floor 0.35 m below the base frame) with
a servo on each of its 12 joints holding a standing pose: hips 0, thighs
a, calves -2 a, a = acos(0.329 / 0.426), which puts the feet' spheres (r
0.02 m at 0.213 + 0.213 m legs) 1 mm above the floor at the start. lagmb:
m.add_servo(joint, target=pose, kp=KP, kd=KD); MuJoCo: a position actuator
on each joint with the same kp and kv = KD, ctrl = the pose. It falls the
millimetre, lands on its four feet, the legs give under the weight until
the servos carry it, and it stands (3 s).

Physics checked before timing: at 3 s the feet' normal forces sum to the
weight in both engines (within 0.5 %) and each foot's force is printed for
both (they agree to the differences of the contact laws: Hertz against
MuJoCo's soft constraints, the weight shared among four feet by the servos'
compliance).

Measure: the final (t = 3 s) height of the base's centre of mass, each
engine against its own reference (lagmb rtol 1e-10, atol 1e-12, checked
against 1e-9; MuJoCo implicitfast at 2.5e-6 s, checked against 5e-6 s), and
the largest difference of a foot's normal force from the reference's.
lagmb at rtol 1e-1 .. 1e-7 (atol 1e-2 rtol); MuJoCo implicitfast on the
grid 2 ms * 2^(-k/2). For each target error (1e-3, 1e-4, 1e-5 m) each
engine's cheapest setting from which it and every finer one of its grid
(MuJoCo: the next two finer) reach the target; those settings are timed
in interleaved rounds (order reversed every other round, median of
--repeat), and the ratio lagmb / MuJoCo is the result.

Also: lagmb's counts (steps, residual evaluations, Newton iterations,
Jacobian evaluations, root evaluations, events) per setting, and its steps
in the last second standing against the same robot in free flight (no
floor) over the same second: at rest the steps should be as long.
--diagnose: lagmb at rtol 1e-2 on variants of its model (interleaved):
the feet' 4 contacts alone (the other 34 shapes never touch: the same
motion), and, to see what its Newton iterations fail on, without the
joints' damping and friction, with the feet's slip_velocity 1e-2 m/s, both,
and without any friction (not the same physics).

    python bench/peers/go1_stand.py [--repeat 5] [--diagnose] [--out bench/results/go1_stand.json]
"""

import argparse
import json
import math
import os
import statistics
import sys
import time
import warnings

if not __package__:  # run as a file: the repository root on the path, for `import bench`
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.record import one_blas_thread  # noqa: E402

one_blas_thread()

import numpy as np  # noqa: E402

from bench.common.paths import RESULTS, robots_dir  # noqa: E402
from bench.common.record import run_versions  # noqa: E402
from bench.peers import contact_scenes as scenes  # noqa: E402

T_END = 3.0
T_REST = 2.0         # "at rest": the steps from here to T_END
KP, KD = 100.0, 1.0  # N m/rad, N m s/rad
LEGS = ("FR", "FL", "RR", "RL")
THIGH = math.acos(0.329 / 0.426)
POSE = {**{f"{leg}_hip_joint": 0.0 for leg in LEGS}, **{f"{leg}_thigh_joint": THIGH for leg in LEGS},
        **{f"{leg}_calf_joint": -2.0 * THIGH for leg in LEGS}}
RESTITUTION = 0.136  # contact_peers.py's calibration: MuJoCo's rebound with its default contact
LAGMB_RTOLS = (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 1e-6, 1e-7)
LAGMB_REF, LAGMB_REF_CHECK = (1e-10, 1e-12), (1e-9, 1e-11)
MJ_DTS = tuple(2e-3 * 2 ** (-k / 2) for k in range(13))  # 2 ms .. 31 us
MJ_REF_DT, MJ_REF_CHECK_DT = 2.5e-6, 5e-6
TARGETS = (1e-3, 1e-4, 1e-5)


def go1_path():
    return os.path.join(robots_dir(), scenes.GO1)


# --------------------------------------------------------------------------
# lagmb
# --------------------------------------------------------------------------

def lagmb_stand(path, ground=True, dynamics=True, contact=None, feet_only=False):
    """The standing robot; the keywords make --diagnose's variants: without
    the joints' damping and friction, another contact law, or contacts of
    the feet alone (the other 34 shapes never touch while it stands)."""
    import lagmb as mb
    from lagmb.urdf.elements import contact_law

    law = {"restitution": RESTITUTION, **(contact or {})}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        m = mb.load_urdf(path, floating_base=True, ground=scenes.GO1_FLOOR if ground and not feet_only else None,
                         positions=POSE, dynamics=dynamics, contact=law if ground and not feet_only else None)
    if feet_only:
        floor = m.add_shape("ground", "plane", (), position=(0.0, 0.0, scenes.GO1_FLOOR), role="collision")
        for shape in list(m.shapes):
            if shape.kind == "sphere" and shape.role == "collision":
                m.add_contact(f"{shape.body[:2]}_foot_ground", shape, floor, **contact_law(law))
    for joint, angle in POSE.items():
        m.add_servo(f"{joint}_servo", joint, target=angle, kp=KP, kd=KD)
    return m


class LagmbStand:
    engine = "lagmb"

    def __init__(self, model):
        import lagmb as mb

        self.mb, self.model = mb, model
        contacts = [kw["name"] for kind, kw in model.elements if kind == "add_contact"]
        self.feet = {leg: next(c for c in contacts if c.startswith(f"{leg}_foot")) for leg in LEGS}
        self.mass = sum(kw["mass"] for kind, kw in model.elements if kind == "add_body")
        model.compiled()

    def run(self, rtol, t_end=T_END, keep=False):
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = self.mb.simulate(self.model, t_end, rtol=rtol, atol=1e-2 * rtol, n_out=31)
        wall = time.perf_counter() - t0
        out = {"time": wall, "height": float(r.body("base").position[-1, 2])}
        if keep:
            out["feet"] = {leg: float(r.contact(c).normal_force[-1]) for leg, c in self.feet.items()}
            out["stats"] = {k: (v if isinstance(v, (int, float, str)) else str(v)) for k, v in r.stats.items()}
        return out


# --------------------------------------------------------------------------
# MuJoCo
# --------------------------------------------------------------------------

def mujoco_stand(path):
    import mujoco

    spec = scenes.mujoco_go1_spec(path, {"cone": "elliptic", "impratio": 1.0})
    for joint in POSE:
        act = spec.add_actuator()
        act.name, act.target, act.trntype = f"{joint}_servo", joint, mujoco.mjtTrn.mjTRN_JOINT
        act.set_to_position(kp=KP, kv=KD)
    return spec.compile()


class MujocoStand:
    engine = "mujoco"

    def __init__(self, model):
        import mujoco

        self.mj, self.model, self.data = mujoco, model, mujoco.MjData(model)
        self.base = model.body("base").id
        self.qpos0 = model.qpos0.copy()
        self.qpos0[:3], self.qpos0[3:7] = 0.0, (1.0, 0.0, 0.0, 0.0)
        for joint, angle in POSE.items():
            self.qpos0[model.jnt_qposadr[model.joint(joint).id]] = angle
        self.ctrl = np.array([POSE[model.actuator(i).name[:-len("_servo")]] for i in range(model.nu)])
        # the foot geoms (the spheres of the calf bodies) by leg
        self.feet = {}
        for g in range(model.ngeom):
            if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_SPHERE:
                self.feet[g] = model.body(model.geom_bodyid[g]).name[:2]
        self.mass = float(model.body_mass.sum())

    def reset(self, dt):
        mj, m, d = self.mj, self.model, self.data
        m.opt.timestep = dt
        mj.mj_resetData(m, d)
        d.qpos[:] = self.qpos0
        d.ctrl[:] = self.ctrl
        mj.mj_forward(m, d)

    def run(self, dt, keep=False):
        mj, m, d = self.mj, self.model, self.data
        n = max(1, round(T_END / dt))
        self.reset(T_END / n)
        t0 = time.perf_counter()
        mj.mj_step(m, d, nstep=n)
        wall = time.perf_counter() - t0
        if not np.all(np.isfinite(d.qpos)):
            raise RuntimeError(f"MuJoCo unstable at dt = {T_END / n:g}")
        mj.mj_forward(m, d)
        out = {"time": wall, "height": float(d.xipos[self.base, 2]), "steps": n}
        if keep:
            feet = dict.fromkeys(LEGS, 0.0)
            f6 = np.zeros(6)
            for i in range(d.ncon):
                c = d.contact[i]
                g = c.geom1 if c.geom1 in self.feet else c.geom2 if c.geom2 in self.feet else None
                if g is None:
                    continue
                mj.mj_contactForce(m, d, i, f6)
                feet[self.feet[g]] += float(f6[0])
            out["feet"] = feet
            out["contacts"] = int(d.ncon)
        return out


# --------------------------------------------------------------------------
# measures
# --------------------------------------------------------------------------

def errors(run, ref):
    return {"height": abs(run["height"] - ref["height"]),
            "feet": max(abs(run["feet"][leg] - ref["feet"][leg]) for leg in LEGS)}


def cheapest(rows, target, finer_needed):
    """The first row (loosest setting) from which it and the next
    `finer_needed` rows (all the rest where None) reach `target`."""
    for i, row in enumerate(rows):
        rest = rows[i:] if finer_needed is None else rows[i:i + 1 + finer_needed]
        if len(rest) >= (1 if finer_needed is None else 1 + finer_needed) and all(
                r["error"]["height"] <= target for r in rest):
            return i
    return None


def lagmb_rest_steps(path, rtol):
    """Steps from T_REST to T_END standing, and in free flight (no floor)."""
    import lagmb as mb

    out = {}
    for label, ground in (("standing", True), ("free flight", False)):
        m = lagmb_stand(path, ground=ground)
        counts = []
        for t in (T_REST, T_END):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                r = mb.simulate(m, t, rtol=rtol, atol=1e-2 * rtol, n_out=2)
            counts.append(int(r.stats["steps"]))
        out[label] = counts[1] - counts[0]
    return out


DIAGNOSE = {"as benchmarked": {}, "feet' contacts alone (the same motion)": {"feet_only": True},
            "no joint damping and friction": {"dynamics": False},
            "feet slip_velocity 1e-2 (1e-4)": {"contact": {"slip_velocity": 1e-2}},
            "both": {"dynamics": False, "contact": {"slip_velocity": 1e-2}},
            "no joint friction, no contact friction": {"dynamics": False, "contact": {"friction": 0.0}}}


def diagnose(path, repeat, log, rtol=1e-2):
    """Where lagmb's time goes: the counts and times of variants of the
    model (not the same physics but the first two), interleaved."""
    runs = {label: LagmbStand(lagmb_stand(path, **kw)) for label, kw in DIAGNOSE.items()}
    times = {label: [] for label in runs}
    out = {}
    for rnd in range(repeat):
        for label in (list(runs) if rnd % 2 == 0 else list(runs)[::-1]):
            run = runs[label].run(rtol, keep=True)
            times[label].append(run["time"])
            out[label] = {"height": run["height"], "stats": run["stats"]}
    for label, row in out.items():
        s = row["stats"]
        row["median"] = statistics.median(times[label])
        log(f"  {label}: {row['median']:.3f} s, steps {s['steps']}, residuals {s['residual_evals']}, Jacobians "
            f"{s['jacobian_evals']}, convergence fails {s['convergence_failures']}, error-test fails "
            f"{s['error_test_failures']}, LU nonzeros {s['lu_nonzeros']}, base height {row['height']:.7f} m")
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--repeat", type=int, default=5, help="timed rounds; the median is reported")
    p.add_argument("--out", default=os.path.join(RESULTS, "go1_stand.json"))
    p.add_argument("--diagnose", action="store_true", help="also time variants of lagmb's model at rtol 1e-2")
    args = p.parse_args()

    def log(msg=""):
        print(msg, flush=True)

    import lagmb as mb
    import mujoco

    versions = run_versions(mb, mujoco=mujoco.__version__, numpy=np.__version__)
    doc = {"benchmark": "go1_stand", "date": time.strftime("%Y-%m-%d %H:%M"), "versions": versions,
           "kp": KP, "kd": KD, "pose": POSE, "restitution": RESTITUTION, "t_end": T_END}
    path = go1_path()
    lag = LagmbStand(lagmb_stand(path))
    mjs = MujocoStand(mujoco_stand(path))
    weight = scenes.G * lag.mass
    log(f"Go1 standing on servos (kp {KP}, kd {KD}), {T_END} s; mass lagmb {lag.mass:.4f} kg, MuJoCo "
        f"{mjs.mass:.4f} kg; {', '.join(f'{k} {v}' for k, v in versions.items())}")

    # references and the physics check
    lref = lag.run(LAGMB_REF[0], keep=True)
    lchk = lag.run(LAGMB_REF_CHECK[0], keep=True)
    mref = mjs.run(MJ_REF_DT, keep=True)
    mchk = mjs.run(MJ_REF_CHECK_DT, keep=True)
    check = {"lagmb_feet": lref["feet"], "mujoco_feet": mref["feet"],
             "lagmb_feet_over_weight": sum(lref["feet"].values()) / weight,
             "mujoco_feet_over_weight": sum(mref["feet"].values()) / weight,
             "base_height": [lref["height"], mref["height"]],
             "lagmb_reference_check": errors(lchk, lref), "mujoco_reference_check": errors(mchk, mref)}
    doc["check"] = check
    log("check at 3 s: foot normal forces (N) " + ", ".join(
        f"{leg} {lref['feet'][leg]:.3f} / {mref['feet'][leg]:.3f}" for leg in LEGS) +
        f" (lagmb / MuJoCo); sums / weight {check['lagmb_feet_over_weight']:.5f} / "
        f"{check['mujoco_feet_over_weight']:.5f}; base height {lref['height']:.5f} / {mref['height']:.5f} m")
    log(f"references: lagmb rtol 1e-10 ({lref['time']:.1f} s; 1e-9 differs by "
        f"{check['lagmb_reference_check']['height']:.1e} m, feet {check['lagmb_reference_check']['feet']:.1e} N), "
        f"MuJoCo {MJ_REF_DT:g} s ({mref['time']:.1f} s; {MJ_REF_CHECK_DT:g} s differs by "
        f"{check['mujoco_reference_check']['height']:.1e} m, feet {check['mujoco_reference_check']['feet']:.1e} N)")
    if not (abs(check["lagmb_feet_over_weight"] - 1) < 5e-3 and abs(check["mujoco_feet_over_weight"] - 1) < 5e-3):
        log("WARNING: the feet do not carry the weight at 3 s")

    # the grids, untimed once
    lrows = []
    for rtol in LAGMB_RTOLS:
        run = lag.run(rtol, keep=True)
        lrows.append({"setting": rtol, "error": errors(run, lref), "time": run["time"], "stats": run["stats"]})
        s = run["stats"]
        log(f"  lagmb rtol {rtol:g}: height error {lrows[-1]['error']['height']:.1e} m, feet "
            f"{lrows[-1]['error']['feet']:.1e} N, {run['time']:.3f} s; steps {s.get('steps')}, residuals "
            f"{s.get('residual_evals')}, Newton {s.get('newton_iterations')}, Jacobians {s.get('jacobian_evals')}, "
            f"LU {s.get('lu_factorizations')}, roots {s.get('root_evals')}, events {s.get('events')}, restarts {s.get('restarts')}, "
            f"error-test fails {s.get('error_test_failures')}, convergence fails {s.get('convergence_failures')}")
    mrows = []
    for dt in MJ_DTS:
        run = mjs.run(dt, keep=True)
        mrows.append({"setting": dt, "error": errors(run, mref), "time": run["time"]})
        log(f"  MuJoCo {dt * 1e3:.3g} ms: height error {mrows[-1]['error']['height']:.1e} m, feet "
            f"{mrows[-1]['error']['feet']:.1e} N, {run['time']:.3f} s")
    doc["lagmb_grid"], doc["mujoco_grid"] = lrows, mrows
    doc["rest_steps"] = {rtol: lagmb_rest_steps(path, rtol) for rtol in (1e-3, 1e-4)}
    for rtol, s in doc["rest_steps"].items():
        log(f"  lagmb rtol {rtol:g}, steps from {T_REST} to {T_END} s: standing {s['standing']}, free flight "
            f"{s['free flight']}")

    if args.diagnose:
        log(f"lagmb variants at rtol 1e-2 (median of {args.repeat}, interleaved):")
        doc["diagnose"] = diagnose(path, args.repeat, log)

    # the matched settings, timed interleaved
    chosen = {}
    for target in TARGETS:
        i, j = cheapest(lrows, target, None), cheapest(mrows, target, 2)
        chosen[target] = (None if i is None else LAGMB_RTOLS[i], None if j is None else MJ_DTS[j])
    timed = sorted({("lagmb", c[0]) for c in chosen.values() if c[0]} | {("mujoco", c[1]) for c in chosen.values()
                                                                          if c[1]} | {("mujoco", MJ_DTS[0])})
    times = {k: [] for k in timed}
    for rnd in range(args.repeat):
        for key in (timed if rnd % 2 == 0 else timed[::-1]):
            engine, setting = key
            times[key].append((lag if engine == "lagmb" else mjs).run(setting)["time"])
    med = {k: statistics.median(v) for k, v in times.items()}
    doc["times"] = [{"engine": e, "setting": s, "times": times[(e, s)], "median": med[(e, s)]} for e, s in timed]
    lines = ["| final error of base height | lagmb rtol | lagmb (s) | MuJoCo step | MuJoCo (s) | lagmb / MuJoCo |",
             "|---:|---:|---:|---:|---:|---:|"]
    doc["matched"] = []
    for target, (rtol, dt) in chosen.items():
        tl = med[("lagmb", rtol)] if rtol else None
        tm = med[("mujoco", dt)] if dt else None
        ratio = tl / tm if tl and tm else None
        doc["matched"].append({"target": target, "rtol": rtol, "dt": dt, "lagmb": tl, "mujoco": tm, "ratio": ratio})
        lines.append(f"| {target:.0e} m | {rtol if rtol else '-'} | {tl if tl else float('nan'):.3f} | "
                     f"{dt * 1e3 if dt else float('nan'):.3g} ms | {tm if tm else float('nan'):.3f} | "
                     f"{ratio if ratio else float('nan'):.2f} |")
    lines.append(f"| (MuJoCo at 2 ms) | | | 2 ms | {med[('mujoco', MJ_DTS[0])]:.3f} | |")
    table = "\n".join(lines)
    log("")
    log(table)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(doc, f, indent=1, default=str)
    with open(os.path.splitext(args.out)[0] + ".md", "w") as f:
        f.write(f"# Go1 standing on servos: lagmb against MuJoCo (bench/peers/go1_stand.py, {doc['date']})\n\n"
                f"median of {args.repeat} interleaved rounds\n\n{table}\n")
    log(f"written {args.out}")


if __name__ == "__main__":
    main()
