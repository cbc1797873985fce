"""The Panda of bench/robots/control_loop.py in each engine, and the runs of
its 1 kHz PD loops: the arm, its gains and targets (Arm); lagmb's Simulator
loop and in-model servo; MuJoCo's mj_step loop and position actuators;
Pinocchio's ABA + DOP853 (the checks). The two cases and what each run
does are described in control_loop.py's docstring.

Every run returns the joint values of all the model's joints (the 7 arm
joints first, then the fingers where the model has them) at every tick,
(TICKS + 1, n), or at the end, (n,); errors are taken on the arm joints.
"""

import os
import xml.etree.ElementTree as ET

import numpy as np

from bench.common.paths import robots_dir
from bench.robots import mujoco_urdf as mjb
from bench.robots.robots import ROBOTS

Q0 = {"panda_joint1": 0.0, "panda_joint2": -0.785, "panda_joint3": 0.0, "panda_joint4": -2.356,
      "panda_joint5": 0.0, "panda_joint6": 1.571, "panda_joint7": 0.785}
ARM = list(Q0)
OFFSET = np.array([0.3, -0.3, 0.3, 0.3, -0.3, 0.3, 0.3])  # the held target's offset from q0 (limits off)
AMPLITUDE, FREQUENCY = 0.3, np.pi  # the tracked target q0 + AMPLITUDE sin(FREQUENCY t) (limits on)
OMEGA, ZETA = 10.0, 0.5
GRAVITY = 9.81
TICK, TICKS = 1e-3, 2000
T_END = TICK * TICKS
INTEGRATORS = {"euler": "mjINT_EULER", "rk4": "mjINT_RK4"}


def panda_urdf():
    """example-robot-data's panda.urdf, the file users load."""
    return os.path.join(robots_dir(), ROBOTS["panda"])


def stripped_urdf(directory, fix_fingers):
    """The panda URDF without visuals and collisions (their package:// meshes
    MuJoCo does not resolve; with contacts off they play no part), and, if
    fix_fingers, its finger slides made fixed joints. (path, fixed joints)."""
    root = ET.parse(panda_urdf()).getroot()
    for link in root.iter("link"):
        for tag in ("visual", "collision"):
            for element in link.findall(tag):
                link.remove(element)
    fixed = []
    for joint in root.iter("joint"):
        if fix_fingers and joint.get("type") == "prismatic":
            joint.set("type", "fixed")
            fixed.append(joint.get("name"))
            for tag in ("limit", "mimic", "dynamics", "axis"):
                for element in joint.findall(tag):
                    joint.remove(element)
    path = os.path.join(directory, "panda_arm.urdf" if fix_fingers else "panda_stripped.urdf")
    ET.ElementTree(root).write(path)
    return path, fixed


class Arm:
    """A URDF's Pinocchio model, its joints (the 7 arm joints, then the
    fingers if the file has them), q0, the gains, the target q*(t) and the
    law tau = Kp (q* - q) - Kd q' + g(q) on the arm joints (g: Pinocchio's
    computeGeneralizedGravity of all the model's joints at their values, its
    arm entries). tracking: q*(t) = q0 + AMPLITUDE sin(FREQUENCY t);
    else q* = q0 + OFFSET, fixed. damping: a viscous joint damping (N m s/rad)
    on the arm joints that only the Pinocchio check adds (-damping q' in
    ABA's torque), to match a model loaded with the URDF's <dynamics>."""

    def __init__(self, path, tracking, damping=0.0):
        import pinocchio as pin

        self.pin, self.path, self.tracking, self.damping = pin, path, tracking, damping
        self.pm = pin.buildModelFromUrdf(path)
        self.pm.gravity.linear[:] = (0.0, 0.0, -GRAVITY)
        self.pd = self.pm.createData()
        self.all_names = [self.pm.names[j] for j in range(1, self.pm.njoints)]
        self.names = self.all_names[:7]
        self.fingers = self.all_names[7:]
        assert self.names == ARM and self.pm.nq == self.pm.nv == len(self.all_names), self.all_names
        self.n = len(self.all_names)
        self.q0 = np.array([Q0[n] for n in self.names])
        self.q0_all = np.concatenate([self.q0, np.zeros(len(self.fingers))])  # fingers closed, on their limits
        self.inertia = np.diag(pin.crba(self.pm, self.pd, self.q0_all))[:7].copy()
        self.kp = OMEGA ** 2 * self.inertia
        self.kd = 2 * ZETA * OMEGA * self.inertia

    def target(self, t):
        if self.tracking:
            return self.q0 + AMPLITUDE * np.sin(FREQUENCY * t)
        return self.q0 + OFFSET

    def gravity(self, q_all):
        return self.pin.computeGeneralizedGravity(self.pm, self.pd, q_all)[:7]

    def torque(self, t, q_all, v_all):
        return self.kp * (self.target(t) - q_all[:7]) - self.kd * v_all[:7] + self.gravity(q_all)


# ---------------------------------------------------------------- lagmb

def _load(path, limits):
    import lagmb as mb

    if limits:  # as the README loads a robot: limits, damping, mimic couplings
        return mb.load_urdf(path, positions=Q0)
    return mb.load_urdf(path, limits=False, dynamics=False, positions=Q0)


def lagmb_loop_model(arm, path, limits):
    """The URDF at `path` with a torque mb.Input (a rotational spring-damper
    with only its torque) on each arm joint."""
    import lagmb as mb

    m = _load(path, limits)
    for n in arm.names:
        m.add_rotational_spring_damper(f"{n}_motor", n, torque=mb.Input(0.0))
    return m, mb.JointSpace(m)


def lagmb_servo_model(arm, path, limits):
    """The URDF at `path` with add_servo on each arm joint and +m_i g at each
    body's centre of mass. Tracking: target mb.Harmonic(AMPLITUDE, FREQUENCY,
    offset q0_i) and feed-forward -kd q*'(t) (a Harmonic with phase pi/2), so
    that the servo's kp (q* - q) + kd (q*' - q') + tau_ff is the law's
    kp (q* - q) - kd q'."""
    import lagmb as mb

    m = _load(path, limits)
    for n, q0, kp, kd, held in zip(arm.names, arm.q0, arm.kp, arm.kd, arm.target(0.0)):
        if arm.tracking:
            m.add_servo(f"{n}_servo", n, target=mb.Harmonic(AMPLITUDE, FREQUENCY, 0.0, float(q0)), kp=float(kp),
                        kd=float(kd), feedforward=mb.Harmonic(-float(kd) * AMPLITUDE * FREQUENCY, FREQUENCY,
                                                              np.pi / 2))
        else:
            m.add_servo(f"{n}_servo", n, target=float(held), kp=float(kp), kd=float(kd))
    masses = {}
    for kind, data in m.elements:
        if kind == "add_body":
            masses[data["name"]] = data["mass"]
            m.add_force(f"{data['name']}_gravity_compensation", data["name"],
                        force=(0.0, 0.0, data["mass"] * GRAVITY))
    return m, mb.JointSpace(m), masses


def lagmb_loop(model, js, arm, timers=None, **options):
    """The 1 kHz loop: (joint values at every tick (TICKS + 1, n), simulator)."""
    import time

    import lagmb as mb

    names, inputs = arm.all_names, [f"{n}_motor" for n in arm.names]
    out = np.empty((TICKS + 1, len(names)))
    sim = mb.Simulator(model, **options)
    clock = time.perf_counter
    for k in range(TICKS + 1):
        if timers is None:
            theta, rate = sim.joints(names)
            out[k] = theta
            if k == TICKS:
                break
            tau = arm.torque(k * TICK, theta, rate)
            sim.set_inputs(dict(zip(inputs, tau)))
            sim.advance(sim.t + TICK)
        else:  # the same, each part timed
            t0 = clock()
            theta, rate = sim.joints(names)
            out[k] = theta
            t1 = clock()
            if k == TICKS:
                break
            tau = arm.torque(k * TICK, theta, rate)
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
    """One simulate call: joint values at the end (n,) or at every tick."""
    import lagmb as mb

    if ticks:
        r = mb.simulate(model, T_END, t_out=np.arange(TICKS + 1) * TICK, **options)
    else:
        r = mb.simulate(model, T_END, n_out=2, **options)
    q = np.array([js.motion(n, r.q, r.v)[:, 0] for n in arm.all_names]).T
    return (q if ticks else q[-1]), r


def lagmb_options(method, rtol=None, step=None):
    options = {} if method == "auto" else {"method": method}
    if rtol is not None:
        options.update(rtol=rtol, atol=1e-2 * rtol)
    if step is not None:
        options["step"] = step
    return options


# ---------------------------------------------------------------- MuJoCo

def _limits_on_spec(path):
    """MuJoCo's model of the stripped URDF as mb.load_urdf(path) builds it:
    every joint limited to its URDF range (MuJoCo's soft limit constraint),
    the URDF's damping (MuJoCo's URDF reader takes <dynamics damping>),
    armature 0, the <mimic> as MuJoCo's joint equality, contacts disabled
    (constraints on)."""
    import mujoco

    spec = mujoco.MjSpec.from_string(open(path).read())
    for joint in spec.joints:
        joint.limited = mujoco.mjtLimited.mjLIMITED_TRUE
        joint.armature = 0.0
    spec.option.gravity = [0.0, 0.0, -GRAVITY]
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    return spec


def mujoco_loop_model(arm, path, limits):
    if not limits:
        return mjb.load(path, arm.all_names)
    model = _limits_on_spec(path).compile()
    return model, mjb.JointMap(model, arm.all_names)


def mujoco_servo_model(arm, path, limits):
    import mujoco

    spec = _limits_on_spec(path) if limits else mjb._spec(path)
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
    jmap = mjb.JointMap(model, arm.all_names)
    order = [model.actuator(f"{n}_servo").id for n in arm.names]
    return model, jmap, order


def _mujoco_data(model, jmap, arm, integrator, dt):
    import mujoco

    model.opt.integrator = getattr(mujoco.mjtIntegrator, INTEGRATORS[integrator])
    model.opt.timestep = dt
    data = mujoco.MjData(model)
    mujoco.mj_resetData(model, data)
    data.qpos[jmap.qadr] = arm.q0_all
    return data


def mujoco_loop(model, jmap, arm, integrator, dt=TICK):
    """The 1 kHz loop, tau held over TICK / dt substeps of dt: joint values at every tick."""
    import mujoco

    data = _mujoco_data(model, jmap, arm, integrator, dt)
    substeps = round(TICK / dt)
    qadr, vadr, arm_vadr = jmap.qadr, jmap.vadr, jmap.vadr[:7]
    out = np.empty((TICKS + 1, len(qadr)))
    step = mujoco.mj_step
    for k in range(TICKS + 1):
        q = data.qpos[qadr]
        out[k] = q
        if k == TICKS:
            break
        data.qfrc_applied[arm_vadr] = arm.torque(k * TICK, q, data.qvel[vadr])
        if substeps == 1:
            step(model, data)
        else:
            step(model, data, nstep=substeps)
    return out


def mujoco_servo(model, jmap, order, arm, integrator, dt=TICK, ticks=False):
    """The in-model law. Held target: ctrl = q* once, one mj_step(nstep) call
    (ticks=True: one call per tick, the same arithmetic). Tracking: ctrl =
    q*(t) written before every step of dt (one mj_step per tick at dt =
    TICK: the Python loop a user writes)."""
    import mujoco

    data = _mujoco_data(model, jmap, arm, integrator, dt)
    per_tick = round(TICK / dt)
    qadr = jmap.qadr
    if not arm.tracking:
        data.ctrl[order] = arm.target(0.0)
        if not ticks:
            mujoco.mj_step(model, data, nstep=per_tick * TICKS)
            return data.qpos[qadr].copy()
        out = np.empty((TICKS + 1, len(qadr)))
        out[0] = data.qpos[qadr]
        for k in range(TICKS):
            mujoco.mj_step(model, data, nstep=per_tick)
            out[k + 1] = data.qpos[qadr]
        return out
    out = np.empty((TICKS + 1, len(qadr)))
    out[0] = data.qpos[qadr]
    step, ctrl, target = mujoco.mj_step, data.ctrl, arm.target
    for k in range(TICKS):
        for i in range(per_tick):
            ctrl[order] = target(k * TICK + i * dt)
            step(model, data)
        out[k + 1] = data.qpos[qadr]
    return out if ticks else out[-1]


# ---------------------------------------------------------------- Pinocchio + DOP853 (checks)

def _aba(arm, x, tau):
    n = arm.n
    return np.concatenate([x[n:], arm.pin.aba(arm.pm, arm.pd, x[:n], x[n:], tau - arm.damping * x[n:])])


def pinocchio_sampled(arm, rtol=1e-12):
    """The sampled loop on the arm's Pinocchio model (no limits: a model
    without fingers or with none that moves), tick to tick."""
    from scipy.integrate import solve_ivp

    n = arm.n
    y = np.concatenate([arm.q0_all, np.zeros(n)])
    out = np.empty((TICKS + 1, n))
    for k in range(TICKS + 1):
        out[k] = y[:n]
        if k == TICKS:
            break
        tau = arm.torque(k * TICK, y[:n], y[n:])
        y = solve_ivp(lambda t, x: _aba(arm, x, tau), (k * TICK, (k + 1) * TICK), y, method="DOP853",
                      rtol=rtol, atol=rtol).y[:, -1]
    return out


def pinocchio_continuous(arm, rtol=1e-12):
    from scipy.integrate import solve_ivp

    n = arm.n
    sol = solve_ivp(lambda t, x: _aba(arm, x, arm.torque(t, x[:n], x[n:])), (0.0, T_END),
                    np.concatenate([arm.q0_all, np.zeros(n)]), method="DOP853", rtol=rtol, atol=rtol,
                    t_eval=np.arange(TICKS + 1) * TICK)
    return sol.y[:n].T

