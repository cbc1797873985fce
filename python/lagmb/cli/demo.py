"""lagmb demo: the seed pendulum against its closed forms (lagmb.demo)."""

from ._common import OK, need_matplotlib


def add_parser(sub):
    """lagmb demo's parser."""
    demo = sub.add_parser("demo", help="simulate the seed pendulum and check it against closed forms")
    demo.add_argument("--plot", metavar="PNG", help="write a plot of angle and pin force")
    demo.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")


def handle(args):
    """Runs lagmb.demo, printing its checks unless --quiet."""
    from .. import demo as d

    if args.plot:
        need_matplotlib("--plot")
    d.run(plot=args.plot, out=(lambda *a, **k: None) if args.quiet else print)
    return OK
