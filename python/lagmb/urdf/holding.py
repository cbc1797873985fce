"""The joints load_urdf holds as fixed joints: those whose motion no mass
or inertia follows (found in the null space of the joint-space mass
matrix), and those its ``hold`` names; with the followers of their mimics.
"""

import warnings

import numpy as np

from .. import _checks
from .joint_values import leader_of, mimics_of
from .mass_matrix import MOTIONLESS, mass_matrix
from .reader import MOVING, UrdfError, UrdfWarning


def motionless_joints(reader, links, joints, order, pose, followers, floating_base):
    """The joints whose motion no mass or inertia follows, in the
    configuration the model is built in: [(joint, partners)], partners None
    for a joint whose coordinate alone moves no mass or inertia (a massless
    finger), else [(joint, rate)] of a motion of several joints that moves
    none (icub's point-mass head, turning about the line from the neck to
    its centre of mass) in which this joint takes part (rates scaled to at
    most 1). Only revolute, continuous and prismatic joints that mimic none
    are held; a mimic's follower is held with its leader.

    The joint-space mass matrix M (Sum over links of m J_c^T J_c +
    J_w^T I J_w, with each independent coordinate's twist at its joint) is
    read first on its diagonal: a coordinate that moves no mass is held;
    then the rest, scaled to a unit diagonal, by its eigenvalues: for each
    (numerically) zero one a joint of its null space is held, the one with
    the largest rate in what is left of it (a QR with column pivoting of
    the null space in joint rates), so that the joints that stay free have a
    regular mass matrix."""
    M, holdable = mass_matrix(links, joints, order, pose, followers, floating_base)
    if M is None:
        return []
    n = len(holdable)
    diagonal = np.diag(M).copy()
    largest = diagonal.max()
    zero = diagonal <= MOTIONLESS * largest
    held = [(holdable[c], None) for c in range(n) if zero[c] and holdable[c] is not None]
    rest = np.flatnonzero(~zero)
    if rest.size == 0:
        return held
    scale = 1.0 / np.sqrt(diagonal[rest])
    scaled = M[np.ix_(rest, rest)] * np.outer(scale, scale)
    values = np.linalg.eigvalsh(scaled)  # (the vectors, several times the work, only where needed)
    if not np.any(values <= MOTIONLESS * values.max()):
        return held
    values, vectors = np.linalg.eigh(scaled)
    null = vectors[:, values <= MOTIONLESS * values.max()]
    if null.shape[1] == 0:
        return held
    rates = np.linalg.qr(null * scale[:, None])[0]  # (the null space in joint rates, orthonormal)
    left = rates.copy()
    can = np.array([holdable[c] is not None for c in rest])
    for _ in range(null.shape[1]):  # pivoted: the joint with the largest rate in what is left of the null space
        norms = np.where(can, np.linalg.norm(left, axis=1), 0.0)
        k = int(np.argmax(norms))
        if norms[k] <= 1e-6:  # (what is left moves no joint that can be held: simulate names it)
            break
        direction = left[k] / norms[k]
        v = left @ direction  # the motion of what is left where this joint's rate is largest
        left = left - np.outer(v, direction)
        can[k] = False
        v = v / np.abs(v).max()
        partners = [(holdable[rest[i]] if holdable[rest[i]] is not None else "a planar or floating joint",
                     float(v[i])) for i in np.argsort(-np.abs(v)) if abs(v[i]) > 1e-6]
        held.append((holdable[rest[k]], partners))
    return held



def hold_motionless(reader, joints, followers, held, value, strict):
    """Each joint of `held` (and the followers of its mimics) fixed at its
    value, with one UrdfWarning naming each joint, its line and why; with
    strict a UrdfError naming the first."""
    def why(name, partners):
        if partners is None:
            return "no mass or inertia moves with it"
        others = [(other, rate) for other, rate in partners if other != name]
        shown = ", ".join(f"'{other}' {rate:.3g}" for other, rate in others)
        rate = dict(partners)[name]
        return (f"turned at {rate:.3g} with {shown} (rad/s, m/s for a prismatic), it moves no mass or inertia"
                if others else "no mass or inertia moves with it")

    if strict:
        name, partners = held[0]
        more = f" ({len(held)} joints in all: {', '.join(repr(h) for h, _ in held)})" if len(held) > 1 else ""
        reader.fail(joints[name]["element"], f"{why(name, partners)}, so the forces do not determine its motion"
                    f"{more}; strict=True refuses this: give the links it moves mass and inertia, or load with "
                    "strict=False to hold it at its initial position", f"joint '{name}'")
    mimics = mimics_of(followers)
    shown = []
    for name, partners in held:
        also = f", with its mimic{'s' if len(mimics[name]) > 1 else ''} {', '.join(repr(f) for f in mimics[name])}" \
            if mimics.get(name) else ""
        shown.append(f"joint '{name}' (line {joints[name]['element'].line}{also}): {why(name, partners)}")
    fix(joints, followers, [name for name, _ in held], value)
    count = len(held)
    warnings.warn(UrdfWarning(
        f"{reader.path}: {count} joint{'s are' if count > 1 else ' is'} held at {'their' if count > 1 else 'its'} "
        f"initial position{'s' if count > 1 else ''} (as a fixed joint, {'their' if count > 1 else 'its'} limits "
        f"and damping left out), because the forces would not determine {'their' if count > 1 else 'its'} "
        "motion: " + "; ".join(shown) + ". Give the links they move mass and inertia to let them move "
        "(strict=True refuses such a file)"), stacklevel=4)  # (load_urdf's caller)


def fix(joints, followers, names, value):
    """The joints `names` (leaders or joints that mimic none) and the
    followers of their mimics made fixed joints at their values: their
    child links merge into their parents' bodies; `moves_as` keeps what
    they were for the poses."""
    mimics = mimics_of(followers)
    for name in names:
        for joint in [name, *mimics.get(name, ())]:
            joints[joint].update(moves_as=joints[joint]["type"], type="fixed", locked=value[joint], held=True)
            followers.pop(joint, None)



def held_by_argument(reader, joints, followers, hold):
    """The joints of load_urdf's `hold`: names of joints of the file with
    one coordinate that follow no mimic (a leader's mimics are held with
    it)."""
    names = []
    for name in hold:
        joint = joints.get(name) if isinstance(name, str) else None
        if joint is not None and joint.get("moves_as"):
            raise UrdfError(f"{reader.path}: hold: joint '{name}' is locked at {joint['locked']!r} by its equal limits "
                            "already")
        if joint is None or joint["type"] not in MOVING:
            movable = [j["name"] for j in joints.values() if j["type"] in MOVING]
            raise UrdfError(f"{reader.path}: hold: {_checks.show(name)} is not a revolute, continuous or prismatic "
                            f"joint of the file (those are: {', '.join(movable)})")
        if name in followers:
            raise UrdfError(f"{reader.path}: hold: joint '{name}' mimics '{followers[name]['joint']}': hold "
                            f"'{leader_of(followers, name)}' (its mimics are held with it), or load with mimic=False")
        if name not in names:
            names.append(name)
    return names

