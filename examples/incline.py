"""A sphere rolls, one block sticks and another slides on the same incline.

    python examples/incline.py [--picture incline.png] [--gif incline.gif]

A plane tilted 20 degrees (downhill along -x) carries three bodies side by
side, each touching it through its own contact (k = 1e8 N/m^1.5, e = 0.5,
slip velocity 1e-4 m/s), all let go at rest, pressed in by their static
penetrations:

- a solid sphere (R = 0.1 m, 1 kg, J = 2/5 m R^2), friction 0.5: it rolls.
  A sphere's contact point is not a material point, so its contact never
  sticks; rolling on the compliant contact is on the radius R - d0 (d0 its
  static penetration), so the centre accelerates at
  g sin a / (1 + J / (m (R - d0)^2)) (5/7 g sin a on a rigid plane);
- a cube (0.2 m, 1 kg) with friction 0.5 > tan 20 deg = 0.364: its four
  lower corners stick (constraint rows hold its contact in place) from the
  start, and it does not move: the friction its rows hold is m g sin a;
- a cube with friction 0.2 < tan 20 deg: it lets go at once and slides at
  g (sin a - mu cos a).
"""

import argparse
import math
import sys

import numpy as np

import lagmb as mb

G, ALPHA, K, R, EDGE = 9.81, math.radians(20.0), 1e8, 0.1, 0.2


def slope_axes():
    """The plane's axes: x downhill-reversed (uphill), z its outward normal."""
    c, s = math.cos(ALPHA), math.sin(ALPHA)
    return np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])


def build():
    m = mb.Model(gravity=(0.0, 0.0, -G), dimension=3)
    axes = slope_axes()
    slope = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), axes, role="collision")
    d_ball = (G * math.cos(ALPHA) / K) ** (2.0 / 3.0)
    d_cube = (G * math.cos(ALPHA) / (4 * K)) ** (2.0 / 3.0)  # on four corners
    for name, y, half, d in (("ball", -0.4, R, d_ball), ("stuck", 0.0, EDGE / 2, d_cube), ("slider", 0.4, EDGE / 2, d_cube)):
        centre = tuple((half - d) * axes[:, 2] + np.array([0.0, y, 0.0]))
        if name == "ball":
            m.add_body(name, mass=1.0, inertia=(0.4 * R * R,) * 3, position=centre)
            shape = m.add_shape(name, "sphere", (R,), centre, role="collision")
        else:
            m.add_body(name, mass=1.0, inertia=(EDGE * EDGE / 6,) * 3, position=centre, orientation=axes)
            shape = m.add_shape(name, "box", (EDGE,) * 3, centre, axes, role="collision")
        m.add_contact(f"{name}_slope", shape, slope, stiffness=K, restitution=0.5,
                      friction=0.2 if name == "slider" else 0.5)
    return m, d_ball


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH",
                        help="draw the three on the incline at 1 s to PATH (.png)")
    parser.add_argument("--gif", metavar="PATH", help="write an animation to PATH (.gif)")
    args = parser.parse_args(argv)
    m, d0 = build()
    r = mb.simulate(m, 1.0, rtol=1e-9, atol=1e-11, n_out=201)
    uphill = slope_axes()[:, 0]
    late = r.t >= 0.5

    def acceleration(body):
        s = r.body(body).position @ uphill
        return -2.0 * np.polyfit(r.t[late], s[late], 2)[0]

    print(f"sphere acceleration = {acceleration('ball'):.10f} m/s^2")
    print(f"sphere closed form = {G * math.sin(ALPHA) / (1 + 2 * R * R / (5 * (R - d0) ** 2)):.10f} m/s^2")
    print(f"sphere on a rigid plane = {5 / 7 * G * math.sin(ALPHA):.10f} m/s^2")
    stuck = r.body("stuck").position[r.t >= 0.1]
    print(f"stuck cube moved after 0.1 s = {np.max(np.linalg.norm(stuck - stuck[0], axis=1)):.3e} m")
    print(f"stuck cube friction = {np.linalg.norm(r.contact('stuck_slope').friction_force[-1]):.9f} N")
    print(f"m g sin a = {G * math.sin(ALPHA):.9f} N")
    print(f"stuck cube state at 1 s = {r.contact('stuck_slope').state[-1]}")
    print(f"slider acceleration = {acceleration('slider'):.9f} m/s^2")
    print(f"slider closed form = {G * (math.sin(ALPHA) - 0.2 * math.cos(ALPHA)):.9f} m/s^2")
    print(f"friction events = {sum(e['kind'] == 'friction' for e in r.events)}")
    print(f"steps = {r.stats['steps']}")
    if args.picture:
        from lagmb.plotting import picture
        picture(r, args.picture, view=(18.0, -75.0), title="on a 20 degree incline: a sphere rolls, "
                "a cube sticks (mu 0.5), a cube slides (mu 0.2)")
        print(f"picture written to {args.picture}")
    if args.gif:
        from lagmb.plotting import animate
        animate(r, args.gif, view=(18.0, -75.0))
        print(f"animation written to {args.gif}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
