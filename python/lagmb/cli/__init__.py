"""The lagmb command.

    lagmb run SCENE [-o results.npz|results.csv] [--plot out.png] [--animate out.gif] [--html out.html]
                    [--fps F] [--speed S] [--frames N] [--trace POINT ...] [--view ELEV,AZIM]
                    [--t-end T] [--rtol R] [--n-out N] [--quiet]
    lagmb info SCENE [--parameters] | --methods | --kinds
    lagmb accuracy SCENE [--methods M ...] [--tolerances RTOL ...] [--t-end T] [--error E ...]
                   [-o table.json] [--plot out.png] [--quiet]
    lagmb fmu SCENE [-o model.fmu] [--name NAME] [--quiet]
    lagmb modes SCENE [--at-time T] [--count K] [--gif out.gif] [--mode I] [--view ELEV,AZIM]
    lagmb sweep SCENE --vary NAME=SPEC [--vary ...] [--output KIND[=ARG] ...] [-o study.zarr]
                [--workers N | --scheduler ADDRESS] [--t-end T] [--batch-size B]
    lagmb sweep --plot study.zarr [-o study.png]
    lagmb demo [--plot out.png] [--quiet]
    lagmb --cmake-prefix

--cmake-prefix prints the folder holding the C++ package of an installed
wheel (headers, liblagmb.so, lib/cmake/lagmb): cmake -DCMAKE_PREFIX_PATH=...
finds it with find_package(lagmb). It exits 2 where lagmb was built without
it (make's build from a clone: there cmake --install installs the library).

run, info, modes and sweep also take a robot's URDF file as SCENE, with
--floating-base, --no-limits, --no-dynamics and --no-mimic (mb.load_urdf).

Exit status: 0 done; 2 a usage or scene error (one line naming the file,
line, table and key, or the option); 1 the simulation failed (the results
computed until then are still written to -o, if given); 3 an internal error,
a bug in lagmb (one line; LAGMB_TRACEBACK=1 shows the traceback); 130
interrupted (Ctrl-C). lagmb modes exits 1 where the scene has no static
equilibrium (a free body under gravity) or its joints cannot be closed.
lagmb sweep exits 0 when at least one case ran (failed cases are listed),
1 when every case failed.

Each subcommand is a module of this package with add_parser(subparsers)
and handle(args); the shared pieces are in _common.
"""

import argparse
import os
import sys
import warnings

from .._version import __version__
from . import accuracy, demo, fmu, info, modes, run, sweep
from ._common import INTERNAL, Exit

#: subcommand -> its module (add_parser, handle), in the order --help lists them
COMMANDS = {"run": run, "info": info, "accuracy": accuracy, "fmu": fmu, "modes": modes, "sweep": sweep,
            "demo": demo}


def cmake_prefix():
    """The folder to put on CMAKE_PREFIX_PATH for find_package(lagmb), or
    None where this installation has no C++ package (built without
    LAGMB_BUNDLED_DEPS)."""
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    config = os.path.join(package, "lib", "cmake", "lagmb", "lagmbConfig.cmake")
    return package if os.path.isfile(config) else None


class _CMakePrefix(argparse.Action):
    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        prefix = cmake_prefix()
        if prefix is None:
            parser.exit(2, "lagmb: --cmake-prefix: this lagmb has no C++ package (it was built from a clone "
                           "with make; there `cmake --install build/... --component cpp` installs the "
                           "library, or build the wheel with make wheel)\n")
        print(prefix)
        parser.exit(0)


def _parser():
    parser = argparse.ArgumentParser(prog="lagmb", description="Planar and spatial multibody dynamics")
    parser.add_argument("--version", action="version", version=f"lagmb {__version__}")
    parser.add_argument("--cmake-prefix", action=_CMakePrefix,
                        help="print the folder of the wheel's C++ package (for CMAKE_PREFIX_PATH) and exit")
    sub = parser.add_subparsers(dest="command", required=True)
    for command in COMMANDS.values():
        command.add_parser(sub)
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
        return COMMANDS[args.command].handle(args)
    except Exit as e:
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
