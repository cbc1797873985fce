"""``mb.sweep``: a model run over many cases, end to end: the arguments
checked, the cases cut into batches, the batches run (lagmb.studies.runs)
and written to the store as they finish (lagmb.studies.store), and the
results returned as one Dataset (lagmb.studies.dataset).
"""

import concurrent.futures
import math
import numbers
import pickle
import warnings

from .._checks import array, show
from ..errors import ModelError, SimulationError, extra_module
from ..model import checked as _checked_model
from ..progress import Progress
from .cases import CASE_BYTES, SETTING_UNITS, cases_of, checked_cases
from .dataset import dataset, grid_text
from .made_of import made_of
from .runs import completed, lost_worker_errors, run_batch, submit_batch, worker_count
from .store import Store, description, ignored_warning, read, scan


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
    per_case = CASE_BYTES + 8 * len(outputs) + 16 * len(t_out or ()) * len(coordinate_names)
    cases, grid = cases_of(parameters, who, per_case)
    cases = checked_cases(model, cases, who)
    names = list(dict.fromkeys(k for case in cases for k in case))
    text = model.to_text()
    n = len(cases)
    workers = worker_count(executor)
    if batch_size is None:
        batch_size = max(1, min(256, math.ceil(n / (4 * workers))))
    elif isinstance(batch_size, bool) or not isinstance(batch_size, numbers.Integral) or batch_size < 1:
        raise ModelError(f"{who}: batch_size must be a positive integer, got {show(batch_size)}")
    batch_size = int(batch_size)

    held = None
    if store is not None:
        made = made_of(text, cases, run_settings, outputs, t_out)
        held = Store(store, description(made, n, batch_size, outputs, grid_text(grid)), who)  # locked until the end
    # the units the Dataset's variables carry (attrs["units"]): the varied parameters' and the
    # built-in outputs' (a function of the user's has none)
    units = {p["name"]: p["unit"] for p in model.parameter_info if p["name"] in names}
    units.update({name: unit for name, unit in SETTING_UNITS.items() if name in names})
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
            part = dataset(cases, records, names, outputs, grid, t_out, coordinate_names, range(first, last),
                            units)
            writes.append(writer.submit(held.write, b, first, last, part))
            for i in range(first, last):  # in the store now: the final Dataset is read from there
                del records[i]
        finished += last - first
        computed += last - first
        bar(finished)

    lost = lost_worker_errors(executor)
    try:
        if executor is None:
            for batch in batches:
                b, first, last = batch
                take(batch, run_batch(text, first, cases[first:last], run_settings, outputs, t_out))
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
                    futures[submit_batch(executor, text, first, cases[first:last], run_settings, outputs, t_out)] = batch
            except (TypeError, AttributeError) as e:  # pickle: a lambda or a local function for a process pool
                for f in futures:
                    f.cancel()
                raise ModelError(f"{who}: the tasks could not be sent to the executor ({e}); a process or Dask "
                                 "executor needs outputs it can pickle: module-level functions or the built-ins"
                                 ) from None
            taken = set()
            try:
                for future in completed(executor, list(futures)):
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
        ds = dataset(cases, records, names, outputs, grid, t_out, coordinate_names, units=units)
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

