"""A four-bar linkage from a MuJoCo file, its loop closed by an equality.

    python examples/mjcf_four_bar.py [--picture four_bar_mjcf-picture.png] [--plot four_bar_mjcf.png]

examples/four_bar_mjcf.xml describes the crank and coupler as a chain of
hinges and the rocker as a second chain; `<connect>` joins the coupler's tip
to the rocker's. MuJoCo holds such an equality softly; mb.load_mjcf (MuJoCo's
compiler, the `mjcf` extra) turns it into a spherical joint, so in lagmb the
loop is closed exactly. The linkage falls under gravity for 2 s without
friction: the energy stays put and the loop stays closed.
"""

import argparse
import os
import sys
import warnings

import numpy as np

import lagmb as mb

HERE = os.path.dirname(os.path.abspath(__file__))


def draw(result, path, **kwargs):
    """The mechanism at one output (lagmb.plotting.picture, needs matplotlib)."""
    from lagmb.plotting import picture
    picture(result, path, size=(640, 480), **kwargs)
    print(f"picture written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH", help="draw the linkage at 2 s to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)
    try:
        with warnings.catch_warnings():
            # three parallel hinges and a ball joint repeat one equation: it is dropped and named
            warnings.simplefilter("ignore", mb.RedundantConstraintWarning)
            model = mb.load_mjcf(os.path.join(HERE, "four_bar_mjcf.xml"), contacts="ignore")
            r = mb.simulate(model, 2.0, n_out=401, rtol=1e-10, atol=1e-12)
    except mb.ModelError as e:
        print(e)
        return 1
    print(f"bodies = {len(model.bodies)}")
    print(f"crank angle at 2 s = {r.joint('A').angle[-1]:.9f} rad")
    print(f"max loop residual = {np.max(r.residual):.3e} m")
    print(f"energy drift = {np.ptp(r.energy):.3e} J")
    print(f"redundant equations = {len(r.redundant_rows)}")
    if args.picture:
        draw(r, args.picture, view=(25.0, -60.0))
    if args.plot:
        from lagmb.plotting import plot_result
        plot_result(r, args.plot)
        print(f"plot written to {args.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
