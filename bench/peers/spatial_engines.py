"""The spatial chain of bench/peers/spatial_peers.py in each engine (that
script's docstring gives the problem, and what each engine's run covers):
the poses, the three models (lagmb, Pinocchio, MuJoCo's MJCF) and an Engine
per engine whose run(method, level) returns the tip, the time of the
integration call and the counters."""

import math
import time

import numpy as np

ANGLE0 = 0.1
G = 9.81
INERTIA = (1e-4, 1.0 / 12.0, 1.0 / 12.0)
AXES = (np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0]))  # joint k: AXES[k % 2]
RTOLS = tuple(10.0 ** (-k / 2) for k in range(4, 23))  # 1e-2 .. 1e-11, half decades


def turn(axis, angle):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


def poses(n, angle=ANGLE0):
    """The posed chain: joints [(point, axis in world axes)], bodies
    [(centre, rotation)], tip (far end of rod N-1)."""
    R, p = np.eye(3), np.zeros(3)
    ex = np.array([1.0, 0.0, 0.0])
    joints, bodies = [], []
    for k in range(n):
        if k > 0:
            p = p + R @ ex
        a = AXES[k % 2]
        joints.append((p.copy(), R @ a))
        R = R @ turn(a, angle)
        bodies.append((p + R @ (0.5 * ex), R.copy()))
    return joints, bodies, p + R @ ex


# --------------------------------------------------------------------------
# the three models
# --------------------------------------------------------------------------

def lagmb_chain(n):
    import lagmb as mb

    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    joints, bodies, _ = poses(n)
    prev = m.ground
    for k in range(n):
        (at, axis), (com, R) = joints[k], bodies[k]
        b = m.add_body(f"rod{k}", 1.0, INERTIA, position=tuple(com), orientation=R)
        m.add_revolute(f"j{k}", prev, b, at=tuple(at), axis=tuple(axis), angle=ANGLE0)
        prev = b
    return m


def pinocchio_chain(n):
    import pinocchio as pin

    model = pin.Model()
    model.gravity.linear = np.array([0.0, 0.0, -G])
    parent = 0
    rod = pin.Inertia(1.0, np.array([0.5, 0.0, 0.0]), np.diag(INERTIA))
    for k in range(n):
        placement = pin.SE3(np.eye(3), np.array([0.0 if k == 0 else 1.0, 0.0, 0.0]))
        jm = pin.JointModelRY() if k % 2 == 0 else pin.JointModelRZ()
        jid = model.addJoint(parent, jm, placement, f"j{k}")
        model.appendBodyToJoint(jid, rod, pin.SE3.Identity())
        parent = jid
    return model


def mjcf(n):
    """The chain as MJCF text: nested bodies, one hinge each, a site at the tip."""
    bodies, close = [], []
    for k in range(n):
        ax = "0 1 0" if k % 2 == 0 else "0 0 1"
        tip = '<site name="tip" pos="1 0 0"/>' if k == n - 1 else ""
        bodies.append(f'<body name="rod{k}" pos="{0 if k == 0 else 1} 0 0">'
                      f'<joint name="j{k}" type="hinge" axis="{ax}" damping="0" armature="0" stiffness="0"/>'
                      f'<inertial pos="0.5 0 0" mass="1" diaginertia="{INERTIA[0]!r} {INERTIA[1]!r} {INERTIA[2]!r}"/>'
                      f'{tip}')
        close.append("</body>")
    return ('<mujoco model="spatial_chain"><compiler inertiafromgeom="false" angle="radian"/>'
            f'<option timestep="0.01" integrator="RK4" gravity="0 0 {-G!r}">'
            '<flag contact="disable" constraint="disable"/></option>'
            f'<worldbody>{"".join(bodies)}{"".join(close)}</worldbody></mujoco>')


# --------------------------------------------------------------------------
# engines: run(method, level) -> {"tip", "time", ...}
# --------------------------------------------------------------------------

class LagmbEngine:
    name = "lagmb"
    METHODS = {"auto": {}, "projection-erk": dict(formulation="projection", integrator="erk"),
               "ggl": dict(formulation="ggl")}

    def __init__(self, n):
        import lagmb as mb

        self.mb, self.n = mb, n
        self.model = lagmb_chain(n)
        self.model.compiled()
        self.last_stats = {}

    def methods(self):
        return [{"method": m, "kind": "rtol", "levels": RTOLS} for m in self.METHODS]

    def run(self, method, rtol, atol=None):
        mb = self.mb
        atol = 1e-2 * rtol if atol is None else atol
        t0 = time.perf_counter()
        r = mb.simulate(self.model, 1.0, rtol=rtol, atol=atol, n_out=2, **self.METHODS[method])
        wall = time.perf_counter() - t0
        tip = r.point(f"rod{self.n - 1}", (0.5, 0.0, 0.0))[-1]
        out = {"tip": [float(x) for x in tip], "time": wall, "steps": int(r.stats["steps"]),
               "evals": int(r.stats["residual_evals"])}
        if "method_choice" in r.stats:
            out["method_choice"] = str(r.stats["method_choice"])
        return out

    def accelerations(self, q, v):
        """Joint accelerations at joint angles q, rates v (Pinocchio's order)."""
        mb = self.mb
        js = mb.JointSpace(self.model)
        names = [f"j{k}" for k in range(self.n)]
        qc, vc, _ = js.coordinates(dict(zip(names, q)), dict(zip(names, v)))
        a = mb.solve_accelerations(self.model, qc, vc)[0]
        return np.array([js.motion(nm, qc, vc, a)[2] for nm in names])


class PinocchioEngine:
    name = "pinocchio"

    def __init__(self, n):
        import pinocchio as pin

        self.pin, self.n = pin, n
        self.model = pinocchio_chain(n)
        self.data = self.model.createData()
        self.tau = np.zeros(n)

    def methods(self):
        return [{"method": "DOP853", "kind": "rtol", "levels": RTOLS}]

    def rhs(self, t, y):
        n = self.n
        a = self.pin.aba(self.model, self.data, y[:n], y[n:], self.tau)
        return np.concatenate([y[n:], a])

    def tip(self, q):
        self.pin.forwardKinematics(self.model, self.data, q)
        return self.data.oMi[self.n].act(np.array([1.0, 0.0, 0.0]))

    def run(self, method, rtol, atol=None):
        from scipy.integrate import solve_ivp

        n = self.n
        atol = 1e-2 * rtol if atol is None else atol
        y0 = np.concatenate([np.full(n, ANGLE0), np.zeros(n)])
        t0 = time.perf_counter()
        sol = solve_ivp(self.rhs, (0.0, 1.0), y0, method=method, rtol=rtol, atol=atol)
        wall = time.perf_counter() - t0
        if not sol.success:
            raise RuntimeError(sol.message)
        tip = self.tip(sol.y[:n, -1].copy())
        return {"tip": [float(x) for x in tip], "time": wall, "steps": int(sol.t.size - 1), "evals": int(sol.nfev)}

    def accelerations(self, q, v):
        return self.pin.aba(self.model, self.data, np.asarray(q, float), np.asarray(v, float), self.tau).copy()


class MujocoEngine:
    name = "mujoco"

    def __init__(self, n):
        import mujoco

        self.mj, self.n = mujoco, n
        self.warnings = []
        mujoco.set_mju_user_warning(self.warnings.append)
        try:
            self.model = mujoco.MjModel.from_xml_string(mjcf(n))
            self.built_from = "MJCF text"
        except ValueError as e:  # (the XML parser's element-depth limit, near N = 200)
            raise RuntimeError(f"MJCF refused: {e}") from None
        m = self.model
        assert m.nq == m.nv == n and m.nbody == n + 1
        m.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
        self.data = mujoco.MjData(m)
        self.site = m.site("tip").id

    def methods(self):
        return [{"method": "RK4", "kind": "steps", "levels": None}]

    def run(self, method, steps):
        mj, m, d = self.mj, self.model, self.data
        m.opt.timestep = 1.0 / steps
        mj.mj_resetData(m, d)
        d.qpos[:] = ANGLE0
        t0 = time.perf_counter()
        mj.mj_step(m, d, nstep=steps)
        wall = time.perf_counter() - t0
        bad = sum(int(d.warning[w].number) for w in (mj.mjtWarning.mjWARN_BADQACC, mj.mjtWarning.mjWARN_BADQVEL,
                                                     mj.mjtWarning.mjWARN_BADQPOS))
        if bad or not np.all(np.isfinite(d.qpos)):
            raise RuntimeError(f"unstable at {steps} steps: MuJoCo flagged bad qacc/qvel/qpos")
        if abs(d.time - 1.0) > 1e-9:
            raise RuntimeError(f"ended at t = {d.time}")
        mj.mj_kinematics(m, d)
        return {"tip": [float(x) for x in d.site_xpos[self.site]], "time": wall, "steps": steps}

    def accelerations(self, q, v):
        mj, m = self.mj, self.model
        d = mj.MjData(m)
        d.qpos[:], d.qvel[:] = q, v
        mj.mj_forward(m, d)
        if d.nefc or d.ncon:
            raise RuntimeError(f"mj_forward made {d.nefc} constraint rows, {d.ncon} contacts")
        return d.qacc.copy()


ENGINES = {"lagmb": LagmbEngine, "pinocchio": PinocchioEngine, "mujoco": MujocoEngine}
