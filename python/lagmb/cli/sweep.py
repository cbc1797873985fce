"""lagmb sweep SCENE --vary ...: a parameter study (lagmb.studies.sweep), its
table and its store; lagmb sweep --plot STORE: a finished study drawn."""

import math
import os
import sys
import warnings

from .. import _output_names
from ..errors import ModelError, SimulationError
from ..registry import BY_METHOD, SPATIAL_BY_METHOD
from ._common import (FAILED, OK, USAGE, Exit, cannot_write, load, need_matplotlib, number, option_number,
                      robot_options, whole)

_OUTPUT_KINDS = {  # --output KIND: what its ARG names (None: no ARG)
    "peak_reaction": "a joint or driver",
    "peak_effort": "a driver",
    "final": "a coordinate",
    "energy_drift": None,
}
_ROWS = 20          # more cases than this: the first and last rows and each output's range
_ENDS = 5           # rows shown at each end then


def add_parser(sub):
    """lagmb sweep's parser."""
    sweep = sub.add_parser(
        "sweep", help="a parameter study: a scene run over a grid of parameter values",
        description="Run a scene once per combination of the --vary values (mb.sweep): in this process, on "
                    "N processes (--workers N) or on a Dask cluster (--scheduler ADDRESS). Print each case's "
                    "parameters, status and outputs (for many cases the first and last rows and each "
                    "output's range); -o keeps them in a Zarr store, written as the cases finish, so the same "
                    "command run again finishes an interrupted study. With --plot STORE: draw a study's "
                    "outputs against its parameters instead.")
    sweep.add_argument("scene", nargs="?", help="the scene file (.toml), or a robot's URDF file (.urdf; give "
                                                "--t-end)")
    sweep.add_argument("--vary", action="append", metavar="NAME=SPEC",
                       help="a parameter and its values. NAME: a parameter of `lagmb info SCENE --parameters` "
                            "(crank.mass, B.at.y, rod.angle.start, ...) or a run setting (t_end, rtol, atol, "
                            "max_step, n_out, max_steps); SPEC: A:B:N (N values from A to B, both included, as "
                            "numpy.linspace) or V1,V2,... (a list). Several --vary make a grid of every "
                            "combination, the last varying fastest")
    sweep.add_argument("--output", action="append", dest="outputs", metavar="KIND[=ARG]",
                       help="a number each case gives, under the name in brackets: peak_reaction=JOINT, the "
                            "largest reaction force of a joint or driver in N [peak_reaction_JOINT]; "
                            "peak_effort=DRIVER, the largest magnitude of a driver's force or torque "
                            "[peak_effort_DRIVER]; final=COORDINATE, a coordinate's value at the end, e.g. "
                            "final=slider.x, der(slider.x) its rate [final_slider.x]; energy_drift, the largest "
                            "change of the energy in J [energy_drift]")
    sweep.add_argument("-o", dest="out", metavar="STORE",
                       help="the Zarr store (a folder, e.g. study.zarr) the cases are written to as they "
                            "finish; the same command again computes only the cases not there. With --plot: "
                            "the figure (default: the store's name with .png)")
    sweep.add_argument("--workers", type=whole, metavar="N",
                       help="run the cases on N processes (default 1: in this process)")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="run the cases on a Dask cluster, its scheduler's address (tcp://host:8786); "
                            "its workers run them (no --workers)")
    sweep.add_argument("--t-end", type=number, metavar="T", help="end time, instead of the scene's")
    sweep.add_argument("--batch-size", type=whole, metavar="B",
                       help="cases per task and per batch written to the store (default: the cases over 4 "
                            "tasks per worker, at most 256)")
    sweep.add_argument("--plot", metavar="STORE",
                       help="draw the study in STORE (a plot per output against the varied parameters, "
                            "lagmb.plotting.plot_sweep) to -o, instead of running one")
    robot_options(sweep)


def handle(args):
    """Runs the study (or, with --plot, draws one) and prints its table."""
    import time

    if args.plot is not None:
        return _plot(args)
    if not args.scene:
        raise Exit(USAGE, "give a scene file and --vary NAME=SPEC (or --plot STORE to draw a study)")
    scene = load(args.scene, args)
    # the options first: a mistake there costs no run
    grid, typed = _grid(args.vary)
    outputs = _outputs(scene, args.outputs or [])
    t0 = scene.settings.get("t0", 0.0)
    option_number("--t-end", args.t_end, above=t0)
    if args.workers is not None and args.workers < 1:
        raise Exit(USAGE, f"--workers {args.workers}: must be at least 1")
    if args.scheduler is not None and args.workers is not None:
        raise Exit(USAGE, f"--workers {args.workers}: the cluster at --scheduler {args.scheduler} runs the "
                          "cases on its own workers; give one or the other")
    if args.batch_size is not None and args.batch_size < 1:
        raise Exit(USAGE, f"--batch-size {args.batch_size}: must be at least 1")
    try:
        import xarray  # noqa: F401 - the results' type
        if args.out:
            import zarr  # noqa: F401
    except ImportError:
        raise Exit(USAGE, "lagmb sweep needs xarray (and zarr for -o): pip install 'lagmb[sweep]'") from None
    store = _checked_store(args.out) if args.out else None
    t_end = args.t_end if args.t_end is not None else scene.settings.get("t_end")
    if t_end is None and scene.settings.get("t_out") is not None:
        t_end = scene.settings["t_out"][-1]  # the sweep's cases take n_out output times, not t_out
    if t_end is None and "t_end" not in grid:
        raise Exit(USAGE, f"{args.scene}: no end time: give t_end in [simulation], --t-end or --vary t_end=...")
    from ..studies import sweep

    n = math.prod(len(values) for values in grid.values())
    executor, where = None, "in this process"
    if args.scheduler is not None:
        try:
            from distributed import Client
        except ImportError:
            raise Exit(USAGE, f"--scheduler {args.scheduler}: needs dask.distributed: "
                              "pip install 'lagmb[sweep]'") from None
        try:
            executor = Client(args.scheduler, timeout=10)
        except Exception as e:  # noqa: BLE001 - any failure to reach it: the address is the user's
            raise Exit(USAGE, f"--scheduler {args.scheduler}: cannot connect: {e}") from None
        where = f"on the Dask cluster at {args.scheduler}"
    elif args.workers and args.workers > 1:
        from concurrent.futures import ProcessPoolExecutor

        executor = ProcessPoolExecutor(args.workers, initializer=_quiet_worker)
        where = f"on {args.workers} processes"
    start = time.monotonic()
    interrupted = False
    ended = False
    try:
        ds = sweep(scene, grid, outputs=outputs, t_end=t_end, executor=executor, store=store, progress=True,
                   batch_size=args.batch_size)
        ended = True
    except ModelError as e:  # names a --vary, the store, or else the scene as a whole
        raise Exit(USAGE, _usage_error(str(e), args, typed)) from None
    except KeyboardInterrupt:
        if not store:
            raise
        interrupted = True
    except SimulationError as e:  # a worker process died (killed, out of memory): mb.sweep says what is kept
        raise Exit(FAILED, f"{args.scene}: the study stopped: {' '.join(str(e).split())}") from None
    except OSError as e:  # a cluster lost, a disk full
        text = " ".join(str(e).split()).rstrip(".")
        raise Exit(FAILED, f"{args.scene}: the study stopped: {type(e).__name__}" + (f": {text}" if text else "")
                   + (f"; the finished cases are in {store}: the same command finishes the study" if store
                      else "")) from None
    finally:
        if hasattr(executor, "scheduler_info"):
            executor.close()
        elif executor is not None:
            if not ended:  # interrupted or failed: the running batches are not waited for
                _stop_workers(executor)
            executor.shutdown(wait=True, cancel_futures=True)
    if interrupted:
        import gc

        with warnings.catch_warnings():  # zarr's writes cut short: not the user's concern
            warnings.filterwarnings("ignore", "coroutine .* was never awaited", RuntimeWarning)
            gc.collect()
        kept = os.path.isdir(store) and any(name.startswith("batch_") for name in os.listdir(store))
        raise Exit(130, f"interrupted; the finished cases are in {store}: the same command finishes the study"
                   if kept else f"interrupted before any case was written to {store}")
    elapsed = time.monotonic() - start

    span = "t_end varied" if "t_end" in grid else f"t = {t0:g} .. {t_end:g} s"
    print(f"{args.scene}: {_count(n, 'case')} (" + " x ".join(f"{name} {len(v)}" for name, v in grid.items())
          + f"), {span}, {where}")
    for line in _table(ds, list(grid), list(outputs)):
        print(line)
    if not outputs and (ds["steps"].values[ds["status"].values == "ok"] == 0).all() and \
            (ds["status"].values == "ok").any():
        print("  steps 0: every degree of freedom is driven, so each output is solved from the drivers "
              "(kinematic analysis), with no integration steps")
    computed = int(ds.attrs.get("computed_cases", n))
    line = f"  computed {computed} of {_count(n, 'case')} in {elapsed:.2f} s"
    if store and computed < n:
        line += f"; the other {n - computed} were in the store"
    print(line)
    if store:
        print(f"  results in {store} (lagmb sweep --plot {store} draws them)")
    else:
        print("  nothing written: -o STORE keeps the results (a Zarr store, resumable)")
    if not (ds["status"].values == "ok").any():
        print("lagmb sweep: every case failed", file=sys.stderr)
        return FAILED
    return OK


def _quiet_worker():
    """A --workers process ignores Ctrl-C (SIGINT goes to the terminal's
    whole process group): lagmb stops it, and prints one line, not each
    worker's traceback."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _stop_workers(executor):
    """Ends a process pool's workers now, their batches unfinished."""
    terminate = getattr(executor, "terminate_workers", None)  # Python 3.14
    if terminate is not None:
        terminate()
        return
    for process in list((getattr(executor, "_processes", None) or {}).values()):
        process.terminate()


def _count(n, one):
    return f"{n:,} {one}{'' if n == 1 else 's'}"


def _grid(specs):
    """({name: values}, {name: the --vary as typed}) from the --vary options
    (lagmb.studies.grid_from_text reads them)."""
    from ..studies import grid_from_text

    try:
        grid = grid_from_text(specs or [], who="--vary")
    except ModelError as e:
        raise Exit(USAGE, str(e)) from None
    return grid, dict(zip(grid, specs))


def _outputs(scene, specs):
    """{variable name: the built-in output} from the --output options,
    their arguments checked against the scene."""
    from ..studies import energy_drift, final, peak_effort, peak_reaction

    model = scene.model
    kinds = BY_METHOD if getattr(model, "dimension", 2) == 2 else SPATIAL_BY_METHOD
    roles = {kw["name"]: kinds[method].role for method, kw in model.elements if method in kinds}
    constraints = [name for name, role in roles.items() if role in ("joint", "driver")]
    drivers = [name for name, role in roles.items() if role == "driver"]
    coordinates = model.coordinate_names
    outputs = {}
    for spec in specs:
        kind, eq, arg = (s.strip() for s in spec.partition("="))
        if kind not in _OUTPUT_KINDS:
            raise Exit(USAGE, f"--output {spec}: unknown kind {kind!r}; the kinds are peak_reaction=JOINT, "
                              "peak_effort=DRIVER, final=COORDINATE and energy_drift")
        what = _OUTPUT_KINDS[kind]
        if what is None:
            if eq:
                raise Exit(USAGE, f"--output {spec}: {kind} takes no argument: --output {kind}")
            name, f = kind, energy_drift()
        else:
            if not arg:
                raise Exit(USAGE, f"--output {spec}: give {kind}=NAME, NAME {what} of the scene")
            if kind == "peak_reaction" and arg not in constraints:
                raise Exit(USAGE, f"--output {spec}: {scene.path} has no joint or driver {arg!r}; "
                                  + _listed("its joints and drivers", constraints))
            if kind == "peak_effort" and arg not in drivers:
                raise Exit(USAGE, f"--output {spec}: {scene.path} has no driver {arg!r}; "
                                  + _listed("its drivers", drivers))
            if kind == "final":
                plain = _output_names.parse(arg).base
                if plain not in coordinates:
                    raise Exit(USAGE, f"--output {spec}: {scene.path} has no coordinate {plain!r}; "
                                      + _listed("its coordinates", coordinates)
                                      + " (der(NAME) for a rate)")
            name, f = f"{kind}_{arg}", {"peak_reaction": peak_reaction, "peak_effort": peak_effort,
                                        "final": final}[kind](arg)
        if name in outputs:
            raise Exit(USAGE, f"--output {spec}: given twice")
        outputs[name] = f
    return outputs


def _listed(what, names):
    return f"{what} are {', '.join(names)}" if names else "it has none"


def _checked_store(path):
    """The -o store, checked before any case runs as mb.sweep checks it
    (lagmb.studies.check_store: a new folder, or a study's store; no folder
    of another's), in a folder that can take it."""
    from ..studies import check_store

    try:
        check_store(path)
    except ModelError as e:
        raise Exit(USAGE, f"-o {path}: {e}") from None
    target = path
    while not os.path.lexists(target):  # missing folders are made when writing
        target = os.path.dirname(os.path.abspath(target))
    if not os.path.isdir(target):
        raise Exit(USAGE, f"-o {path}: {target} is not a folder")
    why = cannot_write(target)
    if why:
        raise Exit(USAGE, f"-o {path}: {why}")
    return path


def _usage_error(text, args, typed):
    """mb.sweep's ModelError as a usage error naming the option it is about."""
    if args.out and repr(args.out) in text:  # the store: another sweep's, in use, damaged
        return f"-o {args.out}: {text}"
    for name, spec in typed.items():
        if f"'{name}'" in text or f" {name} = " in text:
            return f"--vary {spec}: {text}"
    return f"{args.scene}: {text}"


def _table(ds, names, outputs):
    """The lines lagmb sweep prints: a row a case (case number, the varied
    parameters, ok or failed, the outputs; steps without outputs), or for
    many cases the first and last rows and each output's range, then the
    failed cases' errors and the warnings."""
    import numpy as np

    n = ds.sizes["case"]
    status = ds["status"].values
    ok = status == "ok"
    shown = outputs or ["steps"]
    head = ["case"] + names + ["status"] + shown

    def cell(v):
        v = float(v)
        return "-" if math.isnan(v) else f"{v:.6g}"

    def row(i):
        return ([str(int(ds["case"].values[i]))] + [cell(ds[name].values[i]) for name in names]
                + ["ok" if ok[i] else "failed"]
                + [cell(ds[name].values[i]) if ok[i] or name != "steps" else "-" for name in shown])

    if n <= _ROWS:
        rows = [row(i) for i in range(n)]
    else:
        rows = ([row(i) for i in range(_ENDS)] + [["..."] + [""] * (len(head) - 1)]
                + [row(i) for i in range(n - _ENDS, n)])
    width = [max(len(r[k]) for r in rows + [head]) for k in range(len(head))]
    lines = ["  " + "  ".join(c.rjust(w) for c, w in zip(r, width)).rstrip() for r in [head] + rows]
    if n > _ROWS:
        lines.append(f"  the first and last {_ENDS} of {n:,} cases; over the {int(ok.sum()):,} ok cases:")
        w = max(len(name) for name in shown)
        for name in shown:
            values = np.where(ok, ds[name].values.astype(float), np.nan)
            if np.isnan(values).all():
                lines.append(f"    {name:<{w}}  no values")
                continue
            lo, hi = int(np.nanargmin(values)), int(np.nanargmax(values))
            lines.append(f"    {name:<{w}}  min {cell(values[lo])} (case {int(ds['case'].values[lo])}), "
                         f"max {cell(values[hi])} (case {int(ds['case'].values[hi])})")
    failed = np.flatnonzero(~ok)
    if len(failed):
        lines.append(f"  {len(failed):,} of {_count(n, 'case')} failed:")
        for i in failed[:5]:
            lines.append(f"    case {int(ds['case'].values[i])}: " + " ".join(str(status[i]).split())[:300])
        if len(failed) > 5:
            lines.append(f"    and {len(failed) - 5:,} more (the status variable holds every message)")
    warned = np.flatnonzero(ds["warnings"].values != "")
    if len(warned):
        i = warned[0]
        lines.append(f"  {_count(len(warned), 'case')} gave warnings (the warnings variable), e.g. case "
                     f"{int(ds['case'].values[i])}: " + " ".join(str(ds['warnings'].values[i]).split())[:300])
    return lines


def _plot(args):
    """lagmb sweep --plot STORE [-o FIG]: a study's outputs against its parameters."""
    given = [(option, value) for option, value in (
        ("--vary", args.vary), ("--output", args.outputs), ("--workers", args.workers),
        ("--scheduler", args.scheduler), ("--t-end", args.t_end), ("--batch-size", args.batch_size))
        if value is not None]
    if args.scene:
        raise Exit(USAGE, f"{args.scene}: --plot {args.plot} draws a finished study from its store; give no "
                          "scene with it")
    if given:
        option, value = given[0]
        shown = " ".join(value) if isinstance(value, list) else f"{value:g}" if isinstance(value, float) else value
        raise Exit(USAGE, f"{option} {shown}: --plot {args.plot} draws a finished study from its store; give "
                          f"no {option} with it")
    need_matplotlib("--plot")
    from ..scene.reader import plot_format_problem

    store = args.plot
    path = args.out or os.path.splitext(store.rstrip("/\\") or store)[0] + ".png"
    reason = plot_format_problem(path)
    if reason:
        raise Exit(USAGE, f"-o {path}: {reason}")
    try:
        from ..studies import open_store

        ds = open_store(store)
    except ImportError:
        raise Exit(USAGE, "lagmb sweep --plot needs xarray and zarr: pip install 'lagmb[sweep]'") from None
    except ModelError as e:
        raise Exit(USAGE, f"--plot {store}: {e}") from None
    except Exception as e:  # noqa: BLE001 - a folder zarr cannot read
        raise Exit(USAGE, f"--plot {store}: not a study's store ({type(e).__name__}: {e})") from None
    from .. import plotting
    from ..plotting import sweeps

    kinds = list(_OUTPUT_KINDS)
    try:  # the store keeps no order: lagmb sweep's kinds in --output's order, then the others by name
        drawn = sorted(sweeps.sweep_outputs(ds), key=lambda name: (
            next((k for k, kind in enumerate(kinds) if name.startswith(kind)), len(kinds)), name))
        plotting.plot_sweep(ds, path, outputs=drawn)
    except ValueError as e:
        raise Exit(USAGE, f"--plot {store}: {e}") from None
    except OSError as e:
        raise Exit(USAGE, f"-o {path}: cannot write: {e.strerror or e}") from None
    print(f"{store}: {_count(ds.sizes['case'], 'case')}, {_count(len(drawn), 'output')} "
          f"({', '.join(drawn)}) drawn in {path}")
    return OK
