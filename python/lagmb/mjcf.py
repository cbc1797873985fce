"""MuJoCo models (MJCF) as lagmb models: ``mb.load_mjcf``.

MuJoCo's own compiler (the ``mujoco`` package, the ``mjcf`` extra) reads the
file: defaults, includes, frames and inertias from geoms are resolved as
MuJoCo resolves them. lagmb then reads the compiled model in its reference
configuration (qpos0): bodies (those without a joint merged into their
parent, as fixed links are), joints (hinge, slide, ball, free) and equality
constraints (connect, weld), so a closed loop that MJCF describes with an
equality constraint runs with exact constraints. What lagmb does not read is
refused by name (MjcfError), or, for contacts, named in a warning.
"""

import math
import os
import warnings

import numpy as np

from . import _checks
from .errors import ModelError
from .functions import Constant
from .model import Model
from ._model_files import GROUND_CONTACT, LARGEST, Namespace


class MjcfError(ModelError):
    """An MJCF file that cannot make a lagmb model (a ModelError): the
    message names the file and the MuJoCo element."""


class MjcfWarning(UserWarning):
    """Something of an MJCF file lagmb leaves out (contacts between geoms),
    or a name it changes (MuJoCo keeps bodies, joints and equalities in
    namespaces of their own, lagmb has one)."""


def _mujoco():
    try:
        import mujoco
    except ImportError:
        raise ModelError("load_mjcf needs MuJoCo's compiler: pip install mujoco (or lagmb's mjcf extra)") from None
    return mujoco


def load_mjcf(path, *, contacts="warn", contact=None):
    """A spatial :class:`lagmb.Model` of the MuJoCo model in an MJCF file.

    Bodies: each MuJoCo body with its mass, centre of mass and inertia (a
    body without joints is merged into its parent, and one fixed to the
    world is the ground). Joints: a hinge becomes a revolute, a slide a
    translational joint (``angle``/``slide`` their qpos0 values, so lagmb's
    joint values are MuJoCo's), a ball a spherical joint, a free joint
    leaves the body free. A hinge's or slide's ``damping`` becomes viscous
    joint friction (``NAME_damping``). Equality constraints: ``connect``
    becomes a spherical joint at its anchor, ``weld`` a weld in the
    reference configuration, ``joint`` (linear polycoef) a joint coupling,
    or with one joint a constant driver.
    Gravity is the model's. Names are MuJoCo's (``body3``, ``joint2``,
    ``equality0`` where it has none); MuJoCo keeps bodies, joints and
    equalities apart and lagmb has one namespace, so a joint named like a
    body is called ``NAME_joint``, and any other name already taken (a body
    named ``ground``, an equality named like a joint, a joint ``j_damping``
    beside the damping of ``j``) gets its kind and then a number added
    (``ground_body``, ``j_damping_2``), each change listed in an
    MjcfWarning. What the model's ``<option><flag>``
    disables MuJoCo leaves out and so does lagmb: gravity (``gravity``),
    joint damping (``damper``), equality constraints (``equality`` or
    ``constraint``).

    Contacts between geoms: ``contacts="simulate"`` makes each colliding
    geom (MuJoCo's ``contype``/``conaffinity``, or one of a ``<pair>``) a
    collision shape (plane, sphere, capsule, cylinder, box at its pose in
    the reference configuration) and adds a contact (``GEOM1_GEOM2``) for
    each pair MuJoCo would test: geoms on different bodies whose contype
    and conaffinity bits meet, not a body and its parent unless the parent
    is the world (MuJoCo's filterparent), not an ``<exclude>``d pair; and
    every ``<pair>``. The law is lagmb's Hertz contact (MuJoCo's solref and
    solimp have no counterpart): ``mb.urdf.GROUND_CONTACT``'s stiffness and
    restitution, the larger of the two geoms' sliding friction, as
    ``contact`` (a dict of add_contact's keywords) updates them. Pairs of
    shapes lagmb has no contact for (box-box, ...) and geoms of other types
    (ellipsoid, mesh, height field) are left out, named in an MjcfWarning.
    Otherwise contacts are not simulated: ``contacts="warn"`` names the
    colliding geoms in an MjcfWarning, ``"ignore"`` says nothing, ``"error"``
    raises. MjcfError (a ModelError) for what lagmb does not read yet:
    tendons, actuators, flexes, plugins, a body with more than one joint,
    joint equalities beyond the linear term or of ball and free joints,
    armature, friction loss, stiffness (linear or not), limits, damping of
    a ball or free joint, nonlinear damping
    (``damping`` with more than one coefficient), gravity compensation
    (``gravcomp``), fluid forces (``density`` or ``viscosity``), an
    equality that does not hold in the reference configuration (a weld's
    ``relpose``).
    """
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise MjcfError(f"load_mjcf: path must be a file name (a str or os.PathLike), got {_checks.show(path)}")
    path = os.fsdecode(path)
    if "\0" in path:  # (MuJoCo would read the file named by the part before it)
        raise MjcfError(f"load_mjcf: path {_checks.show(path)} holds a NUL character")
    if not (isinstance(contacts, str) and contacts in ("warn", "ignore", "error", "simulate")):
        raise MjcfError(f"load_mjcf: contacts must be 'warn', 'ignore', 'error' or 'simulate', got "
                        f"{_checks.show(contacts)}")
    if contact is not None and (contacts != "simulate" or not isinstance(contact, dict)):
        raise MjcfError("load_mjcf: contact (a dict of add_contact's keywords) goes with contacts='simulate', got "
                        f"{_checks.show(contact)}")
    mujoco = _mujoco()
    try:
        m = mujoco.MjModel.from_xml_path(path)
    except (ValueError, OSError) as e:
        raise MjcfError(f"{path}: MuJoCo's compiler refused it: {e}") from None
    d = mujoco.MjData(m)
    d.qpos[:] = m.qpos0
    mujoco.mj_forward(m, d)

    def name(kind, index, fallback):
        text = mujoco.mj_id2name(m, kind, index)
        return text if text else f"{fallback}{index}"

    def refuse(what):
        raise MjcfError(f"{path}: {what}")

    obj = mujoco.mjtObj
    off = mujoco.mjtDisableBit

    def disabled(*bits):  # what <option><flag .../> switches off in MuJoCo
        return any(int(m.opt.disableflags) & int(bit) for bit in bits)

    if m.ntendon:
        refuse(f"tendon '{name(obj.mjOBJ_TENDON, 0, 'tendon')}': tendons are not supported")
    if m.nu:
        refuse(f"actuator '{name(obj.mjOBJ_ACTUATOR, 0, 'actuator')}': actuators are not supported yet")
    if m.nflex:
        refuse(f"flex '{name(obj.mjOBJ_FLEX, 0, 'flex')}': flexes (deformable bodies) are not supported")
    if m.nplugin:
        refuse(f"plugin '{name(obj.mjOBJ_PLUGIN, 0, 'plugin')}': plugins are not supported (one may add forces "
               "lagmb does not know)")
    if m.opt.density or m.opt.viscosity:
        refuse(f"option density={m.opt.density:g} viscosity={m.opt.viscosity:g}: fluid forces are not supported")
    for b in range(1, m.nbody):
        if m.body_gravcomp[b]:
            refuse(f"body '{name(obj.mjOBJ_BODY, b, 'body')}': gravity compensation (gravcomp) is not supported")
    colliding = [g for g in range(m.ngeom) if m.geom_contype[g] or m.geom_conaffinity[g]]
    colliding += sorted({int(g) for p in range(m.npair) for g in (m.pair_geom1[p], m.pair_geom2[p])} - set(colliding))
    if colliding and not disabled(off.mjDSBL_CONTACT, off.mjDSBL_CONSTRAINT) and contacts not in ("ignore",
                                                                                                  "simulate"):
        listed = ", ".join(repr(name(obj.mjOBJ_GEOM, g, "geom")) for g in colliding[:5])
        text = (f"{path}: contacts between geoms are not simulated by lagmb ({len(colliding)} geoms collide in "
                f"MuJoCo: {listed}{', ...' if len(colliding) > 5 else ''}); pass contacts='ignore' to say nothing")
        if contacts == "error":
            raise MjcfError(text)
        warnings.warn(MjcfWarning(text), stacklevel=2)

    # groups: a body without joints moves with its parent
    group = {0: 0}
    for b in range(1, m.nbody):
        group[b] = b if m.body_jntnum[b] > 0 else group[int(m.body_parentid[b])]
    equalities = range(0 if disabled(off.mjDSBL_EQUALITY, off.mjDSBL_CONSTRAINT) else m.neq)
    names = {0: "ground"}  # body id -> its name in the model
    label = {}  # (kind, id) -> the model's name of a body, joint or equality: the file's names first
    space = Namespace()
    elements = [("body", obj.mjOBJ_BODY, b) for b in range(1, m.nbody) if group[b] == b] + \
        [("joint", obj.mjOBJ_JOINT, j) for j in range(m.njnt) if m.jnt_type[j] != mujoco.mjtJoint.mjJNT_FREE] + \
        [("equality", obj.mjOBJ_EQUALITY, e) for e in equalities if m.eq_active0[e]]
    for given in (True, False):
        for kind, code, index in elements:
            text = mujoco.mj_id2name(m, code, index)
            if bool(text) == given:
                label[kind, index] = space.claim(text or f"{kind}{index}", kind,
                                                 f"{kind} '{text}'" if text else f"{kind} {index} (unnamed)",
                                                 quiet=("body",) if kind == "joint" else (), made=not text)

    def add(what, method, *args, **kwargs):  # (the core's checks, naming MuJoCo's element)
        try:
            return method(*args, **kwargs)
        except ModelError as e:
            refuse(f"{what}: {e}")

    joint_value = {}  # MuJoCo joint id -> (its name in the model, its value at qpos0): hinges and slides
    gravity = np.zeros(3) if disabled(off.mjDSBL_GRAVITY) else m.opt.gravity
    model = Model(gravity=tuple(float(g) for g in gravity), dimension=3,
                  name=os.path.splitext(os.path.basename(str(path)))[0])
    for b in range(1, m.nbody):
        if group[b] != b:
            continue
        members = [c for c in range(1, m.nbody) if group[c] == b]
        what = f"body '{name(obj.mjOBJ_BODY, b, 'body')}'"
        names[b] = label["body", b]
        if m.body_jntnum[b] > 1:
            refuse(f"{what} has {m.body_jntnum[b]} joints; lagmb takes one joint per body (joints "
                   "in series need bodies between them)")
        for c in members:  # (beyond LARGEST, squares overflow: lagmb's equations hold none)
            if not (np.abs(d.xipos[c]).max() <= LARGEST and np.abs(d.xpos[c]).max() <= LARGEST and
                    m.body_mass[c] <= LARGEST and np.abs(m.body_inertia[c]).max() <= LARGEST):
                refuse(f"body '{name(obj.mjOBJ_BODY, c, 'body')}': its position, mass or inertia is beyond what a "
                       f"model can hold (at most {LARGEST:g} m, kg, kg m^2: lagmb squares them, and larger squares "
                       "overflow)")
        mass = float(sum(m.body_mass[c] for c in members))
        com = sum(m.body_mass[c] * d.xipos[c] for c in members) / mass if mass > 0 else d.xpos[b].copy()
        inertia = np.zeros((3, 3))
        with np.errstate(over="ignore", invalid="ignore"):  # (m r^2 may overflow: refused below)
            for c in members:  # each body's principal inertia about the common centre, world axes
                R = d.ximat[c].reshape(3, 3)
                r = d.xipos[c] - com
                inertia += R @ np.diag(m.body_inertia[c]) @ R.T + m.body_mass[c] * (r @ r * np.eye(3) -
                                                                                    np.outer(r, r))
        if not np.abs(inertia).max() <= LARGEST:
            refuse(f"{what}: its inertia about its centre of mass ({np.abs(inertia).max():g} kg m^2) is beyond what a "
                   f"model can hold (at most {LARGEST:g})")
        R0 = d.xmat[b].reshape(3, 3)
        inertia_body = R0.T @ inertia @ R0
        add(what, model.add_body, names[b], mass, 0.5 * (inertia_body + inertia_body.T), position=tuple(com),
            orientation=R0)

    for j in range(m.njnt):
        b = int(m.jnt_bodyid[j])
        mj_name = name(obj.mjOBJ_JOINT, j, "joint")
        what = f"joint '{mj_name}'"
        kind = int(m.jnt_type[j])
        parent = names[group[int(m.body_parentid[b])]]
        at, axis = tuple(d.xanchor[j]), tuple(d.xaxis[j])
        dof = int(m.jnt_dofadr[j])
        dofs = slice(dof, dof + (6 if kind == 0 else 3 if kind == 1 else 1))
        for quantity, values in (("armature", m.dof_armature), ("frictionloss", m.dof_frictionloss)):
            if np.any(values[dofs] != 0):
                refuse(f"{what}: {quantity} is not supported yet")
        if m.jnt_stiffness[j] != 0 or np.any(m.jnt_stiffnesspoly[j] != 0):
            refuse(f"{what}: stiffness is not supported yet")
        if m.jnt_limited[j]:
            refuse(f"{what}: limits (range) are not read yet")
        value = float(m.qpos0[m.jnt_qposadr[j]]) if kind in (2, 3) else 0.0
        damping = 0.0 if disabled(off.mjDSBL_DAMPER) else float(m.dof_damping[dof])
        if damping and kind in (mujoco.mjtJoint.mjJNT_FREE, mujoco.mjtJoint.mjJNT_BALL):
            refuse(f"{what}: damping of a {('free', 'ball')[kind]} joint is not supported yet")
        if not disabled(off.mjDSBL_DAMPER) and np.any(m.dof_dampingpoly[dofs] != 0):
            refuse(f"{what}: nonlinear damping (damping with more than one coefficient) is not supported")
        if kind == mujoco.mjtJoint.mjJNT_FREE:
            continue
        if not (np.abs(at).max() <= LARGEST and abs(value) <= LARGEST and abs(damping) <= LARGEST):
            refuse(f"{what}: its anchor, qpos0 value or damping is beyond what a model can hold (at most {LARGEST:g})")
        label_j = label["joint", j]
        if kind == mujoco.mjtJoint.mjJNT_BALL:
            add(what, model.add_spherical, label_j, parent, names[b], at=at)
        elif kind == mujoco.mjtJoint.mjJNT_SLIDE:
            add(what, model.add_translational, label_j, parent, names[b], at=at, axis=axis, slide=value)
        else:
            add(what, model.add_revolute, label_j, parent, names[b], at=at, axis=axis,
                angle=math.remainder(value, 2 * math.pi))
        if damping:  # (a hinge's or a slide's)
            add(what, model.add_joint_friction,
                space.claim(f"{label_j}_damping", "damping", f"the damping of {what}", made=True), joint=label_j,
                viscous=damping)
        joint_value[j] = (label_j, value if kind == mujoco.mjtJoint.mjJNT_SLIDE else math.remainder(value, 2 * math.pi))

    for e in equalities:
        what = f"equality '{name(obj.mjOBJ_EQUALITY, e, 'equality')}'"
        kind = int(m.eq_type[e])
        if kind == mujoco.mjtEq.mjEQ_JOINT:
            if m.eq_active0[e]:
                _couple_joints(model, m, e, what, label["equality", e], joint_value, refuse, add)
            continue
        if kind not in (mujoco.mjtEq.mjEQ_CONNECT, mujoco.mjtEq.mjEQ_WELD) or \
                m.eq_objtype[e] != obj.mjOBJ_BODY:
            refuse(f"{what}: only connect and weld between bodies and joint equalities are read "
                   "(tendon and distance equalities are not supported yet)")
        if not m.eq_active0[e]:
            continue
        # lagmb joins the bodies as they are at qpos0: MuJoCo must hold them there too (a weld's relpose)
        gap = max((abs(d.efc_pos[r]) for r in range(d.nefc)
                   if d.efc_type[r] == mujoco.mjtConstraint.mjCNSTR_EQUALITY and d.efc_id[r] == e), default=0.0)
        if gap > 1e-9:
            refuse(f"{what}: MuJoCo holds its bodies elsewhere than where they are in the reference "
                   f"configuration (qpos0; {gap:.3g} apart; a weld's relpose), and lagmb joins them as they are there")
        b1, b2 = int(m.eq_obj1id[e]), int(m.eq_obj2id[e])
        i, k = names[group[b1]], names[group[b2]]
        if kind == mujoco.mjtEq.mjEQ_CONNECT:
            anchor = d.xpos[b1] + d.xmat[b1].reshape(3, 3) @ m.eq_data[e][:3]
            if not np.abs(anchor).max() <= LARGEST:
                refuse(f"{what}: its anchor is beyond what a model can hold (at most {LARGEST:g} m)")
            add(what, model.add_spherical, label["equality", e], i, k, at=tuple(anchor))
        else:
            add(what, model.add_weld, label["equality", e], i, k)
    if contacts == "simulate" and colliding and not disabled(off.mjDSBL_CONTACT, off.mjDSBL_CONSTRAINT):
        _contacts(model, m, d, path, colliding, group, names, space, contact or {}, disabled(off.mjDSBL_FILTERPARENT))
    space.warn(path, MjcfWarning)
    return model


def _contacts(model, m, d, path, colliding, group, names, space, given, no_filter):
    """The collision shapes of the colliding geoms and a contact for each
    pair MuJoCo tests (load_mjcf, contacts="simulate")."""
    import mujoco

    obj, geom = mujoco.mjtObj, mujoco.mjtGeom

    def gname(g):
        return mujoco.mj_id2name(m, obj.mjOBJ_GEOM, g) or f"geom{g}"

    kinds = {int(geom.mjGEOM_PLANE): "plane", int(geom.mjGEOM_SPHERE): "sphere", int(geom.mjGEOM_CAPSULE): "capsule",
             int(geom.mjGEOM_CYLINDER): "cylinder", int(geom.mjGEOM_BOX): "box"}
    shapes, left_out = {}, []
    for g in colliding:
        kind = kinds.get(int(m.geom_type[g]))
        if kind is None:
            left_out.append(f"geom '{gname(g)}' (its type is not a collision shape lagmb has)")
            continue
        size = m.geom_size[g]
        size = {"plane": (), "sphere": (size[0],), "capsule": (size[0], 2 * size[1]),
                "cylinder": (size[0], 2 * size[1]), "box": tuple(2 * size)}[kind]
        shapes[g] = model.add_shape(names[group[int(m.geom_bodyid[g])]], kind, tuple(float(x) for x in size),
                                    position=tuple(d.geom_xpos[g]), orientation=d.geom_xmat[g].reshape(3, 3),
                                    role="collision")
    excluded = {int(x) for x in m.exclude_signature[:m.nexclude]} if m.nexclude else set()
    pairs = [(int(m.pair_geom1[p]), int(m.pair_geom2[p])) for p in range(m.npair)]
    listed = set(pairs)
    for a, b in ((a, b) for i, a in enumerate(colliding) for b in colliding[i + 1:]):
        ba, bb = int(m.geom_bodyid[a]), int(m.geom_bodyid[b])
        ga, gb = group[ba], group[bb]
        if ga == gb or (a, b) in listed or (b, a) in listed:
            continue
        if not (m.geom_contype[a] & m.geom_conaffinity[b] or m.geom_contype[b] & m.geom_conaffinity[a]):
            continue
        parents = {group[int(m.body_parentid[ba])], group[int(m.body_parentid[bb])]}
        if not no_filter and (ga in parents or gb in parents) and 0 not in (ga, gb):
            continue
        if (min(ba, bb) << 16) + max(ba, bb) in excluded:  # (MuJoCo's signature of a body pair)
            continue
        pairs.append((a, b))
    law = dict(GROUND_CONTACT)
    for a, b in pairs:
        if a not in shapes or b not in shapes:
            continue
        values = dict(law, friction=float(max(m.geom_friction[a][0], m.geom_friction[b][0])))
        values.update(given)
        name = space.claim(f"{gname(a)}_{gname(b)}", "contact", f"the contact of geoms '{gname(a)}' and "
                           f"'{gname(b)}'", made=True)
        try:
            model.add_contact(name, shapes[a], shapes[b], **values)
        except ModelError as e:
            if "no contact between" not in str(e):
                raise MjcfError(f"{path}: geoms '{gname(a)}' and '{gname(b)}': {e}") from None
            left_out.append(f"geoms '{gname(a)}' and '{gname(b)}' ({shapes[a].kind}-{shapes[b].kind})")
    if left_out:
        warnings.warn(MjcfWarning(f"{path}: contacts='simulate' leaves out " + "; ".join(left_out)), stacklevel=3)


def _couple_joints(model, m, e, what, label, joint_value, refuse, add):
    """An MJCF <joint> equality, y - y0 = a0 + a1 (x - x0) (MuJoCo's
    polycoef; y joint1, x joint2, y0 and x0 their values at qpos0): a joint
    coupling y = a1 x + (y0 + a0 - a1 x0). Without joint2, y = y0 + a0: the
    joint held by a constant driver. Only the linear polynomial is read."""
    a = m.eq_data[e][:5]
    j1, j2 = int(m.eq_obj1id[e]), int(m.eq_obj2id[e])
    if np.any(a[2:] != 0):
        refuse(f"{what}: a joint equality with polycoef beyond the linear term "
               f"({' '.join(f'{c:g}' for c in a)}) is not supported")
    for j in (j1, j2):
        if j >= 0 and j not in joint_value:
            refuse(f"{what}: couples a ball or free joint (only hinge and slide joints have one coordinate)")
    name1, y0 = joint_value[j1]
    if j2 < 0:
        add(what, model.drive_joint, label, name1, Constant(y0 + a[0]))
        return
    name2, x0 = joint_value[j2]
    if a[1] == 0:
        refuse(f"{what}: polycoef a1 = 0 holds '{name1}' still without '{name2}'; leave joint2 out")
    with np.errstate(over="ignore", invalid="ignore"):
        offset = float(y0 + a[0] - a[1] * x0)
    if not (abs(a[1]) <= LARGEST and abs(offset) <= LARGEST):
        refuse(f"{what}: polycoef {a[0]:g} {a[1]:g} is beyond what a model can hold (at most {LARGEST:g})")
    add(what, model.add_joint_coupling, label, name1, leader=name2, multiplier=float(a[1]), offset=offset)
