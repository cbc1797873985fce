"""Parameter studies: ``mb.sweep`` runs a model over a grid, a table or a
design of experiments on any ``concurrent.futures.Executor`` (a Dask
``Client`` included) and returns an ``xarray.Dataset``, optionally kept in
a Zarr store as cases finish so that an interrupted study resumes.

Each task carries the model as its description text (``ModelSpec``'s, the
FMU's), a batch of cases (parameter values and run settings) and the
output functions; a worker builds the model once per process and runs each
case with ``simulate(model, ..., parameters=case)``, exactly as a run alone
would. A case that fails is recorded with its error; the others go on.
The store (its batches, markers and lock) is lagmb._store's.
"""

import concurrent.futures
import functools
import hashlib
import inspect
import itertools
import json
import marshal
import math
import numbers
import os
import pickle
import warnings

import numpy as np

from . import _output_names
from ._checks import array, decimal, real, show
from ._store import MAX_CASES, Store, description, ignored_warning, open_store, read, scan
from ._store import check_store  # noqa: F401 - public here: mb.sweep's and lagmb sweep -o's check of a store
from .errors import ModelError, SimulationError, extra_module
from .model import Model, checked as _checked_model
from .progress import Progress
from .simulation import WARNINGS_INTO, simulate

# the settings a case may vary beside the model's parameters (simulate's keywords)
#: the units of the run settings a sweep may vary (the others are numbers without one, or names)
_SETTING_UNITS = {"t_end": "s", "max_step": "s"}

RUN_SETTINGS = ("t_end", "rtol", "atol", "method", "formulation", "integrator", "analysis", "start", "max_step",
                "n_out", "max_steps")
_CASE_BYTES = 2500  # memory a case takes: its dict, the checked copy, its record, its row (measured)


# --- built-in outputs (picklable: module-level classes) ----------------------


class Final:
    """The value of a coordinate (``"slider.x"``, ``"rod.angle"``; ``der(...)``
    for its rate) at the run's last output."""

    def __init__(self, coordinate):
        self.coordinate = str(coordinate)

    def __call__(self, r):
        output = _output_names.parse(self.coordinate)
        names = r._core.coordinate_names()
        if output.base not in names:
            body = output.base.rpartition(".")[0]
            first, count = r._core.body_coordinates(body)
            has = ", ".join(n.rpartition(".")[2] for n in names[first:first + count])
            raise ModelError(f"final: no coordinate {output.base!r} (body {body!r} has {has})")
        return float((r.v if output.rate else r.q)[-1, names.index(output.base)])

    def unit(self, model):
        """m, rad (or 1 for an Euler parameter), per s for a rate."""
        output = _output_names.parse(self.coordinate)
        unit = {"x": "m", "y": "m", "z": "m", "angle": "rad"}.get(output.base.rpartition(".")[2], "")
        return (f"{unit}/s" if unit else "1/s") if output.rate else unit

    def __repr__(self):
        return f"final({self.coordinate!r})"


class PeakReaction:
    """The largest magnitude of the force a joint or driver applies on its
    second body over the run (N): max over outputs of the norm of the
    reaction's force components."""

    def __init__(self, element):
        self.element = str(element)

    def __call__(self, r):
        R = r.reaction(self.element)
        force = R[:, :3] if R.shape[1] == 6 else R[:, :2]
        return float(np.linalg.norm(force, axis=1).max())

    def unit(self, model):
        return "N"

    def __repr__(self):
        return f"peak_reaction({self.element!r})"


class PeakEffort:
    """The largest magnitude of a driver's effort over the run (N along a
    slide or a body's x, y, z; N m along an angle)."""

    def __init__(self, driver):
        self.driver = str(driver)

    def __call__(self, r):
        return float(np.abs(r.effort(self.driver)).max())

    def unit(self, model):
        from . import registry
        from ._drawing import effort_unit

        kinds = registry.BY_METHOD if model.dimension == 2 else registry.SPATIAL_BY_METHOD
        return effort_unit(model.elements, kinds, self.driver)

    def __repr__(self):
        return f"peak_effort({self.driver!r})"


class EnergyDrift:
    """max abs(E(t) - E(0)) over the run (J): for a conservative model, the
    integration error in energy."""

    def __call__(self, r):
        E = r.energy
        return float(np.abs(E - E[0]).max())

    def unit(self, model):
        return "J"

    def __repr__(self):
        return "energy_drift()"


def final(coordinate):
    """Output: the coordinate's value at the last output (:class:`Final`)."""
    return Final(coordinate)


def peak_reaction(element):
    """Output: the largest force magnitude of a joint or driver (:class:`PeakReaction`)."""
    return PeakReaction(element)


def peak_effort(driver):
    """Output: the largest magnitude of a driver's effort (:class:`PeakEffort`)."""
    return PeakEffort(driver)


def energy_drift():
    """Output: the largest change of the energy over the run (:class:`EnergyDrift`)."""
    return EnergyDrift()


# --- designs ------------------------------------------------------------------


class Design:
    """Cases made by a design of experiments: ``cases`` (a list of dicts),
    ``kind`` and ``seed``. Pass it as ``mb.sweep(model, design)``."""

    def __init__(self, cases, kind, seed):
        self.cases, self.kind, self.seed = cases, kind, seed

    def __len__(self):
        return len(self.cases)

    def __repr__(self):
        return f"<lagmb.sweep.Design: {self.kind}, {len(self.cases)} cases, seed {self.seed}>"


def _bounds(bounds, who):
    if not isinstance(bounds, dict) or not bounds:
        raise ModelError(f"{who}: give the parameters as a non-empty dict {{name: (low, high)}}, got {bounds!r}")
    names, lows, highs = [], [], []
    for name, pair in bounds.items():
        try:
            low, high = (float(x) for x in pair)
        except (TypeError, ValueError, OverflowError):
            raise ModelError(f"{who}: {name!r} needs (low, high), got {show(pair)}") from None
        if not (np.isfinite(low) and np.isfinite(high) and low < high):
            raise ModelError(f"{who}: {name!r} needs finite low < high, got ({low}, {high})")
        names.append(name), lows.append(low), highs.append(high)
    return names, np.array(lows), np.array(highs)


def _count(n, who):
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
        raise ModelError(f"{who}: n must be a positive integer, got {show(n)}")
    if n > MAX_CASES:
        raise ModelError(f"{who}: n = {show(n)} cases: at most {MAX_CASES:,} in one design (sweep.MAX_CASES)")
    return int(n)


def _seed(seed, who):
    """The seed as numpy takes it: None (fresh entropy) or an integer >= 0
    (a Generator or SeedSequence passes as is)."""
    if seed is None or isinstance(seed, (np.random.Generator, np.random.SeedSequence)):
        return seed
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0:
        raise ModelError(f"{who}: seed must be an integer >= 0 (or None), got {show(seed)}")
    return int(seed)


def monte_carlo(distributions, n, seed):
    """n random cases: ``distributions`` maps a parameter to (low, high) (a
    uniform distribution) or to a frozen ``scipy.stats`` distribution
    (anything with ``rvs(size=, random_state=)``); reproducible from
    ``seed`` (numpy's default generator)."""
    who = "sweep.monte_carlo"
    n = _count(n, who)
    if not isinstance(distributions, dict) or not distributions:
        raise ModelError(f"{who}: give the parameters as a non-empty dict {{name: (low, high) or distribution}}")
    rng = np.random.default_rng(_seed(seed, who))
    columns = {}
    for name, d in distributions.items():
        if hasattr(d, "rvs"):
            columns[name] = np.asarray(d.rvs(size=n, random_state=rng), dtype=float)
        else:
            _, low, high = _bounds({name: d}, who)
            columns[name] = rng.uniform(low[0], high[0], size=n)
    return Design([{k: float(v[i]) for k, v in columns.items()} for i in range(n)], "monte_carlo", seed)


def _qmc(kind, bounds, n, seed):
    from scipy.stats import qmc

    who = f"sweep.{kind}"
    n = _count(n, who)
    seed = _seed(seed, who)
    names, low, high = _bounds(bounds, who)
    sampler = (qmc.LatinHypercube(d=len(names), seed=seed) if kind == "latin_hypercube"
               else qmc.Sobol(d=len(names), scramble=True, seed=seed))
    points = qmc.scale(sampler.random(n), low, high)
    return Design([dict(zip(names, map(float, row))) for row in points], kind, seed)


def latin_hypercube(bounds, n, seed):
    """n cases of a Latin hypercube over ``bounds`` ({name: (low, high)}),
    scipy.stats.qmc, reproducible from ``seed``."""
    return _qmc("latin_hypercube", bounds, n, seed)


def sobol(bounds, n, seed):
    """n cases of a scrambled Sobol sequence over ``bounds`` ({name: (low,
    high)}), scipy.stats.qmc, reproducible from ``seed`` (n a power of 2
    keeps its balance)."""
    return _qmc("sobol", bounds, n, seed)


# --- a grid written as text -------------------------------------------------------

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


# --- the cases ------------------------------------------------------------------


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


def _cases(parameters, who, per_case=_CASE_BYTES):
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


def _check_cases(model, cases, who):
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


# --- running (in a worker) ---------------------------------------------------------

_MODELS = {}  # description text -> Model, per process: built once per worker


def _model_of(text):
    model = _MODELS.get(text)
    if model is None:
        model = _MODELS[text] = Model.from_text(text)
    return model


def _run_case(model, case, settings, outputs, t_out):
    """One case: a dict with status, outputs, steps, wall_time and, with
    t_out, the coordinates there."""
    params = {k: v for k, v in case.items() if k not in RUN_SETTINGS}
    run = dict(settings)
    run.update({k: v for k, v in case.items() if k in RUN_SETTINGS})
    if t_out is not None:
        run.pop("n_out", None)
        run["t_out"] = t_out
        run.setdefault("t_end", t_out[-1])
    record = {"status": "ok", "warnings": "", "outputs": {}, "steps": -1, "wall_time": float("nan"),
              "history": None}
    # lagmb's warnings are kept with the case (handed back, not warned: the
    # warnings module's catch_warnings is not thread-safe, and threads run cases)
    caught = []
    token = WARNINGS_INTO.set(caught)
    try:
        r = simulate(model, parameters=params or None, **run)
    except Exception as e:  # a case that fails is recorded, the sweep goes on
        record["status"] = f"{type(e).__name__}: {e}"
        r = None
    finally:
        WARNINGS_INTO.reset(token)
    record["warnings"] = "; ".join(f"{type(w).__name__}: {w}" for w in caught)
    if r is None:
        return record
    record["steps"] = int(r.stats.get("steps", 0))
    record["wall_time"] = float(r.stats.get("wall_time", float("nan")))
    if t_out is not None:
        record["history"] = np.asarray(r.q, dtype=float)
    for name, f in outputs.items():
        try:
            record["outputs"][name] = np.asarray(f(r), dtype=float)
        except Exception as e:  # noqa: BLE001 - the output function is the user's
            record["status"] = f"output {name!r} failed: {type(e).__name__}: {e}"
            record["outputs"] = {}
            break
    return record


def _run_batch(text, first, cases, settings, outputs, t_out):
    """A batch of consecutive cases in one task: [(index, record), ...]."""
    model = _model_of(text)
    return [(first + i, _run_case(model, case, settings, outputs, t_out)) for i, case in enumerate(cases)]


# --- the Dataset ---------------------------------------------------------------------


def _dataset(cases, records, names, outputs, grid, t_out, coordinate_names, indices=None, units=None):
    """The cases' records as an xarray.Dataset indexed by case; each varied
    parameter's and output's unit (``units``: {name: unit}) in its
    ``attrs["units"]``."""
    import xarray as xr

    indices = list(range(len(cases))) if indices is None else list(indices)
    k = len(indices)
    data = {
        "status": ("case", np.array([records[i]["status"] for i in indices], dtype=object)),
        "warnings": ("case", np.array([records[i]["warnings"] for i in indices], dtype=object)),
        "steps": ("case", np.array([records[i]["steps"] for i in indices], dtype=np.int64)),
        "wall_time": ("case", np.array([records[i]["wall_time"] for i in indices], dtype=float)),
    }
    for name in outputs:
        shape = next((records[i]["outputs"][name].shape for i in indices if name in records[i]["outputs"]), ())
        values = np.full((k,) + shape, np.nan)
        for row, i in enumerate(indices):
            v = records[i]["outputs"].get(name)
            if v is not None:
                if v.shape != shape:
                    raise ModelError(f"sweep: output {name!r} gave shape {v.shape} in case {i} and {shape} in "
                                     "another: an output must have one shape in every case")
                values[row] = v
        data[name] = (("case",) + tuple(f"{name}_dim{d}" for d in range(len(shape))), values)
    coords = {"case": np.array(indices, dtype=np.int64)}
    for name in names:
        column = [cases[i].get(name, np.nan) for i in indices]
        try:
            coords[name] = ("case", np.array(column, dtype=float))
        except (TypeError, ValueError):
            coords[name] = ("case", np.array([str(c) for c in column], dtype=object))
    if t_out is not None:
        coords["time"] = np.asarray(t_out, dtype=float)
        coords["coordinate"] = np.array(coordinate_names, dtype=object)
        q = np.full((k, len(t_out), len(coordinate_names)), np.nan)
        for row, i in enumerate(indices):
            h = records[i]["history"]
            if h is not None and h.shape[0] == len(t_out):
                q[row] = h
        data["q"] = (("case", "time", "coordinate"), q)
    ds = xr.Dataset(data, coords=coords)
    for name, unit in (units or {}).items():
        if unit and name in ds.variables:
            ds[name].attrs["units"] = unit
    ds.attrs["grid"] = _grid_text(grid)
    return ds


def _grid_text(grid):
    """A grid [(name, values), ...] as JSON, as a Dataset's attrs["grid"]
    and a store keep it (as_grid reads it); "" for cases of no grid."""
    return json.dumps([[name, [float(v) if isinstance(v, numbers.Real) else str(v) for v in values]]
                       for name, values in grid]) if grid else ""


def as_grid(ds):
    """A grid sweep's Dataset reshaped to its dimensions (one per varied
    parameter, in the order given), instead of indexed by case."""
    grid = json.loads(ds.attrs.get("grid") or "[]")
    if not grid:
        raise ModelError("sweep.as_grid: this sweep was not a grid (a table or a design has no dimensions)")
    names = [g[0] for g in grid]
    return ds.set_index(case=names).unstack("case")


# --- what a sweep is made of (its store's fingerprint) ---------------------------------

_BUILT_IN = (Final, PeakReaction, PeakEffort, EnergyDrift)


def _digest(data):
    return hashlib.sha256(data).hexdigest()[:16]


def _pickled(value):
    """A digest of value's pickle (of its type's name, if it has none)."""
    try:
        return _digest(pickle.dumps(value, protocol=4))
    except Exception:  # noqa: BLE001 - any pickling failure: the type is what is known
        return _digest(f"{type(value).__module__}.{type(value).__qualname__}".encode())


def _what(f):
    """What an output computes, as its store records it: a built-in's kind
    and argument; a function's module and qualified name with a digest of
    its code (its source; the bytecode if it has none), defaults, closure
    and bound object; a partial's function and arguments; another
    callable's class and pickle. A function changed under the same name is
    another output."""
    if isinstance(f, _BUILT_IN):
        return repr(f)
    if isinstance(f, functools.partial):
        return f"partial({_what(f.func)}, {_pickled((f.args, f.keywords))})"
    func = getattr(f, "__func__", f)  # a bound method: its function, and its object below
    code = getattr(func, "__code__", None)
    if code is None:  # a callable object
        return f"{type(f).__module__}.{type(f).__qualname__} ({_pickled(f)})"
    try:
        text = inspect.getsource(func).encode()
    except (OSError, TypeError):  # made by exec or at a prompt: its bytecode
        text = marshal.dumps(code)
    closure = []
    for cell in func.__closure__ or ():
        try:
            closure.append(cell.cell_contents)
        except ValueError:  # a cell not filled yet
            closure.append(None)
    state = _digest(" ".join(_pickled(v) for v in [func.__defaults__, func.__kwdefaults__,
                                                    getattr(f, "__self__", None)] + closure).encode())
    return f"{func.__module__}.{func.__qualname__} ({_digest(text)} {state})"


def _made_of(text, cases, settings, outputs, t_out):
    """What a sweep is made of, as its store keeps it: a digest of the
    model, the cases, the run settings and the output times, and what each
    output computes (_what)."""
    def digest(value):
        return _digest(json.dumps(value, sort_keys=True, default=str).encode())

    return {"model": digest(text), "cases": digest(cases), "settings": digest(settings),
            "histories": digest(None if t_out is None else list(map(float, t_out))),
            "outputs": {name: _what(f) for name, f in outputs.items()}}


# --- sweep ------------------------------------------------------------------------------


def _workers(executor):
    if executor is None:
        return 1
    if hasattr(executor, "scheduler_info"):  # a dask.distributed Client
        try:
            return max(1, sum(w.get("nthreads", 1) for w in executor.scheduler_info()["workers"].values()))
        except Exception:  # noqa: BLE001 - an estimate for the batch size only
            return 1
    return max(1, int(getattr(executor, "_max_workers", 1) or 1))


def _submit(executor, *args):
    if hasattr(executor, "scheduler_info"):  # dask: every batch its own task (not cached by its arguments)
        return executor.submit(_run_batch, *args, pure=False)
    return executor.submit(_run_batch, *args)


def _as_completed(executor, futures):
    if hasattr(executor, "scheduler_info"):
        from distributed import as_completed

        return as_completed(futures)
    return concurrent.futures.as_completed(futures)


def sweep(model, parameters, *, outputs=None, t_end=None, run=None, histories=None, executor=None, store=None,
          progress=True, batch_size=None, **settings):
    """Runs ``model`` (a Model or a Scene) once per case and returns an
    ``xarray.Dataset`` indexed by ``case`` in the order given.

    ``parameters``: the cases, as a grid ``{name: [values, ...]}`` (every
    combination, the last name varying fastest), a list of dicts
    ``[{name: value, ...}, ...]`` (names may differ between cases; a
    missing one keeps the model's value), a pandas DataFrame (a missing
    value, NaN, as in a list of dicts), or a design (:func:`monte_carlo`,
    :func:`latin_hypercube`, :func:`sobol`); at most ``MAX_CASES``
    (10,000,000) cases, and no more than the machine's memory holds (both
    refused before any case is made). Names are
    those of ``model.parameters`` (the FMU's and ``lagmb info``'s:
    ``"crank.mass"``, ``"spring.stiffness"``, ``"rod.angle.start"``) and the
    run settings ``t_end``, ``rtol``, ``atol``, ``method``, ``formulation``,
    ``integrator``, ``analysis``, ``start``, ``max_step``, ``n_out``,
    ``max_steps``. Every name and value is checked before any
    case runs (ModelError naming the case: an unknown name lists the
    parameters; a value the element refuses gives the element's message).
    A case's run setting is one number or name: a list (a per-coordinate
    ``atol``) is a setting of the whole sweep (``atol=[...]``).

    ``outputs``: ``{name: f}`` with ``f(result)`` a number or an array (one
    shape in every case): a module-level function or the built-ins
    :func:`final`, :func:`peak_reaction`, :func:`peak_effort`,
    :func:`energy_drift` (a process or Dask executor pickles them).
    ``histories``: output times; then ``ds["q"]`` (case, time, coordinate)
    holds every coordinate there. Every case also records ``status``
    ("ok", or the error's type and message: a failed case never stops the
    sweep; its outputs are NaN), ``warnings`` (those its run gave, e.g. an
    AssemblyWarning; "" if none), ``steps`` and ``wall_time`` (s).

    Run settings: ``t_end`` and any ``simulate`` keyword (``rtol``,
    ``method``, ...) as keywords or in ``run={...}``; a Scene's
    ``[simulation]`` settings are the defaults.

    ``executor``: None runs in this process; anything with
    ``concurrent.futures.Executor``'s ``submit`` (a ThreadPoolExecutor: the
    runs release the GIL; a ProcessPoolExecutor) or a
    ``dask.distributed.Client`` (``Client("tcp://scheduler:8786")`` runs on
    a cluster). Cases go in batches of ``batch_size`` consecutive cases per
    task (default: the cases over 4 tasks per worker, at most 256). A
    worker process that dies (killed, out of memory) stops the sweep with a
    SimulationError; the batches finished by then stay in the store.

    ``store``: a directory (a Zarr store) where each batch is written as it
    finishes; a sweep run again with the same store and the same model,
    cases, settings and outputs (what each computes: a built-in's
    argument, a function's code) computes only the batches not there (an
    interrupted one resumes; a batch that is not whole, e.g. copied in
    part, is computed again with a warning; another sweep in the store is
    a ModelError saying what differs). The store is a new or empty folder,
    or a sweep's store: any other folder is refused, nothing written into
    it. One sweep at a time writes a store (another is a ModelError naming
    its pid). ``lagmb.sweep.open_store(path)`` reads it back.

    The grid's shape: :func:`as_grid`. ``ds.attrs["computed_cases"]`` counts
    the cases this call ran (0 for a finished store).
    """
    extra_module("xarray", "sweep", "mb.sweep")  # the result's type: a clear error now, not after the runs

    who = "sweep"
    scene_settings = {}
    if hasattr(model, "model") and hasattr(model, "settings"):  # a Scene
        scene_settings = {k: v for k, v in model.settings.items() if k != "t_out"}
        model = model.model
    _checked_model(model, who)
    run_settings = dict(scene_settings)
    run_settings.update(run or {})
    run_settings.update(settings)
    if t_end is not None:
        run_settings["t_end"] = t_end
    if "parameters" in run_settings or "sensitivities" in run_settings:
        raise ModelError(f"{who}: the cases give the parameters; sensitivities are not swept")
    outputs = dict(outputs or {})
    for name, f in outputs.items():
        if not isinstance(name, str) or not callable(f):
            raise ModelError(f"{who}: outputs must be {{name: function of the Result}}, got {name!r}: {f!r}")
        if name in ("status", "warnings", "steps", "wall_time", "q", "case"):
            raise ModelError(f"{who}: the output name {name!r} is taken by what every case records")
    coordinate_names = model.coordinate_names
    t_out = None
    if histories is not None:
        t_out = [float(t) for t in array(histories, f"{who}: histories")]
        if not t_out:
            raise ModelError(f"{who}: histories: give at least one output time")
    # what a case holds in memory until the Dataset is made: refused up front if more than the machine has
    per_case = _CASE_BYTES + 8 * len(outputs) + 16 * len(t_out or ()) * len(coordinate_names)
    cases, grid = _cases(parameters, who, per_case)
    cases = _check_cases(model, cases, who)
    names = list(dict.fromkeys(k for case in cases for k in case))
    text = model.to_text()
    n = len(cases)
    workers = _workers(executor)
    if batch_size is None:
        batch_size = max(1, min(256, math.ceil(n / (4 * workers))))
    elif isinstance(batch_size, bool) or not isinstance(batch_size, numbers.Integral) or batch_size < 1:
        raise ModelError(f"{who}: batch_size must be a positive integer, got {show(batch_size)}")
    batch_size = int(batch_size)

    held = None
    if store is not None:
        made_of = _made_of(text, cases, run_settings, outputs, t_out)
        held = Store(store, description(made_of, n, batch_size, outputs, _grid_text(grid)),
                     who)  # locked until the sweep ends
    # the units the Dataset's variables carry (attrs["units"]): the varied parameters' and the
    # built-in outputs' (a function of the user's has none)
    units = {p["name"]: p["unit"] for p in model.parameter_info if p["name"] in names}
    units.update({name: unit for name, unit in _SETTING_UNITS.items() if name in names})
    units.update({name: f.unit(model) for name, f in outputs.items() if hasattr(f, "unit")})
    try:
        return _sweep(held, text, cases, names, grid, run_settings, outputs, t_out, coordinate_names, executor,
                      batch_size, progress, who, units)
    finally:
        if held is not None:
            held.close()


def _sweep(held, text, cases, names, grid, run_settings, outputs, t_out, coordinate_names, executor, batch_size,
           progress, who, units):
    """sweep's runs, its arguments checked (and its store, if any, locked)."""
    n = len(cases)
    done = set()
    if held is not None:
        batch_size = held.held["batch_size"]  # the batches of the store decide
        whole, damaged, ignored = scan(held.path, held.held)
        done = set(whole)
        if ignored:
            ignored_warning(held.path, held.held, ignored, who, stacklevel=3)
        if damaged:
            warnings.warn(f"{who}: the store {held.path!r}: " + "; ".join(damaged[b] for b in sorted(damaged))
                          + ": computed again", UserWarning, stacklevel=3)
    batches = [(b, b * batch_size, min(n, (b + 1) * batch_size)) for b in range(math.ceil(n / batch_size))
               if b not in done]

    records = {}
    # a batch's store write (about 0.1 s) goes to a thread of its own, so the
    # results of the next batches are taken meanwhile; each write is whole or absent
    writer = concurrent.futures.ThreadPoolExecutor(1) if held is not None else None
    writes = []
    bar = Progress(0, n, enabled=progress, label="sweep", unit="cases")
    finished = n - sum(last - first for _, first, last in batches)
    computed = 0

    def take(batch, result):
        nonlocal finished, computed
        for i, record in result:
            records[i] = record
        b, first, last = batch
        if held is not None:
            part = _dataset(cases, records, names, outputs, grid, t_out, coordinate_names, range(first, last),
                            units)
            writes.append(writer.submit(held.write, b, first, last, part))
            for i in range(first, last):  # in the store now: the final Dataset is read from there
                del records[i]
        finished += last - first
        computed += last - first
        bar(finished)

    lost = _lost_worker(executor)
    try:
        if executor is None:
            for batch in batches:
                b, first, last = batch
                take(batch, _run_batch(text, first, cases[first:last], run_settings, outputs, t_out))
        else:
            if not isinstance(executor, concurrent.futures.ThreadPoolExecutor) and not hasattr(executor, "scheduler_info"):
                try:  # a process pool pickles the task in a thread of its own: say it now, not per batch
                    pickle.dumps((outputs, run_settings))
                except Exception as e:  # noqa: BLE001 - any pickling failure
                    raise ModelError(f"{who}: the outputs cannot be sent to the executor's processes ({e}): a "
                                     "process pool pickles them, so give module-level functions or the "
                                     "built-ins (a Dask client takes lambdas too)") from None
            futures = {}
            try:
                for batch in batches:
                    b, first, last = batch
                    futures[_submit(executor, text, first, cases[first:last], run_settings, outputs, t_out)] = batch
            except (TypeError, AttributeError) as e:  # pickle: a lambda or a local function for a process pool
                for f in futures:
                    f.cancel()
                raise ModelError(f"{who}: the tasks could not be sent to the executor ({e}); a process or Dask "
                                 "executor needs outputs it can pickle: module-level functions or the built-ins"
                                 ) from None
            taken = set()
            try:
                for future in _as_completed(executor, list(futures)):
                    take(futures[future], future.result())
                    taken.add(future)
            except lost:  # the batches finished before a worker died are kept
                for f in futures:
                    if f not in taken and f.done() and not f.cancelled() and f.exception() is None:
                        take(futures[f], f.result())
                    else:
                        f.cancel()
                raise
            except BaseException:
                for f in futures:
                    f.cancel()
                raise
    except lost as e:
        error = e
    else:
        error = None
    finally:
        if writer is not None:  # every finished batch reaches the store, even when the sweep stops
            _finish_writes(writer, writes)
        close = getattr(bar, "close", None)
        if close:
            close()
    for w in writes:
        w.result()  # a write that failed (a full disk) is an error of the sweep
    if error is not None:
        kept = (f"the {finished:,} finished cases are in the store {held.path!r}: the same sweep computes the rest"
                if held is not None else "its finished cases are lost (store= keeps them as they finish)")
        raise SimulationError(f"{who}: a worker process died (killed, out of memory, or crashed) with "
                              f"{n - finished:,} of {n:,} cases unfinished ({type(error).__name__}); {kept}"
                              ) from error

    if held is not None:
        whole, damaged, _ = scan(held.path, held.held)
        ds = read(held.path, held.held, whole, damaged, who, "left out (written wrong just now: the sweep run "
                   "again computes them)", stacklevel=3)
    else:
        ds = _dataset(cases, records, names, outputs, grid, t_out, coordinate_names, units=units)
    ds.attrs["computed_cases"] = computed
    return ds


def _finish_writes(writer, writes):
    """Waits for the store's writes; a Ctrl-C meanwhile lets the write under
    way end (no batch cut short) and starts no other. It waits on the
    writes, not on the thread: an interrupted Thread.join (Python < 3.13)
    takes the thread for ended, and the write under way would be cut at exit."""
    try:
        concurrent.futures.wait(writes)
    except KeyboardInterrupt:
        for w in writes:
            w.cancel()  # those not started
        concurrent.futures.wait(writes)
        raise
    finally:
        writer.shutdown(wait=False)


def _lost_worker(executor):
    """The exceptions that say a worker process died: a broken process pool,
    a Dask worker killed."""
    lost = (concurrent.futures.BrokenExecutor,)
    if hasattr(executor, "scheduler_info"):
        try:
            from distributed import KilledWorker

            lost += (KilledWorker,)
        except ImportError:
            pass
    return lost


sweep.final = final
sweep.peak_reaction = peak_reaction
sweep.peak_effort = peak_effort
sweep.energy_drift = energy_drift
sweep.monte_carlo = monte_carlo
sweep.latin_hypercube = latin_hypercube
sweep.sobol = sobol
sweep.as_grid = as_grid
sweep.grid_from_text = grid_from_text
sweep.open_store = open_store
sweep.MAX_CASES = MAX_CASES
sweep.Design = Design
