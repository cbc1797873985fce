"""MuJoCo beside lagmb and Pinocchio in bench/robots/robots.py: a URDF robot as
MuJoCo model that simulates what the other two do, its RK4 runs and the
checks against the bench's reference.

The model (`load`): the URDF with every <visual> and <collision> element
taken out (their meshes are package:// names that MuJoCo does not resolve,
and with contacts off they play no part; a link's mass and inertia are its
<inertial> element's, as for lagmb and Pinocchio) read by MuJoCo's URDF
reader (links joined by fixed joints fused into one body, as lagmb does;
revolute -> hinge, prismatic -> slide; no floating base: a fixed-base tree,
as the bench's). Then, as mb.load_urdf(limits=False, dynamics=False,
mimic=False) and pin.buildModelFromUrdf build it: every joint's damping,
stiffness, frictionloss and armature set to 0 and its limits off; the
equality constraints MuJoCo makes of <mimic> elements deleted; gravity
(0, 0, -9.81); contacts and all constraints disabled (opt.disableflags
mjDSBL_CONTACT | mjDSBL_CONSTRAINT), so that mj_forward's qacc is the
tree's unconstrained forward dynamics.

Joints are matched by name (Pinocchio's names, as MuJoCo keeps URDF joint
names); `JointMap.qadr`/`.vadr` put a vector in Pinocchio's order into
MuJoCo's qpos/qvel.

A run (`Rk4.run(steps)`): opt.integrator = mjINT_RK4, opt.timestep =
1/steps, mj_resetData, the start state written, mj_step(m, d, nstep=steps)
(the loop in C), the joint angles read in Pinocchio's order. A run in
which MuJoCo warned of bad (NaN, infinite or huge) accelerations,
velocities or positions, whereupon it resets the state and goes on, raises
Unstable.
"""

import time
import xml.etree.ElementTree as ET

import numpy as np


class Unstable(RuntimeError):
    pass


class Unmatched(RuntimeError):
    """The robot cannot be built in MuJoCo as the bench simulates it."""


def _spec(path):
    import mujoco

    root = ET.parse(path).getroot()
    if root.tag != "robot":
        raise Unmatched(f"{path}: not a URDF <robot>")
    for link in root.iter("link"):
        for tag in ("visual", "collision"):
            for element in link.findall(tag):
                link.remove(element)
    spec = mujoco.MjSpec.from_string(ET.tostring(root, encoding="unicode"))
    for joint in spec.joints:
        joint.damping = [0.0, 0.0, 0.0]  # MuJoCo 4: polynomial coefficients
        joint.stiffness = [0.0, 0.0, 0.0]
        joint.frictionloss = 0.0
        joint.armature = 0.0
        joint.limited = mujoco.mjtLimited.mjLIMITED_FALSE
    for equality in list(spec.equalities):  # <mimic> couplings
        spec.delete(equality)
    spec.option.gravity = [0.0, 0.0, -9.81]
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT | mujoco.mjtDisableBit.mjDSBL_CONSTRAINT
    return spec


class JointMap:
    """MuJoCo's qpos/qvel addresses of the joints `names` (Pinocchio's order)."""

    def __init__(self, model, names):
        import mujoco

        mj_names = [model.joint(j).name for j in range(model.njnt)]
        missing = [n for n in names if n not in mj_names]
        extra = [n for n in mj_names if n not in names]
        if missing or extra:
            raise Unmatched(f"joints differ: not in MuJoCo's model {missing}, only in MuJoCo's {extra}")
        kinds = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
        ids = [model.joint(n).id for n in names]
        odd = [n for n, j in zip(names, ids) if int(model.jnt_type[j]) not in kinds]
        if odd or model.nq != len(names) or model.nv != len(names):
            raise Unmatched(f"not a tree of hinges and slides (joints {odd}; nq {model.nq}, nv {model.nv})")
        self.qadr = np.array([model.jnt_qposadr[j] for j in ids])
        self.vadr = np.array([model.jnt_dofadr[j] for j in ids])


def load(path, names):
    """(MjModel, JointMap) for a URDF file, joints `names` in Pinocchio's order."""
    model = _spec(path).compile()
    return model, JointMap(model, names)


def accelerations(model, jmap, q, v):
    """mj_forward's qacc at joint values q, rates v (Pinocchio's order)."""
    import mujoco

    data = mujoco.MjData(model)
    data.qpos[jmap.qadr], data.qvel[jmap.vadr] = q, v
    mujoco.mj_forward(model, data)
    if data.nefc or data.ncon:
        raise Unmatched(f"mj_forward made {data.nefc} constraint rows, {data.ncon} contacts")
    return data.qacc[jmap.vadr].copy()


class Rk4:
    """Fixed-step RK4 runs from (q0, v0) over [0, t_end]."""

    def __init__(self, model, jmap, q0, v0, t_end=1.0):
        import mujoco

        self.mj, self.model, self.jmap = mujoco, model, jmap
        self.data = mujoco.MjData(model)
        self.q0, self.v0, self.t_end = np.asarray(q0, float), np.asarray(v0, float), t_end
        self.warnings = []
        mujoco.set_mju_user_warning(self.warnings.append)  # counted in run() through data.warning
        model.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4

    def run(self, steps):
        """Joint values at t_end after `steps` RK4 steps of t_end/steps."""
        mj, m, d = self.mj, self.model, self.data
        m.opt.timestep = self.t_end / steps
        mj.mj_resetData(m, d)
        d.qpos[self.jmap.qadr], d.qvel[self.jmap.vadr] = self.q0, self.v0
        mj.mj_step(m, d, nstep=steps)
        bad = sum(int(d.warning[w].number) for w in (mj.mjtWarning.mjWARN_BADQACC, mj.mjtWarning.mjWARN_BADQVEL,
                                                     mj.mjtWarning.mjWARN_BADQPOS))
        if bad or not np.all(np.isfinite(d.qpos)):
            raise Unstable(f"unstable at {steps} steps: MuJoCo flagged bad qacc/qvel/qpos (and reset the state)")
        return d.qpos[self.jmap.qadr].copy()

    def per_call(self, q, v, calls=200, rounds=5):
        """Seconds of one mj_forward through Python (the state written, then
        mj_forward), best of `rounds` rounds of `calls`."""
        mj, m, d = self.mj, self.model, self.data
        qadr, vadr = self.jmap.qadr, self.jmap.vadr
        fastest = np.inf
        for _ in range(rounds):
            t0 = time.perf_counter()
            for _ in range(calls):
                d.qpos[qadr], d.qvel[vadr] = q, v
                mj.mj_forward(m, d)
            fastest = min(fastest, time.perf_counter() - t0)
        return fastest / calls


def search(rk4, error_of, targets, first=25, max_steps=25 * 2 ** 14):
    """Step counts for the sweep: doubling from `first` until the error is
    below every target (or max_steps), then, for each target, bisection on
    the number of steps between the last doubling level above it and the
    first below it, to 1 % (or one step): the largest step found to reach
    it. Returns (points, doubling) with points [{steps, error} or {steps,
    failed}] sorted by steps; doubling the doubling levels' points, in order
    (for the convergence check)."""
    cache = {}

    def point(steps):
        if steps not in cache:
            try:
                cache[steps] = {"steps": steps, "error": error_of(rk4.run(steps))}
            except Unstable as e:
                cache[steps] = {"steps": steps, "failed": str(e)}
        return cache[steps]

    doubling, steps = [], first
    while steps <= max_steps:
        doubling.append(point(steps))
        if doubling[-1].get("error", np.inf) <= min(targets):
            break
        steps *= 2
    for target in targets:
        ok = lambda p: p.get("error", np.inf) <= target
        above = [p["steps"] for p in doubling if not ok(p)]
        below = [p["steps"] for p in doubling if ok(p)]
        if not below:
            continue
        hi = min(below)
        lo = max([s for s in above if s < hi], default=0)
        while hi - lo > max(1, hi // 100):
            mid = (lo + hi) // 2
            if ok(point(mid)):
                hi = mid
            else:
                lo = mid
    return sorted(cache.values(), key=lambda p: p["steps"]), doubling
