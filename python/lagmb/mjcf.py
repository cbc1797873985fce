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

from .errors import ModelError
from .functions import Constant
from .model import Model


class MjcfError(ModelError):
    """An MJCF file that cannot make a lagmb model (a ModelError): the
    message names the file and the MuJoCo element."""


class MjcfWarning(UserWarning):
    """Something of an MJCF file lagmb leaves out (contacts between geoms)."""


def _mujoco():
    try:
        import mujoco
    except ImportError:
        raise ModelError("load_mjcf needs MuJoCo's compiler: pip install mujoco (or lagmb's mjcf extra)") from None
    return mujoco


def load_mjcf(path, *, contacts="warn"):
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
    ``equality0`` where it has none). What the model's ``<option><flag>``
    disables MuJoCo leaves out and so does lagmb: gravity (``gravity``),
    joint damping (``damper``), equality constraints (``equality`` or
    ``constraint``).

    Contacts between geoms are not simulated: ``contacts="warn"`` names the
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
    mujoco = _mujoco()
    path = os.fspath(path)
    if contacts not in ("warn", "ignore", "error"):
        raise ModelError(f"load_mjcf: contacts must be 'warn', 'ignore' or 'error', got {contacts!r}")
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
    if colliding and not disabled(off.mjDSBL_CONTACT, off.mjDSBL_CONSTRAINT) and contacts != "ignore":
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
    names = {0: "ground"}
    joint_value = {}  # MuJoCo joint id -> (its name in the model, its value at qpos0): hinges and slides
    gravity = np.zeros(3) if disabled(off.mjDSBL_GRAVITY) else m.opt.gravity
    model = Model(gravity=tuple(float(g) for g in gravity), dimension=3)
    for b in range(1, m.nbody):
        if group[b] != b:
            continue
        members = [c for c in range(1, m.nbody) if group[c] == b]
        label = name(obj.mjOBJ_BODY, b, "body")
        names[b] = label
        if m.body_jntnum[b] > 1:
            refuse(f"body '{label}' has {m.body_jntnum[b]} joints; lagmb takes one joint per body (joints "
                   "in series need bodies between them)")
        mass = float(sum(m.body_mass[c] for c in members))
        com = sum(m.body_mass[c] * d.xipos[c] for c in members) / mass if mass > 0 else d.xpos[b].copy()
        inertia = np.zeros((3, 3))
        for c in members:  # each body's principal inertia about the common centre, world axes
            R = d.ximat[c].reshape(3, 3)
            r = d.xipos[c] - com
            inertia += R @ np.diag(m.body_inertia[c]) @ R.T + m.body_mass[c] * (r @ r * np.eye(3) - np.outer(r, r))
        R0 = d.xmat[b].reshape(3, 3)
        inertia_body = R0.T @ inertia @ R0
        try:
            model.add_body(label, mass, 0.5 * (inertia_body + inertia_body.T), position=tuple(com),
                           orientation=R0)
        except ModelError as e:
            refuse(f"body '{label}': {e}")

    for j in range(m.njnt):
        b = int(m.jnt_bodyid[j])
        label = name(obj.mjOBJ_JOINT, j, "joint")
        kind = int(m.jnt_type[j])
        parent = names[group[int(m.body_parentid[b])]]
        at, axis = tuple(d.xanchor[j]), tuple(d.xaxis[j])
        dof = int(m.jnt_dofadr[j])
        dofs = slice(dof, dof + (6 if kind == 0 else 3 if kind == 1 else 1))
        for what, values in (("armature", m.dof_armature), ("frictionloss", m.dof_frictionloss)):
            if np.any(values[dofs] != 0):
                refuse(f"joint '{label}': {what} is not supported yet")
        if m.jnt_stiffness[j] != 0 or np.any(m.jnt_stiffnesspoly[j] != 0):
            refuse(f"joint '{label}': stiffness is not supported yet")
        if m.jnt_limited[j]:
            refuse(f"joint '{label}': limits (range) are not read yet")
        value = float(m.qpos0[m.jnt_qposadr[j]]) if kind in (2, 3) else 0.0
        damping = 0.0 if disabled(off.mjDSBL_DAMPER) else float(m.dof_damping[dof])
        if damping and kind in (mujoco.mjtJoint.mjJNT_FREE, mujoco.mjtJoint.mjJNT_BALL):
            refuse(f"joint '{label}': damping of a {('free', 'ball')[kind]} joint is not supported yet")
        if not disabled(off.mjDSBL_DAMPER) and np.any(m.dof_dampingpoly[dofs] != 0):
            refuse(f"joint '{label}': nonlinear damping (damping with more than one coefficient) is not supported")
        if kind == mujoco.mjtJoint.mjJNT_FREE:
            continue
        if kind == mujoco.mjtJoint.mjJNT_BALL:
            model.add_spherical(label, parent, names[b], at=at)
        elif kind == mujoco.mjtJoint.mjJNT_SLIDE:
            model.add_translational(label, parent, names[b], at=at, axis=axis, slide=value)
        else:
            model.add_revolute(label, parent, names[b], at=at, axis=axis, angle=math.remainder(value, 2 * math.pi))
        if damping:  # (a hinge's or a slide's)
            model.add_joint_friction(f"{label}_damping", joint=label, viscous=damping)
        joint_value[j] = (label, value if kind == mujoco.mjtJoint.mjJNT_SLIDE else math.remainder(value, 2 * math.pi))

    for e in range(0 if disabled(off.mjDSBL_EQUALITY, off.mjDSBL_CONSTRAINT) else m.neq):
        label = name(obj.mjOBJ_EQUALITY, e, "equality")
        kind = int(m.eq_type[e])
        if kind == mujoco.mjtEq.mjEQ_JOINT:
            if m.eq_active0[e]:
                _couple_joints(model, m, e, label, joint_value, refuse)
            continue
        if kind not in (mujoco.mjtEq.mjEQ_CONNECT, mujoco.mjtEq.mjEQ_WELD) or \
                m.eq_objtype[e] != obj.mjOBJ_BODY:
            refuse(f"equality '{label}': only connect and weld between bodies and joint equalities are read "
                   "(tendon and distance equalities are not supported yet)")
        if not m.eq_active0[e]:
            continue
        # lagmb joins the bodies as they are at qpos0: MuJoCo must hold them there too (a weld's relpose)
        gap = max((abs(d.efc_pos[r]) for r in range(d.nefc)
                   if d.efc_type[r] == mujoco.mjtConstraint.mjCNSTR_EQUALITY and d.efc_id[r] == e), default=0.0)
        if gap > 1e-9:
            refuse(f"equality '{label}': MuJoCo holds its bodies elsewhere than where they are in the reference "
                   f"configuration (qpos0; {gap:.3g} apart; a weld's relpose), and lagmb joins them as they are there")
        b1, b2 = int(m.eq_obj1id[e]), int(m.eq_obj2id[e])
        i, k = names[group[b1]], names[group[b2]]
        if kind == mujoco.mjtEq.mjEQ_CONNECT:
            anchor = d.xpos[b1] + d.xmat[b1].reshape(3, 3) @ m.eq_data[e][:3]
            model.add_spherical(label, i, k, at=tuple(anchor))
        else:
            model.add_weld(label, i, k)
    return model


def _couple_joints(model, m, e, label, joint_value, refuse):
    """An MJCF <joint> equality, y - y0 = a0 + a1 (x - x0) (MuJoCo's
    polycoef; y joint1, x joint2, y0 and x0 their values at qpos0): a joint
    coupling y = a1 x + (y0 + a0 - a1 x0). Without joint2, y = y0 + a0: the
    joint held by a constant driver. Only the linear polynomial is read."""
    a = m.eq_data[e][:5]
    j1, j2 = int(m.eq_obj1id[e]), int(m.eq_obj2id[e])
    if np.any(a[2:] != 0):
        refuse(f"equality '{label}': a joint equality with polycoef beyond the linear term "
               f"({' '.join(f'{c:g}' for c in a)}) is not supported")
    for j in (j1, j2):
        if j >= 0 and j not in joint_value:
            refuse(f"equality '{label}': couples a ball or free joint (only hinge and slide joints have one "
                   "coordinate)")
    name1, y0 = joint_value[j1]
    if j2 < 0:
        model.drive_joint(label, name1, Constant(y0 + a[0]))
        return
    name2, x0 = joint_value[j2]
    if a[1] == 0:
        refuse(f"equality '{label}': polycoef a1 = 0 holds '{name1}' still without '{name2}'; leave joint2 out")
    model.add_joint_coupling(label, name1, leader=name2, multiplier=float(a[1]),
                             offset=float(y0 + a[0] - a[1] * x0))
