"""Building a mechanism: bodies, joints, gravity (docs/design.md, section 2.7)."""

import copy
import numbers
import threading
import warnings

import numpy as np

from . import _core, _poses, _rotations
from . import registry
from ._checks import flag as _flag, matrix_or_vector as _matrix_or_vector, real as _number, show
from ._checks import text as _text, vec2 as _vec2, vec3 as _vec3
from .errors import AssemblyWarning, ModelError, RedundantConstraintWarning, translated
from .functions import TimeFunction, as_time_function, from_core
from .handles import Body, Handle, name_of


def _tuple(x):
    return (float(x[0]), float(x[1]))


class Model:
    """A mechanism: rigid bodies, particles and the elements between them,
    planar (``dimension=2``, the default) or spatial (``dimension=3``).

    Coordinates are Cartesian. In the plane: (x, y, phi) of each body's
    centre of mass and angle, (x, y) of each particle. In space: (x, y, z)
    of each body's centre of mass and its Euler parameters (w, x, y, z), a
    unit quaternion kept so by one constraint equation per body. Points are
    global, in the initial configuration, unless the argument name says
    ``local``. Every body and element has a unique name. Gravity is absent
    unless given: (gx, gy) in the plane, (gx, gy, gz) in space. ``name``:
    what pictures and pages call the model (load_urdf: the robot's name,
    load_scene: the file's, load_mjcf: the model's); None: unnamed.

    What a model has is an attribute (``m.bodies``, ``m.elements``,
    ``m.parameters``, ``m.parameter_info``, ``m.coordinate_names``,
    ``m.frames``, ``m.shapes``, ``m.n_coordinates``); what is computed from
    it is a method (``m.assemble()``, ``m.degrees_of_freedom()``,
    ``m.rank()``, ``m.compiled()``, ``m.to_text()``). Calling an attribute
    (``m.elements``, the spelling before 0.1.0's release) still works and
    warns (DeprecationWarning).

    Every add_* and drive_* method returns the handle of what it added
    (mb.Handle; mb.Body for bodies and particles, ``ground`` for the
    ground). A handle prints as its name and goes wherever the name does:
    ``pin = m.add_revolute("pin", ...); m.add_stop("limit", pin, ...);
    r.reaction(pin)``.
    """

    def __init__(self, gravity=None, dimension=2, name=None):
        if isinstance(dimension, bool) or dimension not in (2, 3):
            raise ModelError(f"dimension must be 2 (planar) or 3 (spatial), got {show(dimension)}")
        if name is not None and not isinstance(name, str):
            raise ModelError(f"name must be a text or None, got {show(name)}")
        self.dimension = int(dimension)
        self.name = name
        # the description, the one copy of the model (elements() reads it back);
        # compiled() gives the immutable core Model
        self._spec = _core.ModelSpec(self.dimension)
        self._compiled = None  # kept until the description changes
        # an edit and a compile or a run's snapshot wait for each other (a
        # run in one thread, add_* in another); _edits counts the changes
        self._lock, self._edits = threading.RLock(), 0
        self.ground = Body("ground", self, -1)
        self.gravity = None
        if gravity is not None:
            g = _vec2(gravity, "gravity") if self.dimension == 2 else _vec3(gravity, "gravity")
            self._spec.set_gravity(g)
            self.gravity = tuple(float(x) for x in g)
        # frames and shapes: named places and geometry on bodies, for results
        # and pictures; no part of the equations (add_frame, add_shape)
        self._frames, self._shapes, self._annotations = {}, [], []
        self._hulls = {}  # mesh Shape -> the vertices of its hull a contact uses
        self._joint_aliases = {}  # {a body's or frame's name: the joint it also names} (add_joint_alias)

    def copy(self):
        """An independent copy to edit: the same bodies and elements (time
        functions shared), its own handles. Results of this model keep
        pointing to this one."""
        other = Model.__new__(Model)
        other._lock, other._edits = threading.RLock(), 0
        with self._lock:  # the description and its compiled model together
            other._spec = copy.copy(self._spec)
            other._compiled = self._compiled
        other.ground = Body("ground", other, -1)
        other.gravity = self.gravity
        other.dimension = self.dimension
        other.name = self.name
        other._frames, other._shapes = dict(self._frames), list(self._shapes)
        other._hulls = dict(self._hulls)
        other._annotations = list(self._annotations)
        other._joint_aliases = dict(self._joint_aliases)
        return other

    __copy__ = copy

    def __reduce__(self):
        """Pickled (and deep-copied) as its description: gravity, dimension
        and the elements, replayed on a new Model (time functions by their
        fields, a Python callable by pickle's rules: a module-level function
        travels, a lambda does not), with its shapes and the hulls of its
        collision meshes (the copy reads no mesh file again). Handles and
        results stay with this one."""
        return _rebuilt, (self.gravity, self.dimension, self.elements, tuple(self._annotations), self.name,
                          dict(self._hulls))

    # --- building --------------------------------------------------------

    def _body(self, body, what, context):
        """(name, index) of a body given by its handle or name (index -1:
        the ground); ``what`` is the argument, ``context`` the element."""
        name = name_of(self, body, ("body",), what, context)
        if name == "ground":
            return name, -1
        index = self._spec.body_index(name)
        if index < 0:
            raise ModelError(f"{context}: {what}: no body named '{name}'")
        return name, index

    def _joint(self, joint, context):
        """The name of a joint given by its handle, name or alias (the core
        checks that a name is a joint of the right kind)."""
        return self.joint_name(name_of(self, joint, ("joint",), "joint", context))

    def _name(self, name):
        if not isinstance(name, str):
            raise ModelError(f"names must be strings, got {name!r}")
        return name

    def _value(self, param, value, what):
        """The value of one parameter for the core, checked by its declared
        type (lagmb.registry; the checks of each type: _CHECKS)."""
        if value is None and not param.required:
            value = param.default  # None means "not given"
            if value is None:
                return None
        return _CHECKS[param.type](self, param, value, what, f"{what}: {param.name}")

    def _add(self, kind, name, values):
        """Check the values of one element of `kind` (lagmb.registry.Kind),
        add it to the core's description and return its handle."""
        name = self._name(name)
        what = f"{kind.what} '{name}'"
        core = {}
        for param in kind.params:
            core[param.name] = self._value(param, values[param.name], what)
        with self._lock:
            self._spec.add(kind.name, name, core)  # checks it against the model so far; ModelError
            self._compiled = None
            self._edits += 1
        if kind.role == "body":
            return Body(name, self, self._spec.body_index(name), kind.name)
        return Handle(name, self, kind.name, kind.role)

    def _given(self, param, value, bodies, memo):
        """A value of the description as the user gives it (elements())."""
        if value is None:
            return None
        t = param.type
        if t == "body":
            return "ground" if value < 0 else bodies[value]
        if t == "shape":
            if value[1] == "convex":  # the mesh whose hull it is (a model read from text has no meshes:
                # its hull's vertices as the core holds them)
                body = bodies[value[0]] if value[0] >= 0 else "ground"
                return next((s for s, hull in self._hulls.items() if hull == value[5] and
                             tuple(s.position) == tuple(value[3]) and s.body == body), value)
            return _shape_given(value, bodies)
        if t in ("motion", "function"):
            return from_core(value, memo)
        if t in ("function_pair", "function_triple"):
            calls = [f.callable for f in value]
            if calls[0] is not None and all(c is calls[0] for c in calls) and \
                    [f.component for f in value] == list(range(len(value))):
                return calls[0]  # one callable giving every component
            return tuple(from_core(f, memo) for f in value)
        return value

    # --- questions -------------------------------------------------------

    def compiled(self):
        """The compiled, immutable C++ model (lagmb/spec/spec.hpp): built when
        first asked and again after the model changes. Compiling numbers
        coordinates and rows and builds patterns, in time linear in the
        model's size; it runs no solver (redundant equations are found where
        a run starts). Several threads may run one compiled model."""
        with self._lock:
            if self._compiled is None:
                self._compiled = self._spec.compile()
            return self._compiled

    def _snapshot(self):
        """The model as a run or an analysis sees it from its start: a
        detached copy (description, frames, shapes) whose compiled() is the
        one the run uses, taken at one instant, so that an edit made
        meanwhile (add_* from another thread) reaches neither. Handles of
        this model stand for its elements there (``_source``)."""
        with self._lock:
            self.compiled()  # (kept here too: the next run of an unchanged model compiles nothing)
            snapshot = self.copy()
            snapshot._source, snapshot._edits = self, self._edits
        return snapshot

    def _run_model(self, snapshot, into=None):
        """The model a Result of a run that started from ``snapshot``
        answers for: this one, unless it was edited since the snapshot was
        taken, then the snapshot (with a UserWarning, or into the list
        ``into``), so that the Result still answers for what was run."""
        if self._edits == snapshot._edits:
            return self
        import warnings

        warning = UserWarning("the model was changed (add_* from another thread) while it ran: the result "
                              "answers for the model as it was at the start (its .model is a copy of that)")
        (into.append if into is not None else lambda w: warnings.warn(w, stacklevel=4))(warning)
        return snapshot

    def to_text(self):
        """The model's description as text (``ModelSpec``'s, as the FMU
        carries it): every element with its values as given, numbers to 17
        digits; :meth:`from_text` reads it back to a model that compiles to
        the same numbers. ModelError for a model with a Python callable (it
        has no text). Frames and shapes (pictures, not equations) are not in
        it."""
        return self._spec.to_text()

    @classmethod
    def from_text(cls, text):
        """The model :meth:`to_text` described."""
        if not isinstance(text, str):
            raise ModelError(f"Model.from_text: text must be a string, got {type(text).__name__}")
        spec = _core.ModelSpec.from_text(text)
        model = cls(dimension=spec.dimension)
        model._spec = spec
        for line in text.splitlines():
            if line.startswith("gravity "):
                g = [float(x) for x in line.split()[1:]]
                model.gravity = tuple(g[:model.dimension]) if any(g) else None
                break
        return model

    @property
    def coordinate_names(self):
        """The names of the coordinates q in order, as the FMU names them:
        body.x, body.y, body.angle in the plane; body.x, .y, .z, .e0 ...
        .e3 (Euler parameters) in space."""
        return _Listed("coordinate_names", self.compiled().coordinate_names())

    @property
    def parameters(self):
        """{name: value} of every number given to an element that a run may
        change (``simulate(..., parameters={...})``, ``Simulator``, the FMU's
        parameters): real parameters ("rod.mass", "spring.stiffness") and the
        components of points and vectors ("pin.at.x", "rod.velocity.y"),
        given or the kind's default, element by element in the order added.
        A body's initial coordinate that shares its name with the coordinate
        ends in ".start" ("rod.angle.start"). Inertia tensors, orientations,
        flags and time functions are not parameters."""
        return _Named("parameters", {p["name"]: p["value"] for p in self.compiled().parameters})

    @property
    def parameter_info(self):
        """The parameters with what they are: a list of dicts with name,
        element, key (the add_* argument), component (-1, or 0/1/2 for
        x/y/z), unit, doc and value."""
        return _Listed("parameter_info", [dict(p) for p in self.compiled().parameters])

    def _warn_redundant(self, rows, stacklevel=2, into=None):
        """RedundantConstraintWarning for the rows a run left out; stacklevel
        as warnings.warn counts it from the public function that calls this
        (2: its caller's line). ``into``: a list that takes the warning
        instead (a sweep's case: the warnings module is not thread-safe)."""
        if not rows:
            return
        import warnings

        core = self.compiled()
        named = ", ".join(f"'{core.constraint_name_of_row(r)}' (row {r})" for r in rows)
        (into.append if into is not None else lambda w: warnings.warn(w, stacklevel=stacklevel + 2))(
            RedundantConstraintWarning(
            f"{len(rows)} constraint equation(s) are redundant at the initial configuration: "
            f"{named}. They are dropped: the motion is unique and is simulated, and the "
            "rest of each redundant set carries its reaction (the split among redundant "
            "joints is not unique). The dropped equations are checked at every output."))

    def _warn_moved(self, core, q_start, stacklevel=2, into=None):
        """AssemblyWarning naming the bodies that the start state q_start
        (assembled from the model's initial coordinates) moved by more than
        1e-3 of the mechanism's size (the spread of the bodies' initial
        centres and the origin, at least 0.1 m) or 1e-3 rad: the turn of a
        planar angle, or the angle 2 acos |p0 . p1| between two orientations
        in space."""
        q0 = np.asarray(core.initial_state()[0], dtype=float)
        q1 = np.asarray(q_start, dtype=float)
        names = [name for name, _ in self._spec.bodies]
        if not names:
            return
        d = 3 if self.dimension == 3 else 2
        places = np.array([core.body_coordinates(name) for name in names], dtype=int).reshape(-1, 2)
        first, turns = places[:, 0], places[:, 1] > d  # (a particle has no orientation)
        at = first[:, None] + np.arange(d)
        size = max(0.1, float(np.max(np.ptp(np.vstack([q0[at], np.zeros((1, d))]), axis=0))))
        shift = np.linalg.norm(q1[at] - q0[at], axis=1)
        turn = np.zeros(len(names))
        if turns.any():
            f = first[turns]
            if d == 2:
                turn[turns] = np.abs(np.remainder(q1[f + 2] - q0[f + 2] + np.pi, 2 * np.pi) - np.pi)
            else:
                p0, p1 = q0[f[:, None] + np.arange(3, 7)], q1[f[:, None] + np.arange(3, 7)]
                c = np.abs(np.sum(p0 * p1, axis=1)) / (np.linalg.norm(p0, axis=1) * np.linalg.norm(p1, axis=1))
                turn[turns] = 2.0 * np.arccos(np.minimum(1.0, c))
        moved = [(max(shift[k] / size, turn[k]), f"'{names[k]}' by {shift[k]:.3g} m and {turn[k]:.3g} rad")
                 for k in np.flatnonzero((shift > 1e-3 * size) | (turn > 1e-3))]
        if not moved:
            return
        import warnings

        # the five moved most (relative to the size, or turned), then a count
        named = [text for _, text in sorted(moved, key=lambda m: -m[0])[:5]]
        if len(moved) > 5:
            named.append(f"and {len(moved) - 5} more")
        (into.append if into is not None else lambda w: warnings.warn(w, stacklevel=stacklevel + 2))(AssemblyWarning(
            f"assembly moved {len(moved)} bod{'y' if len(moved) == 1 else 'ies'} to satisfy the joints: "
            f"{', '.join(named)} (more than 1e-3 of the mechanism's size, {size:.3g} m, or 1e-3 rad). "
            "Check the joint points and the initial positions; the run starts from the assembled "
            "configuration."))

    @property
    def elements(self):
        """Everything added, in order: (method name, keyword arguments) with
        bodies by name, points as tuples and time functions as given: the
        model's description, which replayed on Model(gravity=self.gravity,
        dimension=self.dimension) rebuilds it (a handle of an element:
        the add_* call returned it, or give its name wherever a handle goes)."""
        bodies = [name for name, _ in self._spec.bodies]
        memo = {}  # one object per core input within this reading
        out = []
        for kind_name, name, values in self._spec.elements():
            kind = registry.BY_NAME[kind_name]
            given = {"name": name}
            for param in kind.params:
                given[param.name] = self._given(param, values.get(param.name), bodies, memo)
            out.append((kind.method, given))
        return _Listed("elements", out)

    def outline(self, body):
        """Local points (body axes) where joints and forces attach to a body,
        in the order added: what a drawing of the body joins."""
        name = name_of(self, body, ("body",), "body", "Model.outline")
        if name == "ground":
            return []
        index = self._spec.body_index(name)
        if index < 0:
            raise ModelError(f"Model.outline: no body named '{name}'")
        return list(self._spec.outline(index))

    def attachments(self, element):
        """[(body name, local point)] where an element attaches, in the
        order of its parameters (a point on the ground is global): (x, y)
        in a planar model, (x, y, z) in a spatial one."""
        name = name_of(self, element, registry.ROLES, "element", "Model.attachments")
        names = ["ground"] + [body for body, _ in self._spec.bodies]  # by index + 1
        return [(names[b + 1], tuple(point)) for b, *point in self._spec.attachments(name)]

    @property
    def bodies(self):
        """Body handles, in the order of their coordinates."""
        kind = "spatial_body" if self.dimension == 3 else None
        return _Listed("bodies", [Body(name, self, k, kind or ("particle" if particle else "body"))
                                  for k, (name, particle) in enumerate(self._spec.bodies)])

    # --- frames and shapes (no part of the equations) -------------------

    def add_frame(self, name, body, position, orientation=None):
        """A named place fixed in a spatial body: its origin at the global
        ``position`` and its axes along ``orientation`` (a rotation matrix or
        unit quaternion (w, x, y, z); default the global axes), both in the
        initial configuration. Results read it by name as a body
        (``r.body(name)``: its origin's path, its axes' rotation) and
        ``r.point(name, p)`` takes p in its axes. load_urdf adds one for each
        link merged into another's body. Returns the Frame."""
        context = f"frame '{name}'"
        if self.dimension != 3:
            raise ModelError(f"{context}: frames are spatial only; this model has dimension {self.dimension}")
        name = _text(self._name(name), "frame name")
        if name == "ground" or name in self._frames or name in {kw["name"] for _, kw in self.elements}:
            raise ModelError(f"{context}: the name is taken")
        body_name, R, r = _initial_pose(self, body, context)
        at = np.asarray(_vec3(position, f"{context}: position"), dtype=float)
        if not np.all(np.isfinite(at)):
            raise ModelError(f"{context}: position must be finite, got {position!r}")
        axes = np.eye(3) if orientation is None else self._orientation(orientation, context)
        frame = Frame(body_name, R.T @ (at - r), R.T @ axes)
        self._frames[name] = frame
        self._annotations.append(("add_frame", dict(name=name, body=body_name, position=tuple(float(x) for x in at),
                                                    orientation=tuple(map(tuple, axes)))))
        return frame

    @property
    def frames(self):
        """{name: Frame} of the frames added (add_frame)."""
        return _Named("frames", self._frames)

    def add_joint_alias(self, name, joint):
        """A second name for a joint where the name is a body's or frame's:
        a file that keeps joints and links apart (URDF) may give a joint its
        link's name; load_urdf calls the joint NAME_joint and adds NAME as
        its alias. Where a joint is asked for (``r.joint``, ``r.reaction``,
        ``r.multipliers``, a stop's or coupling's ``joint``), the alias is the
        joint; where a body is (``r.body``), the name is the body or frame."""
        context = f"joint alias '{name}'"
        name = _text(self._name(name), "alias")
        joint = name_of(self, joint, ("joint",), "joint", context)
        elements = {kw["name"]: method for method, kw in self.elements}
        if elements.get(name) != "add_body" and name not in self._frames:
            raise ModelError(f"{context}: an alias is a body's or frame's name (a joint's own name is free, "
                             "or another element's)")
        if joint not in elements or name in self._joint_aliases:
            raise ModelError(f"{context}: " + (f"no joint named '{joint}'" if joint not in elements else
                                               f"'{name}' is already the alias of '{self._joint_aliases[name]}'"))
        self._joint_aliases[name] = joint
        self._annotations.append(("add_joint_alias", dict(name=name, joint=joint)))

    def joint_name(self, name):
        """The joint a name stands for: the joint its alias names
        (add_joint_alias), else the name itself."""
        return self._joint_aliases.get(name, name)

    def add_shape(self, body, kind, size, position=(0.0, 0.0, 0.0), orientation=None, *, mesh=None,
                  role="visual"):
        """Geometry on a spatial body or the ground: ``kind`` "box" (size:
        edge lengths), "cylinder" ((radius, length), its axis along its own
        z), "sphere" ((radius,)), "capsule" ((radius, length): a segment of
        that length along its own z swept by a sphere), "plane" (size ():
        the half-space below its own xy plane, outward normal along its own
        z) or "mesh" (size: the scale (3,), ``mesh``: the file); centred at
        the global ``position`` with axes ``orientation``, in the initial
        configuration. ``role`` "visual" (pictures only) or "collision": a
        shape a contact may pair (add_contact). load_urdf adds a link's
        <visual> and <collision> geometry. Returns the Shape."""
        context = f"shape on '{body}'"
        if self.dimension != 3:
            raise ModelError(f"{context}: shapes are spatial only; this model has dimension {self.dimension}")
        if kind not in _SHAPE_SIZES:
            raise ModelError(f"{context}: kind must be one of {', '.join(_SHAPE_SIZES)}, got {kind!r}")
        if role not in ("visual", "collision"):
            raise ModelError(f"{context}: role must be 'visual' or 'collision', got {role!r}")
        try:
            dims = np.asarray(size, dtype=float).reshape(_SHAPE_SIZES[kind])
        except (TypeError, ValueError):
            raise ModelError(f"{context}: a {kind}'s size is {_SHAPE_SIZES[kind]} numbers, got {size!r}") from None
        # (a mesh's scale may be negative: a mirrored mesh)
        positive = dims > 0
        if kind == "capsule":
            positive[1:] = dims[1:] >= 0  # a capsule of length 0 is a sphere
        if not (np.all(np.isfinite(dims)) and np.all((dims != 0) if kind == "mesh" else positive)):
            raise ModelError(f"{context}: a {kind}'s size must be {'nonzero' if kind == 'mesh' else 'positive'}, "
                             f"got {size!r}")
        if (kind == "mesh") != (mesh is not None):
            raise ModelError(f"{context}: a mesh names its file (mesh=...), other kinds do not")
        body_name, R, r = _initial_pose(self, body, context)
        at = np.asarray(_vec3(position, f"{context}: position"), dtype=float)
        axes = np.eye(3) if orientation is None else self._orientation(orientation, context)
        shape = Shape(body_name, kind, tuple(float(x) for x in dims), R.T @ (at - r), R.T @ axes,
                      None if mesh is None else str(mesh), role)
        self._shapes.append(shape)
        self._annotations.append(("add_shape", dict(body=body_name, kind=kind, size=shape.size,
                                                    position=tuple(float(x) for x in at),
                                                    orientation=tuple(map(tuple, axes)), mesh=shape.mesh,
                                                    role=role)))
        return shape

    @property
    def shapes(self):
        """The shapes added (add_shape), in order; each Shape's ``position``
        and ``rotation`` are in its body's axes, from its centre of mass
        (add_shape takes them global): their global poses at a state are
        :meth:`poses` ``.shapes``."""
        return _Listed("shapes", self._shapes)

    # where things are at a state (forward kinematics, _poses.py)
    poses = _poses.model_poses
    pose = _poses.model_pose
    lowest_point = _poses.model_lowest_point

    def _orientation(self, orientation, context):
        try:
            a = np.asarray(orientation, dtype=float)
        except (TypeError, ValueError):
            a = None
        if a is None or a.shape not in ((3, 3), (4,)) or not np.all(np.isfinite(a)):
            raise ModelError(f"{context}: orientation must be a 3 x 3 rotation matrix or a unit quaternion, "
                             f"got {orientation!r}")
        if a.shape == (4,):
            if not abs(np.linalg.norm(a) - 1.0) < 1e-6:
                raise ModelError(f"{context}: the quaternion {orientation!r} is not a unit quaternion")
            return _rotation(a)
        if not (np.allclose(a.T @ a, np.eye(3), atol=1e-6) and np.linalg.det(a) > 0):
            raise ModelError(f"{context}: orientation is not a rotation matrix")
        return a

    @property
    def n_coordinates(self):
        return self.compiled().n_coordinates

    @property
    def n_constraints(self):
        return self.compiled().n_constraints

    def assemble(self, t=0.0):
        """Consistent initial state: (q, v, qdd, lam) at time t. Redundant
        equations found there are named in a RedundantConstraintWarning,
        bodies moved far by assembly in an AssemblyWarning."""
        t = _number(t, "t")
        core = self.compiled()
        with translated():
            q, v, qdd, lam, dropped = _core.assemble(core, t)
        self._warn_redundant(dropped)
        self._warn_moved(core, q)
        return q, v, qdd, lam

    def degrees_of_freedom(self):
        """Coordinates minus the number of independent constraint equations,
        counted near the assembled initial position (at a singular position,
        such as a flat parallelogram, as at its regular neighbours)."""
        core = self.compiled()
        with translated():
            return _core.degrees_of_freedom(core, 0.0)

    def rank(self):
        """Rank of the constraint Jacobian at the assembled initial position:
        dict with rank, equations, coordinates, degrees_of_freedom and the
        dependent (redundant) rows."""
        import warnings

        from .errors import RedundantConstraintWarning
        with warnings.catch_warnings():  # the dependent rows are what this returns
            warnings.simplefilter("ignore", RedundantConstraintWarning)
            q = self.assemble()[0]
        with translated():
            return self.compiled().rank(q, 0.0)

    def __repr__(self):
        n_bodies = len(self._spec.bodies)
        return f"<lagmb.Model: {n_bodies} bodies, {len(self._spec) - n_bodies} other elements>"



def checked(value, who):
    """A lagmb.Model given to `who` (a run, an analysis); ModelError otherwise."""
    if not isinstance(value, Model):
        raise ModelError(f"{who}: model must be a lagmb.Model, got {show(value)}")
    return value

def _matrix_or_vector_value(length, shape):
    def check(model, param, value, what, label):
        x = _matrix_or_vector(value, label, length, shape)
        return tuple(float(c) for c in x) if x.ndim == 1 else tuple(tuple(float(c) for c in row) for row in x)
    return check


def _choice_value(model, param, value, what, label):
    if value not in param.choices:
        words = ", ".join(repr(c) for c in param.choices[:-1]) + f" or {param.choices[-1]!r}"
        raise ModelError(f"{label} must be {words}, got {show(value)}")
    return value


def _function_value(value, what, label, derivatives):
    """A time function given as a number (checked as the argument ``label``
    names: "servo 's': target must be finite"), a TimeFunction or a callable
    (whose failures name the element, ``what``)."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        value = _number(value, label)
    return as_time_function(value, what, derivatives=derivatives)


def _functions_value(n, components, result):
    """(f_1(t), ..., f_n(t)) given as n values or one callable giving all n."""
    def check(model, param, value, what, label):
        if callable(value) and not isinstance(value, TimeFunction):
            return tuple(as_time_function(value, what, derivatives=False, component=k, components=n)
                         for k in range(n))
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != n:
            raise ModelError(f"{what}: {param.name} must be {components} or a callable t -> {result}, "
                             f"got {show(value)}")
        names = ("fx", "fy") if n == 2 else tuple(f"{param.name}[{k}]" for k in range(n))
        return tuple(as_time_function(f, f"{what}: {names[k]}", derivatives=False) for k, f in enumerate(value))
    return check


#: How the Python API checks a value of each parameter type, by the names of
#: the core's table of types (lagmb/model/registry.hpp, param_types(); the
#: tests of the registry check that every type has its check here).
_CHECKS = {
    "text": lambda model, param, value, what, label: _text(value, label),
    "real": lambda model, param, value, what, label: _number(value, label),
    "vec2": lambda model, param, value, what, label: _tuple(_vec2(value, label)),
    "bool": lambda model, param, value, what, label: _flag(value, label),
    "body": lambda model, param, value, what, label: model._body(value, param.name, what)[1],
    "joint": lambda model, param, value, what, label: model._joint(value, what),
    "choice": _choice_value,
    "motion": lambda model, param, value, what, label: _function_value(value, what, label, True),
    "function": lambda model, param, value, what, label: _function_value(value, what, label, False),
    "function_pair": _functions_value(2, "(fx, fy)", "(fx, fy)"),
    "vec3": lambda model, param, value, what, label: tuple(float(c) for c in _vec3(value, label)),
    "orientation": _matrix_or_vector_value(4, "a unit quaternion (w, x, y, z) or a 3 x 3 rotation matrix"),
    "inertia": _matrix_or_vector_value(3, "principal moments (Ixx, Iyy, Izz) or a 3 x 3 inertia tensor"),
    "function_triple": _functions_value(3, "(x, y, z) components", "(x, y, z)"),
}


def _called(name):
    warnings.warn(f"Model.{name} is an attribute (what a model has): write m.{name}, not m.{name}(); "
                  "the call is deprecated", DeprecationWarning, stacklevel=3)


class _Listed(list):
    """A list a Model attribute gives that may still be called, as it was a
    method (``m.elements``): the call warns and gives the list."""

    __slots__ = ("_attribute",)

    def __init__(self, attribute, items):
        super().__init__(items)
        self._attribute = attribute

    def __call__(self):
        _called(self._attribute)
        return list(self)

    def __reduce__(self):  # (pickled as a plain list)
        return list, (list(self),)


class _Named(dict):
    """A dict a Model attribute gives that may still be called (``m.parameters``): the call warns."""

    __slots__ = ("_attribute",)

    def __init__(self, attribute, items):
        super().__init__(items)
        self._attribute = attribute

    def __call__(self):
        _called(self._attribute)
        return dict(self)

    def __reduce__(self):
        return dict, (dict(self),)


def _rebuilt(gravity, dimension, elements, annotations=(), name=None, hulls=None):
    """A Model from what Model.__reduce__ gives."""
    model = Model(gravity=gravity, dimension=dimension, name=name)
    model._hulls.update(hulls or {})
    for method, kwargs in list(elements) + list(annotations):
        getattr(model, method)(**kwargs)
    return model


def _initial_pose(model, body, context):
    """(R, r) of a spatial body's axes in the initial configuration (the
    ground: identity, origin), from its add_body values."""
    name, index = model._body(body, "body", context)
    if index < 0:
        return name, np.eye(3), np.zeros(3)
    values = next(kw for method, kw in model.elements if method == "add_body" and kw["name"] == name)
    R = _rotation(values["orientation"])
    return name, R, np.asarray(values["position"], dtype=float)


def _rotation(orientation):
    """A 3 x 3 rotation matrix from a unit quaternion (w, x, y, z) or a matrix."""
    a = np.asarray(orientation, dtype=float)
    if a.shape == (3, 3):
        return a
    return _rotations.matrix(a / np.linalg.norm(a))


class Frame(tuple):
    """A named place on a body (Model.add_frame): ``body`` (its name),
    ``position`` (3,) its origin in the body's axes from the body's centre
    of mass (m), ``rotation`` (3, 3) its axes in the body's axes."""

    __slots__ = ()

    def __new__(cls, body, position, rotation):
        return super().__new__(cls, (body, position, rotation))

    def __getnewargs__(self):  # (pickle and deepcopy call __new__ with these)
        return tuple(self)

    body = property(lambda self: self[0])
    position = property(lambda self: self[1])
    rotation = property(lambda self: self[2])


class Shape(tuple):
    """Geometry on a body for pictures (Model.add_shape): ``body``,
    ``kind`` ("box", "cylinder", "sphere" or "mesh"), ``size`` (box: the
    edge lengths (3,); cylinder: (radius, length) along its z; sphere:
    (radius,); mesh: the scale (3,)), ``position`` and ``rotation`` in the
    body's axes from its centre of mass, ``mesh`` (a file path, or None),
    ``role`` ("visual" or "collision")."""

    __slots__ = ()

    def __new__(cls, body, kind, size, position, rotation, mesh, role):
        return super().__new__(cls, (body, kind, size, position, rotation, mesh, role))

    def __getnewargs__(self):  # (pickle and deepcopy call __new__ with these)
        return tuple(self)

    body = property(lambda self: self[0])
    kind = property(lambda self: self[1])
    size = property(lambda self: self[2])
    position = property(lambda self: self[3])
    rotation = property(lambda self: self[4])
    mesh = property(lambda self: self[5])
    role = property(lambda self: self[6])

    def __eq__(self, other):
        return isinstance(other, Shape) and self.to_dict() == other.to_dict()

    def __ne__(self, other):
        return not self == other

    def __hash__(self):
        return hash(repr(self.to_dict()))

    def to_dict(self):
        """The shape as a scene holds it (an inline table: body, kind, size,
        position and rotation in the body's axes, mesh, role)."""
        d = {"body": self.body, "kind": self.kind, "size": [float(x) for x in self.size],
             "position": [float(x) for x in self.position],
             "rotation": [[float(x) for x in row] for row in np.asarray(self.rotation)]}
        if self.mesh is not None:
            d["mesh"] = self.mesh
        d["role"] = self.role
        return d


_SHAPE_SIZES = {"box": 3, "cylinder": 2, "sphere": 1, "capsule": 2, "plane": 0, "mesh": 3}


def _shape_value(model, param, value, what, label):
    """A collision shape for the core (registry type "shape"): (body index,
    kind, size (3), position (3), axes (3 x 3), vertices) from a Shape of
    role "collision" on a body of this model."""
    if isinstance(value, dict):  # a scene's inline table (Shape.to_dict)
        value = _shape_from_dict(model, value, label)
    if not isinstance(value, Shape):
        raise ModelError(f"{label} must be a Shape (Model.add_shape(..., role='collision')), got {show(value)}")
    if value.role != "collision":
        raise ModelError(f"{label}: a contact pairs collision shapes; this {value.kind} on '{value.body}' has "
                         f"role {value.role!r} (add it with role='collision')")
    index = model._body(value.body, param.name, what)[1]
    axes = tuple(tuple(float(x) for x in row) for row in np.asarray(value.rotation))
    position = tuple(float(x) for x in value.position)
    if value.kind == "mesh":  # its convex hull's vertices (scaled, in its own axes)
        if value not in model._hulls:
            model._hulls[value] = _hull_vertices(value, label)
        return (index, "convex", (0.0, 0.0, 0.0), position, axes, model._hulls[value])
    size = tuple(float(x) for x in value.size) + (0.0,) * (3 - len(value.size))
    return (index, value.kind, size, position, axes, [])


def _hull_vertices(shape, label):
    """Every vertex of a mesh's convex hull (scaled, in the mesh's order of
    unique points): the points a contact uses. Whatever plane a convex hull
    meets, its deepest point is one of its vertices, so none may be left out
    (a vertex sticking out of a face is extreme only in a narrow cone of
    directions). The hull is Qhull's (SciPy), its coplanar points (on a
    face or an edge, never deepest alone) left out."""
    from ._meshes import read_stl

    if not str(shape.mesh).lower().endswith(".stl"):
        raise ModelError(f"{label}: lagmb reads STL meshes only; {shape.mesh!r} cannot be a collision shape")
    try:
        from scipy.spatial import ConvexHull
    except ImportError:
        raise ModelError(f"{label}: the convex hull of mesh {shape.mesh!r} is SciPy's (scipy.spatial.ConvexHull); "
                         "install SciPy (pip install scipy) to make a mesh a collision shape") from None
    points = np.unique(read_stl(shape.mesh).reshape(-1, 3) * np.asarray(shape.size, dtype=float), axis=0)
    if len(points) == 0:
        raise ModelError(f"{label}: the mesh {shape.mesh!r} has no triangles (0 in the file): a collision shape "
                         "needs the vertices of a solid")
    try:
        chosen = np.sort(ConvexHull(points).vertices)
    except (RuntimeError, ValueError):  # (Qhull's error: fewer than 4 points, or all in a plane)
        raise ModelError(f"{label}: mesh {shape.mesh!r} scaled by {tuple(shape.size)} has no convex hull "
                         f"with a volume ({len(points)} distinct points, in a plane or fewer than 4)") from None
    return [tuple(float(x) for x in points[i]) for i in chosen]


_CHECKS["shape"] = _shape_value


def _shape_from_dict(model, d, label):
    """A Shape from what Shape.to_dict gives (a scene), checked; it joins the
    model's shapes (what pictures draw) unless it is one of them."""
    known = {"body", "kind", "size", "position", "rotation", "mesh", "role"}
    if set(d) - known or not {"body", "kind", "size"} <= set(d):
        raise ModelError(f"{label}: a shape is {{body, kind, size, position, rotation, role}}, got {show(d)}")
    kind = d["kind"]
    if kind not in _SHAPE_SIZES:
        raise ModelError(f"{label}: kind must be one of {', '.join(_SHAPE_SIZES)}, got {kind!r}")
    try:
        size = np.asarray(d["size"], dtype=float).reshape(_SHAPE_SIZES[kind])
        position = np.asarray(d.get("position", (0.0, 0.0, 0.0)), dtype=float).reshape(3)
        rotation = np.asarray(d.get("rotation", np.eye(3)), dtype=float).reshape(3, 3)
    except (TypeError, ValueError):
        raise ModelError(f"{label}: a {kind}'s size, position and rotation are {_SHAPE_SIZES[kind]}, 3 and "
                         f"3 x 3 numbers, got {show(d)}") from None
    body = model._body(d["body"], "body", label)[0]
    shape = Shape(body, kind, tuple(float(x) for x in size), position, rotation, d.get("mesh"),
                  d.get("role", "collision"))
    if shape not in model._shapes:
        model._shapes.append(shape)
    return shape


def _shape_given(value, bodies):
    """A core collision shape as the Shape that gave it."""
    index, kind, size, position, axes, _ = value
    return Shape("ground" if index < 0 else bodies[index], kind, tuple(size[:_SHAPE_SIZES[kind]]),
                 np.asarray(position, dtype=float), np.asarray(axes, dtype=float), None, "collision")


def _argument_error(method, dimension, signatures, error, kwargs):
    """What a call of Model.<method> with arguments its signature does not
    take says: Python's complaint, the arguments it takes, and, for a
    keyword of the other dimension's kind (a planar revolute's axis), that
    it belongs there."""
    own = signatures[dimension].parameters
    other = signatures.get(5 - dimension)
    text = f"{method}: {error}"
    foreign = [k for k in kwargs if k not in own]
    if other is not None and foreign and all(k in other.parameters for k in foreign):
        where = "spatial" if dimension == 2 else "planar"
        text += (f"; {', '.join(map(repr, foreign))} {'is' if len(foreign) == 1 else 'are'} for {where} models "
                 f"(Model(dimension={5 - dimension})), this model has dimension {dimension}")
    taken = [n for n in own if n != "self"]
    return text + f". It takes {', '.join(taken)}"


def _method(method):
    """Model.<method>: the kind it adds is the one of the model's dimension
    (add_revolute: a planar or a spatial revolute); its signature and
    docstring from the registry, its checks in Model._add."""
    kinds = {2: registry.BY_METHOD.get(method), 3: registry.SPATIAL_BY_METHOD.get(method)}
    signatures = {d: registry.signature(k) for d, k in kinds.items() if k is not None}

    def add(self, *args, **kwargs):
        kind = kinds[self.dimension]
        if kind is None:
            where = "planar" if self.dimension == 3 else "spatial"
            raise ModelError(f"{method}: {kinds[5 - self.dimension].name.replace('_', ' ')} elements are "
                             f"{where} only; this model has dimension {self.dimension}")
        try:
            values = signatures[self.dimension].bind(self, *args, **kwargs)
        except TypeError as e:
            raise ModelError(_argument_error(method, self.dimension, signatures, e, kwargs)) from None
        values.apply_defaults()
        values = dict(values.arguments)
        del values["self"]
        return self._add(kind, values.pop("name"), values)

    add.__name__ = method
    add.__qualname__ = f"Model.{method}"
    add.__signature__ = signatures.get(2, signatures.get(3))
    add.__doc__ = "\n\n".join((f"In a {'planar' if d == 2 else 'spatial'} model (dimension={d}):\n\n" if
                                len(signatures) > 1 else "") + registry.docstring(k)
                               for d, k in kinds.items() if k is not None)
    return add


for _method_name in dict.fromkeys(k.method for k in registry.ALL_KINDS):
    setattr(Model, _method_name, _method(_method_name))
del _method_name
