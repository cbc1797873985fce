"""A disk rolling down an incline on a compliant contact with friction.

    python examples/rolling_disk.py [--picture rolling_disk-picture.png] [--plot rolling_disk.png]

A uniform disk (radius 0.2 m, 2 kg, J = m R^2 / 2) rests on a 20 degree
incline (the line through the origin along (cos a, -sin a)), pressed in by
its static penetration d0 = (m g cos a / k)^(2/3), and is released. The
contact "incline" (k = 1e9 N/m^1.5, e = 0.5, friction mu = 0.5, slip
velocity 1e-4 m/s) gives a normal force and regularized Coulomb friction;
mu exceeds tan(a) / 3 = 0.121, so the disk rolls.

Rolling without slip on a rigid incline, the centre accelerates at
(2/3) g sin a = 2.23666 m/s^2. On the compliant contact the disk rolls on
the radius R - d0 (the contact point is the centre's projection on the
line) and creeps at a constant slip speed below v_s, so the acceleration is
g sin a / (1 + J / (m (R - d0)^2)), within 3 d0 / R of the rigid value.
"""

import argparse
import math

import numpy as np

import lagmb as mb

G, R, MASS, ALPHA, K, MU = 9.81, 0.2, 2.0, math.radians(20.0), 1e9, 0.5


def build():
    d0 = (MASS * G * math.cos(ALPHA) / K) ** (2.0 / 3.0)
    n = np.array([math.sin(ALPHA), math.cos(ALPHA)])
    centre = (R - d0) * n
    m = mb.Model(gravity=(0.0, -G))
    disk = m.add_body("disk", mass=MASS, inertia=0.5 * MASS * R * R, position=tuple(centre))
    m.add_contact("incline", disk, tuple(centre), R, m.ground, (0.0, 0.0),
                  (math.cos(ALPHA), -math.sin(ALPHA)), stiffness=K, restitution=0.5, friction=MU,
                  slip_velocity=1e-4)
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
                        help="draw the disk at 1 s with a rim point's path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)
    m, d0 = build()
    r = mb.simulate(m, t_end=1.0, rtol=1e-8, atol=1e-10, n_out=201)
    u = np.array([math.cos(ALPHA), -math.sin(ALPHA)])
    s = r.body("disk").position @ u
    late = r.t >= 0.2
    accel = 2.0 * np.polyfit(r.t[late], s[late], 2)[0]
    rigid = 2.0 / 3.0 * G * math.sin(ALPHA)
    compliant = G * math.sin(ALPHA) / (1.0 + 0.5 * R * R / (R - d0) ** 2)
    w = r.body("disk").angular_velocity
    v = r.body("disk").velocity @ u
    print(f"static penetration = {d0:.6e} m")
    print(f"acceleration = {accel:.10f} m/s^2")
    print(f"rolling closed form = {rigid:.10f} m/s^2")
    print(f"compliant closed form = {compliant:.10f} m/s^2")
    print(f"max slip speed = {np.max(np.abs(v[late] + w[late] * (R - d0))):.6e} m/s")
    print(f"contact events = {len(r.events)}")
    print(f"steps = {r.stats['steps']}")
    if args.picture:  # a point on the rim traces a cycloid as the disk rolls
        draw(r, args.picture, trace=[("disk", (0.0, R))], title="a disk rolling down a 20 degree incline: "
             "a rim point's cycloid")
    if args.plot:
        plot(r, args.plot, what=("coordinates", "energy"))


if __name__ == "__main__":
    main()
