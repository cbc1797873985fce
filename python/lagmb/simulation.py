"""Running a model: simulate() and one-instant solves."""

import contextvars

import numpy as np

from . import _core
from ._checks import INT_MAX as _INT_MAX, array as _array, integer as _integer
from . import _deep_start
from ._checks import parameters as _parameters, positive as _positive, real as _real
from ._checks import show as _show, text as _text
from .errors import ModelError, translated
from .model import checked as _model
from .result import Result

#: What every run takes by default: the core's SimulationOptions, by field
#: name (the one place the defaults live; the signatures below read it).
DEFAULTS = _core.default_options()
_D = DEFAULTS



#: Where simulate's warnings go in this context: None (the warnings module)
#: or a list that takes them (mb.sweep's cases: catch_warnings is not
#: thread-safe, and threads run cases).
WARNINGS_INTO = contextvars.ContextVar("lagmb_simulate_warnings_into", default=None)

def _translate(model=None, core=None, snapshot=None):
    """errors.translated, the partial outputs of a failed run of `model`
    (compiled: `core`; as the run saw it: `snapshot`) as a Result."""
    def partial_result(raw):
        partial = Result(model, core, raw, snapshot)
        return partial if len(partial.t) else None

    return translated(partial_result if model is not None else None)


def simulate(model, t_end=None, *, rtol=_D["rtol"], atol=_D["atol"], n_out=_D["n_out"], t_out=None, t0=_D["t0"],
             max_step=None, max_steps=_D["max_steps"], formulation=_D["formulation"], integrator=None,
             max_order=None, baumgarte=None, progress=None, analysis=_D["analysis"], start=_D["start"], step=None,
             parameters=None, newton_rtol=_D["newton_rtol"], newton_atol=_D["newton_atol"], method=None,
             sensitivities=None):
    """Integrate a model from its initial state and return a Result.

    The initial state is first made consistent (positions by least change,
    velocities by projection); then it is integrated by one of the methods
    that :func:`lagmb.methods` lists, named by ``method`` (its listed name,
    any case: ``method="projection-erk"``; ``r.stats["method"]`` says the one
    that ran) or by a ``formulation`` and one of its integrators
    (``integrator=None``: the formulation's first; a listed name is taken as
    ``formulation`` too):

    - ``formulation="auto"`` (default): the method chosen from the model:
      ``"ggl"`` where a contact or joint friction from the loads switches
      the forces or the applied forces are stiff (their fastest rate at the
      start times the span above 1000), else ``"projection"`` with
      ``"erk"``, handing over to ``"ggl"`` if the explicit run fails its
      error test or takes 5,000 steps between two outputs;
      ``r.stats["method_choice"]`` says which and why. No ``integrator``
      or ``baumgarte`` with it.
    - ``"ggl"``: stabilized index 2 (Gear, Gupta,
      Leimkuhler), IDA; positions and velocities stay on the constraints.
    - ``"index3"``: position constraints only, IDA with the multipliers and
      velocities weighted as index-3 and index-2 variables.
    - ``"index1"``: acceleration constraints, IDA; drifts unless
      ``baumgarte=(alpha, beta)`` adds 2 alpha Phi' + beta^2 Phi.
    - ``"projection"``: the ODE in accelerations (augmented system solved at
      every right-hand side), CVODE, q and v projected onto the constraints
      after every step with ``integrator="bdf"`` (CVODE BDF, orders 1-5);
      with ``"adams"`` (Adams-Moulton, orders 1-12) CVODE cannot project,
      so the constraints drift unless ``baumgarte=(alpha, beta)`` is given;
      with ``"erk"`` ARKODE's explicit Runge-Kutta methods (ERKStep; order 8,
      Prince-Dormand 8(7), by default; ``max_order`` 2-6 or 8 picks another), q
      and v projected after every accepted step, the steps stopped at the
      output times (its interpolant is less accurate than its steps): for
      non-stiff mechanisms, such as long free chains, where a few
      high-order steps beat many BDF steps.
    - ``"ali3p"``: index-3 augmented Lagrangian with mass-orthogonal
      projections of velocities and accelerations, trapezoidal rule with the
      fixed ``step`` (s; ``max_step`` is taken as the step if ``step`` is
      not given; integrator ``"trapezoidal"``) (Bayo & Ledesma 1996; Cuadrado et al. 2000). Its Newton
      matrix (multiplier block regularized) stays invertible when the
      constraint Jacobian loses rank, so it runs through singular positions
      (a parallelogram passing its horizontal); a step that lands within
      roundoff of one is retried with another length
      (``stats["convergence_failures"]``). It has no error control, so
      rtol/atol do not apply (ModelError if given other than the
      defaults): ``newton_rtol``/``newton_atol`` (default 1e-10 / 1e-12)
      bound the Newton corrections of q; the step alone sets the
      truncation error (second order; energy error O((omega step)^2), no
      drift).

    ``max_order`` defaults to the method's highest (5 for BDF, 12 for Adams,
    8 for ERK). ``atol`` is one number
    or one per coordinate (applied to q_i and v_i; e.g. smaller for angles
    than for positions measured in km). Outputs: ``n_out`` equally spaced times from t0 to
    t_end, or the explicit increasing times ``t_out`` (t_end defaults to its
    last entry), interpolated by the integrator. ``max_step`` bounds the step
    size (s), ``max_steps`` the number of steps between two outputs, as
    SUNDIALS' mxstep (in a kinematic analysis, of the sub-steps that follow
    the drivers; default 500,000; None: no bound; reaching it raises
    SimulationError with the outputs so far, and a ``max_step`` or ``step``
    that would need more steps than that between two outputs is refused up
    front with ModelError). ``rtol`` is 1e-14 to below 1. ``progress``, if given,
    is called with the time reached about every 0.2 s of wall time.
    Ctrl-C stops a run within a second: the KeyboardInterrupt comes through
    unchanged and carries the outputs so far as ``.result`` (also when a
    time function or ``progress`` raises it, or SystemExit).

    ``analysis`` says what is computed (``r.stats["analysis"]`` tells what was):

    - ``"auto"`` (default): a model whose motion is fully prescribed by its
      drivers (0 degrees of freedom) gets a kinematic analysis with inverse
      dynamics (``"inverse_dynamics"``; ``"kinematic"`` if a body is
      massless), any other model a ``"dynamic"`` run;
    - ``"dynamic"``: integrate the DAE even at 0 degrees of freedom;
    - ``"kinematic"``: positions from Newton on Phi(q, t) = 0 at each output,
      velocities from Phi_q v = -Phi_t, accelerations from Phi_q a = gamma;
      no DAE is integrated (``stats["steps"] == 0``) and the multipliers are
      not computed (``r.lam``, ``r.reaction`` raise KinematicOnlyError);
    - ``"inverse_dynamics"``: kinematic, plus the multipliers (reactions,
      driver efforts) from M a + Phi_q^T lam = Q.

    The last two need 0 degrees of freedom (ModelError naming the count
    otherwise). ``rtol``/``atol`` do not apply to them: positions are solved
    to rounding level (``|dq| <= 1e-12 (1 + |q|)``). Bodies with mass (or
    inertia) 0 are allowed in kinematic analyses only.

    ``start="equilibrium"`` starts a dynamic run at rest in the static
    equilibrium at t0 (``mb.equilibrium``) instead of the given initial
    state (``"given"``).

    ``parameters={"rod.mass": 2.0, ...}`` runs the model with other values
    of the numbers its elements were given (``model.parameters`` lists
    them with their values): the same as a model built with those values,
    without changing ``model``; the Result's reactions and energy are of
    that run. Each value is checked as ``add_*`` checks it.

    ``sensitivities=["rod.mass", "spring.stiffness", ...]`` integrates,
    beside the run, the derivatives of its solution with respect to those
    parameters (``model.parameters`` names them: every number given to an
    element and the bodies' initial coordinates and velocities):
    ``r.sensitivity(name)`` gives dq/dp, dv/dp, da/dp, dlam/dp and the
    derivatives of positions, points, reactions and efforts (a
    :class:`~lagmb.Sensitivity`). IDAS integrates them with the GGL
    form (which ``method="auto"`` then runs; another method is a
    ModelError), its staggered corrector reusing the run's Newton matrix:
    F_y s + F_y' s' + F_p = 0 with the form's exact blocks, F_p a central
    difference of the residual between the models at p +- 1e-4 abs(p)
    (one-sided at a bound of p's range, such as a damping of 0), and
    the initial sensitivities from those models' consistent starts; they
    take part in the error test. ModelError for a model with stops or
    contact (the motion jumps at their events), joint friction, or a fully
    driven model, and for a parameter that has no sensitivity, naming it
    and why (no other value of it nearby makes a model: a component of a
    universal joint's axis; its change alters which equations are
    redundant: a joint of a redundant pair).

    Raises ModelError for bad arguments, AssemblyError if the joints cannot
    be assembled, SimulationError (with ``.t`` and the partial ``.result``)
    if the integrator (or the kinematic Newton solve) fails, or a user
    function (time function, progress) raises (chained as its cause), or an
    output cannot be solved to finite accelerations and multipliers (naming
    the source), or an equation left out as redundant at the start is
    violated later (naming the conflicting elements); EquilibriumError
    if ``start="equilibrium"`` finds none.

    The run works from the model as it is when it starts: an edit from
    another thread during the run changes neither the run nor its Result
    (its ``.model`` is then a copy of the model as it ran, with a warning).
    """
    _model(model, "simulate")
    t0 = _real(t0, "t0")
    if t_out is not None:
        t_out = _array(t_out, "t_out")
        if t_out.size == 0:
            raise ModelError("t_out is empty")
        if t_end is None:
            t_end = float(t_out[-1])
    if t_end is None:
        raise ModelError("give t_end or t_out")
    t_end = _real(t_end, "t_end")
    if not t_end > t0:
        raise ModelError(f"t_end must be finite and greater than t0 = {t0}, got {t_end}")
    options = _run_options(t0=t0, rtol=rtol, atol=atol, formulation=formulation, integrator=integrator,
                           max_step=max_step, step=step, max_order=max_order, baumgarte=baumgarte,
                           max_steps=max_steps, start=start, newton_rtol=newton_rtol, newton_atol=newton_atol,
                           method=method)
    if t_out is not None and t_out.size > 1 and not np.all(np.diff(t_out) > 0):
        raise ModelError("t_out must be strictly increasing")
    if t_out is not None and t_out.size > _INT_MAX:
        raise ModelError(f"t_out has {t_out.size} entries, more than {_INT_MAX}")
    if t_out is None:
        n_out = _integer(n_out, "n_out", 2, _INT_MAX)
    else:
        n_out = 2  # unused
    if progress is not None and not callable(progress):
        raise ModelError(f"progress must be a callable t -> None, got {progress!r}")
    analysis = _text(analysis, "analysis")  # the core parses the choice
    # the model as it is now: an edit from another thread during the run
    # changes neither the run nor its Result
    snapshot = model._snapshot()
    core = _parameters(snapshot, parameters, "simulate")
    sensitivities = _names(sensitivities, "simulate: sensitivities", "parameter names")
    into = WARNINGS_INTO.get()  # (a list that takes lagmb's warnings instead: a sweep's case in a thread)
    start_contacts = _deep_start.warn(snapshot, core, core.initial_state()[0], t0, into=into) \
        if options["start"] == "given" and analysis.strip().lower() != "kinematic" else ([], 0.0)
    with _deep_start.noted(start_contacts, t0), _translate(model, core, snapshot):
        options.update(t_end=t_end, t_out=[] if t_out is None else list(t_out), n_out=n_out, analysis=analysis)
        raw = _core.simulate(core, options, progress, sensitivities)
    snapshot._warn_redundant(raw.get("dropped_rows", []), into=into)
    if options["start"] == "given" and len(raw["t"]) and raw["t"][0] == t0:
        snapshot._warn_moved(core, raw["q"][0], into=into)
    return Result(model._run_model(snapshot, into=into), core, raw, snapshot)


def _names(value, who, what):
    """A list of strings given as a list (or tuple, ...) of them; None: []."""
    if value is None:
        return []
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise ModelError(f"{who} must be a list of {what}, got {_show(value)}")
    value = list(value)
    for x in value:
        if not isinstance(x, str):
            raise ModelError(f"{who} must be a list of {what}, got {_show(x)} among them")
    return value


def method_options(method=None, formulation=_D["formulation"], integrator=None):
    """(formulation, integrator) for a run: from ``method``, a name that
    :func:`methods` lists (or "auto"), in any case; else from ``formulation``
    (which may be such a name too) and ``integrator`` ("" for the
    formulation's first). ModelError for an unknown name, or for ``method``
    given beside a formulation or an integrator."""
    by_name = {m["name"]: m for m in _core.methods()}
    if method is not None:
        name = _text(method, "method").strip().lower()
        if name != "auto" and name not in by_name:
            raise ModelError(f"method {method!r} is not one of: {', '.join(['auto'] + list(by_name))}")
        if integrator is not None or _text(formulation, "formulation").strip().lower() != _D["formulation"]:
            raise ModelError(f"method {method!r} names the formulation and the integrator together: give method, "
                             "or formulation and integrator, not both")
        return ("auto", "") if name == "auto" else (by_name[name]["formulation"], by_name[name]["integrator"])
    formulation = _text(formulation, "formulation").strip().lower()
    integrator = "" if integrator is None else _text(integrator, "integrator").strip().lower()
    listed = by_name.get(formulation)
    if listed is not None and listed["formulation"] != formulation:  # "projection-erk" as a formulation
        if integrator and integrator != listed["integrator"]:
            raise ModelError(f"formulation {formulation!r} names integrator {listed['integrator']!r}, "
                             f"got integrator {integrator!r}")
        return listed["formulation"], listed["integrator"]
    return formulation, integrator


def _run_options(*, t0, rtol, atol, formulation, integrator, max_step, step, max_order, baumgarte, max_steps,
                 start, newton_rtol=_D["newton_rtol"], newton_atol=_D["newton_atol"], method=None):
    """The options every dynamic run takes, checked, by the names of the
    core's SimulationOptions (simulate and Simulator). The choices
    (formulation, integrator, start, analysis) are checked to be strings
    here and parsed by the core, which lists the valid ones."""
    rtol = _positive(rtol, "rtol")
    formulation, integrator = method_options(method, formulation, integrator)
    # the core refuses the same (run_options.cpp, for C++ and FMU callers); checked here first, with the
    # message Python has always given (no "simulate: " before it), before atol's own checks
    if formulation == "ali3p" and not (np.ndim(atol) == 0 and rtol == _D["rtol"] and atol == _D["atol"]):
        raise ModelError("formulation 'ali3p' takes fixed steps without error control: rtol and atol do not "
                         f"apply; its Newton corrections are bounded by newton_rtol (default {_D['newton_rtol']}) "
                         f"and newton_atol (default {_D['newton_atol']})")
    newton_rtol = _positive(newton_rtol, "newton_rtol")
    newton_atol = _positive(newton_atol, "newton_atol")
    atol_coordinates = []
    if np.ndim(atol) > 0:  # one per coordinate (for q_i and v_i)
        atol_coordinates = [_positive(float(a), "atol entry") for a in _array(atol, "atol")]
        atol = float(np.mean(atol_coordinates)) if atol_coordinates else 1e-8
    atol = _positive(atol, "atol")
    max_step = 0.0 if max_step is None else _positive(max_step, "max_step")
    if step is not None:  # the fixed step of ali3p travels as max_step
        if formulation != "ali3p":
            raise ModelError(f"step applies to formulation 'ali3p' (fixed step); "
                             f"for {formulation!r} bound the step with max_step")
        max_step = _positive(step, "step")
    # None: the method's highest; the core checks the method's range
    max_order = 0 if max_order is None else _integer(max_order, "max_order", 1, _INT_MAX)
    if baumgarte is None:
        alpha, beta = 0.0, 0.0
    else:
        try:
            alpha, beta = baumgarte
        except (TypeError, ValueError):
            raise ModelError(f"baumgarte must be a pair (alpha, beta) of numbers, got {baumgarte!r}") from None
        alpha, beta = _real(alpha, "baumgarte alpha"), _real(beta, "baumgarte beta")
    # None: no bound (Ctrl-C still stops the run)
    max_steps = 0 if max_steps is None else _integer(max_steps, "max_steps", 1, 2**62)
    start = _text(start, "start")
    return dict(t0=t0, rtol=rtol, atol=atol, atol_coordinates=atol_coordinates, max_step=max_step,
                max_steps=max_steps, max_order=max_order, formulation=formulation, integrator=integrator,
                baumgarte_alpha=alpha, baumgarte_beta=beta, start=start, newton_rtol=newton_rtol,
                newton_atol=newton_atol)


def solve_accelerations(model, q, v, t=0.0):
    """Accelerations and multipliers (qdd, lam) at one instant: the augmented
    system [M Phi_q^T; Phi_q 0] [qdd; lam] = [Q; gamma]. Rows dependent at
    that instant are left out (their multipliers 0)."""
    core = model.compiled()
    n = core.n_coordinates
    q = _array(q, "q")
    v = _array(v, "v")
    t = _real(t, "t")
    if q.shape != (n,) or v.shape != (n,):
        raise ModelError(f"q and v must have {n} entries, got {q.size} and {v.size}")
    with _translate(model, core):
        return _core.solve_accelerations(core, q, v, t)


def methods():
    """The integration methods, one dict each, the default first: ``name``,
    ``formulation`` and ``integrator`` (what :func:`simulate` takes),
    ``solver``, ``description`` (one line), ``max_order``, and what the
    method supports: ``fixed_step`` (needs ``step``), ``events`` (stops and
    contact), ``contact`` (a contact's onset placed: not the explicit
    method), ``friction`` (joint friction), ``baumgarte``, ``drifts``
    (positions are not held on the constraints)."""
    return [dict(m) for m in _core.methods()]
