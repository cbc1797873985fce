"""A block on a vertical guide, hung from a spring-damper: damped oscillation.

    python examples/spring_damper.py [--picture spring_damper-picture.png] [--plot spring_damper.png]

A 1 kg block slides on a vertical translational joint ("guide"); a
spring-damper ("spring": k = 100 N/m, c = 2 N s/m, free length 1 m) hangs it
from the ground at the origin. Released at rest with the spring unstretched,
it oscillates about the static position l = 1 + m g / k = 1.0981 m:

    omega_n = sqrt(k / m) = 10 rad/s,  zeta = c / (2 sqrt(k m)) = 0.1
    damped period T_d = 2 pi / (omega_n sqrt(1 - zeta^2)) = 0.63148 s
    each swing shrinks by exp(-zeta omega_n T_d) = 0.53180 per period

The damper takes energy out at the rate c ldot^2: r.energy (kinetic +
gravity + spring) falls by exactly the integral of c ldot^2.
"""

import argparse
import math

import numpy as np

import lagmb as mb

MASS, K, C, L0, G = 1.0, 100.0, 2.0, 1.0, 9.81


def build():
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", mass=MASS, inertia=0.01, position=(0.0, -L0))
    m.add_translational("guide", m.ground, block, at=(0.0, -L0), axis=(0.0, 1.0))
    m.add_spring_damper("spring", m.ground, (0.0, 0.0), block, (0.0, -L0),
                        stiffness=K, damping=C, free_length=L0)
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
                        help="draw the block on its spring at 0.5 s to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)

    r = mb.simulate(build(), t_end=3.0, rtol=1e-10, atol=1e-12, n_out=3001)
    y = r.body("block").position[:, 1]
    v = r.body("block").velocity[:, 1]
    a = r.body("block").acceleration[:, 1]
    y_static = -(L0 + MASS * G / K)
    # lowest points: v goes from - to +; refine with one Newton step
    k = np.nonzero((v[:-1] < 0) & (v[1:] >= 0))[0]
    k = np.where(np.abs(v[k]) < np.abs(v[k + 1]), k, k + 1)
    t_low = r.t[k] - v[k] / a[k]
    y_low = y[k] - 0.5 * v[k]**2 / a[k]      # Taylor step to where v = 0
    swing = y_static - y_low

    wn, zeta = math.sqrt(K / MASS), C / (2 * math.sqrt(K * MASS))
    Td = 2 * math.pi / (wn * math.sqrt(1 - zeta**2))
    dissipated = float(np.sum(0.5 * (C * v[1:]**2 + C * v[:-1]**2) * np.diff(r.t)))

    print("1 kg on a vertical guide under a spring-damper (k = 100 N/m, c = 2 N s/m)")
    print(f"static deflection = {MASS * G / K:.10f} m")
    print(f"damped period = {t_low[1] - t_low[0]:.10f} s (closed form {Td:.10f})")
    print(f"decay per period = {swing[1] / swing[0]:.10f} (closed form {math.exp(-zeta * wn * Td):.10f})")
    print(f"final position = {y[-1]:.10f} m (static {y_static:.10f})")
    print(f"energy lost = {r.energy[0] - r.energy[-1]:.10f} J")
    print(f"energy dissipated by the damper = {dissipated:.10f} J")
    if args.picture:
        draw(r, args.picture, time=0.5, trace="block")
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
