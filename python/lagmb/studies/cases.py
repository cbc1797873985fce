"""A sweep's cases: made from a grid (given, or written as text as
``lagmb sweep --vary`` reads it), a table, a DataFrame or a design; each
name and value checked against the model before any case runs.
"""

import itertools
import math
import numbers
import os

import numpy as np

from .._checks import decimal, real, show
from ..errors import ModelError
from .designs import Design
from .store import MAX_CASES

#: the settings a case may vary beside the model's parameters (simulate's keywords)
RUN_SETTINGS = ("t_end", "rtol", "atol", "method", "formulation", "integrator", "analysis", "start", "max_step",
                "n_out", "max_steps")
#: the units of the run settings a sweep may vary (the others are numbers without one, or names)
SETTING_UNITS = {"t_end": "s", "max_step": "s"}
CASE_BYTES = 2500  # memory a case takes: its dict, the checked copy, its record, its row (measured)


_WHOLE_SETTINGS = ("n_out", "max_steps")  # run settings that take whole numbers
_SPEC = "SPEC is A:B:N (N values from A to B) or V1,V2,..."


def grid_from_text(specs, who="sweep.grid_from_text"):
    """The grid ``{name: [values, ...]}`` that :func:`sweep` takes, from
    texts ``"NAME=SPEC"`` as ``lagmb sweep --vary`` reads them: SPEC
    ``A:B:N`` is N values from A to B, both included (``numpy.linspace``),
    ``V1,V2,...`` a list; numbers are written as TOML writes them ("1e-3",
    not "1_0"). The names keep their order (the last varies fastest);
    ``n_out`` and ``max_steps`` get whole numbers. A text that is no such
    SPEC, a name given twice, a value listed twice or more than MAX_CASES
    cases is a ModelError naming the text; ``who`` begins the message (an
    option of a command line, "--vary", is shown before the text as typed)."""
    if isinstance(specs, str):
        specs = [specs]

    def about(spec):
        return f"{who} {spec}" if who.startswith("--") else f"{who}: {spec!r}"

    if not specs:
        if who.startswith("--"):
            raise ModelError(f"give at least one {who} NAME=SPEC (e.g. {who} rod.mass=1:3:5 or "
                             f"{who} rod.mass=1,2,4)")
        raise ModelError(f"{who}: give at least one 'NAME=SPEC' (e.g. 'rod.mass=1:3:5' or 'rod.mass=1,2,4')")
    grid, typed = {}, {}
    for spec in specs:
        name, eq, text = str(spec).partition("=")
        name = name.strip()
        if not eq or not name:
            raise ModelError(f"{about(spec)}: must be NAME=SPEC, SPEC A:B:N (N values from A to B) or V1,V2,...")
        if name in grid:
            raise ModelError(f"{about(spec)}: {name} is varied twice ({about(typed[name])})")
        grid[name], typed[name] = _values_from_text(about(spec), name, text.strip()), spec
    n = math.prod(len(values) for values in grid.values())
    if n > MAX_CASES:
        raise ModelError(f"{who}: {n:,} cases (" + " x ".join(str(len(v)) for v in grid.values())
                         + f"): at most {MAX_CASES:,} in one study")
    return grid


def _values_from_text(about, name, text):
    """The values of NAME=SPEC (SPEC as text): A:B:N as numpy.linspace(A, B,
    N), or V1,V2,...; ``about`` begins each message."""
    def number(s):
        try:
            v = decimal(s, "number")
        except ModelError as e:
            raise ModelError(f"{about}: {str(e).partition(': ')[2]}; {_SPEC}") from None
        if not math.isfinite(v):
            raise ModelError(f"{about}: {s.strip()} must be a finite number")
        return v

    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise ModelError(f"{about}: A:B:N has three parts (N values from A to B), got {len(parts)}")
        a, b, count = (number(p) for p in parts)
        if not count.is_integer() or count < 2:
            raise ModelError(f"{about}: N = {parts[2].strip()} must be a whole number of values, at least 2 (one "
                             f"value: {name}=V)")
        if count > MAX_CASES:
            raise ModelError(f"{about}: N = {parts[2].strip()}: at most {MAX_CASES:,} values")
        if a == b:
            raise ModelError(f"{about}: A:B:N runs from A to B: give A and B apart")
        values = np.linspace(a, b, int(count)).tolist()
    else:
        items = text.split(",")
        if any(not s.strip() for s in items):
            raise ModelError(f"{about}: an empty value; {_SPEC}")
        values = [number(s) for s in items]
        twice = next((v for k, v in enumerate(values) if v in values[:k]), None)
        if twice is not None:
            raise ModelError(f"{about}: {twice:g} is listed twice")
    if name in _WHOLE_SETTINGS:
        if any(not float(v).is_integer() for v in values):
            raise ModelError(f"{about}: {name} takes whole numbers")
        values = [int(v) for v in values]
    return values



def _missing(value):
    """A DataFrame's cell that holds no value (NaN, None, pd.NA): a case
    that does not give that name, as in a list of dicts."""
    import pandas

    try:
        return bool(pandas.isna(value))
    except (TypeError, ValueError):  # a list or an array: a value
        return False


def _physical_memory():
    """The machine's memory (bytes), or None where the system does not say."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return None


def _too_many(n, who, per_case):
    """Refuses n cases past MAX_CASES, or that would take more memory than
    the machine has (per_case bytes each), before they are made."""
    if n > MAX_CASES:
        raise ModelError(f"{who}: {n:,} cases: at most {MAX_CASES:,} in one sweep (sweep.MAX_CASES); split the study")
    memory = _physical_memory()
    if memory and n * per_case > memory:
        raise ModelError(f"{who}: {n:,} cases would take about {n * per_case / 1e9:,.1f} GB of memory (this "
                         f"machine has {memory / 1e9:,.1f} GB): split the study, or ask for fewer history times")


def cases_of(parameters, who, per_case=CASE_BYTES):
    """(list of case dicts, grid or None): a grid is [(name, values), ...]."""
    if isinstance(parameters, Design):
        _too_many(len(parameters.cases), who, per_case)
        return list(parameters.cases), None
    if hasattr(parameters, "to_dict") and hasattr(parameters, "columns"):  # a pandas DataFrame
        _too_many(len(parameters), who, per_case)
        return [{k: v for k, v in row.items() if not _missing(v)}
                for row in parameters.to_dict(orient="records")], None
    if isinstance(parameters, dict):
        if not parameters:
            raise ModelError(f"{who}: the grid is empty: give {{name: [values, ...]}}")
        grid = []
        for name, values in parameters.items():
            values = list(np.atleast_1d(np.asarray(values, dtype=object)))
            if not values:
                raise ModelError(f"{who}: the grid's axis {name!r} has no values")
            grid.append((name, values))
        _too_many(math.prod(len(g[1]) for g in grid), who, per_case)  # before the product is built
        names = [g[0] for g in grid]
        return [dict(zip(names, combo)) for combo in itertools.product(*(g[1] for g in grid))], grid
    if isinstance(parameters, (list, tuple)):
        if not parameters:
            raise ModelError(f"{who}: no cases: the table is empty")
        _too_many(len(parameters), who, per_case)
        for i, case in enumerate(parameters):
            if not isinstance(case, dict):
                raise ModelError(f"{who}: case {i} must be a dict {{name: value}}, got {show(case)}")
        return [dict(c) for c in parameters], None
    raise ModelError(f"{who}: parameters must be a grid {{name: [values]}}, a list of cases {{name: value}}, a "
                     f"pandas DataFrame or a design (sweep.monte_carlo, ...), got {type(parameters).__name__}")


def checked_cases(model, cases, who):
    """Every name known and every value one its element accepts (the
    element's own ModelError), before any case runs; parameters as floats,
    run settings as one number or name each (a list, such as a
    per-coordinate atol, is a setting of the whole sweep, not a case's)."""
    known = model.parameters
    core = model.compiled()
    tried = set()
    out = []
    for i, case in enumerate(cases):
        checked = {}
        for name, value in case.items():
            if isinstance(value, np.generic):
                value = value.item()
            if name in RUN_SETTINGS:
                if isinstance(value, bool) or not isinstance(value, (str, numbers.Real)):
                    raise ModelError(f"{who}: case {i}: the run setting {name!r} must be one number or name a "
                                     f"case, got {show(value)}; a setting that is a list (a per-coordinate "
                                     f"atol) is the whole sweep's: give it as {name}=... or run={{...}}")
                if isinstance(value, numbers.Real):
                    number = real(value, f"{who}: case {i}: {name!r}")
                    value = int(value) if isinstance(value, numbers.Integral) else number
                checked[name] = value
                continue
            if name not in known:
                raise ModelError(f"{who}: case {i}: no parameter {name!r}; the model's parameters are "
                                 f"{', '.join(known)} (and the run settings {', '.join(RUN_SETTINGS)})")
            value = real(value, f"{who}: case {i}: {name!r}")
            if (name, value) not in tried:
                try:
                    core.with_parameters({name: value})
                except Exception as e:  # the element's own message
                    raise ModelError(f"{who}: case {i}: {name} = {value!r}: {e}") from None
                tried.add((name, value))
            checked[name] = value
        out.append(checked)
    return out

