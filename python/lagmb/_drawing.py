"""What a drawing of a run shows of its model, shared by the pictures
(lagmb.plotting) and the browser viewer (lagmb.view): the Scene (bodies,
elements by role, where they attach, the inertia a body is drawn with), a
body's planar outline shape, the faces of a spatial shape (box, cylinder,
sphere, STL mesh), the caption's words, the points a drawing traces
(trace_points) and a model posed along a vibration mode.

What it reads of the model comes from ``model.elements`` (the add_* and
drive_* calls with their arguments, counted by the role the registry of
element kinds gives each) and, from the compiled model the run used, the
local points where elements attach to the bodies (the core's outline and
attachments)."""

import math
import os

import numpy as np

from ._checks import decimal, show
from ._meshes import read_stl
from .errors import ModelError
from .handles import Handle, name_of
from .registry import BY_METHOD, ROLE_WORDS, ROLES, SPATIAL_BY_METHOD, effort_unit


class Scene:
    """What the model says about a result, for drawing it: the bodies, the
    elements by role (lagmb.registry), and where each element attaches to
    its bodies (as points in each body's own axes)."""

    def __init__(self, result):
        self.result = result
        model, core = result.model, result._core  # core: the compiled model the run used
        self.dimension = getattr(model, "dimension", 2)
        self.kinds = kinds = BY_METHOD if self.dimension == 2 else SPATIAL_BY_METHOD  # Model method -> Kind
        # what the run simulated: the model may have grown since
        self.elements = [(method, kw) for method, kw in model.elements if core.has(kw["name"])]
        bodies = [b for b in model.bodies if core.has(b.name)]
        self.bodies = [b.name for b in bodies]
        self.kind_of = {kw["name"]: method for method, kw in self.elements}
        self.particles = {b.name for b in bodies if b.kind == "particle"}
        self.by_role = {role: [kw["name"] for method, kw in self.elements if kinds[method].role == role]
                        for role in ROLES}
        self.joints, self.drivers = self.by_role["joint"], self.by_role["driver"]
        names = ["ground"] + self.bodies  # by core body index + 1
        self._attachments = {
            kw["name"]: [(names[b + 1], np.array(point, dtype=float)) for b, *point in core.attachments(kw["name"])]
            for method, kw in self.elements if kinds[method].role != "body"}
        self.outlines = {b.name: [np.asarray(p, dtype=float) for p in core.outline(b.index)] for b in bodies}
        # mass and inertia about the centre of mass (body axes) as given to add_body
        self.given_body = {kw["name"]: kw for method, kw in self.elements if kinds[method].role == "body"}
        self.mass = {kw["name"]: float(kw.get("mass") or 0.0) for method, kw in self.elements
                     if kinds[method].role == "body"}
        self.inertia = {kw["name"]: _inertia_tensor(kw.get("inertia"), self.dimension)
                        for method, kw in self.elements if kinds[method].role == "body"}

    def attachments(self, name):
        """[(body, local point)] where one element attaches."""
        return self._attachments.get(name, [])

    def path(self, body, local, index=slice(None), result=None):
        """(k, 2) global path of a body's local point (fixed for the ground);
        (k, 3) in space. Of this scene's result, or of ``result`` (the frames)."""
        result = self.result if result is None else result
        if body == "ground":
            return np.broadcast_to(np.asarray(local, dtype=float), (len(result.t), self.dimension))[index]
        return result.point(body, local)[index]

    def planar_local(self, body, point):
        """A point given globally in the initial configuration (as add_*
        elements take them), in the planar body's own axes."""
        p = np.asarray(point, dtype=float)
        if body == "ground":
            return p
        given = self.given_body[body]
        r0 = np.asarray(given.get("position") or (0.0, 0.0), dtype=float)
        a = float(given.get("angle") or 0.0)
        c, s = math.cos(a), math.sin(a)
        d = p - r0
        return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])

    def second_moment(self, body):
        """The body's second moment of mass about its centre, S = sum m x x^T
        in its own axes: (2, 2) or (3, 3), from the inertia given to add_body
        (S = tr(J)/2 - J in space; in the plane only I = S_xx + S_yy is
        known, and S is taken as I along every direction: the body as a rod)."""
        mass, J = self.mass.get(body, 0.0), self.inertia.get(body)
        if J is None or not mass > 0.0:
            return None
        if self.dimension == 2:
            return J * np.eye(2)
        return 0.5 * np.trace(J) * np.eye(3) - J

    def half_length(self, body, direction):
        """Half the length of the uniform rod along ``direction`` (body axes)
        that has the body's mass and second moment along it: sqrt(3 S_uu / m)
        (a rod of length L has S_uu = m L^2 / 12). 0 for a particle."""
        S = self.second_moment(body)
        if S is None:
            return 0.0
        u = np.asarray(direction, dtype=float)
        u = u / np.linalg.norm(u)
        return math.sqrt(3.0 * max(float(u @ S @ u), 0.0) / self.mass[body])

    def drawn_outline(self, body):
        """The local points a body is drawn through: where its elements attach
        (its outline). A body attached at one point only, off its centre of
        mass (a pendulum's rod pinned at one end), is drawn whole: as the
        uniform rod through that point and the centre with the body's mass
        and inertia (half_length); a rod of length L pinned at its end
        reaches L/2 beyond the centre. A point mass (no inertia) keeps the
        line from the point to its centre."""
        points = list(self.outlines.get(body, []))
        distinct = {tuple(np.round(p, 12)) for p in points}
        if len(distinct) != 1 or np.linalg.norm(points[0]) <= 1e-12:
            return points  # two or more points, or pinned at its centre (a cam, a wheel)
        p = points[0]
        d = float(np.linalg.norm(p))
        u = p / d
        h = self.half_length(body, u)
        if h <= 1e-9 * d:
            return points
        return [p] + ([h * u] if h > d * (1.0 + 1e-9) else []) + [-h * u]

    def box(self, body):
        """(8, 3) corners, in body axes, of the uniform box with the body's
        mass and second moment (its principal axes, half extents sqrt(3 s_i /
        m)): what shows a spatial body's orientation; None for a particle or
        a body without inertia."""
        S = self.second_moment(body)
        if S is None or self.dimension != 3:
            return None
        s, V = np.linalg.eigh(0.5 * (S + S.T))
        half = np.sqrt(3.0 * np.clip(s, 0.0, None) / self.mass[body])
        if not half.max() > 0.0:
            return None
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
        return (signs * half) @ V.T

    def heading(self):
        """What a picture is titled: "panda (9 bodies, 10 joints, ...)", the
        model's name (Model.name) with its summary, or the summary alone."""
        name = getattr(self.result.model, "name", None)
        return f"{name} ({self.summary()})" if name else self.summary()

    def summary(self):
        """"2 bodies, 1 joint, 1 stop": each role that has elements."""
        return ", ".join(counted(len(names), *ROLE_WORDS[role]) for role, names in self.by_role.items()
                         if names or role == "body")

    def effort_unit(self, name):
        return effort_unit(self.elements, self.kinds, name)


def _inertia_tensor(inertia, dimension):
    """add_body's inertia as given: a number in the plane; (Ixx, Iyy, Izz)
    or a 3 x 3 tensor in space (None for a particle)."""
    if inertia is None:
        return None
    J = np.asarray(inertia, dtype=float)
    if dimension == 2:
        return float(J.reshape(-1)[0]) if J.size else None
    return np.diag(J) if J.shape == (3,) else J.reshape(3, 3)


def counted(n, one, many=None):
    return f"{n} {one if n == 1 else (many or one + 's')}"


def stats_line(stats):
    if not stats:
        return ""
    wall = stats.get("wall_time")
    parts = []
    if stats.get("formulation"):
        parts.append(f"{stats['formulation']}/{stats.get('integrator', '?')}")
    if "steps" in stats:
        parts.append(f"{stats['steps']} steps")
    if wall is not None:
        parts.append(f"{wall * 1e3:.1f} ms wall" if wall < 1.0 else f"{wall:.2f} s wall")
    return ", ".join(parts)


def _hull(points):
    """Convex hull of 2-D points, counter-clockwise (Andrew's monotone chain)."""
    pts = sorted({(round(p[0], 12), round(p[1], 12)) for p in points})
    if len(pts) <= 2:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def outline_shape(outline):
    """(local points to draw, closed?) for a body's outline: nothing (a dot at
    the centre of mass), a segment from the centre to the one point, a
    segment, or the convex polygon around three or more points."""
    if all(np.hypot(*p) <= 1e-12 for p in outline):  # only the centre: no extent
        return np.zeros((0, 2)), False
    if len(outline) == 1:
        return np.array([np.zeros(2), outline[0]]), False
    if len(outline) == 2:
        return np.array(outline), False
    hull = _hull(outline)
    if len(hull) >= 3:
        area = 0.5 * abs(np.sum(hull[:, 0] * np.roll(hull[:, 1], -1)
                                - np.roll(hull[:, 0], -1) * hull[:, 1]))
        span = np.ptp(hull, axis=0).max()
        if area > 1e-6 * span**2:
            return hull, True
    # collinear: the segment between the two points furthest apart
    pts = np.array(outline)
    d = np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=2)
    a, b = np.unravel_index(np.argmax(d), d.shape)
    return pts[[a, b]], False


def _box_faces(size):
    half = 0.5 * np.asarray(size, dtype=float)
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    quads = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [corners[list(q)] for q in quads]


def _cylinder_faces(radius, length, segments=24):
    a = np.linspace(0.0, 2 * np.pi, segments + 1)
    ring = np.column_stack([radius * np.cos(a), radius * np.sin(a)])
    faces = [np.array([[*ring[k], -0.5 * length], [*ring[k + 1], -0.5 * length], [*ring[k + 1], 0.5 * length],
                       [*ring[k], 0.5 * length]]) for k in range(segments)]
    faces += [np.column_stack([ring, np.full(len(ring), z)]) for z in (-0.5 * length, 0.5 * length)]
    return faces


def _sphere_faces(radius, segments=12):
    u = np.linspace(0.0, 2 * np.pi, 2 * segments + 1)
    v = np.linspace(0.0, np.pi, segments + 1)

    def at(i, j):
        return radius * np.array([np.cos(u[i]) * np.sin(v[j]), np.sin(u[i]) * np.sin(v[j]), np.cos(v[j])])

    return [np.array([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            for i in range(2 * segments) for j in range(segments)]


def _capsule_faces(radius, length):
    faces = _cylinder_faces(radius, length)[:-2]  # (its side; the ends are spheres)
    for z in (-0.5 * length, 0.5 * length):
        faces += [f + np.array([0.0, 0.0, z]) for f in _sphere_faces(radius)]
    return faces


def _plane_faces(half, centre):
    """A square patch of a plane (a half-space's boundary: its own xy), of
    half-width `half` about `centre` (x, y in its own axes)."""
    x, y = float(centre[0]), float(centre[1])
    return [np.array([[x - half, y - half, 0.0], [x + half, y - half, 0.0], [x + half, y + half, 0.0],
                      [x - half, y + half, 0.0]])]


def shape_faces(shape, half=1.0, centre=(0.0, 0.0)):
    """The faces of one shape in its own axes, or None (a mesh lagmb does
    not read: only STL files are drawn). A plane, which has no end, is the
    square of half-width `half` about `centre` (x, y in its own axes)."""
    if shape.kind == "box":
        return _box_faces(shape.size)
    if shape.kind == "cylinder":
        return _cylinder_faces(*shape.size)
    if shape.kind == "sphere":
        return _sphere_faces(shape.size[0])
    if shape.kind == "capsule":
        return _capsule_faces(*shape.size)
    if shape.kind == "plane":
        return _plane_faces(half, centre)
    if not shape.mesh.lower().endswith(".stl") or not os.path.isfile(shape.mesh):
        return None
    return list(read_stl(shape.mesh) * np.asarray(shape.size))


# --- the points a drawing traces -------------------------------------------------


def trace_points(model, trace, context="animate: trace"):
    """The traced points as [(body name, local point)] from what ``animate``
    and ``lagmb run --trace`` take: a body (handle or name: its centre of
    mass), an element (a joint, force, spring: by handle or name; the point
    where it attaches to its moving body, the last it names), a pair
    (body, local point), or "body:x,y" ("body:x,y,z" in space); one of them
    or a list. A ModelError names what cannot be traced, after ``context``."""
    size = getattr(model, "dimension", 2)

    def said(item):
        return str(item) if context.startswith("--") else repr(item)

    if trace is None:
        return []
    if isinstance(trace, (str, Handle)) or (isinstance(trace, (tuple, list)) and len(trace) == 2
                                             and isinstance(trace[0], (str, Handle)) and np.ndim(trace[1]) == 1):
        trace = [trace]  # one of them
    try:
        trace = list(trace)
    except TypeError:
        raise ModelError(f"{context}: expected a body, an element, (body, point), "
                         f"'body:{'x,y' if size == 2 else 'x,y,z'}' or a list of them, got {show(trace)}") from None
    bodies = [b.name for b in model.bodies]

    def body_named(body, item):
        body = name_of(model, body, ("body",), "body", context)
        if body not in bodies:
            raise ModelError(f"{context} {said(item)}: no body named {body!r}; the bodies are " + ", ".join(bodies))
        return body

    out = []
    for item in trace:
        if isinstance(item, (tuple, list)) and len(item) == 2:
            body, point = body_named(item[0], item), item[1]
        elif isinstance(item, str) and ":" in item:
            body, text = item.split(":", 1)
            point = [decimal(x, f"{context} {said(item)}") for x in text.split(",")]
            if len(point) != size:
                raise ModelError(f"{context} {said(item)}: a point on a body is body:{'x,y' if size == 2 else 'x,y,z'} "
                                 "(m, in the body's own axes)")
            body = body_named(body, item)
        elif isinstance(item, Handle) and item.role == "body":
            out.append((body_named(item, item), np.zeros(size)))
            continue
        elif isinstance(item, (str, Handle)):
            if item in bodies:
                out.append((item, np.zeros(size)))
                continue
            try:
                attached = model.attachments(item)
            except ModelError:
                raise ModelError(f"{context} {said(item)}: no body or element of that name; the bodies are "
                                 + ", ".join(bodies)) from None
            moving = [(b, p) for b, p in attached if b != "ground"]
            if not moving:
                raise ModelError(f"{context} {said(item)}: it attaches to no moving body")
            out.append((moving[-1][0], np.asarray(moving[-1][1], dtype=float)))
            continue
        else:
            raise ModelError(f"{context}: expected a body, an element, (body, point) or 'body:x,y', got {item!r}")
        try:
            point = np.asarray(point, dtype=float).reshape(size)
        except (TypeError, ValueError):
            raise ModelError(f"{context} point {point!r}: must be {size} numbers") from None
        if not np.all(np.isfinite(point)):
            raise ModelError(f"{context} point {tuple(point.tolist())}: must be finite")
        out.append((body, point))
    return out


# --- a model posed (a vibration mode's shape) ---------------------------------

def unit_orientations(model, core, q):
    """Normalises, in place, each spatial body's Euler parameters in the rows of q (k, n)."""
    for body in model.bodies:
        if not core.has(body.name):
            continue
        first, count = core.body_coordinates(body.name)
        if count == 7:
            p = q[:, first + 3:first + 7]
            q[:, first + 3:first + 7] = p / np.linalg.norm(p, axis=1, keepdims=True)


_MODE_REACH = 0.1     # the default amplitude moves the mechanism's points by up to this much of its size


def posed(equilibrium, q, t=None):
    """A Result of the equilibrium's model at rest in the poses q (k, n) at
    the times t (default 0 .. k - 1), each spatial body's Euler parameters
    normalised."""
    from .result import Result

    q = np.array(q, dtype=float)
    core = equilibrium._core
    unit_orientations(equilibrium.model, core, q)
    zero = np.zeros_like(q)
    t = np.arange(len(q), dtype=float) if t is None else np.asarray(t, dtype=float)
    raw = {"t": t, "q": q, "v": zero, "a": zero,
           "lam": np.zeros((len(q), len(equilibrium.lam))), "stats": {}}
    return Result(equilibrium.model, core, raw)


def drawn_points(scene, result):
    """(k, p, d): the points the drawing goes through in each pose of result:
    the bodies' centres of mass, the points where elements attach (a pinned
    rod drawn whole) and, in space, the corners of the inertia boxes; the
    points fixed to the ground too."""
    k = len(result.t)
    paths = []
    for b in scene.bodies:
        paths.append(result.body(b).position)
        paths += [scene.path(b, p, result=result) for p in scene.drawn_outline(b)]
        corners = scene.box(b)
        if corners is not None:
            paths += [scene.path(b, c, result=result) for c in corners]
    for kind, kw in scene.elements:
        paths += [np.broadcast_to(p, (k, scene.dimension)) for b, p in scene.attachments(kw["name"])
                  if b == "ground"]
    return np.stack(paths, axis=1)


def mode_amplitude(equilibrium, shape):
    """The default amplitude of a mode's shape (its largest entry 1: m or
    rad): what moves the drawn points by up to _MODE_REACH of the
    mechanism's size (the largest extent of those points at equilibrium),
    from the points' motion along the shape (a difference quotient)."""
    step = 1e-6
    shown = posed(equilibrium, [equilibrium.q, equilibrium.q + step * shape])
    points = drawn_points(Scene(shown), shown)
    size = float(np.max(np.ptp(points[0], axis=0))) if points.shape[1] else 0.0
    if not size > 1e-9:
        size = 1.0  # a point alone: 1 m
    moved = float(np.max(np.linalg.norm(points[1] - points[0], axis=1))) / step if points.shape[1] else 0.0
    if not moved > 1e-9:
        return _MODE_REACH  # the shape moves no drawn point: 0.1 of whatever it moves
    return _MODE_REACH * size / moved
