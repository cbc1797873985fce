"""A joint-space PD controller with gravity compensation on the Franka Panda
at 1 kHz for 2 s: lagmb's Simulator driven from Python, lagmb's in-model
servo, and MuJoCo's mj_step loop, side by side.

The arm: example-robot-data's panda URDF (found as bench/robots/robots.py finds
robots) with its <visual>/<collision> elements taken out and the two finger
slides made fixed joints (the hand and fingers are one rigid body with
link 7), so that every engine sees the same 7-joint tree; lagmb reads it
with mb.load_urdf(limits=False, dynamics=False), Pinocchio with
buildModelFromUrdf, MuJoCo with its URDF reader as bench/robots/mujoco_urdf.py
builds it (damping, armature, limits off; contacts and constraints
disabled). Gravity (0, 0, -9.81). Joints are matched by name.

The control law, the same everywhere: start at rest in q0 (the usual
"ready" pose (0, -0.785, 0, -2.356, 0, 1.571, 0.785)), target
q* = q0 + (0.3, -0.3, 0.3, 0.3, -0.3, 0.3, 0.3) rad, fixed;

    tau = Kp (q* - q) - Kd q' + g(q)

with per-joint gains scaled to the joint-space inertia at q0, Kp_i =
w^2 M_ii(q0), Kd_i = 2 zeta w M_ii(q0), w = 10 rad/s, zeta = 0.5 (M_ii
from 0.0067 kg m^2 at joint 7 to 1.55 at joint 2; one Kd = 20 N m s/rad for
all joints would make the 1 kHz sampled loop unstable at joint 7: Kd h /
M_77 = 3 > 2). The arm is still moving at 2 s (about 0.01 rad from q*).

Two systems, each with its own reference:

- sampled (1 kHz, zero-order hold): at each tick t_k = k ms the state is
  read, tau computed (g(q): Pinocchio's computeGeneralizedGravity) and held
  until the next tick.
  * lagmb Simulator loop: a rotational spring-damper with torque
    mb.Input on each joint; per tick the joint angles and rates by
    sim.joints(names) (one call), tau, one sim.set_inputs({...}), then
    sim.advance(sim.t + 1 ms). Methods: auto (projection-erk here) at rtol
    1e-6 and 1e-8, GGL at 1e-6, and the fixed-step ali3p with step 1 ms.
  * MuJoCo loop: per tick qpos/qvel read, the same tau (Pinocchio's g(q))
    written to data.qfrc_applied, mj_step; Euler (MuJoCo's default) and
    RK4, timestep 1 ms.
  Reference: the lagmb loop at rtol 1e-11 (atol 1e-13); checked against
  the lagmb loop at 1e-10, Pinocchio's ABA integrated by SciPy's DOP853 at
  rtol = atol = 1e-12 from tick to tick, and MuJoCo's RK4 loop with 100
  substeps of 1e-5 s per tick (tau held over the substeps).
- continuous (the law evaluated inside the integrator):
  * lagmb in-model servo: m.add_servo(joint, target=q*, kp, kd) on each
    joint and, for g(q), a force +m_i g (upward) at the centre of mass of
    each moving body (m.add_force), which cancels gravity on the arm
    exactly, as g(q) does; one mb.simulate(m, 2.0, n_out=2). Methods: auto
    (its choice is printed: projection-erk since the forces' rates are
    taken with the joints' inverse mass) and GGL, rtol 1e-6 and 1e-8.
  * MuJoCo in-model: position actuators (kp, kv) on the joints, ctrl = q*,
    every body's gravcomp = 1 (MuJoCo's upward m_i g at the centre of
    mass); one mj_step(nstep=2000) call at 1 ms, Euler and RK4.
  Reference: the lagmb servo at rtol 1e-11 (GGL, atol 1e-13); checked
  against the servo by projection-erk at 1e-11, Pinocchio ABA + DOP853 at
  1e-12 on the same law, and MuJoCo's in-model RK4 at 1e-5 s.

Every row is first checked against its system's reference: the error is
the largest joint-angle difference (rad, over joints) at t = 2 s ("final")
and over all 2001 ticks ("max"; for the in-model rows from a second run
with outputs at every tick: the same steps for GGL and MuJoCo, other steps
for projection-erk, which stops at each output, so its "max" is shown in
parentheses). Then all rows are timed in --repeat interleaved rounds (the
order reversed every other round), one whole 2 s run each (the Simulator's
construction, MuJoCo's mj_resetData included; model building not), and
the median is reported with the ratio to the MuJoCo Euler loop's median.
After the rounds, one instrumented run of the lagmb loop (auto, rtol 1e-6)
splits a tick's time into its parts.

    python bench/robots/control_loop.py [--repeat 5] [--out bench/results/control_loop.json]

writes the JSON and a Markdown table beside it (control_loop.md).
"""

import argparse
import json
import os
import platform
import statistics
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.paths import RESULTS, robots_dir  # noqa: E402
from bench.common.record import run_versions  # noqa: E402
from bench.robots import mujoco_urdf as mjb  # noqa: E402
from bench.robots.robots import ROBOTS, angle_error  # noqa: E402


Q0 = {"panda_joint1": 0.0, "panda_joint2": -0.785, "panda_joint3": 0.0, "panda_joint4": -2.356,
      "panda_joint5": 0.0, "panda_joint6": 1.571, "panda_joint7": 0.785}
OFFSET = np.array([0.3, -0.3, 0.3, 0.3, -0.3, 0.3, 0.3])
OMEGA, ZETA = 10.0, 0.5
GRAVITY = 9.81
TICK, TICKS = 1e-3, 2000
T_END = TICK * TICKS
RTOLS = (1e-6, 1e-8)
REF_RTOL = 1e-11
BASE = ("MuJoCo mj_step loop", "euler 1 ms")  # the row the last column divides by


def arm_urdf(directory):
    """The panda URDF without visuals and collisions, its finger slides fixed."""
    root = ET.parse(os.path.join(robots_dir(), ROBOTS["panda"])).getroot()
    for link in root.iter("link"):
        for tag in ("visual", "collision"):
            for element in link.findall(tag):
                link.remove(element)
    fixed = []
    for joint in root.iter("joint"):
        if joint.get("type") == "prismatic":
            joint.set("type", "fixed")
            fixed.append(joint.get("name"))
            for tag in ("limit", "mimic", "dynamics", "axis"):
                for element in joint.findall(tag):
                    joint.remove(element)
    path = os.path.join(directory, "panda_arm.urdf")
    ET.ElementTree(root).write(path)
    return path, fixed


class Arm:
    """The URDF, the joints, q0, q*, the gains and Pinocchio's model."""

    def __init__(self, path):
        import pinocchio as pin

        self.pin, self.path = pin, path
        self.pm = pin.buildModelFromUrdf(path)
        self.pm.gravity.linear[:] = (0.0, 0.0, -GRAVITY)
        self.pd = self.pm.createData()
        self.names = [self.pm.names[j] for j in range(1, self.pm.njoints)]
        assert self.names == list(Q0) and self.pm.nq == self.pm.nv == 7, self.names
        self.q0 = np.array([Q0[n] for n in self.names])
        self.target = self.q0 + OFFSET
        self.inertia = np.diag(pin.crba(self.pm, self.pd, self.q0)).copy()
        self.kp = OMEGA ** 2 * self.inertia
        self.kd = 2 * ZETA * OMEGA * self.inertia

    def gravity(self, q):
        return self.pin.computeGeneralizedGravity(self.pm, self.pd, q)

    def torque(self, q, v):
        return self.kp * (self.target - q) - self.kd * v + self.gravity(q)


# ---------------------------------------------------------------- lagmb

def lagmb_loop_model(arm):
    import lagmb as mb

    m = mb.load_urdf(arm.path, limits=False, dynamics=False, positions=Q0)
    for n in arm.names:
        m.add_rotational_spring_damper(f"{n}_motor", n, torque=mb.Input(0.0))
    return m, mb.JointSpace(m)


def lagmb_servo_model(arm):
    import lagmb as mb

    m = mb.load_urdf(arm.path, limits=False, dynamics=False, positions=Q0)
    for n, target, kp, kd in zip(arm.names, arm.target, arm.kp, arm.kd):
        m.add_servo(f"{n}_servo", n, target=float(target), kp=float(kp), kd=float(kd))
    masses = {}
    for kind, data in m.elements:
        if kind == "add_body":
            masses[data["name"]] = data["mass"]
            m.add_force(f"{data['name']}_gravity_compensation", data["name"],
                        force=(0.0, 0.0, data["mass"] * GRAVITY))
    return m, mb.JointSpace(m), masses


def lagmb_loop(model, js, arm, timers=None, **options):
    """The 1 kHz loop: (joint angles at every tick (TICKS + 1, 7), simulator)."""
    import lagmb as mb

    names = arm.names
    inputs = [f"{n}_motor" for n in names]
    out = np.empty((TICKS + 1, len(names)))
    sim = mb.Simulator(model, **options)
    clock = time.perf_counter
    for k in range(TICKS + 1):
        if timers is None:
            theta, rate = sim.joints(names)
            out[k] = theta
            if k == TICKS:
                break
            tau = arm.torque(theta, rate)
            sim.set_inputs(dict(zip(inputs, tau)))
            sim.advance(sim.t + TICK)
        else:  # the same, each part timed
            t0 = clock()
            theta, rate = sim.joints(names)
            out[k] = theta
            t1 = clock()
            if k == TICKS:
                break
            tau = arm.torque(theta, rate)
            t2 = clock()
            sim.set_inputs(dict(zip(inputs, tau)))
            t3 = clock()
            sim.advance(sim.t + TICK)
            t4 = clock()
            for key, dt in (("sim.joints", t1 - t0), ("tau (Pinocchio g(q) + PD)", t2 - t1),
                            ("sim.set_inputs", t3 - t2), ("advance", t4 - t3)):
                timers[key] = timers.get(key, 0.0) + dt
    return out, sim


def lagmb_servo(model, js, arm, ticks=False, **options):
    """One simulate call: joint angles at the end (7,) or at every tick."""
    import lagmb as mb

    if ticks:
        r = mb.simulate(model, T_END, t_out=np.arange(TICKS + 1) * TICK, **options)
    else:
        r = mb.simulate(model, T_END, n_out=2, **options)
    q = np.array([js.motion(n, r.q, r.v)[:, 0] for n in arm.names]).T
    return (q if ticks else q[-1]), r


def lagmb_options(method, rtol=None, step=None):
    options = {} if method == "auto" else {"method": method}
    if rtol is not None:
        options.update(rtol=rtol, atol=1e-2 * rtol)
    if step is not None:
        options["step"] = step
    return options


# ---------------------------------------------------------------- MuJoCo

INTEGRATORS = {"euler": "mjINT_EULER", "rk4": "mjINT_RK4"}


def mujoco_loop_model(arm):
    model, jmap = mjb.load(arm.path, arm.names)
    return model, jmap


def mujoco_servo_model(arm):
    import mujoco

    spec = mjb._spec(arm.path)
    for body in spec.bodies:
        if body.name != "world":
            body.gravcomp = 1.0
    for n, kp, kd in zip(arm.names, arm.kp, arm.kd):
        actuator = spec.add_actuator()
        actuator.name = f"{n}_servo"
        actuator.target = n
        actuator.trntype = mujoco.mjtTrn.mjTRN_JOINT
        actuator.set_to_position(kp=float(kp), kv=float(kd))
    model = spec.compile()
    jmap = mjb.JointMap(model, arm.names)
    order = [model.actuator(f"{n}_servo").id for n in arm.names]
    return model, jmap, order


def mujoco_loop(model, jmap, arm, integrator, dt=TICK):
    """The 1 kHz loop, tau held over TICK / dt substeps of dt: joint angles at every tick."""
    import mujoco

    model.opt.integrator = getattr(mujoco.mjtIntegrator, INTEGRATORS[integrator])
    model.opt.timestep = dt
    substeps = round(TICK / dt)
    data = mujoco.MjData(model)
    mujoco.mj_resetData(model, data)
    qadr, vadr = jmap.qadr, jmap.vadr
    data.qpos[qadr] = arm.q0
    out = np.empty((TICKS + 1, len(qadr)))
    step = mujoco.mj_step
    for k in range(TICKS + 1):
        q = data.qpos[qadr]
        out[k] = q
        if k == TICKS:
            break
        data.qfrc_applied[vadr] = arm.torque(q, data.qvel[vadr])
        if substeps == 1:
            step(model, data)
        else:
            step(model, data, nstep=substeps)
    return out


def mujoco_servo(model, jmap, order, arm, integrator, dt=TICK, ticks=False):
    """The in-model law: one mj_step(nstep) call (ticks=True: one call per tick, the same arithmetic)."""
    import mujoco

    model.opt.integrator = getattr(mujoco.mjtIntegrator, INTEGRATORS[integrator])
    model.opt.timestep = dt
    data = mujoco.MjData(model)
    mujoco.mj_resetData(model, data)
    data.qpos[jmap.qadr] = arm.q0
    data.ctrl[order] = arm.target
    per_tick = round(TICK / dt)
    if not ticks:
        mujoco.mj_step(model, data, nstep=per_tick * TICKS)
        return data.qpos[jmap.qadr].copy()
    out = np.empty((TICKS + 1, 7))
    out[0] = data.qpos[jmap.qadr]
    for k in range(TICKS):
        mujoco.mj_step(model, data, nstep=per_tick)
        out[k + 1] = data.qpos[jmap.qadr]
    return out


# ---------------------------------------------------------------- Pinocchio + DOP853 (checks)

def pinocchio_sampled(arm, rtol=1e-12):
    from scipy.integrate import solve_ivp

    pin, pm, pd = arm.pin, arm.pm, arm.pd
    y = np.concatenate([arm.q0, np.zeros(7)])
    out = np.empty((TICKS + 1, 7))
    for k in range(TICKS + 1):
        out[k] = y[:7]
        if k == TICKS:
            break
        tau = arm.torque(y[:7], y[7:])
        f = lambda t, x: np.concatenate([x[7:], pin.aba(pm, pd, x[:7], x[7:], tau)])  # noqa: E731
        y = solve_ivp(f, (k * TICK, (k + 1) * TICK), y, method="DOP853", rtol=rtol, atol=rtol).y[:, -1]
    return out


def pinocchio_continuous(arm, rtol=1e-12):
    from scipy.integrate import solve_ivp

    pin, pm, pd = arm.pin, arm.pm, arm.pd
    f = lambda t, x: np.concatenate([x[7:], pin.aba(pm, pd, x[:7], x[7:], arm.torque(x[:7], x[7:]))])  # noqa: E731
    sol = solve_ivp(f, (0.0, T_END), np.concatenate([arm.q0, np.zeros(7)]), method="DOP853", rtol=rtol,
                    atol=rtol, t_eval=np.arange(TICKS + 1) * TICK)
    return sol.y[:7].T


# ---------------------------------------------------------------- the bench

def errors(run, reference):
    """(final, max over ticks) joint-angle error; run: (TICKS + 1, 7) or the end (7,)."""
    run = np.asarray(run)
    final = angle_error(run[-1] if run.ndim == 2 else run, reference[-1])
    return final, (angle_error(run, reference) if run.ndim == 2 else None)


def jsonable(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(type(x))


def fmt_time(seconds):
    return f"{seconds:.3g}" if seconds >= 0.01 else f"{seconds:.2g}"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="timed rounds; the median is reported")
    parser.add_argument("--out", default=os.path.join(RESULTS, "control_loop.json"))
    args = parser.parse_args(argv)

    import mujoco
    import pinocchio as pin
    import scipy

    import lagmb as mb

    def log(msg=""):
        print(msg, flush=True)

    versions = run_versions(mb, mujoco=mujoco.__version__, pinocchio=pin.__version__, scipy=scipy.__version__,
                            numpy=np.__version__)
    t_start = time.perf_counter()
    tmp = tempfile.mkdtemp(prefix="control_loop_")
    path, fixed = arm_urdf(tmp)
    arm = Arm(path)
    loop_model, loop_js = lagmb_loop_model(arm)
    servo_model, servo_js, masses = lagmb_servo_model(arm)
    mj_loop_model, mj_jmap = mujoco_loop_model(arm)
    mj_servo_model, mj_servo_jmap, mj_order = mujoco_servo_model(arm)
    mj_masses = {mj_servo_model.body(i).name: float(mj_servo_model.body_mass[i])
                 for i in range(1, mj_servo_model.nbody)}
    log(f"control loop: panda (fingers fixed: {fixed}), {TICKS} ticks of {TICK * 1e3:g} ms; gains Kp "
        f"{np.round(arm.kp, 3).tolist()} N m/rad, Kd {np.round(arm.kd, 4).tolist()} N m s/rad; "
        + ", ".join(f"{k} {v}" for k, v in versions.items()))

    # ---- references and their checks
    log("references ...")
    ref = {}
    sampled_ref, ref_sim = lagmb_loop(loop_model, loop_js, arm, **lagmb_options("auto", REF_RTOL))
    ref["sampled"] = {"what": f"lagmb Simulator loop, auto ({ref_sim.stats['method']}), rtol {REF_RTOL:g}",
                      "steps": ref_sim.stats["steps"], "stats": ref_sim.stats}
    checks = {}
    t0 = time.perf_counter()
    run, _ = lagmb_loop(loop_model, loop_js, arm, **lagmb_options("auto", 1e-10))
    checks["sampled: lagmb loop rtol 1e-10"] = errors(run, sampled_ref)
    checks["sampled: Pinocchio ABA + DOP853 rtol 1e-12, tick to tick"] = errors(pinocchio_sampled(arm), sampled_ref)
    checks["sampled: MuJoCo loop RK4, 100 substeps of 1e-5 s"] = errors(
        mujoco_loop(mj_loop_model, mj_jmap, arm, "rk4", dt=1e-5), sampled_ref)
    continuous_ref, ref_r = lagmb_servo(servo_model, servo_js, arm, ticks=True, **lagmb_options("auto", REF_RTOL))
    ref["continuous"] = {"what": f"lagmb in-model servo, auto ({ref_r.stats['method']}), rtol {REF_RTOL:g}",
                         "steps": ref_r.stats["steps"]}
    run, _ = lagmb_servo(servo_model, servo_js, arm, ticks=True, **lagmb_options("projection-erk", REF_RTOL))
    checks["continuous: lagmb servo projection-erk rtol 1e-11"] = errors(run, continuous_ref)
    checks["continuous: Pinocchio ABA + DOP853 rtol 1e-12"] = errors(pinocchio_continuous(arm), continuous_ref)
    checks["continuous: MuJoCo in-model RK4 1e-5 s"] = errors(
        mujoco_servo(mj_servo_model, mj_servo_jmap, mj_order, arm, "rk4", dt=1e-5, ticks=True), continuous_ref)
    checks["sampled vs continuous reference (how different the systems are)"] = errors(sampled_ref, continuous_ref)
    for name, (final, largest) in checks.items():
        log(f"  check {name}: final {final:.1e} rad, max over ticks {largest:.1e} rad")
    log(f"  ({time.perf_counter() - t0:.1f} s); distance to q* at 2 s: "
        f"{angle_error(sampled_ref[-1], arm.target):.2e} rad (sampled), "
        f"{angle_error(continuous_ref[-1], arm.target):.2e} rad (continuous)")

    # ---- the rows: (name, system, method, setting, timed run, check run)
    rows = []

    def lagmb_loop_row(method, rtol=None, step=None):
        options = lagmb_options(method, rtol, step)
        setting = f"{method}, " + (f"rtol {rtol:g}" if rtol else f"step {step * 1e3:g} ms")

        def run():
            return lagmb_loop(loop_model, loop_js, arm, **options)
        rows.append(dict(name="lagmb Simulator loop", system="sampled", setting=setting, run=run))

    def lagmb_servo_row(method, rtol):
        options = lagmb_options(method, rtol)
        rows.append(dict(name="lagmb in-model servo", system="continuous", setting=f"{method}, rtol {rtol:g}",
                         run=lambda: lagmb_servo(servo_model, servo_js, arm, **options),
                         check=lambda: lagmb_servo(servo_model, servo_js, arm, ticks=True, **options)[0]))

    for rtol in RTOLS:
        lagmb_loop_row("auto", rtol)
    lagmb_loop_row("ggl", 1e-6)
    lagmb_loop_row("ali3p", step=TICK)
    for integrator in INTEGRATORS:
        rows.append(dict(name="MuJoCo mj_step loop", system="sampled", setting=f"{integrator} 1 ms",
                         run=lambda i=integrator: mujoco_loop(mj_loop_model, mj_jmap, arm, i)))
    for method in ("auto", "ggl"):
        for rtol in RTOLS:
            lagmb_servo_row(method, rtol)
    for integrator in INTEGRATORS:
        rows.append(dict(name="MuJoCo in-model (position actuators, gravcomp)", system="continuous",
                         setting=f"{integrator} 1 ms",
                         run=lambda i=integrator: mujoco_servo(mj_servo_model, mj_servo_jmap, mj_order, arm, i),
                         check=lambda i=integrator: mujoco_servo(mj_servo_model, mj_servo_jmap, mj_order, arm, i,
                                                                 ticks=True)))
    for row in rows:
        row["key"] = f"{row['name']}, {row['setting']}"

    # ---- each row checked against its system's reference
    log("checks of the rows ...")
    results = []
    for row in rows:
        reference = sampled_ref if row["system"] == "sampled" else continuous_ref
        t0 = time.perf_counter()
        out = row["run"]()
        first = time.perf_counter() - t0
        rec = {"method": row["name"], "system": row["system"], "setting": row["setting"], "times": []}
        if row["name"].startswith("lagmb"):
            q, sim_or_result = out
            stats = dict(sim_or_result.stats)
            rec["steps"] = stats["steps"]
            rec["stats"] = stats
            rec["setting"] = rec["setting"].replace("auto,", f"auto ({stats['method']}),")
        else:
            q = out
            rec["steps"] = TICKS * round(TICK / 1e-3)
        rec["error_final"], rec["error_max"] = errors(q, reference)
        if "check" in row:  # the in-model runs: the max over ticks from a run with outputs at every tick
            check = np.asarray(row["check"]())
            rec["error_max_with_tick_outputs"] = errors(check, reference)[1]
            rec["check_run_final_vs_timed"] = angle_error(check[-1], q if np.ndim(q) == 1 else q[-1])
            if rec["check_run_final_vs_timed"] <= 1e-14:  # the same steps: its max is the timed run's
                rec["error_max"] = rec["error_max_with_tick_outputs"]
        rec["first_run_seconds"] = first
        results.append(rec)
        largest = rec["error_max"] if rec["error_max"] is not None else rec["error_max_with_tick_outputs"]
        log(f"  {row['key']}: final {rec['error_final']:.1e}, max {largest:.1e} rad, "
            f"{rec['steps']} steps, first run {first:.3f} s")

    # ---- timed rounds
    log(f"timing, {args.repeat} interleaved rounds ...")
    order = list(range(len(rows)))
    for round_ in range(args.repeat):
        for i in (order if round_ % 2 == 0 else order[::-1]):
            t0 = time.perf_counter()
            rows[i]["run"]()
            results[i]["times"].append(time.perf_counter() - t0)
        log(f"  round {round_ + 1}: " + ", ".join(f"{r['times'][-1]:.3g}" for r in results))
    for rec in results:
        rec["seconds"] = statistics.median(rec["times"])
    base = next(r["seconds"] for r in results if (r["method"], r["setting"]) == BASE)
    for rec in results:
        rec["ratio_to_mujoco_loop"] = rec["seconds"] / base
        rec["us_per_tick"] = 1e6 * rec["seconds"] / TICKS

    # ---- one tick's time, split
    timers = {}
    t0 = time.perf_counter()
    _, sim = lagmb_loop(loop_model, loop_js, arm, timers=timers, **lagmb_options("auto", 1e-6))
    total = time.perf_counter() - t0
    per_tick = {k: 1e6 * v / TICKS for k, v in timers.items()}
    per_tick["rest (loop, arrays)"] = 1e6 * total / TICKS - sum(per_tick.values())
    per_tick["total"] = 1e6 * total / TICKS
    stats = sim.stats
    tick_split = {"us_per_tick": per_tick, "steps_per_tick": stats["steps"] / TICKS,
                  "residual_evals_per_tick": stats["residual_evals"] / TICKS,
                  "augmented_factorizations_per_tick": stats["augmented_factorizations"] / TICKS,
                  "us_per_residual_eval_in_advance": per_tick["advance"] / (stats["residual_evals"] / TICKS)}
    log("one tick of the lagmb loop (auto, rtol 1e-6), us: "
        + ", ".join(f"{k} {v:.1f}" for k, v in per_tick.items())
        + f"; {tick_split['steps_per_tick']:.2f} steps, {tick_split['residual_evals_per_tick']:.1f} right-hand "
          f"sides per tick")

    doc = {"benchmark": "control_loop", "date": time.strftime("%Y-%m-%d %H:%M"), "machine": platform.platform(),
           "cpus": os.cpu_count(), "python": sys.version.split()[0], "versions": versions, "args": vars(args),
           "scene": {"urdf": ROBOTS["panda"], "fixed_finger_joints": fixed, "joints": arm.names,
                     "q0": arm.q0, "target": arm.target, "omega": OMEGA, "zeta": ZETA,
                     "M_ii_q0": arm.inertia, "kp": arm.kp, "kd": arm.kd, "tick": TICK, "ticks": TICKS,
                     "gravity_compensation": {"sampled loops": "Pinocchio computeGeneralizedGravity(q) at each tick",
                                              "lagmb servo": "add_force +m_i g at each body's centre of mass",
                                              "mujoco in-model": "body gravcomp = 1"},
                     "body_masses_lagmb": masses, "body_masses_mujoco": mj_masses},
           "references": ref, "checks": {k: {"final": v[0], "max": v[1]} for k, v in checks.items()},
           "rows": results, "tick_split": tick_split, "elapsed": time.perf_counter() - t_start}

    # ---- Markdown
    lines = ["| system | method | setting | wall time (s, median) | us per tick | steps | final joint error (rad) "
             "| max joint error over ticks (rad) | time / MuJoCo loop |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|"]
    for r in results:
        largest = f"{r['error_max']:.1e}" if r["error_max"] is not None else \
            f"({r['error_max_with_tick_outputs']:.1e})"
        lines.append(f"| {r['system']} | {r['method']} | {r['setting']} | {fmt_time(r['seconds'])} | "
                     f"{r['us_per_tick']:.1f} | {r['steps']} | {r['error_final']:.1e} | {largest} | "
                     f"{r['ratio_to_mujoco_loop']:.3g} |")
    table = "\n".join(lines)
    loop_stats = [r for r in results if r["method"] == "lagmb Simulator loop"]
    stat_lines = ["| setting | steps | restarts | input changes | right-hand sides | augmented factorizations |",
                  "|---|---:|---:|---:|---:|---:|"]
    for r in loop_stats:
        s = r["stats"]
        stat_lines.append(f"| {r['setting']} | {s['steps']} | {s['restarts']} | {s['input_changes']} | "
                          f"{s['residual_evals']} | {s['augmented_factorizations']} |")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(doc, f, indent=1, default=jsonable)
    stem = os.path.splitext(args.out)[0]
    with open(stem + ".md", "w") as f:
        f.write(f"# PD + gravity compensation on the Panda at 1 kHz for 2 s (bench/robots/control_loop.py, "
                f"{doc['date']})\n\n")
        f.write(f"lagmb {versions['lagmb']}, MuJoCo {versions['mujoco']}, Pinocchio {versions['pinocchio']}; "
                f"{platform.machine()}, {os.cpu_count()} cores; median of {args.repeat} interleaved rounds. "
                f"Gains Kp_i = {OMEGA:g}^2 M_ii(q0), Kd_i = 2 {ZETA:g} {OMEGA:g} M_ii(q0) (Kp from "
                f"{arm.kp.min():.3g} to {arm.kp.max():.3g} N m/rad). Errors against the reference of the row's own "
                f"system: sampled (1 kHz zero-order hold) = {ref['sampled']['what']}; continuous (law inside the "
                f"integrator) = {ref['continuous']['what']}. The last column divides by the time of the MuJoCo "
                f"loop with Euler at 1 ms. MuJoCo's steps are mj_step calls. \"us per tick\" is the wall time over "
                f"{TICKS} (for the in-model rows, which have no ticks, the same division). A max error in "
                f"parentheses comes from a run with outputs at every tick that takes other steps than the timed "
                f"run (projection-erk stops its steps at outputs).\n\n{table}\n\n")
        f.write("Reference checks (final / max over ticks, rad):\n\n")
        for k, v in checks.items():
            f.write(f"- {k}: {v[0]:.1e} / {v[1]:.1e}\n")
        f.write("\nThe lagmb loop's `sim.stats`:\n\n" + "\n".join(stat_lines) + "\n\n")
        f.write("One tick of the lagmb loop (auto, rtol 1e-6), instrumented run, us: "
                + ", ".join(f"{k} {v:.1f}" for k, v in per_tick.items())
                + f"; per tick {tick_split['steps_per_tick']:.2f} steps, {tick_split['residual_evals_per_tick']:.1f} "
                  f"right-hand sides ({tick_split['us_per_residual_eval_in_advance']:.1f} us each, advance's time "
                  f"divided by them).\n")
    log("")
    log(table)
    log(f"written {args.out} and {stem}.md ({doc['elapsed']:.0f} s)")


if __name__ == "__main__":
    main()
