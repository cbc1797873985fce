"""The seed pendulum: a uniform rod pinned at one end, released from horizontal.

    python examples/seed_pendulum.py [--picture pendulum-picture.png] [--plot pendulum.png]

A rod of length L = 1 m and mass m = 1 kg (J = m L^2 / 12) hangs from a pin at
the origin; its centre of mass starts at (L/2, 0) at rest. Closed forms to
compare with (theta = angle below the horizontal):

    energy:        thetadot^2 = 3 g sin(theta) / L
    period:        T = 4 sqrt(2 L / (3 g)) K(sin(pi/4)) = 1.93333 s
    pin force:     m g / 4 upward at release, 5 m g / 2 at the lowest point
"""

import argparse
import math

import numpy as np

import lagmb as mb

L, MASS, G = 1.0, 1.0, 9.81


def elliptic_k(k):
    """Complete elliptic integral of the first kind K(k) (modulus k), by the
    arithmetic-geometric mean: K = pi / (2 AGM(1, sqrt(1 - k^2)))."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    while abs(a - b) > 1e-15 * a:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def build():
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", mass=MASS, inertia=MASS * L**2 / 12.0, position=(0.5 * L, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
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
    parser.add_argument("--picture", metavar="PATH",
                        help="draw the rod at 0.5 s with its tip's path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)

    r = mb.simulate(build(), t_end=2.0, rtol=1e-10, atol=1e-12, n_out=2001)
    rod = r.body("rod")
    # turning points: where the angular velocity changes sign, refined by one
    # Newton step with the angular acceleration
    w, alpha = rod.angular_velocity, rod.angular_acceleration
    k = np.nonzero(w[1:-1] * w[2:] < 0)[0] + 1
    turns = r.t[k] - w[k] / alpha[k]
    mg = MASS * G
    F = r.reaction("pin")

    print("uniform rod (L = 1 m, m = 1 kg) pinned at one end, released from horizontal")
    print(f"period closed form = {4 * math.sqrt(2 * L / (3 * G)) * elliptic_k(math.sin(math.pi / 4)):.10f} s")
    print(f"period simulated = {turns[1]:.10f} s")
    print(f"pin force at release = {F[0, 1] / mg:.10f} m g (closed form 0.25)")
    print(f"max pin force = {np.hypot(F[:, 0], F[:, 1]).max() / mg:.10f} m g (closed form 2.5)")
    print(f"energy drift = {np.ptp(r.energy):.3e} J")
    print(f"max |Phi| = {r.residual.max():.3e} m")
    print(f"steps = {r.stats['steps']}")
    if args.picture:
        draw(r, args.picture, time=0.5, trace=[("rod", (0.5, 0.0))])
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
