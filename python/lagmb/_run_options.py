"""The options every dynamic run takes (simulate, Simulator, the FMU's
setup): the core's defaults (DEFAULTS, the one place they live), the
method named by ``method`` or by a formulation and an integrator, and the
options checked by the names of the core's SimulationOptions.
"""

import numpy as np

from . import _core
from ._checks import INT_MAX as _INT_MAX, array as _array, integer as _integer
from ._checks import positive as _positive, real as _real, text as _text
from .errors import ModelError

#: What every run takes by default: the core's SimulationOptions, by field
#: name (the one place the defaults live; the signatures of simulate and
#: Simulator read it).
DEFAULTS = _core.default_options()
_D = DEFAULTS


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


def run_options(*, t0, rtol, atol, formulation, integrator, max_step, step, max_order, baumgarte, max_steps,
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
