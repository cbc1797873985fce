"""A train of three spur gears: speed ratios, motor torque and tooth forces.

    python examples/gear_train.py [--picture gear_train-picture.png] [--plot gear_train.png]

Three external gears on ground pivots, in a horizontal plane (no gravity).
add_gear(name, i, j, ratio) takes ratio = omega_j / omega_i (negative for
external gears) and finds the pitch radii from the centre distance D:
r_j = D / (|ratio| + 1), r_i = |ratio| r_j.

    g1 at (0, 0),    pitch radius 0.2  }  D = 0.3,  ratio -2
    g2 at (0.3, 0),  pitch radius 0.1  }
    g3 at (0.45, 0), pitch radius 0.05 }  D = 0.15, ratio -2

so omega2 = -2 omega1 and omega3 = 4 omega1. The motor turns g1 at a
constant 5 rad/s against a load torque of -1 N m on g3. At constant speed
nothing accelerates and the power balance gives the motor torque
tau1 omega1 = -tau3 omega3, tau1 = 4 N m; each mesh carries the tooth force
tau3 / r3 = tau1 / r1 = 20 N. The idler g2 changes the direction of
rotation, not the ratio.
"""

import argparse
import math

import numpy as np

import lagmb as mb

OMEGA1, LOAD = 5.0, -1.0


def steel_disk(model, name, radius, centre, thickness=0.01, density=7850.0):
    mass = density * math.pi * radius**2 * thickness
    return model.add_body(name, mass=mass, inertia=0.5 * mass * radius**2, position=centre)


def build():
    m = mb.Model()
    gears = [steel_disk(m, "g1", 0.2, (0.0, 0.0)), steel_disk(m, "g2", 0.1, (0.3, 0.0)),
             steel_disk(m, "g3", 0.05, (0.45, 0.0))]
    for k, (g, x) in enumerate(zip(gears, (0.0, 0.3, 0.45)), start=1):
        m.add_revolute(f"pivot{k}", m.ground, g, at=(x, 0.0))
    m.add_gear("mesh12", gears[0], gears[1], -2.0)
    m.add_gear("mesh23", gears[1], gears[2], -2.0)
    m.drive_joint("motor", "pivot1", mb.Linear(OMEGA1))
    m.add_torque("load", gears[2], LOAD)
    return m


def plot(result, path):
    """Time histories with lagmb.plotting (needs matplotlib)."""
    try:
        from lagmb.plotting import plot_result
        plot_result(result, path)
    except ImportError as e:
        print(f"no plot: {e}")
        return
    print(f"plot written to {path}")


def draw(result, path, **kwargs):
    """The mechanism at one output with traced paths (lagmb.plotting.picture, needs matplotlib)."""
    from lagmb.plotting import picture
    picture(result, path, size=(640, 480), **kwargs)
    print(f"picture written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH", help="draw the gears at 2 s to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)

    r = mb.simulate(build(), t_end=2.0, rtol=1e-10, atol=1e-12, n_out=201)
    w1, w2, w3 = (r.body(g).angular_velocity for g in ("g1", "g2", "g3"))
    # tangential (tooth) force of each mesh: the second joint-frame component
    f12 = r.reaction("mesh12", frame="joint")[:, 1]
    f23 = r.reaction("mesh23", frame="joint")[:, 1]

    print("three spur gears, pitch radii 0.2, 0.1, 0.05 m; g1 driven at 5 rad/s, load -1 N m on g3")
    print(f"omega2 / omega1 = {np.mean(w2 / w1):.12f} (ratio -2)")
    print(f"omega3 / omega1 = {np.mean(w3 / w1):.12f} (closed form (-2) x (-2) = 4)")
    print(f"motor torque = {np.mean(r.effort('motor')):.10f} N m (power balance: 4)")
    print(f"tooth force mesh12 = {np.mean(np.abs(f12)):.10f} N (closed form 20)")
    print(f"tooth force mesh23 = {np.mean(np.abs(f23)):.10f} N (closed form 20)")
    print(f"spread over the run = {max(np.ptp(w3 / w1), np.ptp(r.effort('motor'))):.3e}")
    if args.picture:
        draw(r, args.picture)
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
