"""Double pendulum: two uniform rods in a chain, released from horizontal.

    python examples/double_pendulum.py [--picture double-picture.png] [--plot double.png]

Rods of 1 m and 1 kg (J = m L^2 / 12): "shoulder" pins the upper one to the
ground at the origin, "elbow" pins the lower one to its end at (1, 0). The
motion is chaotic, but nothing dissipates energy, so r.energy stays put.

At release (both rods horizontal, at rest) Lagrange's equations in the
absolute angles reduce to

    [4/3  1/2] [theta1'']        [3/2]
    [1/2  1/3] [theta2''] = -g/L [1/2]

so theta1'' = -9 g / (7 L) and theta2'' = +3 g / (7 L): the elbow kicks the
lower rod upward while the upper one falls faster than a single rod would
(-3 g / (2 L)).
"""

import argparse

import numpy as np

import lagmb as mb

L, MASS, G = 1.0, 1.0, 9.81


def build():
    m = mb.Model(gravity=(0.0, -G))
    upper = m.add_body("upper", mass=MASS, inertia=MASS * L**2 / 12.0, position=(0.5 * L, 0.0))
    lower = m.add_body("lower", mass=MASS, inertia=MASS * L**2 / 12.0, position=(1.5 * L, 0.0))
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("elbow", upper, lower, at=(L, 0.0))
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
                        help="draw the pendulum at 5 s with the lower rod's tip's path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)

    r = mb.simulate(build(), t_end=5.0, rtol=1e-10, atol=1e-12, n_out=1001)
    upper, lower = r.body("upper"), r.body("lower")
    tip = r.point("lower", (0.5 * L, 0.0))
    elbow = r.reaction("elbow")

    print("double pendulum: two uniform rods (1 m, 1 kg), released from horizontal")
    print(f"initial angular acceleration upper = {upper.angular_acceleration[0]:.10f} rad/s^2 "
          f"(closed form -9 g / 7 = {-9 * G / 7:.10f})")
    print(f"initial angular acceleration lower = {lower.angular_acceleration[0]:.10f} rad/s^2 "
          f"(closed form 3 g / 7 = {3 * G / 7:.10f})")
    print(f"lowest tip height = {tip[:, 1].min():.6f} m (at most 2 m below the pivot)")
    print(f"max elbow force = {np.hypot(elbow[:, 0], elbow[:, 1]).max():.6f} N")
    print(f"energy drift = {np.ptp(r.energy):.3e} J (of m g L = {MASS * G * L:.2f} J)")
    print(f"max |Phi| = {r.residual.max():.3e} m")
    print(f"steps = {r.stats['steps']}")
    if args.picture:
        draw(r, args.picture, trace=[("lower", (0.5 * L, 0.0))])
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
