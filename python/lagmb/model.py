"""Building a mechanism: bodies, joints, gravity (DESIGN.md section 5)."""

import math
import numbers

import numpy as np

from . import _core
from .errors import ModelError


class Body:
    """Handle of a body in a model; pass it to joints and results."""

    __slots__ = ("name", "model", "index")

    def __init__(self, name, model, index):
        self.name = name
        self.model = model
        self.index = index  # -1: the ground

    def __repr__(self):
        return f"Body({self.name!r})"


def _vec2(value, what):
    try:
        x = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ModelError(f"{what} must be a pair of numbers, got {value!r}") from None
    if x.shape != (2,):
        raise ModelError(f"{what} must be a pair of numbers, got {value!r}")
    if not np.all(np.isfinite(x)):
        raise ModelError(f"{what} is not finite: {value!r}")
    return x


def _number(value, what):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ModelError(f"{what} must be a number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ModelError(f"{what} is not finite: {value!r}")
    return value


class Model:
    """A planar mechanism: rigid bodies, particles and the elements between them.

    Coordinates are Cartesian: (x, y, phi) of each body's centre of mass and
    angle, (x, y) of each particle. Points are global, in the initial
    configuration, unless the argument name says ``local``. Every body and
    element has a unique name. Gravity is absent unless given.
    """

    def __init__(self, gravity=None):
        self._calls = []  # the add_* calls, replayed when the model changes after a run
        self._core = _core.Model()
        self._bodies = {}
        self.ground = Body("ground", self, -1)
        if gravity is not None:
            self._call("set_gravity", _vec2(gravity, "gravity"))

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

    def _body_index(self, body, element):
        if isinstance(body, str):
            if body == "ground":
                return -1
            if body not in self._bodies:
                raise ModelError(f"'{element}': no body named '{body}'")
            body = self._bodies[body]
        if not isinstance(body, Body):
            raise ModelError(f"'{element}': expected a body or its name, got {body!r}")
        if body.model is not self:
            raise ModelError(f"'{element}': body '{body.name}' belongs to another model")
        return body.index

    def _name(self, name):
        if not isinstance(name, str):
            raise ModelError(f"names must be strings, got {name!r}")
        return name

    def add_body(self, name, mass, inertia, position=(0.0, 0.0), angle=0.0,
                 velocity=(0.0, 0.0), angular_velocity=0.0):
        """Add a rigid body: mass (kg), centroidal inertia (kg m^2), initial
        position of its centre of mass (m), angle (rad), velocity (m/s) and
        angular velocity (rad/s). Returns its handle."""
        name = self._name(name)
        what = f"body '{name}'"
        self._call("add_body", name, _number(mass, f"{what}: mass"),
                   _number(inertia, f"{what}: inertia"), _vec2(position, f"{what}: position"),
                   _number(angle, f"{what}: angle"), _vec2(velocity, f"{what}: velocity"),
                   _number(angular_velocity, f"{what}: angular_velocity"))
        self._bodies[name] = Body(name, self, len(self._bodies))
        return self._bodies[name]

    def add_particle(self, name, mass, position, velocity=(0.0, 0.0)):
        """Add a point mass with two coordinates (x, y). Returns its handle."""
        name = self._name(name)
        what = f"particle '{name}'"
        self._call("add_particle", name, _number(mass, f"{what}: mass"),
                   _vec2(position, f"{what}: position"), _vec2(velocity, f"{what}: velocity"))
        self._bodies[name] = Body(name, self, len(self._bodies))
        return self._bodies[name]

    def add_revolute(self, name, body_i, body_j, at=None, *, local_i=None, local_j=None):
        """Pin body_i and body_j together at the global point ``at`` (in the
        initial configuration), or at ``local_i`` on body_i and ``local_j`` on
        body_j (each in its body's own axes)."""
        name = self._name(name)
        i, j = self._body_index(body_i, name), self._body_index(body_j, name)
        if at is not None:
            if local_i is not None or local_j is not None:
                raise ModelError(f"revolute '{name}': give either 'at' or 'local_i' and 'local_j'")
            self._call("add_revolute", name, i, j, _vec2(at, f"revolute '{name}': at"))
        elif local_i is not None and local_j is not None:
            self._call("add_revolute_local", name, i, j, _vec2(local_i, f"revolute '{name}': local_i"),
                       _vec2(local_j, f"revolute '{name}': local_j"))
        else:
            raise ModelError(f"revolute '{name}': give the joint point 'at' (global) "
                             "or both 'local_i' and 'local_j'")

    # --- questions -------------------------------------------------------

    def compiled(self):
        """The finalized C++ model (built once, rebuilt after changes)."""
        if not self._core.finalized:
            self._core.finalize()
        return self._core

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
        """Consistent initial state: (q, v, qdd, lam) at time t."""
        q, v, qdd, lam, _ = _core.assemble(self.compiled(), t)
        return q, v, qdd, lam

    def degrees_of_freedom(self):
        """Coordinates minus the rank of Phi_q at the assembled initial position."""
        return self.rank()["degrees_of_freedom"]

    def rank(self):
        """Rank of the constraint Jacobian at the assembled initial position:
        dict with rank, equations, coordinates, degrees_of_freedom and the
        dependent (redundant) rows."""
        from .simulation import _translate

        with _translate():
            q = self.assemble()[0]
        return self.compiled().rank(q, 0.0)

    def __repr__(self):
        n_elements = len(self._calls) - len(self._bodies)
        return f"<lagmb.Model: {len(self._bodies)} bodies, {n_elements} other elements>"
