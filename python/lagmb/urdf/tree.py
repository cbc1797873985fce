"""The tree of a URDF file's links: the joints below each link, and the
links' world poses in a configuration of the joints, with the groups of
links fixed together (each group one body).
"""

import numpy as np

from .. import _rotations
from .._model_files import LARGEST


def children(joints):
    """{link: the joints whose parent it is}, in the file's order."""
    out = {}
    for joint in joints.values():
        out.setdefault(joint["parent"], []).append(joint)
    return out


def poses(reader, joints, root, below, value):
    """The world pose (R, p) of each link in the configuration `value`, the
    first link of the group of links fixed together that each belongs to,
    and the links in the order of a walk from the root (parents first)."""
    pose = {root: (np.eye(3), np.zeros(3))}
    group_of = {root: root}
    order, stack = [], [root]
    while stack:
        link = stack.pop()
        order.append(link)
        for joint in reversed(below.get(link, [])):
            R_parent, p_parent = pose[link]
            R_joint, p_joint = R_parent @ joint["R"], p_parent + R_parent @ joint["p"]  # the joint's frame
            x = value.get(joint["name"], 0.0)
            moves_as = joint.get("moves_as", joint["type"])
            if moves_as in ("revolute", "continuous"):
                R_joint = R_joint @ _rotations.turn(joint["axis"], x)
            elif moves_as == "prismatic":
                p_joint = p_joint + R_joint @ (x * joint["axis"])
            if np.abs(p_joint).max() > LARGEST:  # (origins within LARGEST each, but many in a chain)
                reader.fail(joint["element"], f"puts link '{joint['child']}' {np.abs(p_joint).max():g} m from the "
                            f"root: beyond what a model can hold (at most {LARGEST:g} m: lagmb squares lengths, and "
                            "larger squares overflow)", f"joint '{joint['name']}'")
            pose[joint["child"]] = (R_joint, p_joint)
            group_of[joint["child"]] = group_of[link] if joint["type"] == "fixed" else joint["child"]
            stack.append(joint["child"])
    return pose, group_of, order
