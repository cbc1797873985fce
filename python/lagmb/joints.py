"""Joint space: a spatial tree's state given as joint angles and slides
(what robot users think in), and the joint values of any state.

``JointSpace(model)`` reads the tree the model's revolute and translational
joints make (each body the child of at most one joint; a body without one
is free). ``coordinates`` turns joint values into lagmb's coordinates by
the tree's forward kinematics; ``motion`` reads a joint's value, rate and
acceleration from lagmb's coordinates (the core's joint_motion: the
function the joint's drivers hold).
"""

import numpy as np

from . import _rotations, registry
from .errors import ModelError, translated
from .model import Model

#: The joint coordinates JointSpace moves along (a kind's coordinates,
#: lagmb.registry), and what a joint with that one coordinate does; a joint
#: with two (cylindrical) has no one joint value.
_MOVING = {("angle",): "turns", ("slide",): "slides"}


def _unit(x):
    x = np.asarray(x, dtype=float)
    return x / np.linalg.norm(x)


class JointSpace:
    """The joints of a spatial tree model and its state in joint values.

    ``joints``: the revolute and translational joints, parents before
    children; ``free``: the bodies that are no joint's child (free bodies,
    such as a floating base). Raises ModelError for a planar model, or a
    body that is the child of two joints (a closed loop)."""

    def __init__(self, model):
        if model.dimension != 3:
            raise ModelError("JointSpace: the model is planar; joint space reads spatial trees")
        core = model.compiled()
        q0 = core.initial_state()[0]
        self.model = model
        self._bodies = [b.name for b in model.bodies]
        self._index = {name: k for k, name in enumerate(self._bodies)}
        # each body's pose in the initial configuration
        self._R0, self._r0 = {"ground": np.eye(3)}, {"ground": np.zeros(3)}
        for k, name in enumerate(self._bodies):
            self._r0[name] = q0[7 * k:7 * k + 3]
            self._R0[name] = _rotations.matrix(q0[7 * k + 3:7 * k + 7])
        parent_of, joints = {}, {}
        for method, values in model.elements:
            moves = _MOVING.get(registry.SPATIAL_BY_METHOD[method].coordinates)
            if moves is None:
                continue
            name = values["name"]
            body_i, body_j = str(values["body_i"]), str(values["body_j"])
            if body_j in parent_of:
                raise ModelError(f"JointSpace: body '{body_j}' is the child of joints '{parent_of[body_j]}' and "
                                 f"'{name}': joint space is a tree's (a closed loop has no joint coordinates "
                                 "of its own)")
            parent_of[body_j] = name
            Rp, rp = self._R0[body_i], self._r0[body_i]
            axis_p = Rp.T @ _unit(values["axis"])  # in the parent's axes
            at_p = Rp.T @ (np.asarray(values["at"], dtype=float) - rp)
            # the child's pose in the parent's axes at joint value 0 (the
            # initial configuration has the joint's given angle or slide)
            R_rel, r_rel = Rp.T @ self._R0[body_j], Rp.T @ (self._r0[body_j] - rp)
            if moves == "turns":
                back = _rotations.turn(axis_p, -float(values.get("angle") or 0.0))
                R_rel, r_rel = back @ R_rel, back @ (r_rel - at_p) + at_p
            else:
                r_rel = r_rel - float(values.get("slide") or 0.0) * axis_p
            joints[name] = dict(name=name, parent=body_i, child=body_j, kind=moves, axis=axis_p, at=at_p,
                                R=R_rel, r=r_rel)
        # parents before children
        self.joints, placed = [], {"ground"} | {b for b in self._bodies if b not in parent_of}
        pending = list(joints.values())
        while pending:
            ready = [j for j in pending if j["parent"] in placed]
            if not ready:
                raise ModelError(f"JointSpace: the joints {', '.join(j['name'] for j in pending)} do not hang from "
                                 "the ground or a free body (a loop)")
            for j in ready:
                self.joints.append(j["name"])
                placed.add(j["child"])
                pending.remove(j)
        self._joints = joints
        self.free = [b for b in self._bodies if b not in parent_of]

    def coordinates(self, positions, velocities=None, accelerations=None, free=None):
        """lagmb's (q, v, a) for joint values {joint: value} (angles in rad,
        slides in m; each joint 0 where not given), rates and accelerations
        likewise (0 where not given), by forward kinematics down the tree.
        ``free``: {body: dict(position, orientation (w, x, y, z), velocity,
        angular_velocity, acceleration, angular_acceleration)} for the free
        bodies (global axes; as in the initial configuration, at rest, where
        not given)."""
        unknown = set(positions) | set(velocities or {}) | set(accelerations or {})
        unknown -= set(self._joints)
        if unknown:
            raise ModelError(f"JointSpace.coordinates: {', '.join(sorted(map(repr, unknown)))} are not joints of the "
                             f"tree (its joints: {', '.join(self.joints)})")
        zero = np.zeros(3)
        R = {"ground": np.eye(3)}
        r, v, w, a, al = ({"ground": zero} for _ in range(5))
        for body in self.free:
            given = (free or {}).get(body, {})
            R[body] = _rotations.matrix(_unit(given["orientation"])) if "orientation" in given else self._R0[body]
            r[body] = np.asarray(given.get("position", self._r0[body]), dtype=float)
            v[body] = np.asarray(given.get("velocity", zero), dtype=float)
            w[body] = np.asarray(given.get("angular_velocity", zero), dtype=float)
            a[body] = np.asarray(given.get("acceleration", zero), dtype=float)
            al[body] = np.asarray(given.get("angular_acceleration", zero), dtype=float)
        for name in self.joints:
            j = self._joints[name]
            P, C = j["parent"], j["child"]
            x = float(positions.get(name, 0.0))
            xd = float((velocities or {}).get(name, 0.0))
            xdd = float((accelerations or {}).get(name, 0.0))
            u = R[P] @ j["axis"]  # the axis, global
            s = r[P] + R[P] @ j["at"]  # a point of the axis, global
            wP, vP = w[P], v[P]
            if j["kind"] == "turns":
                turn = _rotations.turn(j["axis"], x)
                R[C] = R[P] @ turn @ j["R"]
                r[C] = r[P] + R[P] @ (turn @ (j["r"] - j["at"]) + j["at"])
                d, e = r[C] - r[P], r[C] - s
                w[C] = wP + xd * u
                v[C] = vP + np.cross(wP, d) + xd * np.cross(u, e)
                ud, sd = np.cross(wP, u), vP + np.cross(wP, s - r[P])
                al[C] = al[P] + xdd * u + xd * ud
                a[C] = (a[P] + np.cross(al[P], d) + np.cross(wP, v[C] - vP) + xdd * np.cross(u, e)
                        + xd * np.cross(ud, e) + xd * np.cross(u, v[C] - sd))
            else:
                R[C] = R[P] @ j["R"]
                r[C] = r[P] + R[P] @ (j["r"] + x * j["axis"])
                d = r[C] - r[P]
                w[C], al[C] = wP, al[P]
                v[C] = vP + np.cross(wP, d) + xd * u
                a[C] = a[P] + np.cross(al[P], d) + np.cross(wP, v[C] - vP) + xdd * u + xd * np.cross(wP, u)
        n = 7 * len(self._bodies)
        q, qd, qdd = np.zeros(n), np.zeros(n), np.zeros(n)
        for k, body in enumerate(self._bodies):
            p = _rotations.quaternion(R[body])
            pd = 0.5 * _rotations.E(p).T @ w[body]
            q[7 * k:7 * k + 7] = np.concatenate([r[body], p])
            qd[7 * k:7 * k + 7] = np.concatenate([v[body], pd])
            # alpha = 2 E(p) p'' and p . p'' = -|p'|^2 (p stays a unit quaternion)
            qdd[7 * k:7 * k + 7] = np.concatenate([a[body], 0.5 * _rotations.E(p).T @ al[body] - (pd @ pd) * p])
        return q, qd, qdd

    def with_rates(self, rates):
        """A copy of the model whose bodies start with the velocities of the
        joint rates {joint: rate} (0 where not given) in its initial
        configuration, as forward kinematics gives them (rad/s, m/s)."""
        q, v, _ = self.coordinates({}, rates)
        out = Model(gravity=self.model.gravity, dimension=3)
        for method, values in self.model.elements:
            if method == "add_body":
                k = self._index[values["name"]]
                values = dict(values, velocity=tuple(v[7 * k:7 * k + 3]),
                              angular_velocity=tuple(2.0 * _rotations.E(q[7 * k + 3:7 * k + 7]) @ v[7 * k + 3:7 * k + 7]))
            getattr(out, method)(**values)
        return out

    def motion(self, joint, q, v, a=None):
        """(value, rate, acceleration) of a joint's angle or slide at one
        state or at each row of (k, n) arrays: the core's joint_motion."""
        if joint not in self._joints:
            raise ModelError(f"JointSpace.motion: '{joint}' is not a joint of the tree (its joints: "
                             f"{', '.join(self.joints)})")
        slide = self._joints[joint]["kind"] == "slides"
        one = np.ndim(q) == 1
        rows = [np.atleast_2d(np.asarray(x, dtype=float)) for x in (q, v)]
        acc = np.atleast_2d(np.asarray(a, dtype=float)) if a is not None else np.zeros((0, 0))
        out = self.model.compiled().joint_motion(joint, slide, rows[0], rows[1], acc)
        return out[0] if one else out


def inverse_dynamics(model, joint_trajectory, t=0.0):
    """The joint efforts that make a spatial tree move as given.

    ``joint_trajectory``: {joint: (position, velocity, acceleration)} for
    the tree's revolute and translational joints (rad, rad/s, rad/s^2 or
    m, m/s, m/s^2), each a number or an array (k,) of k states; a joint not
    given holds 0, at rest. ``t``: the time of each state (a number or (k,)).
    Returns {joint: effort} (N m about an angle, N along a slide; numbers,
    or arrays (k,)): the torques and forces that, with the joints' reactions,
    give that motion (M a + Phi_q^T lam = Q + G^T tau, solved by the core's
    inverse_dynamics; for a fixed-base tree recursive Newton-Euler's). The
    free bodies stay as in the initial configuration, at rest; a motion they
    would need forces for raises SimulationError.
    """
    js = JointSpace(model)
    unknown = set(joint_trajectory) - set(js.joints)
    if unknown:
        raise ModelError(f"inverse_dynamics: {', '.join(sorted(map(repr, unknown)))} are not joints of the tree "
                         f"(its joints: {', '.join(js.joints)})")
    arrays = {name: [np.atleast_1d(np.asarray(x, dtype=float)) for x in values]
              for name, values in joint_trajectory.items()}
    for name, values in arrays.items():
        if len(values) != 3:
            raise ModelError(f"inverse_dynamics: joint '{name}' needs (position, velocity, acceleration)")
    lengths = {len(x) for values in arrays.values() for x in values} | {np.size(t)}
    k = max(lengths)
    if not lengths <= {1, k}:
        raise ModelError(f"inverse_dynamics: the joints' arrays and t have different lengths ({sorted(lengths)})")
    times = np.broadcast_to(np.asarray(t, dtype=float), (k,)).copy()
    n = 7 * len(model.bodies)
    Q, V, A = np.zeros((k, n)), np.zeros((k, n)), np.zeros((k, n))
    for s in range(k):
        pick = [{name: float(values[i][s if len(values[i]) > 1 else 0]) for name, values in arrays.items()}
                for i in range(3)]
        Q[s], V[s], A[s] = js.coordinates(*pick)
    joints = [(name, js._joints[name]["kind"] == "slides") for name in js.joints]
    with translated():
        efforts = model.compiled().inverse_dynamics(joints, times, Q, V, A)
    one = k == 1 and np.ndim(t) == 0 and all(np.ndim(x) == 0 for v in joint_trajectory.values() for x in v)
    return {name: (float(efforts[0, i]) if one else efforts[:, i]) for i, name in enumerate(js.joints)}
