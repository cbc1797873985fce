"""The scenes of bench/peers/contact_peers.py, built alike in lagmb and in
MuJoCo (that script's docstring says what each is and why the two are the
same physics): the drop (`drop_bodies`, `lagmb_drop`, `mjcf_drop`), Go1
(`lagmb_go1`, `mujoco_go1`), the slope (`lagmb_slope`, `mjcf_slope`), and
the runs of each engine on them (`LagmbScene`, `MujocoScene`). The
constants are those of the comparison; RESTITUTION is set by
contact_peers.py's calibration before any scene is built."""

import math
import time
import warnings
import xml.etree.ElementTree as ET

import numpy as np

G = 9.81
T_END = 3.0
T_CREEP = 2.0          # creep: displacement between T_CREEP and T_END
N_OUT = 31             # lagmb outputs (every 0.1 s: T_CREEP is output 20)
STIFFNESS = 1e7        # lagmb contact stiffness, N/m^1.5 (mb.urdf.GROUND_CONTACT's)
RESTITUTION = None     # lagmb's e: calibrated to MuJoCo's rebound ratio (calibrate)
FRICTION = 0.5         # drop and slope; Go1: GROUND_CONTACT's 0.8
SLOPE = math.radians(20.0)
TIMECONST, DAMPRATIO = 0.02, 1.0  # MuJoCo solref: its defaults
MJ_VARIANT_REF_DT = 1e-5   # the variants' references, and the free-flight check
GO1 = "go1_description/urdf/go1.urdf"


def quat_to_R(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def rotation_y(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def fl(x):
    return " ".join(repr(float(v)) for v in np.atleast_1d(x))


# --------------------------------------------------------------------------
# the drop scene
# --------------------------------------------------------------------------

def drop_bodies(seed=42, spacing=0.8):
    """20 bodies: dicts of name, shape, size, mass, principal inertia, centre,
    quaternion (w, x, y, z), velocity, angular velocity (global), kind."""
    rng = np.random.default_rng(seed)
    kinds = ["tumble"] * 8 + ["stack"] * 4 + ["ball"] * 4
    rng.shuffle(kinds)
    out = []
    for (i, j), kind in zip([(i, j) for i in range(4) for j in range(4)], kinds):
        cx = (i - 1.5) * spacing + rng.uniform(-0.05, 0.05)
        cy = (j - 1.5) * spacing + rng.uniform(-0.05, 0.05)
        if kind in ("tumble", "stack"):
            size, mass = rng.uniform(0.08, 0.25, 3), rng.uniform(0.3, 3.0)
            if kind == "tumble":
                q = rng.normal(size=4)
                q /= np.linalg.norm(q)
                half = 0.5 * np.abs(quat_to_R(q)) @ size  # half extents along the global axes
                z = half[2] + rng.uniform(0.1, 0.5)
                v = np.array([rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-1.0, 0.5)])
                w = rng.uniform(-4.0, 4.0, 3)
            else:
                yaw = rng.uniform(-math.pi, math.pi)
                q = np.array([math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)])
                z, v, w = size[2] / 2 + rng.uniform(0.02, 0.1), np.zeros(3), np.zeros(3)
            inertia = mass / 12 * np.array([size[1] ** 2 + size[2] ** 2, size[0] ** 2 + size[2] ** 2,
                                            size[0] ** 2 + size[1] ** 2])
            out.append(dict(name=f"box{len(out)}", shape="box", size=size, mass=mass, inertia=inertia,
                            pos=np.array([cx, cy, z]), quat=q, vel=v, omega=w, kind=kind))
            if kind == "stack":
                R, m = rng.uniform(0.04, 0.08), rng.uniform(0.2, 1.0)
                zs = z + size[2] / 2 + R + rng.uniform(0.1, 0.3)
                out.append(dict(name=f"ball{len(out)}", shape="sphere", size=np.array([R]), mass=m,
                                inertia=np.full(3, 0.4 * m * R * R), pos=np.array([cx, cy, zs]),
                                quat=np.array([1.0, 0, 0, 0]), vel=np.array([0.0, 0.0, rng.uniform(-1.0, 0.0)]),
                                omega=np.array([0.0, 0.0, rng.uniform(-5.0, 5.0)]), kind="on a box"))
        else:
            R, m = rng.uniform(0.05, 0.12), rng.uniform(0.3, 3.0)
            out.append(dict(name=f"ball{len(out)}", shape="sphere", size=np.array([R]), mass=m,
                            inertia=np.full(3, 0.4 * m * R * R), pos=np.array([cx, cy, R + rng.uniform(0.1, 0.6)]),
                            quat=np.array([1.0, 0, 0, 0]), vel=np.array([0.0, 0.0, rng.uniform(-1.0, 0.0)]),
                            omega=np.array([0.0, 0.0, rng.uniform(-5.0, 5.0)]), kind="alone"))
    return out


def drop_pairs(bodies, which):
    """Body-body pairs with contact: (sphere, other); `which` "all" (every
    sphere-sphere and sphere-box pair) or "near" (within 0.3 m horizontally
    at the start: a sphere and the box it is dropped onto)."""
    pairs = []
    for i, a in enumerate(bodies):
        for b in bodies[i + 1:]:
            if a["shape"] == "box" and b["shape"] == "box":
                continue
            if which == "near" and math.dist(a["pos"][:2], b["pos"][:2]) > 0.3:
                continue
            pairs.append((a, b) if a["shape"] == "sphere" else (b, a))
    return pairs


def lagmb_drop(bodies, which):
    import lagmb as mb

    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    floor = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), role="collision")
    shapes = {}
    law = dict(stiffness=STIFFNESS, restitution=RESTITUTION, friction=FRICTION)
    for b in bodies:
        R = quat_to_R(b["quat"])
        m.add_body(b["name"], mass=float(b["mass"]), inertia=tuple(map(float, b["inertia"])),
                   position=tuple(map(float, b["pos"])), orientation=R, velocity=tuple(map(float, b["vel"])),
                   angular_velocity=tuple(map(float, b["omega"])))
        shapes[b["name"]] = m.add_shape(b["name"], b["shape"], tuple(map(float, b["size"])),
                                        tuple(map(float, b["pos"])), R, role="collision")
        m.add_contact(f"{b['name']}_floor", shapes[b["name"]], floor, **law)
    for a, b in drop_pairs(bodies, which):
        m.add_contact(f"{a['name']}_{b['name']}", shapes[a["name"]], shapes[b["name"]], **law)
    return m


def mjcf_drop(bodies, opts):
    """Boxes: contype 2, conaffinity 1; spheres 1, 3; floor 3, 3: every pair
    but box-box collides."""
    parts = []
    for b in bodies:
        if b["shape"] == "box":
            geom = f'<geom type="box" size="{fl(b["size"] / 2)}" contype="2" conaffinity="1"/>'
        else:
            geom = f'<geom type="sphere" size="{fl(b["size"][0])}" contype="1" conaffinity="3"/>'
        parts.append(f'<body name="{b["name"]}" pos="{fl(b["pos"])}" quat="{fl(b["quat"])}">'
                     f'<freejoint name="{b["name"]}"/>'
                     f'<inertial pos="0 0 0" mass="{fl(b["mass"])}" diaginertia="{fl(b["inertia"])}"/>{geom}</body>')
    return (f'<mujoco model="drop"><option timestep="0.002" integrator="implicitfast" cone="{opts["cone"]}" '
            f'impratio="{opts["impratio"]!r}" gravity="0 0 {-G!r}"/><default><geom condim="3" '
            f'friction="{FRICTION!r} 0 0" solref="{TIMECONST!r} {DAMPRATIO!r}"/></default><worldbody>'
            '<geom name="floor" type="plane" size="0 0 1" contype="3" conaffinity="3"/>'
            f'{"".join(parts)}</worldbody></mujoco>')


# --------------------------------------------------------------------------
# Go1
# --------------------------------------------------------------------------

GO1_FLOOR = -0.35


def lagmb_go1(path):
    import lagmb as mb

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        return mb.load_urdf(path, floating_base=True, ground=GO1_FLOOR, contact={"restitution": RESTITUTION})


def mujoco_go1(path, opts):
    """MuJoCo's model of the file (see the module's docstring)."""
    return mujoco_go1_spec(path, opts).compile()


def mujoco_go1_spec(path, opts):
    """mujoco_go1's MjSpec before compiling (actuators may be added to it)."""
    import mujoco

    root = ET.parse(path).getroot()
    for link in root.iter("link"):
        for element in link.findall("visual"):
            link.remove(element)
        if link.get("name") == "base":  # its inertia is not positive definite: MuJoCo refuses it
            inertia = link.find("inertial/inertia")
            for key in ("ixy", "ixz", "iyz"):
                inertia.set(key, "0")
    spec = mujoco.MjSpec.from_string(ET.tostring(root, encoding="unicode"))
    spec.worldbody.first_body().add_freejoint()
    for joint in spec.joints:
        if joint.type == mujoco.mjtJoint.mjJNT_HINGE:
            joint.limited = mujoco.mjtLimited.mjLIMITED_TRUE
    friction = 0.8
    for geom in spec.geoms:
        geom.contype, geom.conaffinity, geom.condim = 1, 0, 3  # the robot touches the floor only
        geom.friction = [friction, 0.0, 0.0]
        geom.solref = [TIMECONST, DAMPRATIO]
    floor = spec.worldbody.add_geom()
    floor.name, floor.type, floor.size, floor.pos = "floor", mujoco.mjtGeom.mjGEOM_PLANE, [0, 0, 1], [0, 0, GO1_FLOOR]
    floor.contype, floor.conaffinity, floor.condim = 0, 1, 3
    floor.friction, floor.solref = [friction, 0.0, 0.0], [TIMECONST, DAMPRATIO]
    spec.option.cone = {"elliptic": mujoco.mjtCone.mjCONE_ELLIPTIC, "pyramidal": mujoco.mjtCone.mjCONE_PYRAMIDAL}[
        opts["cone"]]
    spec.option.impratio = opts["impratio"]
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.gravity = [0.0, 0.0, -G]
    return spec


# --------------------------------------------------------------------------
# the slope
# --------------------------------------------------------------------------

CUBE, CUBE_MASS = 0.2, 1.0


def slope_start():
    """The cube's axes (the slope's) and centre, at rest on its four lower
    corners at lagmb's Hertz depth (downhill along -x)."""
    axes = rotation_y(-SLOPE)
    d0 = (CUBE_MASS * G * math.cos(SLOPE) / (4 * STIFFNESS)) ** (2.0 / 3.0)
    return axes, (CUBE / 2 - d0) * axes[:, 2]


def lagmb_slope():
    import lagmb as mb

    axes, centre = slope_start()
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    m.add_body("cube", mass=CUBE_MASS, inertia=(CUBE_MASS * CUBE * CUBE / 6,) * 3, position=tuple(centre),
               orientation=axes)
    slope = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), axes, role="collision")
    cube = m.add_shape("cube", "box", (CUBE,) * 3, tuple(centre), axes, role="collision")
    m.add_contact("slope", cube, slope, stiffness=STIFFNESS, restitution=RESTITUTION, friction=FRICTION)
    return m


def mjcf_slope(opts):
    axes, centre = slope_start()
    q = (math.cos(-SLOPE / 2), 0.0, math.sin(-SLOPE / 2), 0.0)  # rotation_y(-SLOPE)
    return (f'<mujoco model="slope"><option timestep="0.002" integrator="implicitfast" cone="{opts["cone"]}" '
            f'impratio="{opts["impratio"]!r}" gravity="0 0 {-G!r}"/><default><geom condim="3" '
            f'friction="{FRICTION!r} 0 0" solref="{TIMECONST!r} {DAMPRATIO!r}"/></default><worldbody>'
            f'<geom name="slope" type="plane" size="0 0 1" quat="{fl(q)}"/>'
            f'<body name="cube" pos="{fl(centre)}" quat="{fl(q)}"><freejoint name="cube"/>'
            f'<inertial pos="0 0 0" mass="{CUBE_MASS!r}" diaginertia="{fl([CUBE * CUBE / 6 * CUBE_MASS] * 3)}"/>'
            f'<geom type="box" size="{fl([CUBE / 2] * 3)}"/></body></worldbody></mujoco>')


# --------------------------------------------------------------------------
# runs: each returns {"P": (n, 3) centres of mass at T_END, "R": (n, 3, 3),
# "P2": (n, 3) at T_CREEP, "speed": (n,) centre-of-mass speeds at T_END,
# "penetration": deepest at T_END, "time": s, ...}
# --------------------------------------------------------------------------

class LagmbScene:
    engine = "lagmb"

    def __init__(self, model, bodies, downhill=None):
        import lagmb as mb

        self.mb, self.model, self.bodies = mb, model, bodies
        self.downhill = downhill
        self.contacts = [kw["name"] for kind, kw in model.elements if kind == "add_contact"]
        model.compiled()

    def run(self, rtol, atol, n_out=N_OUT, keep=False):
        mb = self.mb
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = mb.simulate(self.model, T_END, rtol=rtol, atol=atol, n_out=n_out)
        wall = time.perf_counter() - t0
        i2 = int(np.argmin(np.abs(r.t - T_CREEP)))
        assert abs(r.t[i2] - T_CREEP) < 1e-12 and abs(r.t[-1] - T_END) < 1e-12
        paths = [r.body(name) for name in self.bodies]
        out = {"time": wall, "steps": int(r.stats["steps"]), "events": int(r.stats["events"]),
               "method": str(r.stats.get("method", "")),
               "P": np.array([p.position[-1] for p in paths]), "P2": np.array([p.position[i2] for p in paths]),
               "R": np.array([p.rotation[-1] for p in paths]),
               "speed": np.array([np.linalg.norm(p.velocity[-1]) for p in paths])}
        if keep:
            readings = [r.contact(c) for c in self.contacts]
            out["penetration"] = float(max(c.penetration[-1] for c in readings))
            out["stuck"] = int(sum(c.state[-1] == "stick" for c in readings))
            out["pressing"] = int(sum(c.penetration[-1] > 0 for c in readings))
            out["stick_events"] = int(sum(e["kind"] == "friction" and e["label"] == "stick" for e in r.events))
            out["result"] = r
        return out


class MujocoScene:
    engine = "mujoco"

    def __init__(self, model, bodies, qpos0=None, qvel0=None, downhill=None):
        import mujoco

        self.mj, self.model, self.data = mujoco, model, mujoco.MjData(model)
        self.ids = [model.body(name).id for name in bodies]
        self.qpos0, self.qvel0 = qpos0, qvel0
        self.downhill = downhill
        self.warnings = []
        mujoco.set_mju_user_warning(self.warnings.append)

    def reset(self, dt):
        mj, m, d = self.mj, self.model, self.data
        m.opt.timestep = dt
        mj.mj_resetData(m, d)
        if self.qpos0 is not None:
            d.qpos[:] = self.qpos0
        if self.qvel0 is not None:
            d.qvel[:] = self.qvel0
        mj.mj_forward(m, d)

    def state(self):
        mj, m, d = self.mj, self.model, self.data
        speed = []
        v = np.zeros(6)
        for i in self.ids:
            mj.mj_objectVelocity(m, d, mj.mjtObj.mjOBJ_BODY, i, v, 0)  # (rot, lin) at the centre of mass
            speed.append(np.linalg.norm(v[3:]))
        return d.xipos[self.ids].copy(), d.xmat[self.ids].reshape(-1, 3, 3).copy(), np.array(speed)

    def run(self, dt, keep=False):
        """3 s at a step of about dt: T_END / n, n = round(T_END / dt)."""
        mj, m, d = self.mj, self.model, self.data
        n = max(1, round(T_END / dt))
        n2 = round(n * T_CREEP / T_END)
        self.reset(T_END / n)
        t0 = time.perf_counter()
        mj.mj_step(m, d, nstep=n2)
        wall = time.perf_counter() - t0
        P2, _, _ = self.state()
        t0 = time.perf_counter()
        mj.mj_step(m, d, nstep=n - n2)
        wall += time.perf_counter() - t0
        bad = sum(int(d.warning[w].number) for w in (mj.mjtWarning.mjWARN_BADQACC, mj.mjtWarning.mjWARN_BADQVEL,
                                                     mj.mjtWarning.mjWARN_BADQPOS))
        if bad or not np.all(np.isfinite(d.qpos)):
            raise RuntimeError(f"unstable at dt = {T_END / n:g}: MuJoCo flagged bad qacc/qvel/qpos")
        mj.mj_forward(m, d)
        P, R, speed = self.state()
        out = {"time": wall, "steps": n, "dt": T_END / n, "P": P, "P2": P2, "R": R, "speed": speed}
        if keep:
            out["penetration"] = float(max(-d.contact.dist[:d.ncon])) if d.ncon else 0.0
            out["contacts"] = int(d.ncon)
            out["qpos"] = d.qpos.copy()
        return out

    def free_flight(self, t, dt=MJ_VARIANT_REF_DT):
        mj, m, d = self.mj, self.model, self.data
        self.reset(dt)
        mj.mj_step(m, d, nstep=round(t / dt))
        mj.mj_forward(m, d)
        return self.state()[:2], int(d.ncon)
