"""An eccentric cam lifting a flat-faced follower through a contact.

    python examples/cam_follower.py [--picture cam_follower-picture.png] [--plot cam_follower.png]

The cam (a circle of radius 0.05 m whose centre is 0.02 m from the pivot)
turns about the ground pin at the origin, driven at 2 pi rad/s. The
follower (0.5 kg) slides on a vertical guide; its flat face (the line
through (0, 0.05) along (-1, 0): its normal points down to the cam) rests on
the cam under gravity. The contact "cam_face" (k = 1e9 N/m^1.5, e = 0.5,
friction 0.1) carries the load; the guide takes the friction's side force.

A flat face on an eccentric circle moves harmonically: the face height is
the cam centre's height plus R, y = e sin(omega t), so the lift is 2 e =
0.04 m and the follower's largest downward acceleration e omega^2 = 0.79
m/s^2 stays below g: the follower never leaves the cam.
"""

import argparse
import math

import numpy as np

import lagmb as mb

G, R, ECC, OMEGA, MASS, K = 9.81, 0.05, 0.02, 2.0 * math.pi, 0.5, 1e9


def build():
    d0 = (MASS * G / K) ** (2.0 / 3.0)  # static penetration under the follower's weight
    m = mb.Model(gravity=(0.0, -G))
    cam = m.add_body("cam", mass=1.0, inertia=2e-3, position=(0.0, 0.0))
    m.add_revolute("pivot", m.ground, cam, at=(0.0, 0.0))
    m.drive_joint("motor", "pivot", mb.Linear(OMEGA))
    follower = m.add_body("follower", mass=MASS, inertia=1e-3, position=(0.0, 0.1 - d0))
    m.add_translational("guide", m.ground, follower, at=(0.0, 0.1 - d0), axis=(0.0, 1.0))
    m.add_contact("cam_face", cam, (ECC, 0.0), R, follower, (0.0, R - d0), (-1.0, 0.0),
                  stiffness=K, restitution=0.5, friction=0.1)
    return m, d0


def plot(result, path, **kwargs):
    """Time histories with lagmb.plotting (needs matplotlib)."""
    from lagmb.plotting import plot_result
    plot_result(result, path, **kwargs)
    print(f"plot written to {path}")


def draw(result, path, **kwargs):
    """The mechanism at one output with a traced path (lagmb.plotting.picture, needs matplotlib)."""
    from lagmb.plotting import picture
    picture(result, path, size=(640, 480), **kwargs)
    print(f"picture written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH",
                        help="draw cam and follower at the top of the lift to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)
    m, d0 = build()
    r = mb.simulate(m, t_end=1.0, rtol=1e-8, atol=1e-10, n_out=1001)
    y = r.body("follower").position[:, 1] - (0.1 - d0)
    ideal = ECC * np.sin(OMEGA * r.t)
    print(f"lift = {y.max() - y.min():.8f} m")
    print(f"lift closed form = {2 * ECC:.8f} m")
    print(f"max deviation from e sin(omega t) = {np.max(np.abs(y - ideal)):.3e} m")
    print(f"contact events = {len(r.events)}")
    print(f"steps = {r.stats['steps']}")
    if args.picture:  # at a quarter turn the cam's centre is highest: the follower at the top
        draw(r, args.picture, time=0.25, trace=[("cam", (ECC, 0.0))],
             title="an eccentric cam lifting a follower: the cam centre's circle")
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
