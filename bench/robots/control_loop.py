"""A joint-space PD controller with gravity compensation on the Franka Panda
at 1 kHz for 2 s: lagmb's Simulator driven from Python, lagmb's in-model
servo, and MuJoCo, side by side, in two cases (--cases off,on):

- "off" (limits off, holding): the arm as before. example-robot-data's
  panda URDF (found as bench/robots/robots.py finds robots) with its
  <visual>/<collision> elements taken out and the two finger slides made
  fixed joints (the hand and fingers are one rigid body with link 7), so
  that every engine sees the same 7-joint tree; lagmb reads it with
  mb.load_urdf(limits=False, dynamics=False), Pinocchio with
  buildModelFromUrdf, MuJoCo with its URDF reader as
  bench/robots/mujoco_urdf.py builds it (damping, armature, limits off;
  contacts and constraints disabled). The target is held:
  q* = q0 + (0.3, -0.3, 0.3, 0.3, -0.3, 0.3, 0.3) rad.
- "on" (limits on, tracking): the robot as users load it (README):
  lagmb reads example-robot-data's panda.urdf itself with
  mb.load_urdf(path, positions=Q0): 9 stops (7 arm joints, 2 finger
  slides), the URDF's joint damping (0.003 N m s/rad on the arm, 0.3 N s/m
  on the fingers), finger 2 coupled to finger 1 (its <mimic>); the fingers
  start closed, on their lower limit 0, and stay there (to 1e-15 m). g(q)
  comes from Pinocchio's model of the same file (9 joints, the fingers at
  their current values). MuJoCo reads the file without its
  <visual>/<collision> elements: every joint limited to its URDF range
  (MuJoCo's soft limit constraint), the URDF's damping (its URDF reader
  takes <dynamics damping>), armature 0, the <mimic> as MuJoCo's joint
  equality, contacts disabled, constraints on. The target moves:
  q*(t) = q0 + 0.3 sin(pi t) rad on every arm joint.

Gravity (0, 0, -9.81) everywhere. Joints are matched by name.

The control law, the same everywhere: start at rest in q0 (the usual
"ready" pose (0, -0.785, 0, -2.356, 0, 1.571, 0.785)), then

    tau = Kp (q*(t) - q) - Kd q' + g(q)

on the 7 arm joints (the fingers get no torque), with per-joint gains
scaled to the joint-space inertia at q0, Kp_i = w^2 M_ii(q0), Kd_i = 2 zeta
w M_ii(q0), w = 10 rad/s, zeta = 0.5 (M_ii from 0.0067 kg m^2 at joint 7 to
1.55 at joint 2; one Kd = 20 N m s/rad for all joints would make the 1 kHz
sampled loop unstable at joint 7: Kd h / M_77 = 3 > 2). Holding, the arm is
still moving at 2 s (about 0.01 rad from q*).

Two systems per case, each with its own reference:

- sampled (1 kHz, zero-order hold): at each tick t_k = k ms the state is
  read, tau computed with q*(t_k) (g(q): Pinocchio's
  computeGeneralizedGravity) and held until the next tick.
  * lagmb Simulator loop: a rotational spring-damper with torque mb.Input
    on each arm joint; per tick the joint values and rates by
    sim.joints(names) (one call, fingers included), tau, one
    sim.set_inputs({...}), then sim.advance(sim.t + 1 ms). Methods: auto
    (projection-erk here) at rtol 1e-6 and 1e-8, GGL at 1e-6, and the
    fixed-step ali3p with step 1 ms.
  * MuJoCo loop: per tick qpos/qvel read, the same tau written to
    data.qfrc_applied, mj_step; Euler (MuJoCo's default) and RK4, timestep
    1 ms.
  Reference: the lagmb loop at rtol 1e-11 (atol 1e-13); checked against
  the lagmb loop at 1e-10, MuJoCo's RK4 loop with 100 substeps of 1e-5 s
  per tick (tau held over the substeps), and Pinocchio's ABA integrated by
  SciPy's DOP853 at rtol = atol = 1e-12 from tick to tick. Pinocchio has
  no unilateral limits: with limits on, ABA cannot hold the fingers on
  their stops, so its check there runs the arm with the fingers fixed
  (the "off" file) and the URDF's arm damping added (-0.003 q' in ABA's
  torque), which is the same system as long as the fingers stay on their
  stops (they do: the check's error says how well).
- continuous (the law evaluated inside the integrator):
  * lagmb in-model servo: m.add_servo(joint, target, kp, kd) on each arm
    joint (tracking: target mb.Harmonic(0.3, pi, 0, q0_i) and feedforward
    mb.Harmonic(-kd 0.3 pi, pi, pi/2) = -kd q*'(t), so that the servo's
    kp (q* - q) + kd (q*' - q') + tau_ff is the law's -kd q'; holding: the
    number q*_i) and, for g(q), a force +m_i g (upward) at the centre of
    mass of each moving body, fingers included (m.add_force), which cancels
    gravity on the arm exactly, as g(q) does; one mb.simulate(m, 2.0,
    n_out=2). Methods: auto (its choice is printed) and GGL, rtol 1e-6 and
    1e-8.
  * MuJoCo in-model: position actuators (kp, kv) on the arm joints, every
    body's gravcomp = 1 (MuJoCo's upward m_i g at the centre of mass).
    Holding: ctrl = q*, one mj_step(nstep=2000) call at 1 ms. Tracking:
    MuJoCo has no time functions in its actuators, so ctrl = q*(t_k) is
    written before each mj_step of 1 ms, in a Python loop (exact for
    Euler, which evaluates the law at the step's start; RK4 holds the
    target over its step, an O(h) error). Euler and RK4.
  Reference: the lagmb servo at rtol 1e-11 (auto, atol 1e-13); checked
  against the servo by projection-erk at 1e-11, Pinocchio ABA + DOP853 at
  1e-12 on the same law (with limits on: the fingers fixed, as above), and
  MuJoCo's in-model RK4 at 1e-5 s (tracking: ctrl written before each
  1e-5 s step).

Every row is first checked against its case's and system's reference: the
error is the largest arm-joint angle difference (rad, over joints) at
t = 2 s ("final") and over all 2001 ticks ("max"; for the in-model rows
from a second run with outputs at every tick: the same steps for GGL and
MuJoCo, other steps for projection-erk, which stops at each output, so its
"max" is shown in parentheses). With limits on, the fingers' largest
|value| over the run is recorded too (lagmb's stops hold them at 0;
MuJoCo's soft limits let them sink in). Then all rows of all cases are
timed in --repeat interleaved rounds (the order reversed every other
round), one whole 2 s run each (the Simulator's construction, MuJoCo's
mj_resetData included; model building not), and the median is reported
with the ratio to the median of its case's MuJoCo Euler loop. After the
rounds, one instrumented run of the lagmb loop (auto, rtol 1e-6) per case
splits a tick's time into its parts; the lagmb loop rows' sim.stats are
reported per tick (augmented factorizations, right-hand sides, root
evaluations, projections, restarts), limits on beside limits off.

OPENBLAS_NUM_THREADS and OMP_NUM_THREADS are set to 1 before numpy is
imported: BLAS threads spinning beside the loop take
a core on a 2-core machine.

    python bench/robots/control_loop.py [--repeat 5] [--cases off,on] [--out bench/results/control_loop.json]

writes the JSON and a Markdown table beside it (control_loop.md).
"""

import os

for _threads in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):  # before numpy is imported (see above)
    os.environ[_threads] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.paths import RESULTS  # noqa: E402
from bench.common.record import run_versions  # noqa: E402
from bench.robots import control_loop_models as cl  # noqa: E402
from bench.robots.robots import ROBOTS, angle_error  # noqa: E402

RTOLS = (1e-6, 1e-8)
REF_RTOL = 1e-11
BASE = ("MuJoCo mj_step loop", "euler 1 ms")  # the row of its case the last column divides by
CASES = {"off": "limits off, holding", "on": "limits on, tracking"}
TICK, TICKS = cl.TICK, cl.TICKS
PER_TICK = ("augmented_factorizations", "residual_evals", "root_evals", "projections", "restarts")


def errors(run, reference):
    """(final, max over ticks) arm-joint angle error; run: (TICKS + 1, n) or the end (n,)."""
    run, reference = np.asarray(run)[..., :7], np.asarray(reference)[..., :7]
    final = angle_error(run[-1] if run.ndim == 2 else run, reference[-1])
    return final, (angle_error(run, reference) if run.ndim == 2 else None)


def finger_excursion(run):
    """The fingers' largest |value| (m) over the run, None without fingers."""
    run = np.asarray(run)
    return float(np.max(np.abs(run[..., 7:]))) if run.shape[-1] > 7 else None


def jsonable(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(type(x))


def fmt_time(seconds):
    return f"{seconds:.3g}" if seconds >= 0.01 else f"{seconds:.2g}"


class Case:
    """One case's arm, models, references, checks and rows (see the module's docstring)."""

    def __init__(self, key, tmp, log):
        self.key, self.label, self.log = key, CASES[key], log
        limits = tracking = key == "on"
        arm_path, self.fixed = cl.stripped_urdf(tmp, fix_fingers=True)
        if limits:
            lagmb_path, mujoco_path = cl.panda_urdf(), cl.stripped_urdf(tmp, fix_fingers=False)[0]
            self.fixed = []
            # the Pinocchio checks: fingers fixed, the URDF's arm damping (see the docstring)
            self.check_arm = cl.Arm(arm_path, tracking, damping=0.003)
        else:
            lagmb_path = mujoco_path = arm_path
            self.check_arm = None
        self.arm = arm = cl.Arm(lagmb_path, tracking)
        if self.check_arm is None:
            self.check_arm = arm
        self.loop = cl.lagmb_loop_model(arm, lagmb_path, limits)
        servo_model, servo_js, self.masses = cl.lagmb_servo_model(arm, lagmb_path, limits)
        self.servo = (servo_model, servo_js)
        self.mj_loop = cl.mujoco_loop_model(arm, mujoco_path, limits)
        self.mj_servo = cl.mujoco_servo_model(arm, mujoco_path, limits)
        model = self.mj_servo[0]
        self.mj_masses = {model.body(i).name: float(model.body_mass[i]) for i in range(1, model.nbody)}

    def references(self):
        arm, log = self.arm, self.log
        ref, checks = {}, {}
        self.sampled_ref, sim = cl.lagmb_loop(*self.loop, arm, **cl.lagmb_options("auto", REF_RTOL))
        ref["sampled"] = {"what": f"lagmb Simulator loop, auto ({sim.stats['method']}), rtol {REF_RTOL:g}",
                          "steps": sim.stats["steps"], "stats": sim.stats}
        t0 = time.perf_counter()
        run, _ = cl.lagmb_loop(*self.loop, arm, **cl.lagmb_options("auto", 1e-10))
        checks["sampled: lagmb loop rtol 1e-10"] = errors(run, self.sampled_ref)
        fixed = " (fingers fixed, arm damping)" if self.key == "on" else ""
        checks[f"sampled: Pinocchio ABA + DOP853 rtol 1e-12, tick to tick{fixed}"] = errors(
            cl.pinocchio_sampled(self.check_arm), self.sampled_ref)
        run = cl.mujoco_loop(*self.mj_loop, arm, "rk4", dt=1e-5)
        checks["sampled: MuJoCo loop RK4, 100 substeps of 1e-5 s"] = errors(run, self.sampled_ref)
        self.fingers = {"sampled reference": finger_excursion(self.sampled_ref),
                        "sampled: MuJoCo loop RK4 1e-5 s": finger_excursion(run)}
        self.continuous_ref, r = cl.lagmb_servo(*self.servo, arm, ticks=True, **cl.lagmb_options("auto", REF_RTOL))
        ref["continuous"] = {"what": f"lagmb in-model servo, auto ({r.stats['method']}), rtol {REF_RTOL:g}",
                             "steps": r.stats["steps"]}
        run, _ = cl.lagmb_servo(*self.servo, arm, ticks=True, **cl.lagmb_options("projection-erk", REF_RTOL))
        checks["continuous: lagmb servo projection-erk rtol 1e-11"] = errors(run, self.continuous_ref)
        checks[f"continuous: Pinocchio ABA + DOP853 rtol 1e-12{fixed}"] = errors(
            cl.pinocchio_continuous(self.check_arm), self.continuous_ref)
        run = cl.mujoco_servo(*self.mj_servo, arm, "rk4", dt=1e-5, ticks=True)
        checks["continuous: MuJoCo in-model RK4 1e-5 s"] = errors(run, self.continuous_ref)
        self.fingers.update({"continuous reference": finger_excursion(self.continuous_ref),
                             "continuous: MuJoCo in-model RK4 1e-5 s": finger_excursion(run)})
        checks["sampled vs continuous reference (how different the systems are)"] = errors(
            self.sampled_ref, self.continuous_ref)
        for name, (final, largest) in checks.items():
            log(f"  [{self.key}] check {name}: final {final:.1e} rad, max over ticks {largest:.1e} rad")
        if self.key == "on":
            log(f"  [{self.key}] fingers' largest |value| (m): "
                + ", ".join(f"{k} {v:.1e}" for k, v in self.fingers.items()))
        target = self.arm.target(cl.T_END)
        log(f"  [{self.key}] ({time.perf_counter() - t0:.1f} s); distance to q*(2 s): "
            f"{angle_error(self.sampled_ref[-1, :7], target):.2e} rad (sampled), "
            f"{angle_error(self.continuous_ref[-1, :7], target):.2e} rad (continuous)")
        self.ref, self.checks = ref, checks

    def rows(self):
        """(name, system, setting, timed run, check run) of the case's rows."""
        arm, loop, servo, mj_loop, mj_servo = self.arm, self.loop, self.servo, self.mj_loop, self.mj_servo
        rows = []

        def lagmb_loop_row(method, rtol=None, step=None):
            options = cl.lagmb_options(method, rtol, step)
            setting = f"{method}, " + (f"rtol {rtol:g}" if rtol else f"step {step * 1e3:g} ms")
            rows.append(dict(name="lagmb Simulator loop", system="sampled", setting=setting,
                             run=lambda: cl.lagmb_loop(*loop, arm, **options)))

        def lagmb_servo_row(method, rtol):
            options = cl.lagmb_options(method, rtol)
            rows.append(dict(name="lagmb in-model servo", system="continuous", setting=f"{method}, rtol {rtol:g}",
                             run=lambda: cl.lagmb_servo(*servo, arm, **options),
                             check=lambda: cl.lagmb_servo(*servo, arm, ticks=True, **options)[0]))

        for rtol in RTOLS:
            lagmb_loop_row("auto", rtol)
        lagmb_loop_row("ggl", 1e-6)
        lagmb_loop_row("ali3p", step=TICK)
        for integrator in cl.INTEGRATORS:
            rows.append(dict(name="MuJoCo mj_step loop", system="sampled", setting=f"{integrator} 1 ms",
                             run=lambda i=integrator: cl.mujoco_loop(*mj_loop, arm, i)))
        for method in ("auto", "ggl"):
            for rtol in RTOLS:
                lagmb_servo_row(method, rtol)
        name = "MuJoCo in-model (position actuators, gravcomp" + (", ctrl = q*(t) per tick)" if arm.tracking else ")")
        for integrator in cl.INTEGRATORS:
            rows.append(dict(name=name, system="continuous", setting=f"{integrator} 1 ms",
                             run=lambda i=integrator: cl.mujoco_servo(*mj_servo, arm, i),
                             check=lambda i=integrator: cl.mujoco_servo(*mj_servo, arm, i, ticks=True)))
        for row in rows:
            row["case"] = self.key
            row["key"] = f"[{self.key}] {row['name']}, {row['setting']}"
        return rows

    def scene(self):
        arm = self.arm
        return {"label": self.label, "urdf": ROBOTS["panda"], "fixed_finger_joints": self.fixed,
                "joints": arm.all_names, "q0": arm.q0, "target": "q0 + 0.3 sin(pi t)" if arm.tracking else
                arm.target(0.0), "omega": cl.OMEGA, "zeta": cl.ZETA, "M_ii_q0": arm.inertia, "kp": arm.kp,
                "kd": arm.kd, "tick": TICK, "ticks": TICKS,
                "gravity_compensation": {"sampled loops": "Pinocchio computeGeneralizedGravity(q) at each tick",
                                         "lagmb servo": "add_force +m_i g at each body's centre of mass",
                                         "mujoco in-model": "body gravcomp = 1"},
                "body_masses_lagmb": self.masses, "body_masses_mujoco": self.mj_masses,
                "fingers_largest_abs_value": getattr(self, "fingers", None)}


def check_row(row, case, log):
    """The row's first run and its errors against its case's reference: the result record."""
    reference = case.sampled_ref if row["system"] == "sampled" else case.continuous_ref
    t0 = time.perf_counter()
    out = row["run"]()
    first = time.perf_counter() - t0
    rec = {"case": row["case"], "method": row["name"], "system": row["system"], "setting": row["setting"],
           "times": []}
    if row["name"].startswith("lagmb"):
        q, sim_or_result = out
        stats = dict(sim_or_result.stats)
        rec["steps"] = stats["steps"]
        rec["stats"] = stats
        rec["setting"] = rec["setting"].replace("auto,", f"auto ({stats['method']}),")
    else:
        q = out
        rec["steps"] = TICKS
    rec["error_final"], rec["error_max"] = errors(q, reference)
    rec["fingers_largest_abs_value"] = finger_excursion(q)
    if "check" in row:  # the in-model runs: the max over ticks from a run with outputs at every tick
        check = np.asarray(row["check"]())
        rec["error_max_with_tick_outputs"] = errors(check, reference)[1]
        rec["fingers_largest_abs_value"] = finger_excursion(check)
        rec["check_run_final_vs_timed"] = angle_error(check[-1, :7], (q if np.ndim(q) == 1 else q[-1])[:7])
        if rec["check_run_final_vs_timed"] <= 1e-14:  # the same steps: its max is the timed run's
            rec["error_max"] = rec["error_max_with_tick_outputs"]
    rec["first_run_seconds"] = first
    largest = rec["error_max"] if rec["error_max"] is not None else rec["error_max_with_tick_outputs"]
    fingers = rec["fingers_largest_abs_value"]
    log(f"  {row['key']}: final {rec['error_final']:.1e}, max {largest:.1e} rad, {rec['steps']} steps, "
        f"first run {first:.3f} s" + (f", fingers within {fingers:.1e} m" if fingers is not None else ""))
    return rec


def tick_split(case):
    """One instrumented run of the case's lagmb loop (auto, rtol 1e-6): us per tick by part, counts per tick."""
    timers = {}
    t0 = time.perf_counter()
    _, sim = cl.lagmb_loop(*case.loop, case.arm, timers=timers, **cl.lagmb_options("auto", 1e-6))
    total = time.perf_counter() - t0
    per_tick = {k: 1e6 * v / TICKS for k, v in timers.items()}
    per_tick["rest (loop, arrays)"] = 1e6 * total / TICKS - sum(per_tick.values())
    per_tick["total"] = 1e6 * total / TICKS
    stats = sim.stats
    return {"us_per_tick": per_tick, "steps_per_tick": stats["steps"] / TICKS,
            "residual_evals_per_tick": stats["residual_evals"] / TICKS,
            "augmented_factorizations_per_tick": stats["augmented_factorizations"] / TICKS,
            "us_per_residual_eval_in_advance": per_tick["advance"] / (stats["residual_evals"] / TICKS)}


def markdown(doc, cases, results, splits, args):
    versions = doc["versions"]
    lines = ["| case | system | method | setting | wall time (s, median) | us per tick | steps | final joint error "
             "(rad) | max joint error over ticks (rad) | time / MuJoCo Euler loop of the case |",
             "|---|---|---|---|---:|---:|---:|---:|---:|---:|"]
    for r in results:
        largest = f"{r['error_max']:.1e}" if r["error_max"] is not None else \
            f"({r['error_max_with_tick_outputs']:.1e})"
        lines.append(f"| {CASES[r['case']]} | {r['system']} | {r['method']} | {r['setting']} | "
                     f"{fmt_time(r['seconds'])} | {r['us_per_tick']:.1f} | {r['steps']} | {r['error_final']:.1e} | "
                     f"{largest} | {r['ratio_to_mujoco_loop']:.3g} |")
    table = "\n".join(lines)
    stat_lines = ["| case | setting | steps | restarts | input changes | right-hand sides | augmented factorizations "
                  "| root evals | projections |", "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    tick_lines = ["| case | setting | us per tick | steps | " + " | ".join(PER_TICK) + " |",
                  "|---|---|---:|---:|" + "---:|" * len(PER_TICK)]
    for r in results:
        if r["method"] != "lagmb Simulator loop":
            continue
        s = r["stats"]
        stat_lines.append(f"| {CASES[r['case']]} | {r['setting']} | {s['steps']} | {s['restarts']} | "
                          f"{s['input_changes']} | {s['residual_evals']} | {s['augmented_factorizations']} | "
                          f"{s['root_evals']} | {s['projections']} |")
        tick_lines.append(f"| {CASES[r['case']]} | {r['setting']} | {r['us_per_tick']:.0f} | "
                          f"{s['steps'] / TICKS:.2f} | " + " | ".join(f"{s[k] / TICKS:.2f}" for k in PER_TICK) + " |")
    out = [f"# PD + gravity compensation on the Panda at 1 kHz for 2 s (bench/robots/control_loop.py, "
           f"{doc['date']})\n",
           f"lagmb {versions['lagmb']}, MuJoCo {versions['mujoco']}, Pinocchio {versions['pinocchio']}; "
           f"{platform.machine()}, {os.cpu_count()} cores; median of {args.repeat} interleaved rounds. "
           f"Cases: limits off, holding q* = q0 + (0.3, -0.3, 0.3, 0.3, -0.3, 0.3, 0.3) (fingers fixed); limits "
           f"on, tracking q*(t) = q0 + 0.3 sin(pi t) (the URDF as mb.load_urdf(path) reads it: 9 stops, damping, "
           f"mimic; MuJoCo's joints limited). Gains Kp_i = {cl.OMEGA:g}^2 M_ii(q0), Kd_i = 2 {cl.ZETA:g} "
           f"{cl.OMEGA:g} M_ii(q0). Errors against the reference of the row's own case and system: sampled "
           f"(1 kHz zero-order hold) = the lagmb Simulator loop at rtol {REF_RTOL:g}; continuous (law inside the "
           f"integrator) = the lagmb servo at rtol {REF_RTOL:g}. The last column divides by the time of the "
           f"case's MuJoCo loop with Euler at 1 ms. MuJoCo's steps are mj_step steps. \"us per tick\" is the wall "
           f"time over {TICKS} (for the in-model rows the same division). A max error in parentheses comes from a "
           f"run with outputs at every tick that takes other steps than the timed run (projection-erk stops its "
           f"steps at outputs).\n", table, ""]
    for key, case in cases.items():
        out.append(f"Reference checks, {case.label} (final / max over ticks, rad):\n")
        out += [f"- {k}: {v[0]:.1e} / {v[1]:.1e}" for k, v in case.checks.items()]
        if key == "on":
            out.append("- fingers' largest |value| (m): " + ", ".join(f"{k} {v:.1e}" for k, v in case.fingers.items()))
        out.append("")
    out += ["The lagmb loop's `sim.stats`:\n", "\n".join(stat_lines), "", "Per tick:\n", "\n".join(tick_lines), ""]
    for key, split in splits.items():
        out.append(f"One tick of the lagmb loop, {CASES[key]} (auto, rtol 1e-6), instrumented run, us: "
                   + ", ".join(f"{k} {v:.1f}" for k, v in split["us_per_tick"].items())
                   + f"; per tick {split['steps_per_tick']:.2f} steps, {split['residual_evals_per_tick']:.1f} "
                     f"right-hand sides ({split['us_per_residual_eval_in_advance']:.1f} us each, advance's time "
                     f"divided by them).\n")
    return "\n".join(out), table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="timed rounds; the median is reported")
    parser.add_argument("--cases", default="off,on", help="comma-separated, of: " + ", ".join(
        f"{k} ({v})" for k, v in CASES.items()))
    parser.add_argument("--out", default=os.path.join(RESULTS, "control_loop.json"))
    args = parser.parse_args(argv)
    keys = [k.strip() for k in args.cases.split(",") if k.strip()]
    unknown = [k for k in keys if k not in CASES]
    if unknown or not keys:
        parser.error(f"--cases: unknown {unknown}; choose from {list(CASES)}")

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
    cases = {k: Case(k, tmp, log) for k in keys}
    arm = next(iter(cases.values())).arm
    log(f"control loop: panda, cases {', '.join(CASES[k] for k in keys)}; {TICKS} ticks of {TICK * 1e3:g} ms; "
        f"gains Kp {np.round(arm.kp, 3).tolist()} N m/rad, Kd {np.round(arm.kd, 4).tolist()} N m s/rad; "
        + ", ".join(f"{k} {v}" for k, v in versions.items()))

    log("references ...")
    for case in cases.values():
        case.references()
    rows = [row for case in cases.values() for row in case.rows()]

    log("checks of the rows ...")
    results = [check_row(row, cases[row["case"]], log) for row in rows]

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
    for rec in results:
        base = next(r["seconds"] for r in results if (r["case"], r["method"], r["setting"]) == (rec["case"], *BASE))
        rec["ratio_to_mujoco_loop"] = rec["seconds"] / base
        rec["us_per_tick"] = 1e6 * rec["seconds"] / TICKS

    splits = {key: tick_split(case) for key, case in cases.items()}
    for key, split in splits.items():
        log(f"one tick of the lagmb loop, {CASES[key]} (auto, rtol 1e-6), us: "
            + ", ".join(f"{k} {v:.1f}" for k, v in split["us_per_tick"].items())
            + f"; {split['steps_per_tick']:.2f} steps, {split['residual_evals_per_tick']:.1f} right-hand sides "
              f"per tick")

    doc = {"benchmark": "control_loop", "date": time.strftime("%Y-%m-%d %H:%M"), "machine": platform.platform(),
           "cpus": os.cpu_count(), "python": sys.version.split()[0], "versions": versions, "args": vars(args),
           "blas_threads": {k: os.environ.get(k) for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS")},
           "cases": {k: c.scene() for k, c in cases.items()},
           "references": {k: c.ref for k, c in cases.items()},
           "checks": {k: {name: {"final": v[0], "max": v[1]} for name, v in c.checks.items()}
                      for k, c in cases.items()},
           "rows": results, "tick_split": splits, "elapsed": time.perf_counter() - t_start}
    text, table = markdown(doc, cases, results, splits, args)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(doc, f, indent=1, default=jsonable)
    stem = os.path.splitext(args.out)[0]
    with open(stem + ".md", "w") as f:
        f.write(text)
    log("")
    log(table)
    log(f"written {args.out} and {stem}.md ({doc['elapsed']:.0f} s)")


if __name__ == "__main__":
    main()
