"""lagmb fmu SCENE: an FMI 3.0 co-simulation FMU of the scene (lagmb.fmu.build_fmu)."""

import os

from ..errors import ModelError
from ._common import FAILED, OK, Exit, load


def add_parser(sub):
    """lagmb fmu's parser."""
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


def handle(args):
    """Builds the FMU; exit 1 where it cannot be built or written."""
    from ..fmu import build_fmu

    scene = load(args.scene)
    stem = os.path.splitext(os.path.basename(args.scene))[0]
    path = args.output or stem + ".fmu"
    try:
        build_fmu(scene, path, name=args.name or stem)
    except ModelError as e:
        raise Exit(FAILED, str(e)) from None
    except OSError as e:
        raise Exit(FAILED, f"cannot write {path}: {e.strerror or e}") from None
    if not args.quiet:
        print(f"wrote {path}")
    return OK
