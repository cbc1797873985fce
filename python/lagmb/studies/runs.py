"""Running a sweep's cases: a batch of cases in a worker (the model built
once per process from its description text, each case a ``simulate`` run
with its warnings and errors recorded), and the executors that run the
batches: this process, a ``concurrent.futures`` pool or a Dask client.
"""

import concurrent.futures

import numpy as np

from ..model import Model
from ..simulation import WARNINGS_INTO, simulate
from .cases import RUN_SETTINGS

_MODELS = {}  # description text -> Model, per process: built once per worker


def _model_of(text):
    model = _MODELS.get(text)
    if model is None:
        model = _MODELS[text] = Model.from_text(text)
    return model


def run_case(model, case, settings, outputs, t_out):
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


def run_batch(text, first, cases, settings, outputs, t_out):
    """A batch of consecutive cases in one task: [(index, record), ...]."""
    model = _model_of(text)
    return [(first + i, run_case(model, case, settings, outputs, t_out)) for i, case in enumerate(cases)]


# --- the executors ---------------------------------------------------------------------


def worker_count(executor):
    """How many cases the executor runs at once (1 in this process): the
    default batch size's divisor."""
    if executor is None:
        return 1
    if hasattr(executor, "scheduler_info"):  # a dask.distributed Client
        try:
            return max(1, sum(w.get("nthreads", 1) for w in executor.scheduler_info()["workers"].values()))
        except Exception:  # noqa: BLE001 - an estimate for the batch size only
            return 1
    return max(1, int(getattr(executor, "_max_workers", 1) or 1))


def submit_batch(executor, *args):
    """run_batch(*args) submitted to the executor: a future."""
    if hasattr(executor, "scheduler_info"):  # dask: every batch its own task (not cached by its arguments)
        return executor.submit(run_batch, *args, pure=False)
    return executor.submit(run_batch, *args)


def completed(executor, futures):
    """The futures as they finish (Dask's as_completed for a client)."""
    if hasattr(executor, "scheduler_info"):
        from distributed import as_completed

        return as_completed(futures)
    return concurrent.futures.as_completed(futures)


def lost_worker_errors(executor):
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

