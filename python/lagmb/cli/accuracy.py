"""lagmb accuracy SCENE: a work-precision study of the scene's methods
(lagmb.accuracy.work_precision)."""

import sys

from ..errors import ModelError, SimulationError
from ._common import FAILED, OK, USAGE, Exit, load, need_matplotlib, number


def add_parser(sub):
    """lagmb accuracy's parser."""
    acc = sub.add_parser("accuracy", help="work-precision study of a scene: error against CPU time",
                         description="Run the scene with each method at each tolerance, measure the "
                                     "error against a tight reference run, the CPU time and the "
                                     "constraint drift; print the table and draw the diagram.")
    acc.add_argument("scene", help="the scene file (.toml)")
    acc.add_argument("--methods", nargs="+", metavar="M",
                     help="methods (default: all): " + ", ".join(_method_names()))
    acc.add_argument("--tolerances", nargs="+", type=number, metavar="RTOL",
                     help="relative tolerances (default: 1e-3 .. 1e-11)")
    acc.add_argument("--t-end", type=number, metavar="T", help="end time, instead of the scene's")
    acc.add_argument("--error", nargs="+", type=number, metavar="E",
                     help="name the cheapest run reaching each of these errors (default: every decade)")
    acc.add_argument("-o", "--output", metavar="JSON", help="write the table as JSON")
    acc.add_argument("--plot", metavar="PNG", help="draw error vs CPU time and drift vs time")
    acc.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")


def _method_names():
    from ..accuracy import METHODS  # the variable-step methods of lagmb.methods(), and presets

    return list(METHODS)


def handle(args):
    """Runs the study, prints its table, writes -o and --plot."""
    from ..accuracy import work_precision

    scene = load(args.scene)
    if args.plot:
        need_matplotlib("--plot")
    t_end = args.t_end or scene.settings.get("t_end")
    if not t_end:
        raise Exit(USAGE, f"{args.scene}: no t_end in [simulation]; give --t-end")
    say = (lambda *a, **k: None) if args.quiet else print

    def progress(i, n, row):
        if not args.quiet:
            print(f"  [{i}/{n}] {row['method']} rtol {row['rtol']:.0e}: {row['status']}",
                  file=sys.stderr)

    try:
        wp = work_precision(scene.model, t_end, methods=args.methods, tolerances=args.tolerances,
                            t0=scene.settings.get("t0", 0.0), progress=progress)
    except ModelError as e:
        raise Exit(USAGE, str(e)) from None
    except SimulationError as e:
        raise Exit(FAILED, str(e)) from None
    say(wp.table())
    say(wp.summary(args.error))
    if args.output:
        wp.save(args.output)
        say(f"table written to {args.output}")
    if args.plot:
        wp.plot(args.plot, title=f"{args.scene}: t = 0 .. {t_end:g} s")
        say(f"diagram written to {args.plot}")
    return OK
