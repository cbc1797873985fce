"""A run driven from outside: advanced in chunks, its inputs set between them,
saved and restored (docs/modelling.md, "Driving a run from outside")."""

from types import SimpleNamespace

import numpy as np

from . import _core, _deep_start, registry
from ._checks import parameters as _parameters, real as _real, show as _show
from .errors import ModelError, SimulationError
from .handles import name_of
from .result import EXERTING, BodyPath, JointPath, Result, element_name, efforts, translated_run
from .model import checked as _model
from ._run_options import DEFAULTS as _D, run_options


class Simulator:
    """A dynamic run of ``model`` that advances when asked::

        sim = mb.Simulator(model, rtol=1e-8)
        while sim.t < 10.0:
            sim.set_input("push", controller(sim.q, sim.v))   # from sim.t on
            sim.advance(sim.t + 0.01)
        r = sim.result()

    The options are :func:`lagmb.simulate`'s without the outputs (``t_end``,
    ``t_out``, ``n_out``), ``analysis`` (a simulator always integrates the
    equations of motion) and ``progress``; ``max_steps`` bounds the steps
    between two outputs. One simulator takes one call at a time: calls from
    other threads wait for the one in progress. The integrator keeps its steps and history from one advance to
    the next: its steps may pass the time asked for, and the state there is
    its interpolant, so many short advances take the steps of one long run.
    It restarts (order 1) at breakpoints and events as simulate does, at a
    change of an input (a jump; a driver's positions are assembled anew), and
    from a saved or restored state.

    ``result()`` holds the state at ``t0``, at the end of every advance and,
    with ``output_interval`` (s), at each of its multiples after ``t0``.
    ``parameters={name: value}``: as in :func:`lagmb.simulate`, the model
    runs with those values of its parameters (``model.parameters``).
    """

    def __init__(self, model, *, t0=_D["t0"], rtol=_D["rtol"], atol=_D["atol"], formulation=_D["formulation"],
                 integrator=None, max_step=None, step=None, max_steps=_D["max_steps"], max_order=None,
                 baumgarte=None, start=_D["start"], output_interval=None, parameters=None,
                 newton_rtol=_D["newton_rtol"], newton_atol=_D["newton_atol"], method=None):
        options = run_options(t0=_real(t0, "t0"), rtol=rtol, atol=atol, formulation=formulation,
                              integrator=integrator, max_step=max_step, step=step, max_order=max_order,
                              baumgarte=baumgarte, max_steps=max_steps, start=start, newton_rtol=newton_rtol,
                              newton_atol=newton_atol, method=method)
        _model(model, "Simulator")
        interval = 0.0 if output_interval is None else _real(output_interval, "output_interval")
        if interval < 0:
            raise ModelError(f"output_interval must be >= 0 (None: outputs at the ends of advances), got {interval}")
        self.model = model
        self._changed = (None, {})  # (t, {input: value}): the inputs last set, and when
        self._joint_names = None
        self._readings = {}  # joints(): {the joints asked for: [(name, slide?)]}
        self._input_order = None  # _inputs()
        self._snapshot = model._snapshot()  # the model it runs, whatever edits follow
        self._core_model = _parameters(self._snapshot, parameters, "Simulator")
        # (contacts deep at the start: warned of here, named by a failure at t0)
        self._t0 = options["t0"]
        self._start_contacts = _deep_start.warn(self._snapshot, self._core_model,
                                                self._core_model.initial_state()[0], self._t0) \
            if options["start"] == "given" else ([], 0.0)
        with _deep_start.noted(self._start_contacts, self._t0), self._translated():
            self._sim = _core.Simulator(self._core_model, options, interval)
        start_state = self._sim.result()
        self._snapshot._warn_redundant(start_state.get("dropped_rows", []))
        if options["start"] == "given":
            self._snapshot._warn_moved(self._core_model, start_state["q"][0])

    # the current state, consistent: copies
    @property
    def t(self):
        """Time reached (s)."""
        return self._sim.t

    @property
    def q(self):
        """Coordinates at :attr:`t` (a copy)."""
        return self._sim.q

    @property
    def v(self):
        """Velocities at :attr:`t`."""
        return self._sim.v

    @property
    def a(self):
        """Accelerations at :attr:`t`, from the augmented system."""
        with self._translated():
            return self._sim.a

    @property
    def lam(self):
        """Lagrange multipliers at :attr:`t`."""
        with self._translated():
            return self._sim.lam

    def body(self, body):
        """A body's state now (handle or name), as :meth:`lagmb.Result.body`
        gives it at one instant: .position, .velocity, .acceleration, and
        .angle, .angular_velocity (planar) or .orientation, .rotation,
        .angular_velocity (spatial)."""
        name = element_name(self.model, self._core_model, body, ("body",), "body", "Simulator.body")
        first, count = self._core_model.body_coordinates(name)
        now = SimpleNamespace(t=[self.t], q=self.q[None], v=self.v[None], a=self.a[None])
        return SimpleNamespace(**{key: value[0] for key, value in vars(BodyPath(now, first, count)).items()})

    def joint(self, joint):
        """A joint's coordinate now (handle or name), as :meth:`lagmb.Result.joint`
        gives it at one instant: .angle (rad, counting whole turns) or .slide
        (m), .rate and .acceleration."""
        name = element_name(self.model, self._core_model, joint, ("joint",), "joint", "Simulator.joint")
        path = JointPath(self._now(self.a), name, "Simulator.joint")
        return SimpleNamespace(**{key: float(value[0]) for key, value in vars(path).items()})

    def joints(self, joints=None):
        """The coordinates of several joints now, in one call: ``(values,
        rates)``, two arrays in the order of ``joints`` (handles or names;
        None: every revolute, translational and cylindrical joint in the
        model's order, :attr:`joint_names`), each joint's angle (rad,
        counting turns) or slide (m) and its rate, as :meth:`joint` reads
        them (a cylindrical joint: its angle). No accelerations are solved."""
        key = None if joints is None else tuple(joints)
        cached = key is None or all(isinstance(j, str) for j in key)
        reading = self._readings.get(key) if cached else None
        if reading is None:  # (resolved once per list of joints: a controller asks every tick)
            names = self.joint_names if joints is None else [
                element_name(self.model, self._core_model, j, ("joint",), "joint", "Simulator.joints")
                for j in joints]
            reading = []
            for name in names:
                declared = registry.kind_of(self._core_model, name)
                coordinates = declared.coordinates if declared else ()
                if not ("angle" in coordinates or "slide" in coordinates):
                    raise ModelError(f"Simulator.joints: '{name}' is a {self._core_model.element_kind(name)}, "
                                     "not a revolute, translational or cylindrical joint")
                reading.append((name, "angle" not in coordinates))
            if cached:
                self._readings[key] = reading
        motion = self._core_model.joint_motions(reading, self.q, self.v, self._sim.run_state)
        return motion[:, 0].copy(), motion[:, 1].copy()

    def effort(self, element):
        """What a driver, stop, force element or joint friction (handle or
        name) applies now, as :meth:`lagmb.Result.effort` reads it at one
        instant: a number (a servo's torque after its limit, a spring's
        force, a driver's effort), or an array for an applied force's or a
        bushing's components; at the inputs set now."""
        name = element_name(self.model, self._core_model, element, EXERTING, "element", "Simulator.effort")
        with self._translated():
            rows = efforts(self._core_model, name, "Simulator.effort", np.array([self.t]), self.q[None],
                           self.v[None], lambda: self.lam[None], np.asarray(self._sim.inputs, dtype=float)[None],
                           np.asarray(self._sim.run_state, dtype=float)[None])
        return float(rows[0]) if rows.ndim == 1 else rows[0].copy()

    @property
    def joint_names(self):
        """The model's revolute, translational and cylindrical joints (those
        :meth:`joint` reads), in the order they were added."""
        if self._joint_names is None:
            self._joint_names = tuple(
                name for kind, name, _ in self._snapshot._spec.elements()
                if {"angle", "slide"} & set(registry.BY_NAME[kind].coordinates))
        return self._joint_names

    def _now(self, a):
        """The state now as a one-output run (what Result's readers take)."""
        return SimpleNamespace(_core=self._core_model, t=np.array([self.t]), q=self.q[None], v=self.v[None],
                               a=np.asarray(a)[None], _run_state=np.asarray(self._sim.run_state)[None])

    def advance(self, t):
        """Integrate to time ``t`` (>= :attr:`t`). Raises SimulationError if
        the integrator fails: :meth:`result` keeps the outputs reached, and
        the simulator refuses to go on until :meth:`set_state`."""
        t = _real(t, "t")
        try:
            with _deep_start.noted(self._start_contacts, self._t0), self._translated():
                self._sim.advance(t)
        except SimulationError as e:
            at, values = self._changed
            if type(e) is not SimulationError or at is None or e.t != at or not values:
                raise
            # a failure at the instant inputs changed, before a step: name them and their values
            feeds = {d["name"]: f"{d['element']}.{d['parameter']}" for d in self._core_model.inputs}
            named = ", ".join(f"'{name}' = {value:g} ({feeds.get(name, name)})" for name, value in values.items())
            raise SimulationError(f"{e} It failed at once where inputs were set (t = {at:g} s: {named}); an input "
                                  "too large for this model (forces whose accelerations overflow the integrator's "
                                  "arithmetic at its first step) fails so.", e.t, e.result) from e.__cause__

    def set_input(self, name, value):
        """Set an input (:attr:`inputs`) from :attr:`t` on. ``name``: the
        input's name, or a handle of the element it feeds."""
        value = _real(value, f"input {name!r}")
        name = self._input_name(name)
        with self._translated():
            self._sim.set_input(name, value)
        self._note_inputs({name: value})

    def set_inputs(self, values):
        """Set several inputs at once from :attr:`t` on: a dict {name or
        handle: value}, or a sequence of values for every input in the order
        of :attr:`inputs`. One restart of the integrator, as one
        :meth:`set_input`."""
        if isinstance(values, np.ndarray) and values.dtype.kind == "f" and values.shape == (len(self._inputs()),):
            # (a controller's array every tick: the core checks each value, naming the input)
            names = self._inputs()
            with self._translated():
                self._sim.set_inputs(names, values.tolist())
            self._note_inputs(dict(zip(names, values.tolist())))
            return
        if isinstance(values, dict):
            items = [(self._input_name(name), _real(value, f"input {name!r}")) for name, value in values.items()]
        else:
            names = [d["name"] for d in self._core_model.inputs]
            given = None
            if not isinstance(values, (str, bytes)) and hasattr(values, "__iter__"):
                try:  # (each value as given, not as float() makes it: None is no number, not nan)
                    given = list(np.asarray(values, dtype=object).ravel())
                except (TypeError, ValueError):
                    given = None
            if given is None or len(given) != len(names):
                raise ModelError(f"set_inputs takes a dict {{name: value}} or {len(names)} numbers in the order "
                                 f"of Simulator.inputs ({', '.join(names)}), got {_show(values)}")
            items = [(name, _real(value, f"input {name!r}")) for name, value in zip(names, given)]
        with self._translated():
            self._sim.set_inputs([name for name, _ in items], [value for _, value in items])
        self._note_inputs(dict(items))

    def _inputs(self):
        """The input names in the order of :attr:`inputs` (made once)."""
        if self._input_order is None:
            self._input_order = [d["name"] for d in self._core_model.inputs]
        return self._input_order

    def _note_inputs(self, values):
        """Keeps the inputs set at this time (what a failure at once names)."""
        at, known = self._changed
        self._changed = (self.t, {**(known if at == self.t else {}), **values})

    def input(self, name):
        """The value of an input now."""
        with self._translated():
            return self._sim.input(self._input_name(name))

    @property
    def inputs(self):
        """{name: value} of the model's inputs."""
        return {d["name"]: float(value) for d, value in zip(self._core_model.inputs, self._sim.inputs)}

    def state(self):
        """The state to come back to with :meth:`set_state`. The integrator
        restarts here on the next advance, so advancing from a restored copy
        repeats the run from here bit for bit."""
        return self._sim.state()

    def set_state(self, state):
        """Go back (or forward) to a saved state: the outputs after its time
        are dropped; the integrator restarts there; a failure is cleared."""
        if not isinstance(state, _core.SimulatorState):
            raise ModelError(f"set_state takes what state() returned, got {_show(state)}")
        with self._translated():
            self._sim.set_state(state)
        self._changed = (None, {})

    def result(self):
        """Everything recorded so far, as a :class:`lagmb.Result`."""
        return Result(self.model._run_model(self._snapshot), self._core_model, self._sim.result(), self._snapshot)

    @property
    def stats(self):
        """Solver counts summed over the run (``restarts``, ``input_changes``, ...)."""
        return dict(self._sim.stats)

    def __repr__(self):
        return f"Simulator(t={self.t!r}, inputs={self.inputs!r})"

    def __reduce__(self):
        raise ModelError(
            "a Simulator cannot be pickled or copied: its integrator's state lives in this process. Send "
            "what the other side needs instead: the model (it pickles) and the options to start a Simulator "
            "there, and the run so far as sim.result() (it pickles) or the state as numbers (sim.t, sim.q, "
            "sim.v, sim.inputs)")

    def _input_name(self, name):
        """An input's name, given as its name or the handle of the element it feeds."""
        if isinstance(name, str):
            return name
        from .handles import Handle

        if isinstance(name, Handle):
            return name_of(self.model, name, registry.ROLES, "input", "Simulator")
        raise ModelError(f"an input is named by a string or a handle, got {_show(name)}")

    def _translated(self):
        return translated_run(self.model, self._core_model, self._snapshot)
