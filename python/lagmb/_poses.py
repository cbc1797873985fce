"""Where a model's bodies, frames and shapes are at a state, without a run:
forward kinematics from the coordinates (Model.poses, Model.pose,
Model.lowest_point).

Each body's coordinates hold its pose: its centre of mass r and its axes
A (the angle phi in the plane, the Euler parameters p in space). A frame
or a shape is fixed in its body at s (from the centre of mass, in the
body's axes) with axes R' (in the body's axes), so it sits at r + A s with
axes A R'. Every reading here is global: positions in m from the origin,
rotations whose columns are the axes in global components.
"""

import warnings

import numpy as np

from . import _rotations
from ._checks import show
from .errors import ModelError


class Pose:
    """Where a body, frame or shape is, in global axes: ``position`` (m; (2,)
    in the plane, (3,) in space), the body's centre of mass, the frame's
    origin or the shape's centre; ``rotation`` ((2, 2) or (3, 3)), its axes
    as columns in global components (a point p given in its axes is at
    position + rotation @ p); in the plane also ``angle`` (rad)."""

    __slots__ = ("position", "rotation", "angle")

    def __init__(self, position, rotation, angle=None):
        self.position = np.array(position, dtype=float)
        self.rotation = np.array(rotation, dtype=float)
        self.angle = angle
        self.position.flags.writeable = self.rotation.flags.writeable = False

    def point(self, local_point):
        """The global position of a point given in these axes."""
        return self.position + self.rotation @ np.asarray(local_point, dtype=float)

    def __repr__(self):
        where = ", ".join(f"{x:.6g}" for x in self.position)
        turn = f", angle={self.angle:.6g}" if self.angle is not None else ""
        return f"<lagmb.Pose at ({where}){turn}>"


class Poses:
    """The poses of a model's bodies, frames and shapes at one state
    (Model.poses), all global (Pose): ``bodies`` {name: Pose} (their
    centres of mass and axes; "ground" too), ``frames`` {name: Pose}
    (Model.frames), ``shapes`` [Pose] in the order of Model.shapes (each
    shape's centre and axes, as add_shape takes them). ``poses[name]`` is a
    body's or a frame's."""

    def __init__(self, bodies, frames, shapes):
        self.bodies, self.frames, self.shapes = bodies, frames, shapes

    def __getitem__(self, name):
        name = str(name)
        if name in self.bodies:
            return self.bodies[name]
        if name in self.frames:
            return self.frames[name]
        raise ModelError(f"Model.pose: no body or frame named {name!r}")

    def __repr__(self):
        return f"<lagmb.Poses: {len(self.bodies)} bodies, {len(self.frames)} frames, {len(self.shapes)} shapes>"


def coordinates(model, q, positions, context):
    """The coordinates the poses are read at: q (n,) as given; the joint
    values ``positions`` {joint: angle or slide} through JointSpace (each
    joint 0 where not given, free bodies where they start); neither: the
    initial configuration as the model gives it (add_body's values,
    before assembly)."""
    core = model.compiled()
    if q is not None and positions is not None:
        raise ModelError(f"{context}: give q (the coordinates) or positions (joint values), not both")
    if positions is not None:
        from .joints import JointSpace

        if not isinstance(positions, dict):
            raise ModelError(f"{context}: positions must be a dict {{joint: angle or slide}}, got {show(positions)}")
        values = {}
        for joint, value in positions.items():
            try:
                values[model.joint_name(str(joint))] = float(value)
            except (TypeError, ValueError):
                raise ModelError(f"{context}: positions[{str(joint)!r}] must be a number, got {show(value)}") from None
        return JointSpace(model).coordinates(values)[0]
    if q is None:
        return np.asarray(core.initial_state()[0], dtype=float)
    try:
        x = np.asarray(q, dtype=float)
    except (TypeError, ValueError):
        x = None
    n = core.n_coordinates
    if x is None or x.shape != (n,) or not np.all(np.isfinite(x)):
        raise ModelError(f"{context}: q must be {n} finite numbers (the model's coordinates, "
                         f"Model.coordinate_names), got {show(q)}")
    return x


def poses(model, q, context="Model.poses"):
    """The Poses of ``model`` at the coordinates q."""
    core = model.compiled()
    spatial = model.dimension == 3
    bodies = {"ground": Pose(np.zeros(3), np.eye(3)) if spatial else Pose(np.zeros(2), np.eye(2), 0.0)}
    for body in model.bodies:
        first, count = core.body_coordinates(body.name)
        x = q[first:first + count]
        if spatial:
            p = x[3:7] / np.linalg.norm(x[3:7])
            bodies[body.name] = Pose(x[:3], _rotations.matrix(p))
        else:
            phi = float(x[2]) if count == 3 else 0.0
            c, s = np.cos(phi), np.sin(phi)
            bodies[body.name] = Pose(x[:2], [[c, -s], [s, c]], phi)
    frames, shapes = {}, []
    for name, frame in getattr(model, "_frames", {}).items():
        at = bodies[frame.body]
        frames[name] = Pose(at.point(frame.position), at.rotation @ np.asarray(frame.rotation, dtype=float))
    for shape in getattr(model, "_shapes", []):
        at = bodies[shape.body]
        shapes.append(Pose(at.point(shape.position), at.rotation @ np.asarray(shape.rotation, dtype=float)))
    return Poses(bodies, frames, shapes)


def support_point(shape, pose, d):
    """The point of ``shape`` (at ``pose``) farthest along the unit
    direction d, global: a sphere's centre + r d; a box's corner; a
    cylinder's rim (or its end's centre, d along its axis); a capsule's end
    sphere; a mesh's vertex (its STL file read). None for a plane
    (unbounded)."""
    c, R = pose.position, pose.rotation
    size = np.asarray(shape.size, dtype=float)
    if shape.kind == "sphere":
        return c + size[0] * d
    if shape.kind == "box":
        return c + R @ (np.where(R.T @ d >= 0.0, 0.5, -0.5) * size)
    if shape.kind in ("cylinder", "capsule"):
        radius, length = size
        u = R[:, 2]
        along = u @ d
        end = c + np.copysign(0.5 * length, along if along != 0.0 else 1.0) * u
        if shape.kind == "capsule":
            return end + radius * d
        across = d - along * u
        norm = np.linalg.norm(across)
        return end + (radius * across / norm if norm > 1e-12 else 0.0)
    if shape.kind == "mesh":
        from ._meshes import read_stl

        points = read_stl(shape.mesh).reshape(-1, 3) * size
        world = c + points @ R.T
        return world[np.argmax(world @ d)]
    return None  # a plane


def lowest_point(model, q, direction, context="Model.lowest_point"):
    """The point of the collision shapes on the model's bodies (the
    ground's left out) farthest along ``direction`` (None: gravity's) at
    the coordinates q, global; ModelError where there is none."""
    if model.dimension != 3:
        raise ModelError(f"{context}: shapes are spatial only; this model has dimension {model.dimension}")
    if direction is None:
        if model.gravity is None or not np.any(np.asarray(model.gravity, dtype=float)):
            raise ModelError(f"{context}: the model has no gravity to say which way is down; give direction=")
        direction = model.gravity
    try:
        d = np.asarray(direction, dtype=float).reshape(3)
    except (TypeError, ValueError):
        d = None
    if d is None or not np.all(np.isfinite(d)) or not np.linalg.norm(d) > 0.0:
        raise ModelError(f"{context}: direction must be a nonzero vector (x, y, z), got {show(direction)}")
    d = d / np.linalg.norm(d)
    at = poses(model, q, context)
    best, left_out = None, []
    for shape, pose in zip(model._shapes, at.shapes):
        if shape.role != "collision" or shape.body == "ground" or shape.kind == "plane":
            continue
        if shape.kind == "mesh" and not str(shape.mesh).lower().endswith(".stl"):
            left_out.append(f"{shape.mesh} on '{shape.body}'")
            continue
        p = support_point(shape, pose, d)
        if best is None or p @ d > best @ d:
            best = p
    if left_out:
        warnings.warn(f"{context}: {len(left_out)} collision mesh(es) left out, not STL files (lagmb reads STL "
                      f"only, and gives them no contact): {', '.join(left_out[:5])}", UserWarning, stacklevel=3)
    if best is None:
        raise ModelError(f"{context}: the model has no collision shapes on its bodies to read (add_shape(..., "
                         "role='collision'); load_urdf keeps each link's <collision> geometry)")
    return best


# --- the Model methods (model.py binds them: Model.poses, .pose, .lowest_point)

def model_poses(self, q=None, *, positions=None):
    """Where every body, frame and shape is at a state, without a run: a
    :class:`Poses` (``.bodies``, ``.frames``, ``.shapes``, ``poses[name]``),
    each a :class:`Pose` in **global** axes: ``position`` (m) of the
    body's centre of mass, the frame's origin or the shape's centre, and
    ``rotation`` (its axes as columns; in the plane also ``angle``).

    The state: ``q`` (the model's coordinates, Model.coordinate_names), or
    ``positions`` {joint: angle (rad) or slide (m)} of a spatial tree's
    revolute and translational joints (a robot's, by the URDF's names or
    their aliases; each joint 0 where not given, free bodies where they
    start: JointSpace.coordinates), or neither: the initial configuration
    as given (add_body's positions; load_urdf's ``positions``), before
    assembly. (Model.shapes and Model.frames hold where each sits in its
    body: body axes, from the centre of mass.)"""
    return poses(self, coordinates(self, q, positions, "Model.poses"))


def model_pose(self, name, q=None, *, positions=None):
    """The global :class:`Pose` of one body or frame (handle or name;
    "ground" too) at a state given as :meth:`poses` takes it: ``position``
    (m) of the body's centre of mass or the frame's origin, ``rotation``
    its axes as columns in global components (``angle`` in the plane)."""
    return model_poses(self, q, positions=positions)[name]


def model_lowest_point(self, q=None, *, positions=None, direction=None):
    """(3,) the lowest point of the model's collision shapes (role
    "collision", on its bodies: the ground's own shapes and planes left
    out), global (m): the point farthest along ``direction`` (default:
    gravity's), at a state given as :meth:`poses` takes it (default: the
    initial configuration). Its height is where a floor just touches the
    model: with gravity along -z, ``load_urdf(..., ground=p[2])``.
    Spheres, boxes, cylinders and capsules exactly; a mesh by its STL
    file's vertices (a mesh that is not STL is left out, with a
    UserWarning, as load_urdf gives it no contact). ModelError for a
    planar model, a model without gravity when no direction is given, or
    one without collision shapes."""
    return lowest_point(self, coordinates(self, q, positions, "Model.lowest_point"), direction)
