"""Chains of three revolutes that can reach a gimbal lock: where the
outer joints' axes line up at an angle of the middle one and their turning
opposite ways moves no mass or inertia. Nothing is held for them; load_urdf
warns (or with strict refuses).
"""

import warnings

import numpy as np

from .. import _rotations
from .joint_values import chain_leaders, joint_values
from .mass_matrix import mass_matrix, subtree_difference, subtree_inertias, turning_inertia, zero_modes
from .reader import UrdfWarning
from .tree import poses

#: A gimbal lock of three revolutes at most this far (rad) beyond the middle
#: joint's limit counts as within it: files write pi/2 to 5 or 6 digits
#: (human.urdf's 1.5708, 3.7e-6 beyond; 1.570795, 1.3e-6 short), and with
#: the middle joint on such a limit the outer joints' turning opposite ways
#: has about angle^2 / 2 (5e-11 here) of the inertia of turning one of them.
LOCK_REACHED = 1e-5


def gimbal_locks(reader, links, joints, root, below, value, limits, followers, floating_base):
    """The middle joints of chains of three revolutes that lock within
    their limits: [(middle, reason)]. A revolute (or continuous) joint J2
    whose parent link's group hangs from a revolute J1 and whose child's
    group carries a revolute J3 is the middle of such a chain where, at
    some angle of J2 (the lock), J3's axis lies on J1's line, and the
    joint-space mass matrix with J2 at the allowed angle nearest the lock
    (within its limits with `limits`, else the lock itself; the other
    joints where the model is built) has more motions that move no mass
    (_zero_modes) than where the model is built: J1 and J3 turning opposite
    ways moves nothing through massless links (human.urdf's neck, Z-X-Y
    with X limited to +-1.5708, 3.7e-6 rad past the lock at -pi/2). Only
    there is that motion undetermined (elsewhere the three joints move what
    J3 carries as a ball joint would), so nothing is held for it: the
    caller warns. Joints that mimic others are not J2."""
    turning = ("revolute", "continuous")
    pose, group_of, order = poses(reader, joints, root, below, value)
    built = None  # (the motions that move no mass where the model is built: counted at the first lock found)
    parts = subtree_inertias(links, joints, order, pose)
    coupled = set(followers) | {leader for leader, _ in chain_leaders(followers).values()}
    hanging = {joint["child"]: joint for joint in joints.values()}
    carried = {}  # group -> the revolutes on its links (each J2's candidates for J3: linear, not a scan of all)
    for joint in joints.values():
        if joint["type"] in turning:
            carried.setdefault(group_of[joint["parent"]], []).append(joint)
    found = []
    for j2 in joints.values():
        if j2["type"] not in turning or j2["name"] in followers:
            continue
        j1 = hanging.get(group_of[j2["parent"]])
        if j1 is None or j1["type"] not in turning:
            continue
        # J1's line and J3's in J2's frame at angle 0 (J3's turned by J2's angle theta about a2)
        R1, p1 = pose[j1["child"]]
        R_parent, p_parent = pose[j2["parent"]]
        R2, p2 = R_parent @ j2["R"], p_parent + R_parent @ j2["p"]
        a2 = j2["axis"] / np.linalg.norm(j2["axis"])
        b = R2.T @ (R1 @ j1["axis"])
        b = b / np.linalg.norm(b)
        c = R2.T @ (p1 - p2)
        R_child, p_child = pose[j2["child"]]  # (J2's frame turned by its initial angle)
        for j3 in carried.get(j2["child"], ()):
            R3, p3 = pose[j3["parent"]]
            u = R_child.T @ (R3 @ j3["R"] @ j3["axis"])
            u = u / np.linalg.norm(u)
            q3 = R_child.T @ (p3 + R3 @ j3["p"] - p_child)
            # b . turn(a2, theta) u = C + A cos(theta) + B sin(theta): +-1 where the axes line up
            C = (b @ a2) * (a2 @ u)
            A, B = b @ u - C, b @ np.cross(a2, u)
            r = np.hypot(A, B)
            if r < 1e-9:  # (the angle between the axes does not change with J2)
                continue
            for lock in (np.arctan2(B, A), np.arctan2(B, A) + np.pi):
                if abs(C + r * np.cos(lock - np.arctan2(B, A))) < 1.0 - 1e-9:
                    continue
                R = _rotations.turn(a2, lock)
                if np.linalg.norm(np.cross(R @ q3 - c, b)) > 1e-9 * (1.0 + np.linalg.norm(c) + np.linalg.norm(q3)):
                    continue  # (parallel axes apart: turning opposite ways moves the links beyond)
                if limits and j2["limit"] is not None:
                    lower, upper = j2["limit"]
                    turns = np.round((np.clip(lock, lower, upper) - lock) / (2 * np.pi))
                    near = min((lock + 2 * np.pi * k for k in (turns - 1, turns, turns + 1)),
                               key=lambda x: abs(np.clip(x, lower, upper) - x))
                    beyond = abs(float(np.clip(near, lower, upper)) - near)
                    if beyond > LOCK_REACHED:
                        continue
                else:
                    near, beyond = lock + 2 * np.pi * np.round((value[j2["name"]] - lock) / (2 * np.pi)), 0.0
                if not {j1["name"], j2["name"], j3["name"]} & coupled:
                    # a first look that costs no mass matrix (a long chain of revolutes through one point has a
                    # lock at each joint): the energy of J1 and J3 turning opposite ways at 1 rad/s at the lock,
                    # the links between J2 and J3 turned there (the line turned back instead), against J3's
                    # (no motion that moves this much can be one the count below finds)
                    axis1 = R1 @ j1["axis"] / np.linalg.norm(j1["axis"])
                    turned = _rotations.turn(R2 @ a2, float(near) - value[j2["name"]])
                    moved = turning_inertia(subtree_difference(parts[j1["child"]], parts[j2["child"]]), axis1, p1) + \
                        turning_inertia(subtree_difference(parts[j2["child"]], parts[j3["child"]]), turned.T @ axis1,
                                         p2 + turned.T @ (p1 - p2))
                    axis3 = R3 @ j3["R"] @ j3["axis"]
                    carried_by_j3 = turning_inertia(parts[j3["child"]], axis3 / np.linalg.norm(axis3),
                                                     p3 + R3 @ j3["p"])
                    whole = parts[j1["child"]]
                    with np.errstate(all="ignore"):
                        slack = 1e-10 * (np.trace(whole[2]) + whole[0] * (p1 @ p1))  # (round-off of the sums)
                    if moved > 1e-6 * (moved + 2 * carried_by_j3) + slack:
                        continue
                at = joint_values(reader, joints, {name: x for name, x in value.items() if name not in followers}
                                   | {j2["name"]: float(near)}, followers, False)  # (J2's mimics with it)
                if built is None:
                    M, _ = mass_matrix(links, joints, order, pose, followers, floating_base)
                    if M is None:
                        return []
                    built = zero_modes(M)
                pose_at, _, order_at = poses(reader, joints, root, below, at)
                M, _ = mass_matrix(links, joints, order_at, pose_at, followers, floating_base)
                if M is None or zero_modes(M) <= built:
                    continue
                if not (limits and j2["limit"] is not None):
                    where = "(no limits)"
                elif beyond == 0.0:
                    where = f"within its limits [{j2['limit'][0]:.10g}, {j2['limit'][1]:.10g}]"
                else:
                    where = f"{beyond:.2g} rad beyond its limit {float(np.clip(near, *j2['limit'])):.10g}"
                found.append((j2["name"], f"at {near:.6g} rad, {where}, the axes of '{j1['name']}' and "
                              f"'{j3['name']}' line up (a gimbal lock) and their turning opposite ways moves no "
                              "mass or inertia"))
                break
            if found and found[-1][0] == j2["name"]:
                break
    return found



def warn_gimbal_locks(reader, joints, locks, strict):
    """One UrdfWarning naming each chain's middle joint, its line and its
    lock (nothing is held: away from the lock the forces determine every
    joint's motion); with strict a UrdfError naming the first."""
    if strict:
        name, reason = locks[0]
        reader.fail(joints[name]["element"], f"{reason}, so there the forces do not determine their motion and a run "
                    f"that reaches the lock fails; strict=True refuses this: give the links between them mass and "
                    f"inertia off their axes, or load with strict=False (hold=['{name}'] keeps the chain away "
                    "from the lock)", f"joint '{name}'")
    count = len(locks)
    shown = "; ".join(f"joint '{name}' (line {joints[name]['element'].line}): {reason}" for name, reason in locks)
    names = ", ".join(repr(name) for name, _ in locks)
    chains = "the chains away from their locks, taking those joints'" if count > 1 else \
        "the chain away from the lock, taking that joint's"
    warnings.warn(UrdfWarning(
        f"{reader.path}: {count} chain{'s' if count > 1 else ''} of revolutes can reach a gimbal lock: {shown}. "
        "Nothing is held (away from a lock the forces determine every joint's motion); at the lock they do not "
        f"determine that turning, and a run that reaches it fails there. hold=[{names}] keeps {chains} motion "
        "away; mass and inertia off the outer joints' axes in the links between them remove the lock "
        "(strict=True refuses such a file)"), stacklevel=4)  # (load_urdf's caller)

