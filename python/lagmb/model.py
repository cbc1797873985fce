"""Building a mechanism: bodies, joints, gravity (docs/design.md, section 2.7)."""

import math
import numbers

from . import _core
from ._checks import real as _number, vec2 as _vec2
from .errors import ModelError
from .functions import TimeFunction, as_time_function
from .handles import KINDS, Body, Handle, name_of


def _tuple(x):
    return (float(x[0]), float(x[1]))


class Model:
    """A planar mechanism: rigid bodies, particles and the elements between them.

    Coordinates are Cartesian: (x, y, phi) of each body's centre of mass and
    angle, (x, y) of each particle. Points are global, in the initial
    configuration, unless the argument name says ``local``. Every body and
    element has a unique name. Gravity is absent unless given.

    Every add_* and drive_* method returns the handle of what it added
    (mb.Handle; mb.Body for bodies and particles, ``ground`` for the
    ground). A handle prints as its name and goes wherever the name does:
    ``pin = m.add_revolute("pin", ...); m.add_stop("limit", pin, ...);
    r.reaction(pin)``.
    """

    def __init__(self, gravity=None):
        self._calls = []  # the core calls, replayed when the model changes after a run
        self._core = _core.Model()
        self._bodies = {}
        self._elements = []  # (method, kwargs) in user terms: see elements()
        self._pose = {"ground": (0.0, 0.0, 0.0)}  # initial (x, y, angle) of each body
        self._outline = {}  # body name -> local attachment points
        self.ground = Body("ground", self, -1)
        self.gravity = None
        if gravity is not None:
            g = _vec2(gravity, "gravity")
            self._call("set_gravity", g)
            self.gravity = (float(g[0]), float(g[1]))

    # --- building --------------------------------------------------------

    def _call(self, method, *args):
        if self._core.finalized:
            # the compiled model is frozen: start a new one with the same elements
            core = _core.Model()
            for m, a in self._calls:
                getattr(core, m)(*a)
            self._core = core
        getattr(self._core, method)(*args)  # validates; raises ModelError
        self._calls.append((method, args))

    def _body(self, body, what, context):
        """(name, index) of a body given by its handle or name (index -1:
        the ground); ``what`` is the argument, ``context`` the element."""
        name = name_of(self, body, ("body",), what, context)
        if name == "ground":
            return name, -1
        if name not in self._bodies:
            raise ModelError(f"{context}: {what}: no body named '{name}'")
        return name, self._bodies[name].index

    def _joint(self, joint, context):
        """The name of a joint given by its handle or name (the core checks
        that a name is a joint of the right kind)."""
        return name_of(self, joint, ("joint",), "joint", context)

    def _name(self, name):
        if not isinstance(name, str):
            raise ModelError(f"names must be strings, got {name!r}")
        return name

    def _record(self, method, **kwargs):
        """Remember an element added (see elements()) and return its handle."""
        self._elements.append((method, kwargs))
        name = kwargs["name"]
        kind, role = KINDS[method]
        return self._bodies[name] if role == "body" else Handle(name, self, kind, role)

    def _local(self, body_name, point):
        """A global point of the initial configuration in the body's axes."""
        x, y, a = self._pose[body_name]
        dx, dy = point[0] - x, point[1] - y
        c, s = math.cos(a), math.sin(a)
        return (c * dx + s * dy, -s * dx + c * dy)

    def _attach(self, body_name, local_point):
        if body_name == "ground":
            return
        pts = self._outline.setdefault(body_name, [])
        p = (float(local_point[0]), float(local_point[1]))
        if all(abs(p[0] - u) + abs(p[1] - v) > 1e-12 for u, v in pts):
            pts.append(p)

    def add_body(self, name, mass, inertia, position=(0.0, 0.0), angle=0.0,
                 velocity=(0.0, 0.0), angular_velocity=0.0):
        """Add a rigid body: mass (kg), centroidal inertia (kg m^2), initial
        position of its centre of mass (m), angle (rad), velocity (m/s) and
        angular velocity (rad/s). Returns its handle."""
        name = self._name(name)
        what = f"body '{name}'"
        args = (_number(mass, f"{what}: mass"), _number(inertia, f"{what}: inertia"),
                _vec2(position, f"{what}: position"), _number(angle, f"{what}: angle"),
                _vec2(velocity, f"{what}: velocity"),
                _number(angular_velocity, f"{what}: angular_velocity"))
        self._call("add_body", name, *args)
        self._bodies[name] = Body(name, self, len(self._bodies))
        self._pose[name] = (float(args[2][0]), float(args[2][1]), args[3])
        self._record("add_body", name=name, mass=args[0], inertia=args[1], position=_tuple(args[2]),
                     angle=args[3], velocity=_tuple(args[4]), angular_velocity=args[5])
        return self._bodies[name]

    def add_particle(self, name, mass, position, velocity=(0.0, 0.0)):
        """Add a point mass with two coordinates (x, y). Returns its handle."""
        name = self._name(name)
        what = f"particle '{name}'"
        mass, position = _number(mass, f"{what}: mass"), _vec2(position, f"{what}: position")
        velocity = _vec2(velocity, f"{what}: velocity")
        self._call("add_particle", name, mass, position, velocity)
        self._bodies[name] = Body(name, self, len(self._bodies), "particle")
        self._pose[name] = (float(position[0]), float(position[1]), 0.0)
        self._record("add_particle", name=name, mass=mass, position=_tuple(position),
                     velocity=_tuple(velocity))
        return self._bodies[name]

    def add_revolute(self, name, body_i, body_j, at=None, *, local_i=None, local_j=None):
        """Pin body_i and body_j together at the global point ``at`` (in the
        initial configuration), or at ``local_i`` on body_i and ``local_j`` on
        body_j (each in its body's own axes)."""
        name = self._name(name)
        what = f"revolute '{name}'"
        bi, i = self._body(body_i, "body_i", what)
        bj, j = self._body(body_j, "body_j", what)
        if at is not None:
            if local_i is not None or local_j is not None:
                raise ModelError(f"{what}: give either 'at' or 'local_i' and 'local_j'")
            at = _vec2(at, f"{what}: at")
            self._call("add_revolute", name, i, j, at)
            handle = self._record("add_revolute", name=name, body_i=bi, body_j=bj, at=_tuple(at))
            self._attach(bi, self._local(bi, at))
            self._attach(bj, self._local(bj, at))
        elif local_i is not None and local_j is not None:
            li = _vec2(local_i, f"{what}: local_i")
            lj = _vec2(local_j, f"{what}: local_j")
            self._call("add_revolute_local", name, i, j, li, lj)
            handle = self._record("add_revolute", name=name, body_i=bi, body_j=bj, local_i=_tuple(li),
                                  local_j=_tuple(lj))
            self._attach(bi, li)
            self._attach(bj, lj)
        else:
            raise ModelError(f"{what}: give the joint point 'at' (global) "
                             "or both 'local_i' and 'local_j'")
        return handle

    def add_translational(self, name, body_i, body_j, at, axis):
        """body_j slides relative to body_i along the line through ``at`` with
        direction ``axis`` (global, initial configuration), without rotating."""
        return self._line_joint("add_translational", "translational", name, body_i, body_j, at, axis)

    def add_weld(self, name, body_i, body_j):
        """Fix body_j to body_i in their initial relative pose."""
        name = self._name(name)
        what = f"weld '{name}'"
        (bi, i), (bj, j) = self._body(body_i, "body_i", what), self._body(body_j, "body_j", what)
        self._call("add_weld", name, i, j)
        handle = self._record("add_weld", name=name, body_i=bi, body_j=bj)
        self._attach(bi, self._local(bi, self._pose[bj][:2]))
        return handle

    def add_distance(self, name, body_i, point_i, body_j, point_j, length=None):
        """A massless rigid link of ``length`` (default: the initial distance)
        between point_i of body_i and point_j of body_j."""
        name = self._name(name)
        what = f"distance '{name}'"
        (bi, i), (bj, j) = self._body(body_i, "body_i", what), self._body(body_j, "body_j", what)
        pi, pj = _vec2(point_i, f"{what}: point_i"), _vec2(point_j, f"{what}: point_j")
        length = None if length is None else _number(length, f"{what}: length")
        self._call("add_distance", name, i, pi, j, pj, length)
        handle = self._record("add_distance", name=name, body_i=bi, point_i=_tuple(pi), body_j=bj,
                              point_j=_tuple(pj), length=length)
        self._attach(bi, self._local(bi, pi))
        self._attach(bj, self._local(bj, pj))
        return handle

    def add_pin_in_slot(self, name, body_i, body_j, at, axis):
        """The pin of body_j at ``at`` moves along the slot of body_i through
        ``at`` in direction ``axis``; rotation is free."""
        return self._line_joint("add_pin_in_slot", "pin_in_slot", name, body_i, body_j, at, axis)

    def _line_joint(self, method, kind, name, body_i, body_j, at, axis):
        name = self._name(name)
        what = f"{kind} '{name}'"
        (bi, i), (bj, j) = self._body(body_i, "body_i", what), self._body(body_j, "body_j", what)
        at, axis = _vec2(at, f"{what}: at"), _vec2(axis, f"{what}: axis")
        self._call(method, name, i, j, at, axis)
        handle = self._record(method, name=name, body_i=bi, body_j=bj, at=_tuple(at), axis=_tuple(axis))
        self._attach(bi, self._local(bi, at))
        self._attach(bj, self._local(bj, at))
        return handle

    def add_gear(self, name, body_i, body_j, ratio, center_i=None, center_j=None):
        """Gear pair with omega_j / omega_i = ratio while the centres stay put
        (negative: external, positive: internal). Centres default to the
        bodies' centres of mass; a gear on the ground needs its centre."""
        name = self._name(name)
        what = f"gear '{name}'"
        (bi, i), (bj, j) = self._body(body_i, "body_i", what), self._body(body_j, "body_j", what)
        ratio = _number(ratio, f"{what}: ratio")
        ci = None if center_i is None else _vec2(center_i, f"{what}: center_i")
        cj = None if center_j is None else _vec2(center_j, f"{what}: center_j")
        self._call("add_gear", name, i, j, ratio, ci, cj)
        return self._record("add_gear", name=name, body_i=bi, body_j=bj, ratio=ratio,
                            center_i=None if ci is None else _tuple(ci),
                            center_j=None if cj is None else _tuple(cj))

    def add_rack_pinion(self, name, pinion, rack, radius, axis):
        """The pinion (centre at its centre of mass, pitch ``radius``) rolls
        on the rack's pitch line along ``axis``; the pinion is on the left
        of the axis (axis turned +90 deg points from the rack to it)."""
        name = self._name(name)
        what = f"rack_pinion '{name}'"
        (bp, p), (br, r) = self._body(pinion, "pinion", what), self._body(rack, "rack", what)
        radius = _number(radius, f"{what}: radius")
        axis = _vec2(axis, f"{what}: axis")
        self._call("add_rack_pinion", name, p, r, radius, axis)
        return self._record("add_rack_pinion", name=name, pinion=bp, rack=br, radius=radius,
                            axis=_tuple(axis))

    # --- drivers ---------------------------------------------------------

    def drive_joint(self, name, joint, f):
        """Prescribe a revolute's relative angle phi_j - phi_i, or a
        translational's slide (0 in the initial configuration), as f(t):
        a number, a time function or a callable t -> (y, dy, ddy).
        ``joint``: the joint's handle or name."""
        name = self._name(name)
        what = f"driver '{name}'"
        joint = self._joint(joint, what)
        self._call("drive_joint", name, joint, as_time_function(f, what))
        return self._record("drive_joint", name=name, joint=joint, f=f)

    def drive_body(self, name, body, coordinate, f):
        """Prescribe a body's "x", "y" or "angle" as f(t)."""
        name = self._name(name)
        what = f"driver '{name}'"
        b, index = self._body(body, "body", what)
        if coordinate not in ("x", "y", "angle"):
            raise ModelError(f"{what}: coordinate must be 'x', 'y' or 'angle', got {coordinate!r}")
        self._call("drive_body", name, index, coordinate, as_time_function(f, what))
        return self._record("drive_body", name=name, body=b, coordinate=coordinate, f=f)

    # --- stops (joint limits with impacts) --------------------------------

    def add_stop(self, name, joint, lower=None, upper=None, restitution=0.0, rest_speed=1e-3):
        """Limit a joint coordinate s to lower <= s <= upper (either may be
        None): a revolute's relative angle phi_j - phi_i (rad) or a
        translational's slide displacement (m, 0 in the initial
        configuration), as for drive_joint; ``joint``: its handle or name.
        Reaching a limit with approaching
        speed is an impact: the relative velocity along s reverses with
        Newton's ``restitution`` e in [0, 1] (s'+ = -e s'-), the joints are
        kept, and the integrator restarts. A rebound slower than
        ``rest_speed`` (rad/s or m/s) while the motion presses on the limit
        stops the run with SimulationError naming the stop (resting contact
        is not modelled). Impacts are listed in ``Result.events``."""
        name = self._name(name)
        what = f"stop '{name}'"
        joint = self._joint(joint, what)
        lo = None if lower is None else _number(lower, f"{what}: lower")
        up = None if upper is None else _number(upper, f"{what}: upper")
        e = _number(restitution, f"{what}: restitution")
        vr = _number(rest_speed, f"{what}: rest_speed")
        self._call("add_stop", name, joint, lo, up, e, vr)
        return self._record("add_stop", name=name, joint=joint, lower=lo, upper=up, restitution=e,
                            rest_speed=vr)

    # --- contact -----------------------------------------------------------

    def add_contact(self, name, circle_body, center, radius, line_body, point, direction, stiffness,
                    restitution, friction=0.0, slip_velocity=1e-4):
        """Contact between a circle on ``circle_body`` (``center``, global in
        the initial configuration, and ``radius``, m) and the line through
        ``point`` along ``direction`` on ``line_body`` (or the ground); the
        circle belongs on the left of the direction (direction turned +90 deg
        points to it). With penetration d > 0 the normal force is
        k d^1.5 (1 + 8 (1 - e) / (5 e) d' / v_impact) (Hunt-Crossley damping
        calibrated to the restitution e in (0, 1], Flores et al. 2011;
        ``stiffness`` k in N/m^1.5), v_impact the approach speed at contact
        onset; Coulomb friction -mu F_n v_t / sqrt(v_t^2 + v_s^2) with
        ``friction`` mu and the ``slip_velocity`` v_s (m/s) below which it is
        smoothed. Onset and release are events (r.events) where the
        integrator restarts."""
        name = self._name(name)
        what = f"contact '{name}'"
        bc, ic = self._body(circle_body, "circle_body", what)
        bl, il = self._body(line_body, "line_body", what)
        c = _vec2(center, f"{what}: center")
        p = _vec2(point, f"{what}: point")
        u = _vec2(direction, f"{what}: direction")
        args = [_number(x, f"{what}: {label}") for x, label in
                ((radius, "radius"), (stiffness, "stiffness"), (restitution, "restitution"),
                 (friction, "friction"), (slip_velocity, "slip_velocity"))]
        R, k, e, mu, vs = args
        self._call("add_contact", name, ic, c, R, il, p, u, k, e, mu, vs)
        handle = self._record("add_contact", name=name, circle_body=bc, center=_tuple(c), radius=R,
                              line_body=bl, point=_tuple(p), direction=_tuple(u), stiffness=k,
                              restitution=e, friction=mu, slip_velocity=vs)
        self._attach(bc, self._local(bc, c))
        return handle

    # --- forces ----------------------------------------------------------

    def add_spring_damper(self, name, body_i, point_i, body_j, point_j, stiffness=0.0, damping=0.0,
                          free_length=None, force=None):
        """Spring (N/m), damper (N s/m) and actuator ``force`` (N, positive
        pushes the points apart; number, time function or callable t -> F)
        between point_i of body_i and point_j of body_j."""
        name = self._name(name)
        what = f"spring_damper '{name}'"
        (bi, i), (bj, j) = self._body(body_i, "body_i", what), self._body(body_j, "body_j", what)
        pi, pj = _vec2(point_i, f"{what}: point_i"), _vec2(point_j, f"{what}: point_j")
        k, c = _number(stiffness, f"{what}: stiffness"), _number(damping, f"{what}: damping")
        l0 = None if free_length is None else _number(free_length, f"{what}: free_length")
        act = None if force is None else as_time_function(force, what, derivatives=False)
        self._call("add_spring_damper", name, i, pi, j, pj, k, c, l0, act)
        handle = self._record("add_spring_damper", name=name, body_i=bi, point_i=_tuple(pi), body_j=bj,
                              point_j=_tuple(pj), stiffness=k, damping=c, free_length=l0, force=force)
        self._attach(bi, self._local(bi, pi))
        self._attach(bj, self._local(bj, pj))
        return handle

    def add_rotational_spring_damper(self, name, body_i, body_j, stiffness=0.0, damping=0.0,
                                     free_angle=None, torque=None):
        """Torsion spring (N m/rad), damper (N m s/rad) and actuator
        ``torque`` (N m, on body_j; body_i gets the opposite)."""
        name = self._name(name)
        what = f"rotational_spring_damper '{name}'"
        (bi, i), (bj, j) = self._body(body_i, "body_i", what), self._body(body_j, "body_j", what)
        k, c = _number(stiffness, f"{what}: stiffness"), _number(damping, f"{what}: damping")
        a0 = None if free_angle is None else _number(free_angle, f"{what}: free_angle")
        act = None if torque is None else as_time_function(torque, what, derivatives=False)
        self._call("add_rotational_spring_damper", name, i, j, k, c, a0, act)
        return self._record("add_rotational_spring_damper", name=name, body_i=bi, body_j=bj,
                            stiffness=k, damping=c, free_angle=a0, torque=torque)

    def add_force(self, name, body, force, point=None, local=False):
        """A force on a body: ``force`` = (fx, fy) of numbers or time
        functions, or a callable t -> (fx, fy); at ``point`` (global,
        initial; default: the centre of mass); ``local``: components in the
        body's axes, turning with it."""
        name = self._name(name)
        what = f"force '{name}'"
        b, index = self._body(body, "body", what)
        if callable(force) and not isinstance(force, TimeFunction):
            fx = as_time_function(force, what, derivatives=False, component=0)
            fy = as_time_function(force, what, derivatives=False, component=1)
        else:
            if isinstance(force, (str, bytes)) or not hasattr(force, "__len__") or len(force) != 2:
                raise ModelError(f"{what}: force must be (fx, fy) or a callable t -> (fx, fy), got {force!r}")
            fx = as_time_function(force[0], f"{what}: fx", derivatives=False)
            fy = as_time_function(force[1], f"{what}: fy", derivatives=False)
            force = tuple(float(f) if isinstance(f, numbers.Real) else f for f in force)
        p = None if point is None else _vec2(point, f"{what}: point")
        self._call("add_force", name, index, fx, fy, p, bool(local))
        handle = self._record("add_force", name=name, body=b, force=force,
                              point=None if p is None else _tuple(p), local=bool(local))
        if p is not None:
            self._attach(b, self._local(b, p))
        return handle

    def add_torque(self, name, body, torque):
        """A pure torque (N m) on a body: number, time function or callable t -> tau."""
        name = self._name(name)
        what = f"torque '{name}'"
        b, index = self._body(body, "body", what)
        tau = as_time_function(torque, what, derivatives=False)
        self._call("add_torque", name, index, tau)
        return self._record("add_torque", name=name, body=b, torque=torque)

    def add_joint_friction(self, name, joint, mu=0.0, viscous=0.0, pin_radius=None,
                           bearing_length=None, preload=0.0, slip_velocity=1e-3,
                           load_smoothing=1e-6):
        """Friction in a revolute or translational joint (``joint``: its
        handle or name; docs/modelling.md, "Joint friction"): Coulomb with
        the load taken from the joint's own
        reaction, plus viscous. With sd the joint's relative rate (rad/s or
        m/s), F = -(mu rho N + preload) sd / sqrt(sd^2 + slip_velocity^2)
        - viscous sd, a torque (revolute: rho = pin_radius, N = |joint force|)
        or a force along the axis (translational: rho = 1, N = |normal force|
        + |reaction moment| / bearing_length, the moment only if
        bearing_length is given) on the joint's second body; the first gets
        the opposite. ``load_smoothing`` (N) rounds |.| of the load near 0."""
        name = self._name(name)
        what = f"joint friction '{name}'"
        joint = self._joint(joint, what)
        values = {
            "mu": _number(mu, f"{what}: mu"),
            "viscous": _number(viscous, f"{what}: viscous"),
            "preload": _number(preload, f"{what}: preload"),
            "pin_radius": None if pin_radius is None else _number(pin_radius, f"{what}: pin_radius"),
            "bearing_length": (None if bearing_length is None
                               else _number(bearing_length, f"{what}: bearing_length")),
            "slip_velocity": _number(slip_velocity, f"{what}: slip_velocity"),
            "load_smoothing": _number(load_smoothing, f"{what}: load_smoothing"),
        }
        for key in ("pin_radius", "bearing_length"):
            if values[key] is not None and not values[key] > 0:
                raise ModelError(f"{what}: {key} must be positive, got {values[key]!r}")
        self._call("add_joint_friction", name, joint, values["mu"], values["viscous"], values["preload"],
                   values["pin_radius"] or 0.0, values["bearing_length"] or 0.0, values["slip_velocity"],
                   values["load_smoothing"])
        return self._record("add_joint_friction", name=name, joint=joint, **values)

    # --- questions -------------------------------------------------------

    def compiled(self):
        """The finalized C++ model (built once, rebuilt after changes).
        Compiling numbers coordinates and rows and builds patterns; it runs
        no solver (redundant equations are found where a run starts)."""
        if not self._core.finalized:
            self._core.finalize()
        return self._core

    def _warn_redundant(self, rows, stacklevel=3):
        """RedundantConstraintWarning for the rows a run left out."""
        if not rows:
            return
        import warnings

        from .errors import RedundantConstraintWarning

        named = ", ".join(f"'{self._core.constraint_name_of_row(r)}' (row {r})" for r in rows)
        warnings.warn(RedundantConstraintWarning(
            f"{len(rows)} constraint equation(s) are redundant at the initial configuration: "
            f"{named}. They are dropped: the motion is unique and is simulated, and the "
            "rest of each redundant set carries its reaction (the split among redundant "
            "joints is not unique). The dropped equations are checked at every output."),
            stacklevel=stacklevel + 1)

    def elements(self):
        """Everything added, in order: (method name, keyword arguments) with
        bodies by name, points as tuples and time functions as given.
        Replaying them on Model(gravity=self.gravity) rebuilds this model."""
        return [(m, dict(kw)) for m, kw in self._elements]

    def outline(self, body):
        """Local points (body axes) where joints and forces attach to a body,
        in the order added: what a drawing of the body joins."""
        name = name_of(self, body, ("body",), "body", "Model.outline")
        return list(self._outline.get(name, []))

    def to_scene(self, path, settings=None, output=None):
        """Write the model (and optional simulation settings) as a TOML scene."""
        from .scene import save_scene

        save_scene(self, path, settings, output)

    @property
    def bodies(self):
        """Body handles, in the order of their coordinates."""
        return list(self._bodies.values())

    @property
    def n_coordinates(self):
        return self.compiled().n_coordinates

    @property
    def n_constraints(self):
        return self.compiled().n_constraints

    def assemble(self, t=0.0):
        """Consistent initial state: (q, v, qdd, lam) at time t. Redundant
        equations found there are named in a RedundantConstraintWarning."""
        from .simulation import _real, _translate

        t = _real(t, "t")
        core = self.compiled()
        with _translate(self, core):
            q, v, qdd, lam, dropped = _core.assemble(core, t)
        self._warn_redundant(dropped)
        return q, v, qdd, lam

    def degrees_of_freedom(self):
        """Coordinates minus the number of independent constraint equations,
        counted near the assembled initial position (at a singular position,
        such as a flat parallelogram, as at its regular neighbours)."""
        from .simulation import _translate

        core = self.compiled()
        with _translate(self, core):
            return _core.degrees_of_freedom(core, 0.0)

    def rank(self):
        """Rank of the constraint Jacobian at the assembled initial position:
        dict with rank, equations, coordinates, degrees_of_freedom and the
        dependent (redundant) rows."""
        import warnings

        from .errors import RedundantConstraintWarning
        from .simulation import _translate

        with warnings.catch_warnings():  # the dependent rows are what this returns
            warnings.simplefilter("ignore", RedundantConstraintWarning)
            q = self.assemble()[0]
        with _translate(self):
            return self.compiled().rank(q, 0.0)

    def __repr__(self):
        n_elements = len(self._calls) - len(self._bodies)
        return f"<lagmb.Model: {len(self._bodies)} bodies, {n_elements} other elements>"
