"""Results of a run as numpy arrays (docs/design.md, section 2.7)."""

import csv
import os
from functools import cached_property

import numpy as np

from . import _core, _rotations, registry
from ._rotations import matrix as rotation_matrices  # (statics reads it from here)
from .errors import KinematicOnlyError, ModelError, SimulationError, translated
from .handles import name_of
from .registry import BY_METHOD, SPATIAL_BY_METHOD


def _frozen(x):
    x = np.asarray(x, dtype=float)
    x.flags.writeable = False
    return x


def element_name(model, core, item, accepts, what, context):
    """The name of a body or element (its handle or its name) of the run's
    model `model`, compiled as `core`; ModelError if there is none, or if a
    handle is of another model or not one of the roles `accepts` (see
    handles.name_of for `what` and `context`). Where a joint is accepted, a
    joint's alias (Model.add_joint_alias) is that joint."""
    name = name_of(model, item, accepts, what, context)
    if "joint" in accepts:
        name = model.joint_name(name)
    if not core.has(name):
        raise ModelError(f"{context}: no body or element named '{name}' in this model")
    return name


_CONSTRAINTS = ("joint", "driver")  # the elements with multipliers
#: The points a reaction's torque may be taken about (Result.reaction's
#: ``about``), each with whether it is the joint's point.
REACTION_POINTS = {"centre of mass": False, "center of mass": False, "joint": True}


def reaction_about(about):
    """Whether a reaction's torque is asked about the joint's point (True)
    or the second body's centre of mass (False); ModelError for another
    ``about``."""
    if not isinstance(about, str) or about not in REACTION_POINTS:
        raise ModelError(f"about must be 'centre of mass' (the second body's, the default) or 'joint' (the "
                         f"joint's point on it), got {about!r}")
    return REACTION_POINTS[about]
RESULTS_FORMATS = (".npz", ".csv")  # what Result.save writes


#: The roles of the elements Result.effort is asked about: those of a kind
#: without an effort (a joint, a contact) are refused by efforts(), saying
#: where their force is read.
EXERTING = ("joint", "driver", "stop", "force", "friction", "contact")


def efforts(core, name, context, t, q, v, lam, inputs, state):
    """What element ``name`` of the compiled model ``core`` applies at each
    of the states (t, q, v): (k,), or (k, width) for a kind whose reading
    has components (Kind.effort_components). ``lam``: a callable giving
    the multipliers, asked only for a kind that reads them (a driver, stop,
    planar joint friction); ``inputs``, ``state``: the inputs and run state
    at each. ModelError for a contact or an element without an effort."""
    kind = registry.kind_of(core, name)
    if kind is not None and kind.role == "contact":
        raise ModelError(f"{context}: '{name}' is a contact: its forces are Result.contact('{name}')")
    if kind is None or not kind.effort:
        raise ModelError(f"{context}: '{name}' is a {core.element_kind(name)}, which has no effort (drivers, "
                         "stops, force elements and joint friction have one; a joint's force is its reaction)")
    multipliers = lam() if kind.role in ("driver", "stop", "friction") else np.zeros((len(t), 0))
    rows = core.effort(name, t, q, v, multipliers, inputs, state)
    return rows if kind.effort_components else rows[:, 0]


def results_format_problem(path):
    """Why Result.save cannot write ``path`` (its suffix is neither .npz nor
    .csv), or None."""
    if os.path.splitext(path)[1].lower() not in RESULTS_FORMATS:
        return "the results file must end in .npz or .csv"
    return None


def core_state(model, core):
    """What rebuilds the compiled model ``core`` of ``model`` elsewhere (a
    pickled Result or Equilibrium): the model, which pickles as its
    description, and {name: value} of the parameters ``core`` was made with
    (simulate's ``parameters=``) where they differ from the model's own."""
    own = {p["name"]: p["value"] for p in model.compiled().parameters}
    return model, {p["name"]: p["value"] for p in core.parameters if own.get(p["name"]) != p["value"]}


def rebuilt_core(model, parameters):
    """The compiled model core_state described."""
    core = model.compiled()
    return core.with_parameters(parameters) if parameters else core


class BodyPath:
    """The motion of one body.

    Planar: position (k, 2) of its centre of mass, angle (k,), velocity
    (k, 2), angular_velocity (k,), acceleration (k, 2), angular_acceleration
    (k,). A particle has no angle (zeros).

    Spatial: position, velocity, acceleration (k, 3); orientation (k, 4),
    the Euler parameters (w, x, y, z); rotation (k, 3, 3), body axes into
    global axes; angular_velocity and angular_acceleration (k, 3) in global
    axes (omega = 2 E(p) p', omega' = 2 E(p) p'')."""

    def __init__(self, result, first, count):
        def cols(x, a, b):
            return x[:, first + a:first + b]

        if count == 7:
            self.position = cols(result.q, 0, 3)
            self.velocity = cols(result.v, 0, 3)
            self.acceleration = cols(result.a, 0, 3)
            self.orientation = cols(result.q, 3, 7)
            E = _rotations.E(self.orientation)
            self.angular_velocity = 2.0 * np.einsum("kij,kj->ki", E, cols(result.v, 3, 7))
            self.angular_acceleration = 2.0 * np.einsum("kij,kj->ki", E, cols(result.a, 3, 7))
            self.rotation = rotation_matrices(self.orientation)
            return
        self.position = cols(result.q, 0, 2)
        self.velocity = cols(result.v, 0, 2)
        self.acceleration = cols(result.a, 0, 2)
        k = len(result.t)
        zero = np.zeros(k)
        self.angle = result.q[:, first + 2] if count == 3 else zero
        self.angular_velocity = result.v[:, first + 2] if count == 3 else zero
        self.angular_acceleration = result.a[:, first + 2] if count == 3 else zero


class FramePath:
    """The motion of a frame fixed in a spatial body (Model.add_frame), from
    its body's: position, velocity, acceleration (k, 3) of its origin;
    rotation (k, 3, 3), its axes into global axes; angular_velocity and
    angular_acceleration (k, 3), the body's. With s = R_b s' its origin
    from the body's centre of mass: v = v_b + w x s, a = a_b + w' x s +
    w x (w x s)."""

    def __init__(self, body, frame, k):
        if body is None:  # a frame of the ground
            self.position = np.tile(frame.position, (k, 1))
            self.velocity = self.acceleration = np.zeros((k, 3))
            self.rotation = np.tile(frame.rotation, (k, 1, 1))
            self.angular_velocity = self.angular_acceleration = np.zeros((k, 3))
            return
        s = np.einsum("kij,j->ki", body.rotation, frame.position)
        w, wd = body.angular_velocity, body.angular_acceleration
        self.position = body.position + s
        self.velocity = body.velocity + np.cross(w, s)
        self.acceleration = body.acceleration + np.cross(wd, s) + np.cross(w, np.cross(w, s))
        self.rotation = np.einsum("kij,jl->kil", body.rotation, frame.rotation)
        self.angular_velocity, self.angular_acceleration = w, wd


class JointPath:
    """A joint's coordinate along a run (Result.joint): ``angle`` (rad) of a
    revolute or cylindrical joint, ``slide`` (m) of a translational or
    cylindrical one, with ``rate`` and ``acceleration`` (k,) of the first it
    has (the angle, for a cylindrical joint: ``slide_rate`` and
    ``slide_acceleration`` for its slide). In the initial configuration the
    joint's ``angle`` or ``slide`` (0 unless given);
    a spatial angle counts the joint's turns (the run counts them after
    every step, model/joint_turns.hpp: right however far apart the outputs
    are), a planar one is the bodies' angle difference."""

    def __init__(self, result, name, who="Result.joint"):
        core = result._core
        kind = core.element_kind(name)
        declared = registry.kind_of(core, name)
        coordinates = declared.coordinates if declared else ()
        turns, slides = "angle" in coordinates, "slide" in coordinates
        if not (turns or slides):
            raise ModelError(f"{who}: '{name}' is a {kind}, not a revolute, translational or cylindrical joint")
        motion = {}
        for slide, present in ((False, turns), (True, slides)):
            if present:
                motion[slide] = core.joint_motion(name, slide, result.q, result.v, result.a, result._run_state)
        if turns:
            self.angle = _frozen(motion[False][:, 0])
        if slides:
            self.slide = _frozen(motion[True][:, 0])
        first = motion[False] if turns else motion[True]
        self.rate, self.acceleration = _frozen(first[:, 1]), _frozen(first[:, 2])
        if turns and slides:
            self.slide_rate, self.slide_acceleration = _frozen(motion[True][:, 1]), _frozen(motion[True][:, 2])


class ContactPath:
    """What a contact did at each output (Result.contact): normal_force (k,)
    in N (>= 0, on the contact's first body along the normal); friction_force
    (k, 2) in the plane ((k, 3) in space), N, on the first body; point (k, 2)
    the contact point, m; normal (k, 2) the outward normal of the second
    body's surface there; penetration (k,) in m (negative: the gap while
    open); slip_speed (k,) in m/s, the speed of the first body's material
    point over the second's in the tangent plane; state (k,) "open", "slip"
    or "stick" (the planar contact's regularized friction never sticks)."""

    STATES = ("open", "slip", "stick")

    def __init__(self, rows, dimension):
        d = dimension
        self.normal_force = rows[:, 0]
        self.friction_force = rows[:, 1:1 + d]
        self.point = rows[:, 1 + d:1 + 2 * d]
        self.normal = rows[:, 1 + 2 * d:1 + 3 * d]
        self.penetration = rows[:, 1 + 3 * d]
        self.slip_speed = rows[:, 2 + 3 * d]
        self.state = np.array(self.STATES, dtype=object)[rows[:, 3 + 3 * d].astype(int)]

    def __repr__(self):
        touching = int(np.count_nonzero(self.state != "open"))
        return f"<lagmb.ContactPath: {len(self.normal_force)} outputs, in contact at {touching}>"


class Result:
    """States at the output times of a run.

    t (k,), q, v, a (k, n) and lam (k, m) in the sign of docs/modelling.md, 'Equations and signs'.
    events: the events handled during the run (impacts at stops, captures
    and releases of stops, contact switches), in time order, each a dict with
    t, element, kind ("impact", "capture", "release", "restart"), label ("lower", "upper", "onset", ...),
    speed_before and speed_after (the element's g' around the jump).
    a and lam are solved from the augmented system at each output state, so
    M a + Phi_q^T lam = Q holds for exactly the reported q and v. Derived
    quantities (energy, residual, reactions) are computed when first asked.
    A Result pickles (a process pool returns it), with the model as the run
    saw it.
    """

    def __init__(self, model, core_model, raw, snapshot=None):
        self.model = model
        self._core = core_model
        # the model as the run saw it (Model._snapshot; None: model): its
        # frames, and its description when pickled (model may change since)
        self._snapshot = snapshot if snapshot is not None else model
        # read-only: the derived quantities rely on t, q, v, a and lam being
        # the run's own, with one row per output
        self._t, self._q, self._v, self._a, self._lam = (
            _frozen(raw[key]) for key in ("t", "q", "v", "a", "lam"))
        # the input values at each output (k, p): what a Simulator was given,
        # else the initial values; kernels evaluated later read these
        names = [d["name"] for d in core_model.inputs]
        inputs = raw.get("inputs")
        if inputs is None or np.shape(inputs) != (len(self._t), len(names)):
            inputs = np.broadcast_to(np.array([d["initial"] for d in core_model.inputs], dtype=float),
                                     (len(self._t), len(names)))
        self._inputs = _frozen(np.asarray(inputs, dtype=float))
        self._input_names = names
        # the run's element state at each output (k, s): the turns of the
        # spatial joints, which angles read there count (model/joint_turns.hpp);
        # absent (an older pickle): the state a run starts with
        state = raw.get("run_state")
        size = core_model.run_state_size
        if state is None or np.shape(state) != (len(self._t), size):
            state = np.zeros((len(self._t), size))
        self._run_state = _frozen(np.asarray(state, dtype=float))
        self.stats = dict(raw["stats"])  # (its "method": the listed name, set by the core)
        self.events = [dict(e) for e in raw.get("events", [])]
        self.redundant_rows = list(raw.get("dropped_rows", []))
        # forward sensitivities (simulate(..., sensitivities=[...])): (k, count, 2n + m) and (k, count, n)
        self.sensitivity_names = list(raw.get("sensitivity_names", []))
        self._sensitivities = raw.get("sensitivities")
        self._sensitivity_a = raw.get("sensitivity_a")

    def __reduce__(self):
        """Pickled as the run's model (its description as the run saw it:
        it pickles as Model does, a Python time function by pickle's rules),
        the parameter values the run was given and the arrays: the copy
        rebuilds the compiled model and answers every query as this one,
        bit for bit. Its .model is the copy's own model."""
        raw = dict(t=self._t, q=self._q, v=self._v, a=self._a, lam=self._lam, inputs=self._inputs,
                   run_state=self._run_state, stats=self.stats, events=self.events, dropped_rows=self.redundant_rows,
                   sensitivity_names=self.sensitivity_names, sensitivities=self._sensitivities,
                   sensitivity_a=self._sensitivity_a)
        return _unpickled_result, (*core_state(self._snapshot, self._core), raw)

    def __len__(self):
        return len(self._t)

    t = property(lambda self: self._t, doc="(k,) output times (s).")
    q = property(lambda self: self._q, doc="(k, n) coordinates.")
    v = property(lambda self: self._v, doc="(k, n) velocities.")
    a = property(lambda self: self._a, doc="(k, n) accelerations.")

    @property
    def lam(self):
        """(k, m) multipliers. A kinematic-only run (stats["analysis"] ==
        "kinematic") has none: asking raises KinematicOnlyError."""
        if self.stats.get("analysis") == "kinematic":
            raise KinematicOnlyError(
                "this run was a kinematic analysis only (analysis='kinematic'): positions, "
                "velocities and accelerations; the multipliers, reactions and driver efforts "
                "were not computed. Run with analysis='inverse_dynamics' (every mass > 0) for them.")
        return self._lam

    def input(self, name):
        """(k,) the value of an input (``mb.Input``) at each output: what a
        Simulator was given, its initial value in simulate."""
        if not isinstance(name, str):
            name = getattr(name, "name", name)
        if name not in self._input_names:
            listed = ", ".join(repr(n) for n in self._input_names) or "none"
            raise ModelError(f"Result.input: no input called {name!r}; the inputs are {listed}")
        return self._inputs[:, self._input_names.index(name)]

    def _name(self, item, accepts, what, context):
        return element_name(self.model, self._core, item, accepts, what, context)

    def body(self, body):
        """Motion of a body (handle or name): .position, .angle, ... In a
        spatial model also of a frame by its name (Model.add_frame: a link
        load_urdf merged into another's body): a FramePath."""
        frame = self._frame(body)
        if frame is not None:
            return FramePath(None if frame.body == "ground" else self.body(frame.body), frame, len(self.t))
        first, count = self._core.body_coordinates(self._name(body, ("body",), "body", "Result.body"))
        return BodyPath(self, first, count)

    def _frame(self, name):
        frames = getattr(self._snapshot, "_frames", {})
        return frames.get(name) if isinstance(name, str) else None

    def point(self, body, local_point):
        """(k, 2) global path of a point given in the body's own axes ((k, 3)
        in a spatial model)."""
        b = self.body(body)
        size = getattr(self.model, "dimension", 2)
        try:
            s = np.asarray(local_point, dtype=float).reshape(size)
        except (TypeError, ValueError, OverflowError):
            words = "a pair of numbers" if size == 2 else "three numbers (x, y, z)"
            raise ModelError(f"local_point must be {words}, got {local_point!r}") from None
        if not np.all(np.isfinite(s)):
            raise ModelError(f"local_point must be finite, got {local_point!r}")
        if size == 3:
            if not hasattr(b, "rotation"):  # the ground
                return np.tile(s, (len(self), 1))
            # (a frame's path: its origin and axes)
            return b.position + np.einsum("kij,j->ki", b.rotation, s)
        c, sn = np.cos(b.angle), np.sin(b.angle)
        return b.position + np.column_stack((c * s[0] - sn * s[1], sn * s[0] + c * s[1]))

    def joint(self, joint):
        """The coordinate of a revolute, translational or cylindrical joint
        (handle or name) at each output: a JointPath (.angle or .slide,
        .rate, .acceleration)."""
        return JointPath(self, self._name(joint, ("joint",), "joint", "Result.joint"))

    def multipliers(self, element):
        """(k, rows) columns of lam that belong to a joint or driver."""
        name = self._name(element, _CONSTRAINTS, "element", "Result.multipliers")
        row0, rows = self._core.constraint_rows(name)
        return self.lam[:, row0:row0 + rows]

    def reaction(self, element, frame="global", about="centre of mass"):
        """(k, 3): force (x, y) in N on the element's second body, and the
        torque in N m about that body's centre of mass, from the element.
        frame="joint": the force in the element's own axes (docs/modelling.md).
        In a spatial model (k, 6): force (x, y, z) and torque (x, y, z), both
        in the element's axes with frame="joint".

        ``about``: the point the torque is taken about. "centre of mass"
        (or "center of mass"; the default): the second body's centre of
        mass, M_G. "joint": the joint's own point on the second body (a
        revolute's pin, a spherical's or universal's centre, a
        translational's ``at``, a distance's end on body_j; a weld's is
        body_j's centre of mass), where Adams and Inventor report a
        joint's moment: M_P = M_G + (r_G - r_P) x F with r_G the centre of
        mass and r_P that point (the same F; with frame="joint" in the
        joint's axes too). A door on a hinge reads 0 about its centre of
        mass and its weight's couple m g d about the hinge. Drivers,
        stops, gears and couplings have no point of their own: ModelError."""
        if frame not in ("global", "joint"):
            raise ModelError(f"frame must be 'global' or 'joint', got {frame!r}")
        about_joint = reaction_about(about)
        name = self._name(element, _CONSTRAINTS, "element", "Result.reaction")
        kind = registry.kind_of(self._core, name)
        if kind is not None and kind.role == "contact":
            raise ModelError(f"Result.reaction: '{name}' is a contact, not a joint or driver: its forces are "
                             f"Result.contact('{name}')")
        return self._core.reaction(name, self.t, self.q, self.lam, frame == "joint", self._inputs,
                                   self._run_state, about_joint)

    def effort(self, element):
        """What a driver, stop, force element or joint friction applies at
        each output, as its kind says (``lagmb info --kinds``: the line
        "r.effort(name)" of each kind; ``registry.BY_NAME[kind].effort``):

        - a driver: (k,) the force (N) or torque (N m) along what it
          drives, imposing its motion, positive along the coordinate
          (-lam of its row);
        - a stop: (k,) the force or torque along the joint's coordinate
          while the joint rests on a limit, 0 while it is off its limits
          (its rows are the gaps s - lower and upper - s, whose multipliers
          push with -lam along +g: lam_upper - lam_lower);
        - a servo: (k,) its torque about the joint's axis (N m) or force
          along its slide (N) on the joint's second body, as applied: after
          the clamp to its limit;
        - a spring-damper: (k,) its force F (N) along the line, positive
          pushing the points apart, -k (l - l0) - c l' + f(t); a
          rotational one: (k,) its torque (N m) on body_j;
        - a bushing: (k, 6) the force on body_j along the axes of its frame
          in body_i (N) and the torque about them (N m);
        - an applied force: (k, 2) or (k, 3) its vector in global axes as
          applied (a local one turned with its body; inputs at their values
          in the run); an applied torque: (k,) in the plane, (k, 3) in
          space;
        - a joint friction: (k,) its torque (N m) or force (N) on the
          joint's second body (as :meth:`friction`).

        A driver's, stop's and a planar joint friction's come from the
        multipliers (a kinematic analysis has none: KinematicOnlyError);
        a force element's from the states and inputs. A joint has none
        (its force is :meth:`reaction`), nor a contact (:meth:`contact`)."""
        name = self._name(element, EXERTING, "element", "Result.effort")
        rows = efforts(self._core, name, "Result.effort", self.t, self.q, self.v, lambda: self.lam, self._inputs,
                       self._run_state)
        return self._finite(rows, f"the effort of '{name}'")

    def contact(self, element):
        """What the contact `element` did at each output (a ContactPath:
        normal_force, friction_force, point, normal, penetration, slip_speed,
        state), from the run's own states and the impact speed each onset
        recorded (docs/modelling.md, "Contact")."""
        name = self._name(element, ("contact",), "contact", "Result.contact")
        rows = self._core.contact(name, self.t, self.q, self.v, self._run_state, self._lam)
        return ContactPath(self._finite(rows, f"contact '{name}'"), self.model.dimension)

    def friction(self, element):
        """(k,) the friction torque (N m) or force (N) of a joint friction on
        the joint's second body (docs/modelling.md, "Joint friction"),
        evaluated from the run's own states and reactions."""
        name = self._name(element, ("friction",), "element", "Result.friction")
        return self._core.friction(name, self.q, self.v, self.lam)[:, 0]

    def friction_power(self, element):
        """(k,) power (W, <= 0) of a joint friction: its torque or force
        times the joint's relative rate. Its time integral is the work
        friction did, the energy it took out of the system."""
        name = self._name(element, ("friction",), "element", "Result.friction_power")
        f = self._core.friction(name, self.q, self.v, self.lam)
        return f[:, 0] * f[:, 1]

    @cached_property
    def energy(self):
        """(k,) kinetic + potential energy (J) of the conservative forces.
        SimulationError if it overflows double precision (e.g. a body 1e308 m
        up under gravity), rather than an inf or a NaN."""
        return self._finite(self._core.energy(self.t, self.q, self.v, self._inputs, self._run_state), "the energy")

    @cached_property
    def residual(self):
        """(k,) max |Phi| (position-level constraint violation)."""
        return self._finite(self._core.residual(self.t, self.q, self._inputs, self._run_state), "the constraint residual")

    @cached_property
    def velocity_residual(self):
        """(k,) max ``|Phi_q v + Phi_t|`` (velocity-level constraint violation)."""
        return self._finite(self._core.velocity_residual(self.t, self.q, self.v, self._inputs, self._run_state),
                            "the velocity residual")

    def sensitivity(self, parameter):
        """The derivative of this run with respect to a parameter it was
        run with ``sensitivities=[...]`` for: a :class:`Sensitivity`, whose
        ``q``, ``v``, ``a``, ``lam`` and accessors (``body``, ``point``,
        ``reaction``, ...) are d/dp of this Result's. ModelError for a name
        the run has no sensitivity to (naming those it has)."""
        if parameter not in self.sensitivity_names:
            have = ", ".join(repr(n) for n in self.sensitivity_names)
            raise ModelError(f"Result.sensitivity: this run has no sensitivity to {parameter!r}; "
                             + (f"it has {have}" if have else "run simulate(..., sensitivities=[...]) for them"))
        return Sensitivity(self, self.sensitivity_names.index(parameter), parameter)

    def save(self, path, *, reactions=None, efforts=None, frame="global", energy=False):
        """Writes the run to ``path`` as ``lagmb run -o`` does, by its suffix
        (missing folders are made):

        - .npz (numpy.savez): arrays t, q, v, a, energy, residual,
          coordinates (their names, :meth:`Model.coordinate_names`), lam
          (not for a kinematic analysis), ``reaction_NAME`` (k, 3) or (k,
          6) per joint or driver in ``reactions`` (default: every joint)
          and ``effort_NAME`` per element in ``efforts`` (drivers, stops,
          force elements, joint friction: :meth:`effort`; default: every
          driver);
        - .csv: a header row, then one row per output time: t, the
          coordinates, per element in ``reactions`` NAME.fx, NAME.fy,
          NAME.torque (NAME.f1, NAME.f2 with frame="joint"), per element in
          ``efforts`` NAME.effort (NAME.effort.x, ... for one of several
          components; default: none of either), and the energy
          with ``energy=True``; floats as repr, so they read back exactly.

        ``frame``: the reactions' frame, as :meth:`reaction` takes it. A
        kinematic analysis has no reactions or efforts (none by default;
        asking is its KinematicOnlyError). Another suffix is a ModelError."""
        path = os.fspath(path)
        problem = results_format_problem(path)
        if problem:
            raise ModelError(f"Result.save: {path}: {problem}")
        npz = path.lower().endswith(".npz")
        kinematic = self.stats.get("analysis") == "kinematic"
        if reactions is None:
            reactions = self._names_of("joint") if npz and not kinematic else []
        if efforts is None:
            efforts = self._names_of("driver") if npz and not kinematic else []
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        if npz:
            arrays = dict(t=self.t, q=self.q, v=self.v, a=self.a, energy=self.energy, residual=self.residual,
                          coordinates=np.array(self.model.coordinate_names))
            if not kinematic:
                arrays["lam"] = self.lam
            for name in reactions:
                arrays[f"reaction_{name}"] = self.reaction(name, frame=frame)
            for name in efforts:
                arrays[f"effort_{name}"] = self.effort(name)
            with open(path, "wb") as fh:
                np.savez(fh, **arrays)
            return
        columns = ["t"] + self.model.coordinate_names
        blocks = [self.t[:, None], self.q]
        force = ("f1", "f2") if frame == "joint" else ("fx", "fy")
        for name in reactions:
            columns += [f"{name}.{force[0]}", f"{name}.{force[1]}", f"{name}.torque"]
            blocks.append(self.reaction(name, frame=frame))
        for name in efforts:
            effort = np.asarray(self.effort(name))
            if effort.ndim == 1:
                columns.append(f"{name}.effort")
            else:  # (an applied force's components, a bushing's six)
                columns += [f"{name}.effort.{c}" for c in registry.kind_of(self._core, str(name)).effort_components]
            blocks.append(effort.reshape(len(self.t), -1))
        if energy:
            columns.append("energy")
            blocks.append(self.energy[:, None])
        data = np.hstack([np.asarray(b, dtype=float).reshape(len(self.t), -1) for b in blocks])
        with open(path, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(columns)
            w.writerows(data.tolist())  # floats as repr: they read back exactly

    def _names_of(self, role):
        """The names of the run's elements of a role ("joint", "driver"), in the order added."""
        kinds = BY_METHOD if self.model.dimension == 2 else SPATIAL_BY_METHOD
        return [given["name"] for method, given in self.model.elements if kinds[method].role == role]

    def _finite(self, values, what):
        """values, read-only, if all are finite; else SimulationError naming
        the first output where they overflow (the states themselves are finite)."""
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            t = float(self.t[bad[0]])
            raise SimulationError(f"{what} is not finite at t = {t:g} s (it overflows double precision for "
                                  f"this model's magnitudes: largest |q| {np.max(np.abs(self.q)):.3g})", t)
        return _frozen(values)

    def __repr__(self):
        return (f"<lagmb.Result: {len(self.t)} outputs, t = {self.t[0]:g}..{self.t[-1]:g} s, "
                f"{self.stats.get('steps', 0)} steps>")


def _unpickled_result(model, parameters, raw):
    return Result(model, rebuilt_core(model, parameters), raw)


def _difference(plus, minus, scale):
    """(plus - minus) * scale for arrays, attribute by attribute for paths
    (BodyPath, JointPath, FramePath)."""
    if isinstance(plus, np.ndarray) or np.isscalar(plus):
        return (np.asarray(plus, dtype=float) - np.asarray(minus, dtype=float)) * scale
    out = _Derivative()
    for key, value in vars(plus).items():
        if isinstance(value, np.ndarray):
            setattr(out, key, _frozen((value - getattr(minus, key)) * scale))
    return out


def _sum(a, b):
    if isinstance(a, np.ndarray):
        return _frozen(a + b)
    out = _Derivative()
    for key, value in vars(a).items():
        setattr(out, key, _frozen(value + getattr(b, key)))
    return out


class _Derivative:
    """The derivative of a path (BodyPath, JointPath, FramePath): the same
    attributes, each d/dp of the path's."""

    def __repr__(self):
        return f"<lagmb derivative of a path: {', '.join(sorted(vars(self)))}>"


class Sensitivity:
    """The derivative of a run with respect to one parameter p
    (``Result.sensitivity(name)``, from ``simulate(..., sensitivities=[...])``).

    - ``parameter``: its name; ``value``: p in the run.
    - ``q``, ``v``, ``a`` (k, n) and ``lam`` (k, m): dq/dp, dv/dp, da/dp and
      dlam/dp at the outputs, integrated by IDAS beside the run (a is the
      derivative of dv/dp; lam is the run's GGL multiplier, equal to the
      Result's to the integration tolerance).
    - ``body(b)``, ``point(b, local_point)``, ``joint(j)``,
      ``multipliers(e)``, ``reaction(e, frame)``, ``effort(d)``, ``energy``:
      d/dp of the Result's: for a quantity f(q, v, a, lam; p), the total
      derivative f_y s + f_p, its first part by a central difference along
      the sensitivity s (f is smooth in the state: a relative step of 1e-6,
      error about 1e-10 relative) and f_p (a reaction's geometry, a spring's
      energy) by a central difference between the models at p +- 1e-6 abs(p)
      evaluated at the run's states (one-sided at a bound of p's range: a
      damping of 0).
    """

    def __init__(self, result, index, parameter):
        self._result = result
        self.parameter = parameter
        values = {p["name"]: p["value"] for p in result._core.parameters}
        self.value = float(values[parameter])
        n, m = result.q.shape[1], result._lam.shape[1]
        k = len(result.t)
        s = np.asarray(result._sensitivities)[:k, index]
        self.q = _frozen(s[:, :n])
        self.v = _frozen(s[:, n:2 * n])
        self.lam = _frozen(s[:, 2 * n:2 * n + m])
        self.a = _frozen(np.asarray(result._sensitivity_a)[:k, index])
        self._along = None

    def _results(self):
        """The Results moved by +- h along the sensitivity (the model of the
        run), the step h, and the Results of the run's states under the
        models at p + delta and p - delta, and the distance between them:
        2 delta, or delta where p is at a bound of its range (a damping of
        0), which takes the model at p itself for the side beyond it."""
        if self._along is None:
            r = self._result
            pairs = [(r.q, self.q), (r.v, self.v), (r.a, self.a), (r._lam, self.lam)]
            h = min((1.0 + np.abs(x).max(initial=0.0)) / np.abs(sx).max()
                    for x, sx in pairs if sx.size and np.abs(sx).max() > 0) if any(
                sx.size and np.abs(sx).max() > 0 for _, sx in pairs) else 1.0
            h *= 1e-6

            def raw(sign, core=None):
                return dict(t=r.t, q=r.q + sign * h * self.q, v=r.v + sign * h * self.v,
                            a=r.a + sign * h * self.a, lam=r._lam + sign * h * self.lam, inputs=r._inputs,
                            run_state=r._run_state, stats=r.stats, dropped_rows=r.redundant_rows)

            along = [Result(r.model, r._core, raw(sign), r._snapshot) for sign in (1.0, -1.0)]
            delta = 1e-6 * (abs(self.value) if self.value != 0.0 else 1.0)
            cores, span, refused = [], 0.0, []
            for sign in (1.0, -1.0):
                try:
                    cores.append(r._core.with_parameters({self.parameter: self.value + sign * delta}))
                    span += delta
                except ModelError as e:  # beyond a bound: the model at p itself on this side
                    cores.append(r._core)
                    refused.append(str(e))
            if span == 0.0:
                raise ModelError(f"Sensitivity: {self.parameter!r} = {self.value:g} allows no nearby value to "
                                 f"differentiate by: {'; '.join(refused)}")
            at_p = [Result(r.model, core, raw(0.0), r._snapshot) for core in cores]
            self._along = (along, h, at_p, span)
        return self._along

    def _derivative(self, ask):
        along, h, at_p, span = self._results()
        return _sum(_difference(ask(along[0]), ask(along[1]), 0.5 / h),
                    _difference(ask(at_p[0]), ask(at_p[1]), 1.0 / span))

    def body(self, body):
        """d/dp of ``Result.body(body)``: its attributes' derivatives."""
        return self._derivative(lambda r: r.body(body))

    def point(self, body, local_point):
        """d/dp of ``Result.point(body, local_point)``."""
        return self._derivative(lambda r: r.point(body, local_point))

    def joint(self, joint):
        """d/dp of ``Result.joint(joint)``."""
        return self._derivative(lambda r: r.joint(joint))

    def multipliers(self, element):
        """d/dp of ``Result.multipliers(element)``."""
        return self._derivative(lambda r: r.multipliers(element))

    def reaction(self, element, frame="global", about="centre of mass"):
        """d/dp of ``Result.reaction(element, frame, about)``."""
        return self._derivative(lambda r: r.reaction(element, frame, about))

    def effort(self, element):
        """d/dp of ``Result.effort(element)``."""
        return self._derivative(lambda r: r.effort(element))

    @property
    def energy(self):
        """d/dp of ``Result.energy``."""
        return self._derivative(lambda r: r.energy)

    def __repr__(self):
        return f"<lagmb.Sensitivity to {self.parameter} = {self.value:g}: {len(self.q)} outputs>"


def translated_run(model=None, core=None, snapshot=None):
    """errors.translated for a run of `model` (compiled: `core`; as the
    run saw it: `snapshot`): a failed run's partial outputs as a Result on
    the exception (simulate, Simulator, equilibrium, solve_accelerations)."""
    def partial_result(raw):
        partial = Result(model, core, raw, snapshot)
        return partial if len(partial.t) else None

    return translated(partial_result if model is not None else None)
