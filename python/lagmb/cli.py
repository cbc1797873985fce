"""The lagmb command.

    lagmb run SCENE [-o results.npz|results.csv] [--plot out.png] [--animate out.gif]
                    [--fps F] [--speed S] [--frames N] [--trace POINT ...] [--view ELEV,AZIM]
                    [--t-end T] [--rtol R] [--n-out N] [--quiet]
    lagmb info SCENE [--parameters] | --methods | --kinds
    lagmb accuracy SCENE [--methods M ...] [--tolerances RTOL ...] [--t-end T]
                   [-o table.json] [--plot out.png] [--quiet]
    lagmb modes SCENE [--at-time T] [--count K] [--gif out.gif] [--mode I] [--view ELEV,AZIM]
    lagmb sweep SCENE --vary NAME=SPEC [--vary ...] [--output KIND[=ARG] ...] [-o study.zarr]
                [--workers N | --scheduler ADDRESS] [--t-end T] [--batch-size B]
    lagmb sweep --plot study.zarr [-o study.png]
    lagmb demo [--plot out.png] [--quiet]

Exit status: 0 done; 2 a usage or scene error (one line naming the file,
line, table and key, or the option); 1 the simulation failed (the results
computed until then are still written to -o, if given); 3 an internal error,
a bug in lagmb (one line; LAGMB_TRACEBACK=1 shows the traceback); 130
interrupted (Ctrl-C). lagmb modes exits 1 where the scene has no static
equilibrium (a free body under gravity) or its joints cannot be closed.
lagmb sweep exits 0 when at least one case ran (failed cases are listed),
1 when every case failed.
"""

import argparse
import csv
import math
import os
import re
import sys
import warnings

from ._version import __version__
from .errors import ModelError, SimulationError
from .registry import BY_METHOD, SPATIAL_BY_METHOD, markdown
from .scene.schema import ELEMENT_TABLES, elements, methods

OK, FAILED, USAGE, INTERNAL = 0, 1, 2, 3


class _Exit(Exception):
    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def _number(text):
    """argparse type: a number as TOML and XML Schema write it
    (lagmb._checks.decimal; float() would read '1_0' as 10)."""
    from ._checks import decimal

    try:
        return decimal(text, "number")
    except ModelError as e:
        raise argparse.ArgumentTypeError(str(e).partition(": ")[2]) from None


def _whole(text):
    """argparse type: a whole number, written as _number reads it (its
    range is the option's own check, which names the limit)."""
    try:
        value = _number(text)
    except argparse.ArgumentTypeError:
        value = math.nan
    if not (math.isfinite(value) and value.is_integer()):
        raise argparse.ArgumentTypeError(f"{text.strip()!r} is not a whole number")
    return int(value)


def _parser():
    parser = argparse.ArgumentParser(prog="lagmb", description="Planar and spatial multibody dynamics")
    parser.add_argument("--version", action="version", version=f"lagmb {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    run = sub.add_parser("run", help="simulate a scene file and write its results",
                         description="Simulate a scene file (TOML, docs/scene-format.md) with its "
                                     "[simulation] settings; write what -o and [output] ask for.")
    run.add_argument("scene", help="the scene file (.toml), or a robot's URDF file (.urdf; give --t-end)")
    run.add_argument("-o", "--output", metavar="FILE",
                     help="results file: .npz (all arrays) or .csv (t, coordinates, listed "
                          "reactions); default: [output] file")
    run.add_argument("--plot", metavar="PNG", help="plot the results (default: [output] plot)")
    run.add_argument("--animate", metavar="GIF",
                     help="animate the mechanism (default: [output] animate)")
    run.add_argument("--html", metavar="HTML",
                     help="write the run as an interactive page (3D view, play, time slider, plots; opens "
                          "offline in a browser: lagmb.view)")
    run.add_argument("--view", metavar="ELEV,AZIM",
                     help="viewpoint of a spatial animation, degrees (default: [output] view, else 25,-60)")
    run.add_argument("--fps", metavar="F",
                     help="frames per second of the animation, above 0 and at most 50 (default 25)")
    run.add_argument("--speed", metavar="S",
                     help="speed of the animation: 1 plays the run in real time, 0.1 ten times slower "
                          "(default 1, except that a run shorter than 1 s plays in 1 s)")
    run.add_argument("--frames", metavar="N",
                     help="at most N frames in the animation (default 1000; they then last longer, the "
                          "animation keeps its duration)")
    run.add_argument("--trace", nargs="+", metavar="POINT",
                     help="draw the paths of these points in the animation: a body (its centre of mass), a "
                          "joint or other element (where it attaches to its moving body), or BODY:X,Y "
                          "(BODY:X,Y,Z in space; m, in the body's axes)")
    run.add_argument("--t-end", type=_number, metavar="T", help="end time, instead of the scene's")
    run.add_argument("--rtol", type=_number, metavar="R", help="relative tolerance, instead of the scene's")
    run.add_argument("--n-out", type=_whole, metavar="N", help="number of output times, instead of the scene's")
    run.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    _robot_options(run)

    info = sub.add_parser("info", help="bodies, coordinates, constraints and degrees of freedom",
                          description="Load a scene and report its size, the rank of its "
                                      "constraint Jacobian at the assembled initial position, "
                                      "its degrees of freedom and any redundant equations; "
                                      "or, with --methods, the integration methods; with --kinds, "
                                      "the element kinds.")
    info.add_argument("scene", nargs="?", help="the scene file (.toml), or a robot's URDF file (.urdf)")
    info.add_argument("--methods", action="store_true",
                      help="list the integration methods (formulation, integrator, what each supports)")
    info.add_argument("--kinds", action="store_true",
                      help="the element kinds and their parameters (Markdown; docs/modelling.md)")
    info.add_argument("--parameters", action="store_true",
                      help="also list the scene's run-time parameters (the names simulate(..., "
                           "parameters=...), sweeps and the FMU take), with value, unit and meaning")
    _robot_options(info)

    acc = sub.add_parser("accuracy", help="work-precision study of a scene: error against CPU time",
                         description="Run the scene with each method at each tolerance, measure the "
                                     "error against a tight reference run, the CPU time and the "
                                     "constraint drift; print the table and draw the diagram.")
    acc.add_argument("scene", help="the scene file (.toml)")
    acc.add_argument("--methods", nargs="+", metavar="M",
                     help="methods (default: all): " + ", ".join(_method_names()))
    acc.add_argument("--tolerances", nargs="+", type=_number, metavar="RTOL",
                     help="relative tolerances (default: 1e-3 .. 1e-11)")
    acc.add_argument("--t-end", type=_number, metavar="T", help="end time, instead of the scene's")
    acc.add_argument("-o", "--output", metavar="JSON", help="write the table as JSON")
    acc.add_argument("--plot", metavar="PNG", help="draw error vs CPU time and drift vs time")
    acc.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")

    fmu = sub.add_parser("fmu", help="build an FMI 3.0 co-simulation FMU of a scene",
                         description="Build a binary FMI 3.0 co-simulation FMU for this platform "
                                     "that embeds the scene: its inputs are the scene's inputs, its "
                                     "outputs the body coordinates and rates and the reactions and "
                                     "efforts of [output], its parameters the numbers given to the "
                                     "elements (docs/modelling.md). Needs FMPy's FMI headers "
                                     "(pip install 'lagmb[fmu]') and a C compiler.")
    fmu.add_argument("scene", help="the scene file (.toml)")
    fmu.add_argument("-o", "--output", metavar="FMU", help="the FMU file (default: the scene's name .fmu)")
    fmu.add_argument("--name", help="the model's name in the FMU (default: the scene file's name)")
    fmu.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")

    modes = sub.add_parser("modes", help="vibration modes about the static equilibrium",
                           description="Find the scene's static equilibrium (mb.equilibrium; an unstable "
                                       "one too) and its vibration modes about it (mb.modes); print each "
                                       "mode's kind, frequency, damping ratio and the coordinate it moves "
                                       "most, lowest frequency first; --gif animates one.")
    modes.add_argument("scene", help="the scene file (.toml), or a robot's URDF file (.urdf)")
    modes.add_argument("--at-time", type=_number, metavar="T",
                       help="the time the equilibrium holds at, for drivers and forces that depend on time "
                            "(default the scene's t0, else 0)")
    modes.add_argument("--count", type=_whole, metavar="K", help="list the K lowest modes only (default all)")
    modes.add_argument("--gif", metavar="GIF",
                       help="animate a mode: its shape about the equilibrium (lagmb.plotting.animate_mode)")
    modes.add_argument("--mode", type=_whole, metavar="I",
                       help="the mode --gif animates, by its number in the table (default the first "
                            "vibration mode)")
    modes.add_argument("--view", metavar="ELEV,AZIM",
                       help="viewpoint of a spatial model's --gif, degrees (default: [output] view, else 25,-60)")
    _robot_options(modes)

    _sweep_parser(sub)

    demo = sub.add_parser("demo", help="simulate the seed pendulum and check it against closed forms")
    demo.add_argument("--plot", metavar="PNG", help="write a plot of angle and pin force")
    demo.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    return parser


def main(argv=None):
    parser = _parser()
    args = parser.parse_args(argv)  # usage errors exit 2 here
    with warnings.catch_warnings():  # restores showwarning for callers of main()
        warnings.showwarning = _one_line_warning(args.command)
        return _main(args)


def _one_line_warning(command):
    """A warning as one line, without the source line Python shows."""
    def show(message, category, filename, lineno, file=None, line=None):
        text = " ".join(str(message).split())
        print(f"lagmb {command}: {category.__name__}: {text}", file=file or sys.stderr)
    return show


def _main(args):
    try:
        if args.command == "demo":
            return _demo(args)
        if args.command == "info":
            return _info(args)
        if args.command == "accuracy":
            return _accuracy(args)
        if args.command == "fmu":
            return _fmu(args)
        if args.command == "modes":
            return _modes(args)
        if args.command == "sweep":
            return _sweep(args)
        return _run(args)
    except _Exit as e:
        print(f"lagmb {args.command}: " + " ".join(str(e).splitlines()), file=sys.stderr)
        return e.code
    except KeyboardInterrupt:
        print(f"lagmb {args.command}: interrupted", file=sys.stderr)
        return 130
    except Exception as e:  # noqa: BLE001 - a bug: one line, not a traceback, unless asked
        if os.environ.get("LAGMB_TRACEBACK"):
            raise
        text = " ".join(str(e).split())
        print(f"lagmb {args.command}: internal error: {type(e).__name__}"
              + (f": {text[:300]}" if text else "")
              + " (a bug in lagmb; LAGMB_TRACEBACK=1 shows where)", file=sys.stderr)
        return INTERNAL


def _fmu(args):
    from .fmu import build_fmu

    scene = _load(args.scene)
    stem = os.path.splitext(os.path.basename(args.scene))[0]
    path = args.output or stem + ".fmu"
    try:
        build_fmu(scene, path, name=args.name or stem)
    except ModelError as e:
        raise _Exit(FAILED, str(e)) from None
    except OSError as e:
        raise _Exit(FAILED, f"cannot write {path}: {e.strerror or e}") from None
    if not args.quiet:
        print(f"wrote {path}")
    return OK


def _method_names():
    from .accuracy import METHODS  # the variable-step methods of lagmb.methods(), and presets

    return list(METHODS)


def _accuracy(args):
    from .accuracy import work_precision

    scene = _load(args.scene)
    if args.plot:
        _need_matplotlib("--plot")
    t_end = args.t_end or scene.settings.get("t_end")
    if not t_end:
        raise _Exit(USAGE, f"{args.scene}: no t_end in [simulation]; give --t-end")
    say = (lambda *a, **k: None) if args.quiet else print

    def progress(i, n, row):
        if not args.quiet:
            print(f"  [{i}/{n}] {row['method']} rtol {row['rtol']:.0e}: {row['status']}",
                  file=sys.stderr)

    try:
        wp = work_precision(scene.model, t_end, methods=args.methods, tolerances=args.tolerances,
                            t0=scene.settings.get("t0", 0.0), progress=progress)
    except ModelError as e:
        raise _Exit(USAGE, str(e)) from None
    except SimulationError as e:
        raise _Exit(FAILED, str(e)) from None
    say(wp.table())
    for ref in wp.reference_info.values():
        say(f"reference run: {ref['method']} at rtol {ref['rtol']:.0e}, atol {ref['atol']:.0e}")
    if args.output:
        wp.save(args.output)
        say(f"table written to {args.output}")
    if args.plot:
        wp.plot(args.plot, title=f"{args.scene}: t = 0 .. {t_end:g} s")
        say(f"diagram written to {args.plot}")
    return OK


def _need_matplotlib(what):
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise _Exit(USAGE, f"{what} needs matplotlib: pip install 'lagmb[plot]'") from None


def _demo(args):
    from . import demo as d

    if args.plot:
        _need_matplotlib("--plot")
    d.run(plot=args.plot, out=(lambda *a, **k: None) if args.quiet else print)
    return OK


def _robot_options(command):
    """The options of mb.load_urdf, for a .urdf given as the scene."""
    robot = command.add_argument_group("a URDF file (mb.load_urdf)")
    robot.add_argument("--floating-base", action="store_true", help="the root link is a free body")
    robot.add_argument("--no-limits", action="store_true", help="leave the joints' position limits out")
    robot.add_argument("--no-dynamics", action="store_true", help="leave the joints' damping and friction out")
    robot.add_argument("--no-mimic", action="store_true", help="read mimic joints as joints of their own")


def _load_urdf(args):
    """A Scene of the robot in a URDF file: its model, no settings (the
    command line gives them), its elements listed by table."""
    from .scene import Scene, SceneElement
    from .urdf import load_urdf

    try:
        model = load_urdf(args.scene, floating_base=args.floating_base, limits=not args.no_limits,
                          dynamics=not args.no_dynamics, mimic=not args.no_mimic)
    except ModelError as e:
        raise _Exit(USAGE, str(e)) from None
    kinds = elements(3)
    listed = [SceneElement(kinds[method].table, kinds[method].type, values["name"], None)
              for method, values in model.elements()]
    if not model.bodies:
        raise _Exit(USAGE, f"{args.scene}: no bodies: every link is fixed to the root (give --floating-base to "
                           "let the root move)")
    return Scene(model, path=args.scene, elements=listed)


def _load(path, args=None):
    from .scene import load_scene

    if str(path).lower().endswith(".urdf") and args is not None:
        return _load_urdf(args)
    try:
        scene = load_scene(path)
    except ModelError as e:
        raise _Exit(USAGE, str(e)) from None
    except OSError as e:
        raise _Exit(USAGE, f"cannot read {path}: {e.strerror or e}") from None
    if not scene.names("bodies") and not scene.names("particles"):
        # nothing moves, and the core is not asked about an empty model
        raise _Exit(USAGE, f"{path}: no bodies: a scene needs at least one [[bodies]] or "
                           "[[particles]] table (enabled)")
    return scene


def _option_number(option, value, above):
    """A command-line number, if given, must be finite and greater than above."""
    if value is not None and not (math.isfinite(value) and value > above):
        raise _Exit(USAGE, f"{option} {value:g}: must be finite and greater than {above:g}")


def _output(scene, given, option, key, problem):
    """The path of an output: the option's (given) or else the scene's [output]
    key. Checked before the run that fills it: its format (problem(path) says
    why not, or None) and that its folder can take it."""
    path = given or scene.output.get(key)
    if not path:
        return None

    def refuse(reason):
        if given:
            raise _Exit(USAGE, f"{option} {path}: {reason}")
        raise _Exit(USAGE, str(scene.output_error(key, f"{path!r}: {reason}")))

    reason = problem(path)
    if reason:
        refuse(reason)
    if os.path.isdir(path):
        refuse("is a directory")
    folder = os.path.dirname(os.path.abspath(path))
    while not os.path.lexists(folder):  # missing folders are made when writing
        folder = os.path.dirname(folder)
    if not os.path.isdir(folder):
        refuse(f"{folder} is not a folder")
    target = path if os.path.exists(path) else folder
    why = _cannot_write(target)
    if why:
        refuse(why)
    return path


def _cannot_write(target):
    """Why a file cannot be written (target a file) or made (target a
    folder), or None: tried, not read from the permission bits, which root
    passes everywhere (a folder such as /proc refuses it all the same)."""
    import tempfile

    where = f"cannot make a file in {target}" if os.path.isdir(target) else f"cannot write {target}"
    try:
        if os.path.isdir(target):
            fd, probe = tempfile.mkstemp(dir=target, prefix=".lagmb-probe-")
            os.close(fd)
            os.remove(probe)
        elif os.path.isfile(target):
            with open(target, "ab"):  # opened to append, nothing written: the file is left as it is
                pass
        elif not os.access(target, os.W_OK):  # a device or a pipe: not opened (a pipe would wait)
            return f"{where}: permission denied"
    except OSError as e:
        return f"{where}: {e.strerror or e}"
    return None


def _results_format_problem(path):
    if os.path.splitext(path)[1].lower() not in (".npz", ".csv"):
        return "the results file must end in .npz or .csv"
    return None


# --- run ------------------------------------------------------------------------

def _run(args):
    from .progress import Progress
    from .scene import MAX_OUTPUTS, SceneError
    from .scene.reader import animation_format_problem, plot_format_problem

    scene = _load(args.scene, args)
    # the options, outputs and formats first: a mistake there costs no run
    _option_number("--t-end", args.t_end, above=scene.settings.get("t0", 0.0))
    _option_number("--rtol", args.rtol, above=0.0)
    if args.n_out is not None and not 2 <= args.n_out <= MAX_OUTPUTS:
        raise _Exit(USAGE, f"--n-out {args.n_out}: must be at least 2 and at most {MAX_OUTPUTS:,}")
    out = _output(scene, args.output, "-o", "file", _results_format_problem)
    if args.plot or scene.output.get("plot"):
        _need_matplotlib("plotting")
    plot = _output(scene, args.plot, "--plot", "plot", plot_format_problem)
    if args.animate or scene.output.get("animate"):
        _need_matplotlib("animating")
    animate = _output(scene, args.animate, "--animate", "animate", animation_format_problem)
    html_page = _output(scene, args.html, "--html", "html",
                        lambda p: None if p.lower().endswith((".html", ".htm")) else "must end in .html")
    if html_page:
        try:
            from .viewer import _three_js

            _three_js()
        except ModelError as e:  # three.js comes with the 'view' extra
            raise _Exit(USAGE, f"--html {html_page}: {e}") from None
    view = _view(scene, args.view)
    motion = _animation_options(args, scene, animate)

    overrides = {}
    if args.t_end is not None:
        overrides["t_end"] = args.t_end
    if args.rtol is not None:
        overrides["rtol"] = args.rtol
    if args.n_out is not None:
        overrides["n_out"] = args.n_out
    settings = {**scene.settings, **overrides}
    if "t_end" not in settings and "t_out" not in settings:
        raise _Exit(USAGE, f"{args.scene}: no end time: give t_end in [simulation] or --t-end")
    t_end = settings.get("t_end")
    if t_end is None:
        t_end = settings["t_out"][-1]

    progress = Progress(settings.get("t0", 0.0), t_end, enabled=not args.quiet)
    try:
        result = scene.run(progress=progress, **overrides)
    except SceneError as e:  # names the file, line and key
        raise _Exit(USAGE, str(e)) from None
    except ModelError as e:  # about an option it names, or else the scene as a whole
        words = set(re.findall(r"\w+", str(e)))
        option = next((f"--{k.replace('_', '-')} {v:g}: " for k, v in overrides.items()
                       if k in words), "")
        raise _Exit(USAGE, f"{args.scene}: {option}{e}") from None
    except MemoryError:  # e.g. millions of outputs of a large model
        n = overrides.get("n_out") or len(settings.get("t_out") or ()) or settings.get("n_out", 101)
        raise _Exit(FAILED, f"{args.scene}: out of memory in the run ({n} outputs); "
                            "ask for fewer outputs (n_out, --n-out)") from None
    except SimulationError as e:
        progress.close()
        reason = " ".join(str(e).split()).rstrip(".")
        message = f"{args.scene}: simulation failed at t = {e.t:.6g} s: {reason}"
        partial = e.result
        if out:  # on the same line: one line per failure
            if partial is not None and len(partial.t):
                try:
                    _write(out, partial, scene)
                    message += (f"; partial results ({len(partial.t)} outputs, t = "
                                f"{partial.t[0]:.6g} .. {partial.t[-1]:.6g} s) written to {out}")
                except Exception as w:  # noqa: BLE001 - report, keep the exit status
                    message += f"; the partial results could not be written to {out}: {w}"
            else:
                message += f"; no outputs were computed, {out} not written"
        raise _Exit(FAILED, message) from None
    finally:
        progress.close()

    say = (lambda *a: None) if args.quiet else print
    _summary(scene, result, say)
    try:
        if out:
            _write(out, result, scene)
            say(f"  results written to {out}")
        if plot:
            _plotting().plot_result(result, plot)
            say(f"  plot written to {plot}")
        if animate:
            _plotting().animate(result, animate, view=view, progress=not args.quiet, **motion)
            say(f"  animation written to {animate}")
        if html_page:
            from .viewer import view as view_page

            folder = os.path.dirname(os.path.abspath(html_page))
            os.makedirs(folder, exist_ok=True)
            try:
                page = view_page(result, html_page, title=os.path.basename(str(scene.path or args.scene)))
            except ModelError as e:  # it could not be written after all
                raise _Exit(USAGE, f"--html {html_page}: {e}") from None
            say(f"  interactive view written to {html_page} ({page.size / 1e6:.2f} MB; open it in a browser)")
        if not (out or plot or animate or html_page):
            say("  nothing written: -o FILE (.npz or .csv), --plot, --animate or --html keep the outputs")
    except OSError as e:
        raise _Exit(USAGE, f"cannot write {e.filename or ''}: {e.strerror or e}") from None
    return OK


def _view(scene, given):
    """The viewpoint of a spatial animation: --view ELEV,AZIM, else the
    scene's [output] view, else (25, -60)."""
    view = tuple(scene.output.get("view", (25.0, -60.0)))
    if given is not None:
        try:
            view = tuple(_number(x) for x in given.split(","))
        except argparse.ArgumentTypeError:
            view = ()
        if len(view) != 2 or not all(math.isfinite(x) for x in view):
            raise _Exit(USAGE, f"--view {given}: must be two numbers ELEV,AZIM (degrees)")
    return view


def _plotting():
    from . import plotting

    return plotting


def _animation_options(args, scene, animate):
    """animate's fps, speed, frames and trace from --fps, --speed, --frames
    and --trace, checked before the run (a usage error, exit 2, names the
    option and the value as typed); they need an animation (--animate or
    [output] animate)."""
    plotting = _plotting()
    from .plotting import frames
    given = [(option, value) for option, value in (("--fps", args.fps), ("--speed", args.speed),
                                                   ("--frames", args.frames)) if value is not None]
    if args.trace:
        given.append(("--trace", " ".join(args.trace)))
    if given and not animate:
        option, value = given[0]
        raise _Exit(USAGE, f"{option} {value}: there is no animation to apply it to; give --animate GIF "
                           "(or animate in [output])")
    motion = {}
    try:
        if args.fps is not None:
            motion["fps"] = frames.checked_setting("--fps", _typed(args.fps), 0.0, frames.MAX_FPS)
        if args.speed is not None:
            motion["speed"] = frames.checked_setting("--speed", _typed(args.speed), 0.0)
        if args.frames is not None:
            motion["frames"] = frames.checked_setting("--frames", _typed(args.frames), 0, whole=True)
        if args.trace:
            plotting.trace_points(scene.model, args.trace, context="--trace")
            motion["trace"] = list(args.trace)
    except ModelError as e:
        raise _Exit(USAGE, str(e)) from None
    return motion


class _NoNumber(str):
    """Text of the command line that _number does not read ('1_0'): shown
    as typed, and float() of it fails, as for any word."""

    def __float__(self):
        raise ValueError(f"{str(self)!r} is not a decimal number")


def _typed(text):
    """A number option's text for a checker that calls float(): as typed,
    or a _NoNumber if _number does not read it (float() takes '1_0' for 10)."""
    try:
        _number(text)
    except argparse.ArgumentTypeError:
        return _NoNumber(text)
    return text


def _summary(scene, r, say):
    s = r.stats
    say(f"{scene.path}: {len(r.t)} outputs, t = {r.t[0]:.6g} .. {r.t[-1]:.6g} s")
    parts = [f"{s[k]} {label}" for k, label in (
        ("steps", "steps"), ("residual_evals", "residual evaluations"),
        ("jacobian_evals", "Jacobians"), ("lu_factorizations", "LU factorizations"),
        ("augmented_factorizations", "augmented-system factorizations")) if k in s]
    if "wall_time" in s:
        parts.append(f"{1e3 * s['wall_time']:.1f} ms")
    say(f"  method {s.get('method', s.get('formulation', '?'))}: " + ", ".join(parts))
    say(f"  max |Phi| {r.residual.max():.2e}")


def coordinate_names(model):
    """Names of the coordinates in order: body.x, body.y, body.angle (a
    particle has .x, .y); in space body.x, body.y, body.z and the Euler
    parameters body.e0 .. body.e3 (w, x, y, z)."""
    core = model.compiled()
    names = [f"q{i}" for i in range(core.n_coordinates)]
    for body in model.bodies:
        first, count = core.body_coordinates(body.name)
        suffixes = ("x", "y", "z", "e0", "e1", "e2", "e3") if count == 7 else ("x", "y", "angle")[:count]
        for k, suffix in enumerate(suffixes):
            names[first + k] = f"{body.name}.{suffix}"
    return names


def _selection(scene):
    """(reactions, efforts) for npz and csv files, from [output]."""
    output = scene.output
    joints = scene.names("joints")
    drivers = scene.names("drivers")
    npz = (output.get("reactions", joints), output.get("efforts", drivers))
    csv_ = (output.get("reactions", []), output.get("efforts", []))
    return npz, csv_


def _reaction(r, name, frame):
    return r.reaction(name, frame="joint") if frame == "joint" else r.reaction(name)


def _write(path, r, scene):
    import numpy as np

    frame = scene.output.get("reaction_frame", "global")
    (npz_reactions, npz_efforts), (csv_reactions, csv_efforts) = _selection(scene)
    parent = os.path.dirname(os.path.abspath(path))
    os.makedirs(parent, exist_ok=True)
    if r.stats.get("analysis") == "kinematic":  # no multipliers: no reactions, no efforts
        listed = list(scene.output.get("reactions", [])) + list(scene.output.get("efforts", []))
        if listed:
            print(f"lagmb: a kinematic analysis computes no reactions or driver efforts; "
                  f"{', '.join(listed)} not written", file=sys.stderr)
        npz_reactions = npz_efforts = csv_reactions = csv_efforts = []
    if path.lower().endswith(".npz"):
        arrays = dict(t=r.t, q=r.q, v=r.v, a=r.a, energy=r.energy,
                      residual=r.residual, coordinates=np.array(coordinate_names(r.model)))
        if r.stats.get("analysis") != "kinematic":
            arrays["lam"] = r.lam
        for name in npz_reactions:
            arrays[f"reaction_{name}"] = _reaction(r, name, frame)
        for name in npz_efforts:
            arrays[f"effort_{name}"] = r.effort(name)
        with open(path, "wb") as fh:
            np.savez(fh, **arrays)
        return
    columns = ["t"] + coordinate_names(r.model)
    blocks = [r.t[:, None], r.q]
    force = ("f1", "f2") if frame == "joint" else ("fx", "fy")
    for name in csv_reactions:
        columns += [f"{name}.{force[0]}", f"{name}.{force[1]}", f"{name}.torque"]
        blocks.append(_reaction(r, name, frame))
    for name in csv_efforts:
        columns.append(f"{name}.effort")
        blocks.append(np.asarray(r.effort(name))[:, None])
    if scene.output.get("energy", False):
        columns.append("energy")
        blocks.append(r.energy[:, None])
    data = np.hstack([np.asarray(b, dtype=float).reshape(len(r.t), -1) for b in blocks])
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(columns)
        w.writerows(data.tolist())  # floats as repr: they read back exactly


# --- modes ----------------------------------------------------------------------

def _modes(args):
    from .errors import EquilibriumError
    from .linear import modes as vibration_modes
    from .scene.reader import animation_format_problem
    from .statics import equilibrium

    scene = _load(args.scene, args)
    # the options first: a mistake there costs no analysis
    t = float(scene.settings.get("t0", 0.0)) if args.at_time is None else args.at_time
    if not math.isfinite(t):
        raise _Exit(USAGE, f"--at-time {args.at_time:g}: must be a finite time (s)")
    if args.count is not None and args.count < 1:
        raise _Exit(USAGE, f"--count {args.count}: must be at least 1")
    if args.mode is not None and args.mode < 0:
        raise _Exit(USAGE, f"--mode {args.mode}: must be the number of a mode in the table, 0 or more")
    gif = None
    if args.gif:
        _need_matplotlib("--gif")
        gif = _output(scene, args.gif, "--gif", "animate", animation_format_problem)
    else:
        given = [(option, value) for option, value in (("--mode", args.mode), ("--view", args.view))
                 if value is not None]
        if given:
            option, value = given[0]
            raise _Exit(USAGE, f"{option} {value}: there is no animation to apply it to; give --gif GIF")
    view = _view(scene, args.view)

    try:
        at = equilibrium(scene.model, t, allow_unstable=True)
        found = vibration_modes(scene.model, at)
    except EquilibriumError as e:  # none nearby (a free body under gravity), or a force function failed
        raise _Exit(FAILED, f"{scene.path}: {e}") from None
    except ModelError as e:  # the scene as a whole (non-conservative forces: no real modes)
        raise _Exit(USAGE, f"{scene.path}: {e}") from None
    except SimulationError as e:  # the joints cannot be closed
        raise _Exit(FAILED, f"{scene.path}: the equilibrium cannot be found: {e}") from None
    n = len(found)
    index = None
    if gif:
        if args.mode is not None and args.mode >= n:
            raise _Exit(USAGE, f"--mode {args.mode}: the scene has {n} mode{'' if n == 1 else 's'}"
                               + (f" (0 .. {n - 1})" if n else ""))
        if not n:
            raise _Exit(USAGE, f"--gif {gif}: the scene has no modes to animate (nothing can move)")
        index = args.mode if args.mode is not None else \
            next((i for i, kind in enumerate(found.kinds) if kind == "vibration"), 0)

    for line in _modes_table(scene, found, t, args.count):
        print(line)
    if gif:
        try:
            _plotting().animate_mode(found, index, gif, view=view)
        except OSError as e:
            raise _Exit(USAGE, f"cannot write {e.filename or gif}: {e.strerror or e}") from None
        print(f"  mode {index} ({found.kinds[index]}) animated in {gif}")
    return OK


def _modes_table(scene, found, t, count=None):
    """The lines lagmb modes prints: what the modes are about, then one row
    a mode (the first count): its number, kind, frequency (Hz), omega
    (rad/s), damping ratio and the coordinate its shape moves most."""
    n = len(found)
    state = {True: "stable", False: "unstable", None: "static"}[found.equilibrium.stable]
    lines = [f"{scene.path}: {n} mode{'' if n == 1 else 's'} about the {state} equilibrium at t = {t:g} s"]
    if not n:
        return lines + ["  no modes: every degree of freedom is driven, nothing can move"]
    names = coordinate_names(scene.model)
    head = ("mode", "kind", "frequency (Hz)", "omega (rad/s)", "damping ratio", "moves most")
    rows = []
    for i in range(n if count is None else min(count, n)):
        zeta, rigid = found.damping_ratios[i], found.kinds[i] == "rigid-body"  # its omega: round-off about 0
        rows.append((str(i), found.kinds[i], "0" if rigid else f"{found.frequencies[i]:.6g}",
                     "0" if rigid else f"{found.omega[i]:.6g}", "-" if math.isnan(zeta) else f"{zeta:.4g}",
                     names[int(abs(found.shapes[i]).argmax())]))
    width = [max(len(r[k]) for r in rows + [head]) for k in range(len(head))]
    right = (True, False, True, True, True, False)
    for r in [head] + rows:
        lines.append("  " + "  ".join(c.rjust(w) if ok else c.ljust(w) for c, w, ok in zip(r, width, right)).rstrip())
    if len(rows) < n:
        lines.append(f"  the {len(rows)} lowest of {n} modes (--count)")
    if "unstable" in found.kinds[:len(rows)]:
        lines.append("  unstable: the equilibrium is unstable in this mode; omega is the rate exp(omega t) it grows at")
    if "rigid-body" in found.kinds[:len(rows)]:
        lines.append("  rigid-body: a motion nothing resists (frequency 0)")
    return lines


# --- sweep ----------------------------------------------------------------------

_SWEEP_KINDS = {  # --output KIND: what its ARG names (None: no ARG)
    "peak_reaction": "a joint or driver",
    "peak_effort": "a driver",
    "final": "a coordinate",
    "energy_drift": None,
}
_SWEEP_ROWS = 20          # more cases than this: the first and last rows and each output's range
_SWEEP_ENDS = 5           # rows shown at each end then


def _sweep_parser(sub):
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
    sweep.add_argument("--workers", type=_whole, metavar="N",
                       help="run the cases on N processes (default 1: in this process)")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="run the cases on a Dask cluster, its scheduler's address (tcp://host:8786); "
                            "its workers run them (no --workers)")
    sweep.add_argument("--t-end", type=_number, metavar="T", help="end time, instead of the scene's")
    sweep.add_argument("--batch-size", type=_whole, metavar="B",
                       help="cases per task and per batch written to the store (default: the cases over 4 "
                            "tasks per worker, at most 256)")
    sweep.add_argument("--plot", metavar="STORE",
                       help="draw the study in STORE (a plot per output against the varied parameters, "
                            "lagmb.plotting.plot_sweep) to -o, instead of running one")
    _robot_options(sweep)


def _sweep(args):
    import time

    if args.plot is not None:
        return _sweep_plot(args)
    if not args.scene:
        raise _Exit(USAGE, "give a scene file and --vary NAME=SPEC (or --plot STORE to draw a study)")
    scene = _load(args.scene, args)
    # the options first: a mistake there costs no run
    grid, typed = _sweep_grid(args.vary)
    outputs = _sweep_outputs(scene, args.outputs or [])
    t0 = scene.settings.get("t0", 0.0)
    _option_number("--t-end", args.t_end, above=t0)
    if args.workers is not None and args.workers < 1:
        raise _Exit(USAGE, f"--workers {args.workers}: must be at least 1")
    if args.scheduler is not None and args.workers is not None:
        raise _Exit(USAGE, f"--workers {args.workers}: the cluster at --scheduler {args.scheduler} runs the "
                           "cases on its own workers; give one or the other")
    if args.batch_size is not None and args.batch_size < 1:
        raise _Exit(USAGE, f"--batch-size {args.batch_size}: must be at least 1")
    try:
        import xarray  # noqa: F401 - the results' type
        if args.out:
            import zarr  # noqa: F401
    except ImportError:
        raise _Exit(USAGE, "lagmb sweep needs xarray (and zarr for -o): pip install 'lagmb[sweep]'") from None
    store = _sweep_store(args.out) if args.out else None
    t_end = args.t_end if args.t_end is not None else scene.settings.get("t_end")
    if t_end is None and scene.settings.get("t_out") is not None:
        t_end = scene.settings["t_out"][-1]  # the sweep's cases take n_out output times, not t_out
    if t_end is None and "t_end" not in grid:
        raise _Exit(USAGE, f"{args.scene}: no end time: give t_end in [simulation], --t-end or --vary t_end=...")
    from .studies import sweep

    n = math.prod(len(values) for values in grid.values())
    executor, where = None, "in this process"
    if args.scheduler is not None:
        try:
            from distributed import Client
        except ImportError:
            raise _Exit(USAGE, f"--scheduler {args.scheduler}: needs dask.distributed: "
                               "pip install 'lagmb[sweep]'") from None
        try:
            executor = Client(args.scheduler, timeout=10)
        except Exception as e:  # noqa: BLE001 - any failure to reach it: the address is the user's
            raise _Exit(USAGE, f"--scheduler {args.scheduler}: cannot connect: {e}") from None
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
        raise _Exit(USAGE, _sweep_error(str(e), args, typed)) from None
    except KeyboardInterrupt:
        if not store:
            raise
        interrupted = True
    except SimulationError as e:  # a worker process died (killed, out of memory): mb.sweep says what is kept
        raise _Exit(FAILED, f"{args.scene}: the study stopped: {' '.join(str(e).split())}") from None
    except OSError as e:  # a cluster lost, a disk full
        text = " ".join(str(e).split()).rstrip(".")
        raise _Exit(FAILED, f"{args.scene}: the study stopped: {type(e).__name__}" + (f": {text}" if text else "")
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
        raise _Exit(130, f"interrupted; the finished cases are in {store}: the same command finishes the study"
                    if kept else f"interrupted before any case was written to {store}")
    elapsed = time.monotonic() - start

    span = "t_end varied" if "t_end" in grid else f"t = {t0:g} .. {t_end:g} s"
    print(f"{args.scene}: {_count(n, 'case')} (" + " x ".join(f"{name} {len(v)}" for name, v in grid.items())
          + f"), {span}, {where}")
    for line in _sweep_table(ds, list(grid), list(outputs)):
        print(line)
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


def _sweep_grid(specs):
    """({name: values}, {name: the --vary as typed}) from the --vary options
    (lagmb.studies.grid_from_text reads them)."""
    from .studies import grid_from_text

    try:
        grid = grid_from_text(specs or [], who="--vary")
    except ModelError as e:
        raise _Exit(USAGE, str(e)) from None
    return grid, dict(zip(grid, specs))


def _sweep_outputs(scene, specs):
    """{variable name: the built-in output} from the --output options,
    their arguments checked against the scene."""
    from .studies import energy_drift, final, peak_effort, peak_reaction

    model = scene.model
    kinds = BY_METHOD if getattr(model, "dimension", 2) == 2 else SPATIAL_BY_METHOD
    roles = {kw["name"]: kinds[method].role for method, kw in model.elements() if method in kinds}
    constraints = [name for name, role in roles.items() if role in ("joint", "driver")]
    drivers = [name for name, role in roles.items() if role == "driver"]
    coordinates = coordinate_names(model)
    outputs = {}
    for spec in specs:
        kind, eq, arg = (s.strip() for s in spec.partition("="))
        if kind not in _SWEEP_KINDS:
            raise _Exit(USAGE, f"--output {spec}: unknown kind {kind!r}; the kinds are peak_reaction=JOINT, "
                               "peak_effort=DRIVER, final=COORDINATE and energy_drift")
        what = _SWEEP_KINDS[kind]
        if what is None:
            if eq:
                raise _Exit(USAGE, f"--output {spec}: {kind} takes no argument: --output {kind}")
            name, f = kind, energy_drift()
        else:
            if not arg:
                raise _Exit(USAGE, f"--output {spec}: give {kind}=NAME, NAME {what} of the scene")
            if kind == "peak_reaction" and arg not in constraints:
                raise _Exit(USAGE, f"--output {spec}: {scene.path} has no joint or driver {arg!r}; "
                                   + _listed("its joints and drivers", constraints))
            if kind == "peak_effort" and arg not in drivers:
                raise _Exit(USAGE, f"--output {spec}: {scene.path} has no driver {arg!r}; "
                                   + _listed("its drivers", drivers))
            if kind == "final":
                plain = arg[4:-1] if arg.startswith("der(") and arg.endswith(")") else arg
                if plain not in coordinates:
                    raise _Exit(USAGE, f"--output {spec}: {scene.path} has no coordinate {plain!r}; "
                                       + _listed("its coordinates", coordinates)
                                       + " (der(NAME) for a rate)")
            name, f = f"{kind}_{arg}", {"peak_reaction": peak_reaction, "peak_effort": peak_effort,
                                        "final": final}[kind](arg)
        if name in outputs:
            raise _Exit(USAGE, f"--output {spec}: given twice")
        outputs[name] = f
    return outputs


def _listed(what, names):
    return f"{what} are {', '.join(names)}" if names else "it has none"


def _sweep_store(path):
    """The -o store, checked before any case runs as mb.sweep checks it
    (lagmb.studies.check_store: a new folder, or a study's store; no folder
    of another's), in a folder that can take it."""
    from .studies import check_store

    try:
        check_store(path)
    except ModelError as e:
        raise _Exit(USAGE, f"-o {path}: {e}") from None
    target = path
    while not os.path.lexists(target):  # missing folders are made when writing
        target = os.path.dirname(os.path.abspath(target))
    if not os.path.isdir(target):
        raise _Exit(USAGE, f"-o {path}: {target} is not a folder")
    why = _cannot_write(target)
    if why:
        raise _Exit(USAGE, f"-o {path}: {why}")
    return path


def _sweep_error(text, args, typed):
    """mb.sweep's ModelError as a usage error naming the option it is about."""
    if args.out and repr(args.out) in text:  # the store: another sweep's, in use, damaged
        return f"-o {args.out}: {text}"
    for name, spec in typed.items():
        if f"'{name}'" in text or f" {name} = " in text:
            return f"--vary {spec}: {text}"
    return f"{args.scene}: {text}"


def _sweep_table(ds, names, outputs):
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

    if n <= _SWEEP_ROWS:
        rows = [row(i) for i in range(n)]
    else:
        rows = ([row(i) for i in range(_SWEEP_ENDS)] + [["..."] + [""] * (len(head) - 1)]
                + [row(i) for i in range(n - _SWEEP_ENDS, n)])
    width = [max(len(r[k]) for r in rows + [head]) for k in range(len(head))]
    lines = ["  " + "  ".join(c.rjust(w) for c, w in zip(r, width)).rstrip() for r in [head] + rows]
    if n > _SWEEP_ROWS:
        lines.append(f"  the first and last {_SWEEP_ENDS} of {n:,} cases; over the {int(ok.sum()):,} ok cases:")
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


def _sweep_plot(args):
    """lagmb sweep --plot STORE [-o FIG]: a study's outputs against its parameters."""
    given = [(option, value) for option, value in (
        ("--vary", args.vary), ("--output", args.outputs), ("--workers", args.workers),
        ("--scheduler", args.scheduler), ("--t-end", args.t_end), ("--batch-size", args.batch_size))
        if value is not None]
    if args.scene:
        raise _Exit(USAGE, f"{args.scene}: --plot {args.plot} draws a finished study from its store; give no "
                           "scene with it")
    if given:
        option, value = given[0]
        shown = " ".join(value) if isinstance(value, list) else f"{value:g}" if isinstance(value, float) else value
        raise _Exit(USAGE, f"{option} {shown}: --plot {args.plot} draws a finished study from its store; give "
                           f"no {option} with it")
    _need_matplotlib("--plot")
    from .scene.reader import plot_format_problem

    store = args.plot
    path = args.out or os.path.splitext(store.rstrip("/\\") or store)[0] + ".png"
    reason = plot_format_problem(path)
    if reason:
        raise _Exit(USAGE, f"-o {path}: {reason}")
    try:
        from .studies import open_store

        ds = open_store(store)
    except ImportError:
        raise _Exit(USAGE, "lagmb sweep --plot needs xarray and zarr: pip install 'lagmb[sweep]'") from None
    except ModelError as e:
        raise _Exit(USAGE, f"--plot {store}: {e}") from None
    except Exception as e:  # noqa: BLE001 - a folder zarr cannot read
        raise _Exit(USAGE, f"--plot {store}: not a study's store ({type(e).__name__}: {e})") from None
    plotting = _plotting()
    from .plotting import sweeps
    kinds = list(_SWEEP_KINDS)
    try:  # the store keeps no order: lagmb sweep's kinds in --output's order, then the others by name
        drawn = sorted(sweeps.sweep_outputs(ds), key=lambda name: (
            next((k for k, kind in enumerate(kinds) if name.startswith(kind)), len(kinds)), name))
        plotting.plot_sweep(ds, path, outputs=drawn)
    except ValueError as e:
        raise _Exit(USAGE, f"--plot {store}: {e}") from None
    except OSError as e:
        raise _Exit(USAGE, f"-o {path}: cannot write: {e.strerror or e}") from None
    print(f"{store}: {_count(ds.sizes['case'], 'case')}, {_count(len(drawn), 'output')} "
          f"({', '.join(drawn)}) drawn in {path}")
    return OK


# --- info -----------------------------------------------------------------------

def _methods_table():
    """lagmb.methods() as a table: name, formulation, integrator, support, description."""
    from .simulation import methods

    rows = []
    for m in methods():
        notes = [f"order <= {m['max_order']}", "fixed step" if m["fixed_step"] else "error control"]
        notes += [w for w, has in (("no events", not m["events"]), ("no contact", m["events"] and not m["contact"]),
                                   ("no friction", not m["friction"]),
                                   ("baumgarte", m["baumgarte"]), ("drifts", m["drifts"])) if has]
        rows.append((m["name"], m["formulation"], m["integrator"], ", ".join(notes), m["description"]))
    head = ("method", "formulation", "integrator", "supports", "")
    width = [max(len(r[k]) for r in rows + [head]) for k in range(4)]
    return ["  ".join(c.ljust(w) for c, w in zip(r[:4], width)) + "  " + r[4] for r in [head] + rows]


def _info(args):
    if args.kinds:
        if args.scene or args.methods:
            raise _Exit(USAGE, "--kinds lists the element kinds of lagmb; give no scene or --methods with it")
        print(markdown(), end="")
        return OK
    if args.methods:
        if args.scene:
            raise _Exit(USAGE, "--methods lists the methods of lagmb; give no scene with it")
        for line in _methods_table():
            print(line.rstrip())
        return OK
    if not args.scene:
        raise _Exit(USAGE, "give a scene file, or --methods")
    scene = _load(args.scene, args)
    model = scene.model
    say = print

    def listing(table):
        names = scene.names(table)
        return f"{len(names)}" + (f" ({', '.join(names)})" if names else "")

    def kinds(table):
        els = [e for e in scene.elements if e.table == table]
        counts = {}
        for e in els:
            counts[e.type] = counts.get(e.type, 0) + 1
        return f"{len(els)}" + (" (" + ", ".join(f"{k} {n}" for k, n in counts.items()) + ")"
                                if els else "")

    gravity = getattr(model, "gravity", None)
    dimension = getattr(model, "dimension", 2)
    kinds_here, methods_here = elements(dimension), methods(dimension)
    by_method = BY_METHOD if dimension == 2 else SPATIAL_BY_METHOD
    say(f"scene: {scene.path}")
    if dimension != 2:
        say(f"dimension: {dimension}")
    say(f"gravity: {'none' if gravity is None else tuple(float(g) for g in gravity)}")
    for table in ELEMENT_TABLES:  # from the registry of element kinds
        if not methods_here[table]:
            continue  # no such elements in this dimension
        typed = any(e.table == table and e.type for e in kinds_here.values())
        say(f"{table}: {kinds(table) if typed else listing(table)}")
    try:
        core = model.compiled()
        say(f"coordinates: {core.n_coordinates}")
        say(f"constraint equations: {core.n_constraints}")
        inputs = core.inputs
        say(f"inputs: {len(inputs)}" + (" (" + ", ".join(
            f"{i['name']} {i['initial']:g}" + (f" {i['unit']}" if i["unit"] else "") for i in inputs) + ")"
            if inputs else ""))
        parameters = model.parameter_info()
        say(f"parameters: {len(parameters)}" + ("" if args.parameters else " (--parameters lists them)"))
        if args.parameters:
            width = max((len(p["name"]) for p in parameters), default=0)
            for p in parameters:
                value = f"{p['value']:.10g}" + (f" {p['unit']}" if p["unit"] else "")
                say(f"  {p['name']:<{width}}  {value:<18}  {p['doc']}")
        rank = model.rank()
    except ModelError as e:
        raise _Exit(USAGE, f"{scene.path}: {e}") from None
    except SimulationError as e:
        raise _Exit(FAILED, f"{scene.path}: the initial position cannot be assembled: {e}") from None
    say(f"rank of the constraint Jacobian: {rank['rank']}")
    say(f"degrees of freedom: {rank['degrees_of_freedom']}")
    dependent = list(rank.get("dependent_rows", []))
    if not dependent:
        say("redundant equations: none")
    else:
        say(f"redundant equations: {len(dependent)}")
        owners = []
        for e in scene.elements:
            if by_method[methods_here[e.table][e.type]].role in ("joint", "driver"):  # they have rows
                row0, rows = core.constraint_rows(e.name)
                owners.append((row0, rows, e))
        for row in dependent:
            for row0, rows, e in owners:
                if row0 <= row < row0 + rows:
                    say(f"  row {row}: {e.table[:-1]} {e.name!r} ({e.type}, equation "
                        f"{row - row0 + 1} of {rows}" + (f"; line {e.line})" if e.line else ")"))
                    break
            else:
                say(f"  row {row}")
    if scene.settings:
        say("simulation: " + ", ".join(f"{k} = {v!r}" for k, v in scene.settings.items()))
    return OK


if __name__ == "__main__":
    sys.exit(main())
