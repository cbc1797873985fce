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
    leaves the body free. A hinge's ``damping`` becomes a rotational damper
    (``NAME_damping``). Equality constraints: ``connect`` becomes a spherical
    joint at its anchor, ``weld`` a weld in the reference configuration.
    Gravity is the model's. Names are MuJoCo's (``body3``, ``joint2``,
    ``equality0`` where it has none).

    Contacts between geoms are not simulated: ``contacts="warn"`` names the
    colliding geoms in an MjcfWarning, ``"ignore"`` says nothing, ``"error"``
    raises. MjcfError (a ModelError) for what lagmb does not read yet:
    tendons, actuators, a body with more than one joint, joint equalities,
    armature, friction loss, stiffness, limits, a slide's damping.
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
    if m.ntendon:
        refuse(f"tendon '{name(obj.mjOBJ_TENDON, 0, 'tendon')}': tendons are not supported")
    if m.nu:
        refuse(f"actuator '{name(obj.mjOBJ_ACTUATOR, 0, 'actuator')}': actuators are not supported yet")
    colliding = [g for g in range(m.ngeom) if m.geom_contype[g] or m.geom_conaffinity[g]]
    if colliding and not (m.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT) and contacts != "ignore":
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
    model = Model(gravity=tuple(float(g) for g in m.opt.gravity), dimension=3)
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
        for what, values in (("armature", m.dof_armature), ("frictionloss", m.dof_frictionloss)):
            if np.any(values[dof:dof + (6 if kind == 0 else 3 if kind == 1 else 1)] != 0):
                refuse(f"joint '{label}': {what} is not supported yet")
        if m.jnt_stiffness[j] != 0:
            refuse(f"joint '{label}': stiffness is not supported yet")
        if m.jnt_limited[j]:
            refuse(f"joint '{label}': limits (range) are not read yet")
        value = float(m.qpos0[m.jnt_qposadr[j]]) if kind in (2, 3) else 0.0
        if kind == mujoco.mjtJoint.mjJNT_FREE:
            continue
        if kind == mujoco.mjtJoint.mjJNT_BALL:
            model.add_spherical(label, parent, names[b], at=at)
        elif kind == mujoco.mjtJoint.mjJNT_SLIDE:
            model.add_translational(label, parent, names[b], at=at, axis=axis, slide=value)
        else:
            model.add_revolute(label, parent, names[b], at=at, axis=axis, angle=math.remainder(value, 2 * math.pi))
        damping = float(m.dof_damping[dof])
        if damping:
            if kind != mujoco.mjtJoint.mjJNT_HINGE:
                refuse(f"joint '{label}': damping of a {('free', 'ball', 'slide')[kind]} joint is not supported yet")
            model.add_rotational_spring_damper(f"{label}_damping", joint=label, damping=damping)

    for e in range(m.neq):
        label = name(obj.mjOBJ_EQUALITY, e, "equality")
        kind = int(m.eq_type[e])
        if kind not in (mujoco.mjtEq.mjEQ_CONNECT, mujoco.mjtEq.mjEQ_WELD) or \
                m.eq_objtype[e] != obj.mjOBJ_BODY:
            refuse(f"equality '{label}': only connect and weld between bodies are read (joint, tendon and "
                   "distance equalities are not supported yet)")
        if not m.eq_active0[e]:
            continue
        b1, b2 = int(m.eq_obj1id[e]), int(m.eq_obj2id[e])
        i, k = names[group[b1]], names[group[b2]]
        if kind == mujoco.mjtEq.mjEQ_CONNECT:
            anchor = d.xpos[b1] + d.xmat[b1].reshape(3, 3) @ m.eq_data[e][:3]
            model.add_spherical(label, i, k, at=tuple(anchor))
        else:
            model.add_weld(label, i, k)
    return model
