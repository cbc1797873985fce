"""MuJoCo (minimal coordinates, fixed step) on the peer chain.

The model is generated in code: a nested chain of N bodies, each with one
hinge joint about z at its own origin; body 0 at the world origin, body i
1 m along body i-1's x axis. Each body's inertial element is set
explicitly (compiler inertiafromgeom off): mass 1 kg, centre of mass
ipos = (0.5, 0, 0), principal moments diaginertia = (1e-3, 1/12, 1/12)
kg m^2 about that centre. MuJoCo's diaginertia is about the centre of mass
in the inertial frame; for a rod along x the in-plane moment is the z entry,
1/12; the x entry only has to be positive and satisfy the triangle
inequality (Ixx + Iyy >= Izz) and plays no part with hinge-z joints.
Gravity (0, -9.81, 0); contacts disabled; no geoms (a visual capsule would
not change the dynamics with inertiafromgeom off, and is left out).

MJCF text is what `mjcf(n)` writes, but MuJoCo's XML parser refuses nesting
deeper than its element-depth limit (N = 512 fails), so the timed models
are built with the equivalent MjSpec calls (`build`); the self-check
compares the two at small N (same accelerations).

Hinge angles are relative (qpos_i = rod i's angle minus rod i-1's), so the
stiff variant's spring-dampers are the joints' own stiffness k and damping
c (springref = 0 = the initial relative angle) on joints 1 .. N-1; none at
joint 0. Integrators: RK4 (fourth order, explicit); for the stiff variant
also implicitfast and implicit (first order, implicit in the velocity
forces: damping, not stiffness) and discrete (MuJoCo 4's step map in the
metric M + hD + h^2 K, implicit in stiffness too; first order). The step
is h = 1/steps with steps = 25 * 2^j, so that t = 1 s is reached exactly;
a run is mj_resetData + mj_step(m, d, nstep) in 8 chunks of steps/8,
timed around mj_step. A run in which MuJoCo flagged bad accelerations,
velocities or positions (it then resets the state and goes on) counts as
failed (unstable) and stops at the end of that chunk. The tip is rod N-1's centre, d.xipos[N].

    /tmp/peers-venv/bin/python bench/peers/peer_mujoco.py [--n 8] [--stiff]
"""

import os
import sys
import time

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

NAME = "mujoco"
STEPS = tuple(25 * 2 ** j for j in range(13))  # 25 .. 102400 steps per second


def available():
    try:
        import mujoco
    except ImportError as e:
        return False, f"not importable: {e}"
    return True, f"mujoco {mujoco.__version__}"


def mjcf(n, integrator="RK4", h=0.01, k=0.0, c=0.0):
    """The model as MJCF text (same model as build(); usable up to N ~ 200)."""
    bodies, close = [], []
    for i in range(n):
        sd = f' stiffness="{k!r}" damping="{c!r}"' if i > 0 and (k or c) else ""
        bodies.append(f'<body name="rod{i}" pos="{0.0 if i == 0 else 1.0} 0 0">'
                      f'<joint name="j{i}" type="hinge" axis="0 0 1"{sd}/>'
                      f'<inertial pos="0.5 0 0" mass="1" diaginertia="0.001 {1 / 12!r} {1 / 12!r}"/>')
        close.append("</body>")
    return (f'<mujoco><compiler inertiafromgeom="false" angle="radian"/>'
            f'<option timestep="{h!r}" integrator="{integrator}" gravity="0 -9.81 0">'
            f'<flag contact="disable"/></option>'
            f'<worldbody>{"".join(bodies)}{"".join(close)}</worldbody></mujoco>')


def build(n, k=0.0, c=0.0):
    """The same model through MjSpec (no XML depth limit)."""
    import mujoco

    spec = mujoco.MjSpec()
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.option.gravity = [0.0, -9.81, 0.0]
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    parent = spec.worldbody
    for i in range(n):
        b = parent.add_body(name=f"rod{i}", pos=[0.0 if i == 0 else 1.0, 0.0, 0.0], mass=1.0,
                            ipos=[0.5, 0.0, 0.0], inertia=[1e-3, 1.0 / 12.0, 1.0 / 12.0])
        j = b.add_joint(name=f"j{i}", type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0.0, 0.0, 1.0])
        if i > 0 and (k or c):
            j.stiffness = [k, 0.0, 0.0]  # linear coefficient, higher polynomial terms 0
            j.damping = [c, 0.0, 0.0]
            j.springref = 0.0
        parent = b
    return spec.compile()


INTEGRATORS = {"RK4": "mjINT_RK4", "implicitfast": "mjINT_IMPLICITFAST", "implicit": "mjINT_IMPLICIT",
               "discrete": "mjINT_DISCRETE", "Euler": "mjINT_EULER"}


class Engine:
    name = NAME

    def __init__(self, n, k=0.0, c=0.0):
        import mujoco

        self.mj = mujoco
        self.n = n
        self.warnings = []
        mujoco.set_mju_user_warning(self.warnings.append)  # unstable runs are reported by run()
        self.model = build(n, k, c)
        self.data = mujoco.MjData(self.model)

    def methods(self, stiff):
        names = ["RK4"] + (["implicitfast", "implicit", "discrete"] if stiff else [])
        return [{"method": m, "kind": "steps", "levels": STEPS} for m in names]

    def run(self, method, steps):
        mj, m, d = self.mj, self.model, self.data
        m.opt.integrator = getattr(mj.mjtIntegrator, INTEGRATORS[method])
        m.opt.timestep = 1.0 / steps
        mj.mj_resetData(m, d)
        # in 8 chunks, so that an unstable run stops at the first sign (MuJoCo
        # resets the state on bad accelerations and would go on to t = 1)
        chunks = [steps // 8 + (1 if j < steps % 8 else 0) for j in range(8)]
        wall = 0.0
        for j, nstep in enumerate(chunks):
            t0 = time.perf_counter()
            mj.mj_step(m, d, nstep=nstep)
            wall += time.perf_counter() - t0
            bad = sum(int(d.warning[w].number) for w in (mj.mjtWarning.mjWARN_BADQACC, mj.mjtWarning.mjWARN_BADQVEL,
                                                         mj.mjtWarning.mjWARN_BADQPOS))
            if bad or not np.all(np.isfinite(d.qpos)):
                raise RuntimeError(f"unstable: MuJoCo flagged bad qacc/qvel/qpos (and reset the state) in "
                                   f"chunk {j + 1} of 8")
        if abs(d.time - 1.0) > 1e-9:
            raise RuntimeError(f"ended at t = {d.time}")
        mj.mj_kinematics(m, d)
        tip = d.xipos[self.n]
        return {"tip": [float(tip[0]), float(tip[1])], "time": wall, "steps": steps, "evals": None}


def check_mjcf(n=8, k=100.0, c=1.0, seed=3):
    """MJCF text and MjSpec give the same model: max |qacc difference|."""
    import mujoco

    a = mujoco.MjModel.from_xml_string(mjcf(n, k=k, c=c))
    b = build(n, k, c)
    q = np.random.default_rng(seed).normal(size=(2, n))
    out = []
    for m in (a, b):
        d = mujoco.MjData(m)
        d.qpos[:], d.qvel[:] = q
        mujoco.mj_forward(m, d)
        out.append(d.qacc.copy())
    return float(np.max(np.abs(out[0] - out[1])))


if __name__ == "__main__":
    from bench.peers.selfcheck import selfcheck

    if available()[0]:
        print(f"MJCF vs MjSpec model (N = 8, with springs): max |qacc difference| {check_mjcf():.1e}")
    selfcheck(sys.modules[__name__])
