"""The joint-space mass matrix of a URDF robot in a configuration, summed
as the composite-rigid-body algorithm sums it, and the motions of its
coordinates that move no mass or inertia (its numerically zero modes).
"""

import numpy as np

from .joint_values import chain_leaders
from .reader import MOVING

#: A joint coordinate moves no mass or inertia where its diagonal entry of
#: the joint-space mass matrix is at most this fraction of the largest
#: diagonal entry; a combination of coordinates does where the mass matrix
#: scaled to a unit diagonal has an eigenvalue at most this fraction of its
#: largest (the core's test of the augmented matrix at the start is 1e-12
#: of the largest eigenvalue too).
MOTIONLESS = 1e-12


def mass_matrix(links, joints, order, pose, followers, floating_base):
    """The joint-space mass matrix M (Sum over links of m J_c^T J_c +
    J_w^T I J_w, with each independent coordinate's twist at its joint) in
    the configuration of `pose`, and the joint of each of its columns (None:
    a planar, floating or base coordinate); (None, columns) where no column
    is a joint that can be held or M is not finite.

    Summed as the composite-rigid-body algorithm sums it: with s_k the
    unit twists (angular velocity, velocity of the point at the world
    origin) of the coordinates, and S_k the spatial inertia about the
    origin of every link that s_k moves, [[J_O, [h]x], [[h]x^T, m 1]]
    (mass m, first moment h, inertia J_O about the origin, summed from the
    leaves up), each pair of twists i above (or at) k adds s_i^T S_k s_k to
    M[c_i, c_k] and M[c_k, c_i] (a mimic's follower adds to its leader's
    column): time linear in the links times the depth of the tree, where
    summing the links' m J_c^T J_c would be cubic in a long chain."""
    columns = {}  # independent coordinate -> its column
    holdable = []  # the joint of each column that may be held (None: a planar, floating or base coordinate)
    twists = {}  # joint -> [(column, twist (angular, velocity of the point at the world origin))]
    leaders = chain_leaders(followers)

    def column(key, joint):
        if key not in columns:
            columns[key] = len(holdable)
            holdable.append(joint)
        return columns[key]

    def free_twists(key, origin):
        out = []
        for k, e in enumerate(np.eye(3)):
            out.append((column((key, k), None), np.concatenate([np.zeros(3), e])))
            out.append((column((key, 3 + k), None), np.concatenate([e, np.cross(origin, e)])))
        return out

    for joint in joints.values():
        kind = joint["type"]
        if kind == "fixed":
            continue
        R_parent, p_parent = pose[joint["parent"]]
        at = p_parent + R_parent @ joint["p"]
        axis = R_parent @ joint["R"] @ joint["axis"]
        if kind in MOVING:
            leader, factor = leaders.get(joint["name"], (joint["name"], 1.0))
            twist = np.concatenate([axis, np.cross(at, axis)]) if kind in ("revolute", "continuous") else \
                np.concatenate([np.zeros(3), axis])
            twists[joint["name"]] = [(column(leader, leader), factor * twist)]
        elif kind == "planar":
            u = np.linalg.svd(axis[None, :])[2][1:]  # (two directions in the plane)
            twists[joint["name"]] = [(column((joint["name"], k), None), np.concatenate([np.zeros(3), u[k]]))
                                     for k in (0, 1)] + \
                [(column((joint["name"], 2), None), np.concatenate([axis, np.cross(at, axis)]))]
        else:  # floating
            twists[joint["name"]] = free_twists(joint["name"], pose[joint["child"]][1])
    root = order[0]
    base = free_twists(("base",), pose[root][1]) if floating_base else []
    n = len(holdable)
    if not any(h is not None for h in holdable):
        return None, holdable
    parent_joint = {joint["child"]: joint for joint in joints.values()}
    M = np.zeros((n, n))
    below = {}  # link -> the spatial inertia of it and the links below it
    for link, (m, h, J) in subtree_inertias(links, joints, order, pose).items():
        h = np.cross(np.eye(3), h)  # ([h]x: its rows e_i x h)
        below[link] = np.block([[J, h], [h.T, m * np.eye(3)]])
    with np.errstate(all="ignore"):  # (values beyond what a model holds: refused when the bodies are built)
        # the twists above each link, walked in `order` (parents first, each subtree in turn): a link's
        # ancestors' twists are the first `depth[parent]` rows, which its siblings' subtrees leave alone
        rows = len(base) + sum(len(t) for t in twists.values())
        path, path_columns, depth = np.zeros((rows, 6)), np.zeros(rows, dtype=int), {}

        def add(link, moving, start):
            for q, (c, twist) in enumerate(moving):
                path[start + q], path_columns[start + q] = twist, c
                values = path[:start + q + 1] @ (below[link] @ twist)
                np.add.at(M, (path_columns[:start + q + 1], c), values)
                np.add.at(M, (c, path_columns[:start + q]), values[:-1])
            depth[link] = start + len(moving)

        add(root, base, 0)
        for link in order[1:]:
            joint = parent_joint[link]
            add(link, twists.get(joint["name"], ()), depth[joint["parent"]])
    if not np.all(np.isfinite(M)):
        return None, holdable
    return 0.5 * (M + M.T), holdable


def zero_modes(M):
    """How many motions of the coordinates move no mass or inertia: the
    coordinates whose diagonal entry of M is at most MOTIONLESS of the
    largest, and the eigenvalues of the rest, scaled to a unit diagonal, at
    most MOTIONLESS of the largest."""
    diagonal = np.diag(M)
    zero = diagonal <= MOTIONLESS * diagonal.max()
    rest = np.flatnonzero(~zero)
    if rest.size == 0:
        return int(zero.sum())
    scale = 1.0 / np.sqrt(diagonal[rest])
    values = np.linalg.eigvalsh(M[np.ix_(rest, rest)] * np.outer(scale, scale))
    return int(zero.sum()) + int(np.sum(values <= MOTIONLESS * values.max()))


def subtree_inertias(links, joints, order, pose):
    """{link: (mass, first moment, inertia about the world origin) of it and
    every link below it} in the configuration of `pose` (`order`: parents
    first): sums, so one subtree's less another's within it are the links
    between."""
    parent = {joint["child"]: joint["parent"] for joint in joints.values()}
    out = {}
    with np.errstate(all="ignore"):  # (values beyond what a model holds: refused when the bodies are built)
        for link in reversed(order):  # (children first: each has added itself to its link when it comes)
            data = links[link]
            R, p = pose[link]
            m, c = data["mass"], p + R @ data["com"]
            own = (m, m * c, R @ data["inertia"] @ R.T + m * (c @ c * np.eye(3) - np.outer(c, c)))
            out[link] = _plus(out[link], own) if link in out else own
            if link in parent:
                up = parent[link]
                out[up] = _plus(out[up], out[link]) if up in out else out[link]
    return out


def _plus(part, other):
    return part[0] + other[0], part[1] + other[1], part[2] + other[2]


def subtree_difference(part, other):
    return part[0] - other[0], part[1] - other[1], part[2] - other[2]


def turning_inertia(part, axis, point):
    """The moment of inertia of `part` (mass m, first moment h, inertia
    J_O about the world origin) about the line through `point` along the
    unit `axis`: a . J_O a - 2 (a x h) . (a x point) + m |a x point|^2
    (twice the kinetic energy of its turning at 1 rad/s about the line)."""
    m, h, J = part
    ap = np.cross(axis, point)
    with np.errstate(all="ignore"):
        return float(axis @ J @ axis - 2 * np.cross(axis, h) @ ap + m * ap @ ap)

