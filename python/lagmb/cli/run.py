"""lagmb run SCENE: simulate a scene and write what -o, --plot, --animate
and --html (or its [output] table) ask for."""

import argparse
import os
import re
import sys

from ..errors import ModelError, SimulationError
from ..result import results_format_problem
from ._common import (FAILED, OK, USAGE, Exit, load, need_matplotlib, number, option_number, output_path,
                      robot_options, viewpoint, whole)


def add_parser(sub):
    """lagmb run's parser."""
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
    run.add_argument("--t-end", type=number, metavar="T", help="end time, instead of the scene's")
    run.add_argument("--rtol", type=number, metavar="R", help="relative tolerance, instead of the scene's")
    run.add_argument("--n-out", type=whole, metavar="N", help="number of output times, instead of the scene's")
    run.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    robot_options(run)


def handle(args):
    """Checks the options and outputs, runs the scene, writes the outputs."""
    from .. import plotting
    from ..progress import Progress
    from ..scene import MAX_OUTPUTS, SceneError
    from ..scene.reader import animation_format_problem, plot_format_problem

    scene = load(args.scene, args)
    # the options, outputs and formats first: a mistake there costs no run
    option_number("--t-end", args.t_end, above=scene.settings.get("t0", 0.0))
    option_number("--rtol", args.rtol, above=0.0)
    if args.n_out is not None and not 2 <= args.n_out <= MAX_OUTPUTS:
        raise Exit(USAGE, f"--n-out {args.n_out}: must be at least 2 and at most {MAX_OUTPUTS:,}")
    out = output_path(scene, args.output, "-o", "file", results_format_problem)
    plot = output_path(scene, args.plot, "--plot", "plot", plot_format_problem)
    animate = output_path(scene, args.animate, "--animate", "animate", animation_format_problem)
    html_page = output_path(scene, args.html, "--html", "html",
                            lambda p: None if p.lower().endswith((".html", ".htm")) else "must end in .html")
    view = viewpoint(scene, args.view)
    motion = _animation_options(args, scene, animate)
    # then what the outputs need installed (a mistyped option is named first, with or without it)
    if plot:
        need_matplotlib("plotting")
    if animate:
        need_matplotlib("animating")
    if html_page:
        try:
            from ..viewer import three_js

            three_js()
        except ModelError as e:  # three.js comes with the 'view' extra
            raise Exit(USAGE, f"--html {html_page}: {e}") from None

    overrides = {}
    if args.t_end is not None:
        overrides["t_end"] = args.t_end
    if args.rtol is not None:
        overrides["rtol"] = args.rtol
    if args.n_out is not None:
        overrides["n_out"] = args.n_out
    settings = {**scene.settings, **overrides}
    if "t_end" not in settings and "t_out" not in settings:
        raise Exit(USAGE, f"{args.scene}: no end time: give t_end in [simulation] or --t-end")
    t_end = settings.get("t_end")
    if t_end is None:
        t_end = settings["t_out"][-1]

    progress = Progress(settings.get("t0", 0.0), t_end, enabled=not args.quiet)
    try:
        result = scene.run(progress=progress, **overrides)
    except SceneError as e:  # names the file, line and key
        raise Exit(USAGE, str(e)) from None
    except ModelError as e:  # about an option it names, or else the scene as a whole
        words = set(re.findall(r"\w+", str(e)))
        option = next((f"--{k.replace('_', '-')} {v:g}: " for k, v in overrides.items()
                       if k in words), "")
        raise Exit(USAGE, f"{args.scene}: {option}{e}") from None
    except MemoryError:  # e.g. millions of outputs of a large model
        n = overrides.get("n_out") or len(settings.get("t_out") or ()) or settings.get("n_out", 101)
        raise Exit(FAILED, f"{args.scene}: out of memory in the run ({n} outputs); "
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
        raise Exit(FAILED, message) from None
    finally:
        progress.close()

    say = (lambda *a: None) if args.quiet else print
    _summary(scene, result, say)
    try:
        if out:
            _write(out, result, scene)
            say(f"  results written to {out}")
        if plot:
            plotting.plot_result(result, plot)
            say(f"  plot written to {plot}")
        if animate:
            plotting.animate(result, animate, view=view, progress=not args.quiet, **motion)
            say(f"  animation written to {animate}")
        if html_page:
            from ..viewer import view as view_page

            folder = os.path.dirname(os.path.abspath(html_page))
            os.makedirs(folder, exist_ok=True)
            try:
                page = view_page(result, html_page, title=os.path.basename(str(scene.path or args.scene)))
            except ModelError as e:  # it could not be written after all
                raise Exit(USAGE, f"--html {html_page}: {e}") from None
            say(f"  interactive view written to {html_page} ({page.size / 1e6:.2f} MB; open it in a browser)")
        if not (out or plot or animate or html_page):
            say("  nothing written: -o FILE (.npz or .csv), --plot, --animate or --html keep the outputs")
    except OSError as e:
        raise Exit(USAGE, f"cannot write {e.filename or ''}: {e.strerror or e}") from None
    return OK


def _animation_options(args, scene, animate):
    """animate's fps, speed, frames and trace from --fps, --speed, --frames
    and --trace, checked before the run (a usage error, exit 2, names the
    option and the value as typed); they need an animation (--animate or
    [output] animate)."""
    from .. import plotting
    from ..plotting import frames

    given = [(option, value) for option, value in (("--fps", args.fps), ("--speed", args.speed),
                                                   ("--frames", args.frames)) if value is not None]
    if args.trace:
        given.append(("--trace", " ".join(args.trace)))
    if given and not animate:
        option, value = given[0]
        raise Exit(USAGE, f"{option} {value}: there is no animation to apply it to; give --animate GIF "
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
        raise Exit(USAGE, str(e)) from None
    return motion


class _NoNumber(str):
    """Text of the command line that number() does not read ('1_0'): shown
    as typed, and float() of it fails, as for any word."""

    def __float__(self):
        raise ValueError(f"{str(self)!r} is not a decimal number")


def _typed(text):
    """A number option's text for a checker that calls float(): as typed,
    or a _NoNumber if number() does not read it (float() takes '1_0' for 10)."""
    try:
        number(text)
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


def _write(path, r, scene):
    """The run's results to -o (Result.save), with what the scene's [output]
    lists: the reactions and efforts (an .npz holds every joint's and
    driver's unless listed), their frame, the energy column of a .csv."""
    output = scene.output
    reactions, efforts = output.get("reactions"), output.get("efforts")
    if r.stats.get("analysis") == "kinematic":  # no multipliers: no reactions, no efforts (Result.save writes none)
        listed = list(reactions or []) + list(efforts or [])
        if listed:
            print(f"lagmb: a kinematic analysis computes no reactions or driver efforts; "
                  f"{', '.join(listed)} not written", file=sys.stderr)
        reactions = efforts = None
    r.save(path, reactions=reactions, efforts=efforts, frame=output.get("reaction_frame", "global"),
           energy=output.get("energy", False))
