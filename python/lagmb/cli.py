"""The lagmb command."""

import argparse
import sys

from . import __version__


def main(argv=None):
    parser = argparse.ArgumentParser(prog="lagmb", description="Planar multibody dynamics")
    parser.add_argument("--version", action="version", version=f"lagmb {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser("demo", help="simulate the seed pendulum and check it against closed forms")
    demo.add_argument("--plot", metavar="PNG", help="write a plot of angle and pin force")
    args = parser.parse_args(argv)

    if args.command == "demo":
        from . import demo as d

        if args.plot:
            try:
                import matplotlib  # noqa: F401
            except ImportError:
                parser.error("--plot needs matplotlib: pip install 'lagmb[plot]'")
        d.run(plot=args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
