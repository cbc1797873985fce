"""A Franka Emika Panda arm falling under gravity, with damped joints.

    python examples/panda.py [--plot panda.png] [--gif panda.gif] [--picture arm.png]

The robot is example-robot-data's URDF (pip install example-robot-data, or
the `robots` extra), read by mb.load_urdf: 7 arm joints and 2 finger slides,
from the zero configuration (the arm straight up), at rest. Each arm joint
gets a viscous damper of 0.5 N m s/rad. Its joint limits are left out
(limits=False): the zero configuration lies beyond joint 4's, and a joint
coming to rest on a limit would end the run; so are the file's own tiny
damping values (dynamics=False). The second finger mimics the first (the
file's <mimic>, a joint coupling).

Prints the energy balance of the 2 s fall: the energy the arm lost equals
the work the dampers did, the integral of c w^2 over the joints.
"""

import argparse
import os
import site
import sys
import sysconfig

import numpy as np

import lagmb as mb

DAMPING = 0.5  # N m s/rad at each arm joint
ARM = [f"panda_joint{k}" for k in range(1, 8)]


def panda_urdf():
    """The Panda's URDF in the example-robot-data package (None if absent)."""
    for base in sorted({sysconfig.get_paths()["purelib"], *site.getsitepackages()}):
        path = os.path.join(base, "cmeel.prefix", "share", "example-robot-data", "robots", "panda_description",
                            "urdf", "panda.urdf")
        if os.path.isfile(path):
            return path
    return None


def build(path):
    model = mb.load_urdf(path, limits=False, dynamics=False)
    for joint in ARM:
        model.add_rotational_spring_damper(f"{joint}_damper", joint=joint, damping=DAMPING)
    return model


def plot(result, path):
    """The arm's joint angles against time (needs matplotlib)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        print(f"no plot: {e}")
        return
    fig, ax = plt.subplots(figsize=(7, 4), dpi=120)
    for joint in ARM:
        ax.plot(result.t, result.joint(joint).angle, label=joint.replace("panda_", ""))
    ax.set_xlabel("t (s)")
    ax.set_ylabel("joint angle (rad)")
    ax.set_title("Panda falling from its zero configuration, damped joints")
    ax.legend(ncol=4, fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    print(f"plot written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plot", metavar="PATH", help="write the joint angles to PATH (.png, .pdf)")
    parser.add_argument("--gif", metavar="PATH", help="write an animation to PATH (.gif)")
    parser.add_argument("--picture", metavar="PATH", help="draw the arm with its collision meshes at 0.3 s to PATH")
    args = parser.parse_args(argv)
    path = panda_urdf()
    if path is None:
        print("example-robot-data is not installed: pip install example-robot-data")
        return 1
    model = build(path)
    r = mb.simulate(model, 2.0, n_out=2001, formulation="projection", integrator="erk", rtol=1e-9, atol=1e-11)
    print(f"bodies = {len(model.bodies)}")
    print(f"joints = {len(mb.JointSpace(model).joints)}")
    print(f"steps = {r.stats['steps']}")
    rates = np.array([r.joint(joint).rate for joint in ARM])
    power = DAMPING * np.sum(rates ** 2, axis=0)  # W, what the dampers take
    dissipated = float(np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(r.t)))
    lost = float(r.energy[0] - r.energy[-1])
    print(f"energy lost = {lost:.6f} J")
    print(f"damper work = {dissipated:.6f} J")
    print(f"elbow angle at 2 s = {r.joint('panda_joint4').angle[-1]:.6f} rad")
    if args.plot:
        plot(r, args.plot)
    if args.picture:
        from lagmb.plotting import picture
        picture(r, args.picture, time=0.3, title="Franka Panda from URDF (example-robot-data), falling")
        print(f"picture written to {args.picture}")
    if args.gif:
        from lagmb.plotting import animate
        animate(r, args.gif, view=(15.0, -60.0))
        print(f"animation written to {args.gif}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
