"""Parameter studies: ``mb.sweep`` runs a model over a grid, a table or a
design of experiments on any ``concurrent.futures.Executor`` (a Dask
``Client`` included) and returns an ``xarray.Dataset``, optionally kept in
a Zarr store as cases finish so that an interrupted study resumes.

Each task carries the model as its description text (``ModelSpec``'s, the
FMU's), a batch of cases (parameter values and run settings) and the
output functions; a worker builds the model once per process and runs each
case with ``simulate(model, ..., parameters=case)``, exactly as a run alone
would. A case that fails is recorded with its error; the others go on.
"""

import concurrent.futures
import hashlib
import itertools
import json
import math
import numbers
import os
import pickle
import shutil
import time
import uuid

import numpy as np

from . import _core
from .errors import ModelError
from .model import Model, checked as _checked_model
from .progress import Progress
from .simulation import simulate

# the settings a case may vary beside the model's parameters (simulate's keywords)
RUN_SETTINGS = ("t_end", "rtol", "atol", "method", "formulation", "integrator", "analysis", "start", "max_step",
                "n_out", "max_steps")
_STORE_FORMAT = 1


# --- built-in outputs (picklable: module-level classes) ----------------------


class Final:
    """The value of a coordinate (``"slider.x"``, ``"rod.angle"``; ``der(...)``
    for its rate) at the run's last output."""

    def __init__(self, coordinate):
        self.coordinate = str(coordinate)

    def __call__(self, r):
        rate = self.coordinate.startswith("der(") and self.coordinate.endswith(")")
        name = self.coordinate[4:-1] if rate else self.coordinate
        body, _, which = name.rpartition(".")
        first, count = r._core.body_coordinates(body)
        suffixes = ("x", "y", "z", "e0", "e1", "e2", "e3") if count == 7 else ("x", "y", "angle")
        if which not in suffixes[:count]:
            raise ModelError(f"final: no coordinate {name!r} (body {body!r} has {', '.join(suffixes[:count])})")
        j = first + suffixes.index(which)
        return float((r.v if rate else r.q)[-1, j])

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

    def __repr__(self):
        return f"peak_reaction({self.element!r})"


class PeakEffort:
    """The largest magnitude of a driver's effort over the run (N or N m)."""

    def __init__(self, driver):
        self.driver = str(driver)

    def __call__(self, r):
        return float(np.abs(r.effort(self.driver)).max())

    def __repr__(self):
        return f"peak_effort({self.driver!r})"


class EnergyDrift:
    """max abs(E(t) - E(0)) over the run (J): for a conservative model, the
    integration error in energy."""

    def __call__(self, r):
        E = r.energy
        return float(np.abs(E - E[0]).max())

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
        except (TypeError, ValueError):
            raise ModelError(f"{who}: {name!r} needs (low, high), got {pair!r}") from None
        if not (np.isfinite(low) and np.isfinite(high) and low < high):
            raise ModelError(f"{who}: {name!r} needs finite low < high, got ({low}, {high})")
        names.append(name), lows.append(low), highs.append(high)
    return names, np.array(lows), np.array(highs)


def _count(n, who):
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
        raise ModelError(f"{who}: n must be a positive integer, got {n!r}")
    return int(n)


def monte_carlo(distributions, n, seed):
    """n random cases: ``distributions`` maps a parameter to (low, high) (a
    uniform distribution) or to a frozen ``scipy.stats`` distribution
    (anything with ``rvs(size=, random_state=)``); reproducible from
    ``seed`` (numpy's default generator)."""
    who = "sweep.monte_carlo"
    n = _count(n, who)
    if not isinstance(distributions, dict) or not distributions:
        raise ModelError(f"{who}: give the parameters as a non-empty dict {{name: (low, high) or distribution}}")
    rng = np.random.default_rng(seed)
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


# --- the cases ------------------------------------------------------------------


def _cases(parameters, who):
    """(list of case dicts, grid or None): a grid is [(name, values), ...]."""
    if isinstance(parameters, Design):
        return list(parameters.cases), None
    if hasattr(parameters, "to_dict") and hasattr(parameters, "columns"):  # a pandas DataFrame
        return [dict(row) for row in parameters.to_dict(orient="records")], None
    if isinstance(parameters, dict):
        if not parameters:
            raise ModelError(f"{who}: the grid is empty: give {{name: [values, ...]}}")
        grid = []
        for name, values in parameters.items():
            values = list(np.atleast_1d(np.asarray(values, dtype=object)))
            if not values:
                raise ModelError(f"{who}: the grid's axis {name!r} has no values")
            grid.append((name, values))
        names = [g[0] for g in grid]
        return [dict(zip(names, combo)) for combo in itertools.product(*(g[1] for g in grid))], grid
    if isinstance(parameters, (list, tuple)):
        if not parameters:
            raise ModelError(f"{who}: no cases: the table is empty")
        for i, case in enumerate(parameters):
            if not isinstance(case, dict):
                raise ModelError(f"{who}: case {i} must be a dict {{name: value}}, got {case!r}")
        return [dict(c) for c in parameters], None
    raise ModelError(f"{who}: parameters must be a grid {{name: [values]}}, a list of cases {{name: value}}, a "
                     f"pandas DataFrame or a design (sweep.monte_carlo, ...), got {type(parameters).__name__}")


def _check_cases(model, cases, who):
    """Every name known and every value one its element accepts (the
    element's own ModelError), before any case runs; values as floats
    (run settings: as simulate takes them)."""
    known = model.parameters()
    core = model.compiled()
    tried = set()
    out = []
    for i, case in enumerate(cases):
        checked = {}
        for name, value in case.items():
            if name in RUN_SETTINGS:
                checked[name] = value.item() if isinstance(value, np.generic) else value
                continue
            if name not in known:
                raise ModelError(f"{who}: case {i}: no parameter {name!r}; the model's parameters are "
                                 f"{', '.join(known)} (and the run settings {', '.join(RUN_SETTINGS)})")
            if isinstance(value, bool) or not isinstance(value, (numbers.Real, np.number)):
                raise ModelError(f"{who}: case {i}: {name!r} must be a number, got {value!r}")
            value = float(value)
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
    try:
        r = simulate(model, parameters=params or None, _warnings=caught, **run)
    except Exception as e:  # a case that fails is recorded, the sweep goes on
        record["status"] = f"{type(e).__name__}: {e}"
        r = None
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


def _dataset(cases, records, names, outputs, grid, t_out, coordinate_names, indices=None):
    """The cases' records as an xarray.Dataset indexed by case."""
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
    ds.attrs["grid"] = json.dumps([[name, [float(v) if isinstance(v, numbers.Real) else str(v) for v in values]]
                                   for name, values in grid]) if grid else ""
    return ds


def as_grid(ds):
    """A grid sweep's Dataset reshaped to its dimensions (one per varied
    parameter, in the order given), instead of indexed by case."""
    grid = json.loads(ds.attrs.get("grid") or "[]")
    if not grid:
        raise ModelError("sweep.as_grid: this sweep was not a grid (a table or a design has no dimensions)")
    names = [g[0] for g in grid]
    return ds.set_index(case=names).unstack("case")


# --- the store -------------------------------------------------------------------------


def _fingerprint(text, cases, settings, outputs, t_out):
    payload = json.dumps({"model": text, "cases": cases, "settings": settings,
                          "outputs": sorted(outputs), "t_out": None if t_out is None else list(map(float, t_out))},
                         sort_keys=True, default=str)
    return hashlib.sha256(payload.encode()).hexdigest()


class _Store:
    """A Zarr directory store: the sweep's description in the root
    attributes, and one group per finished batch ("batch_000012"), written
    under a temporary name and renamed when complete, so a group that
    exists is whole."""

    def __init__(self, path, description):
        import zarr

        self.path = os.fspath(path)
        root = zarr.open_group(self.path, mode="a")
        held = root.attrs.get("lagmb_sweep")
        if held is None:
            root.attrs["lagmb_sweep"] = description
        elif held.get("fingerprint") != description["fingerprint"]:
            raise ModelError(f"sweep: the store {self.path!r} holds another sweep (other cases, settings, outputs "
                             "or model): give another store, or delete this one to start again")
        for name in os.listdir(self.path):  # the leftovers of a batch interrupted while written
            if name.startswith("tmp_"):
                shutil.rmtree(os.path.join(self.path, name), ignore_errors=True)

    def finished(self):
        return sorted(int(name[len("batch_"):]) for name in os.listdir(self.path) if name.startswith("batch_"))

    def write(self, batch, ds):
        tmp = f"tmp_{batch:06d}_{uuid.uuid4().hex}"
        ds.to_zarr(self.path, group=tmp, mode="w", consolidated=False)
        os.rename(os.path.join(self.path, tmp), os.path.join(self.path, f"batch_{batch:06d}"))


def open_store(path):
    """The Dataset of a sweep's store (what ``mb.sweep(..., store=path)``
    wrote), its finished cases in case order."""
    import xarray as xr
    import zarr

    path = os.fspath(path)
    if not os.path.isdir(path):
        raise ModelError(f"sweep.open_store: no store at {path!r}")
    description = zarr.open_group(path, mode="r").attrs.get("lagmb_sweep")
    if description is None:
        raise ModelError(f"sweep.open_store: {path!r} is not a sweep's store")
    parts = [xr.open_zarr(path, group=name, consolidated=False).load()
             for name in sorted(os.listdir(path)) if name.startswith("batch_")]
    if not parts:
        raise ModelError(f"sweep.open_store: {path!r} holds no finished case yet")
    ds = xr.concat(parts, dim="case").sortby("case")
    # the variables in the order a sweep makes them (a store lists them by name)
    order = ["status", "warnings", "steps", "wall_time"] + list(description.get("outputs", [])) + ["q"]
    ds = ds[[v for v in order if v in ds.data_vars] + [v for v in ds.data_vars if v not in order]]
    ds.attrs["grid"] = description.get("grid", "")
    return ds


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
    missing one keeps the model's value), a pandas DataFrame, or a design
    (:func:`monte_carlo`, :func:`latin_hypercube`, :func:`sobol`). Names are
    those of ``model.parameters()`` (the FMU's and ``lagmb info``'s:
    ``"crank.mass"``, ``"spring.stiffness"``, ``"rod.angle.start"``) and the
    run settings ``t_end``, ``rtol``, ``atol``, ``method``, ``formulation``,
    ``integrator``, ``analysis``, ``start``, ``max_step``, ``n_out``,
    ``max_steps``. Every name and value is checked before any
    case runs (ModelError naming the case: an unknown name lists the
    parameters; a value the element refuses gives the element's message).

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
    task (default: the cases over 4 tasks per worker, at most 256).

    ``store``: a directory (a Zarr store) where each batch is written as it
    finishes; a sweep run again with the same store and the same model,
    cases, settings and outputs computes only the batches not there (an
    interrupted one resumes; another sweep in the store is a ModelError).
    ``lagmb.sweep.open_store(path)`` reads it back.

    The grid's shape: :func:`as_grid`. ``ds.attrs["computed_cases"]`` counts
    the cases this call ran (0 for a finished store).
    """
    import xarray  # noqa: F401 - the result's type; a clear ImportError now, not after the runs

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
    cases, grid = _cases(parameters, who)
    cases = _check_cases(model, cases, who)
    names = list(dict.fromkeys(k for case in cases for k in case))
    t_out = None if histories is None else [float(t) for t in np.atleast_1d(histories)]
    text = model.to_text()
    coordinate_names = model.coordinate_names()
    n = len(cases)
    workers = _workers(executor)
    if batch_size is None:
        batch_size = max(1, min(256, math.ceil(n / (4 * workers))))
    elif isinstance(batch_size, bool) or not isinstance(batch_size, numbers.Integral) or batch_size < 1:
        raise ModelError(f"{who}: batch_size must be a positive integer, got {batch_size!r}")
    batches = [(b, b * batch_size, min(n, (b + 1) * batch_size)) for b in range(math.ceil(n / batch_size))]

    held = None
    if store is not None:
        description = {"format": _STORE_FORMAT, "fingerprint": _fingerprint(text, cases, run_settings, outputs, t_out),
                       "cases": n, "batch_size": int(batch_size), "outputs": list(outputs),
                       "grid": json.dumps([[g[0], [float(v) if isinstance(v, numbers.Real) else str(v)
                                                   for v in g[1]]] for g in grid]) if grid else ""}
        held = _Store(store, description)
        import zarr

        batch_size_held = zarr.open_group(held.path, mode="r").attrs["lagmb_sweep"]["batch_size"]
        if batch_size_held != batch_size:  # the batches of the store decide
            batch_size = batch_size_held
            batches = [(b, b * batch_size, min(n, (b + 1) * batch_size)) for b in range(math.ceil(n / batch_size))]
        done = set(held.finished())
        batches = [b for b in batches if b[0] not in done]

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
        first, last = batch[1], batch[2]
        if held is not None:
            part = _dataset(cases, records, names, outputs, grid, t_out, coordinate_names, range(first, last))
            writes.append(writer.submit(held.write, batch[0], part))
        finished += last - first
        computed += last - first
        bar(finished)

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
            try:
                for future in _as_completed(executor, list(futures)):
                    take(futures[future], future.result())
            except BaseException:
                for f in futures:
                    f.cancel()
                raise
    finally:
        if writer is not None:  # every finished batch reaches the store, even when the sweep stops
            writer.shutdown(wait=True)
        close = getattr(bar, "close", None)
        if close:
            close()
    for w in writes:
        w.result()  # a write that failed (a full disk) is an error of the sweep

    if held is not None:
        ds = open_store(held.path)
    else:
        ds = _dataset(cases, records, names, outputs, grid, t_out, coordinate_names)
    ds.attrs["computed_cases"] = computed
    return ds


sweep.final = final
sweep.peak_reaction = peak_reaction
sweep.peak_effort = peak_effort
sweep.energy_drift = energy_drift
sweep.monte_carlo = monte_carlo
sweep.latin_hypercube = latin_hypercube
sweep.sobol = sobol
sweep.as_grid = as_grid
sweep.open_store = open_store
sweep.Design = Design
