"""Four-bar linkage (crank-rocker) swinging freely under gravity.

    python examples/four_bar.py [--picture four_bar-picture.png] [--plot four_bar.png]

Ground pivots A = (0, 0) and D = (4, 0); crank AB = 1 m, coupler BC = 3.5 m,
rocker DC = 3 m; uniform bars of 1 kg per metre. Grashof: shortest + longest
= 1 + 4 < 3.5 + 3, and the shortest link is the crank, so the crank can turn
fully while the rocker swings between the two positions where crank and
coupler are in line (AC = 3.5 - 1 and 3.5 + 1): the angle ADC goes from
acos((4^2 + 3^2 - 2.5^2) / 24) = 38.62 deg to acos((25 - 4.5^2) / 24) =
78.58 deg, a swing of 39.96 deg.

The crank starts at 60 deg turning at 12 rad/s, and every bar is given the
velocity that goes with it (loop closure, below). lagmb would make any given
velocities consistent itself, but by the least change in kinetic energy: a
crank given 12 rad/s with the heavy coupler and rocker at rest would start
at 0.4 rad/s.

Counting (Gruebler): 3 moving bodies, 4 revolutes: 3 (4 - 1) - 2 x 4 = 1
degree of freedom. A closed loop is where joint coordinates get awkward and
body coordinates do not: each revolute is two equations, nothing more.
"""

import argparse
import math

import numpy as np

import lagmb as mb

G = 9.81
A, D = np.array([0.0, 0.0]), np.array([4.0, 0.0])
CRANK, COUPLER, ROCKER = 1.0, 3.5, 3.0


def circle_intersection(c0, r0, c1, r1):
    """The intersection of two circles to the left of the line c0 -> c1."""
    d = np.linalg.norm(c1 - c0)
    a = (r0**2 - r1**2 + d**2) / (2 * d)
    h = math.sqrt(r0**2 - a**2)
    u = (c1 - c0) / d
    return c0 + a * u + h * np.array([-u[1], u[0]])


def bar(model, name, p, q, **kw):
    """A uniform bar of 1 kg/m from p to q (centre at the midpoint)."""
    length = float(np.linalg.norm(q - p))
    return model.add_body(name, mass=length, inertia=length**3 / 12, position=0.5 * (p + q),
                          angle=math.atan2(q[1] - p[1], q[0] - p[0]), **kw)


def perp(w, r):
    """The velocity w x r of a point at r from a centre of rotation."""
    return w * np.array([-r[1], r[0]])


def build(crank_angle=math.radians(60.0), omega=12.0):
    B = A + CRANK * np.array([math.cos(crank_angle), math.sin(crank_angle)])
    C = circle_intersection(B, COUPLER, D, ROCKER)
    # loop closure, differentiated: v_C = w_crank x (B - A) + w_coupler x (C - B)
    # = w_rocker x (C - D), two equations for w_coupler and w_rocker
    vB = perp(omega, B - A)
    w_coupler, w_rocker = np.linalg.solve(
        np.column_stack([perp(1.0, C - B), -perp(1.0, C - D)]), -vB)
    m = mb.Model(gravity=(0.0, -G))
    crank = bar(m, "crank", A, B, velocity=0.5 * vB, angular_velocity=omega)
    coupler = bar(m, "coupler", B, C, velocity=vB + perp(w_coupler, 0.5 * (C - B)),
                  angular_velocity=w_coupler)
    rocker = bar(m, "rocker", D, C, velocity=perp(w_rocker, 0.5 * (C - D)),
                 angular_velocity=w_rocker)
    m.add_revolute("A", m.ground, crank, at=A)
    m.add_revolute("B", crank, coupler, at=B)
    m.add_revolute("C", coupler, rocker, at=C)
    m.add_revolute("D", rocker, m.ground, at=D)
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
                        help="draw the linkage at 3 s with the coupler's midpoint path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)

    model = build()
    r = mb.simulate(model, t_end=3.0, rtol=1e-10, atol=1e-12, n_out=3001)
    crank, rocker = r.body("crank"), r.body("rocker")
    # the coupler's ends, each taken from the bar it is pinned to
    B = r.point("crank", (0.5 * CRANK, 0.0))
    C = r.point("rocker", (0.5 * ROCKER, 0.0))
    coupler_error = np.abs(np.hypot(*(C - B).T) - COUPLER).max()

    print("four-bar crank-rocker (1, 3.5, 3, ground 4 m), swinging freely for 3 s")
    print(f"degrees of freedom = {model.degrees_of_freedom()} (Gruebler: 3 (4 - 1) - 2 x 4 = 1)")
    print(f"crank speed at start = {crank.angular_velocity[0]:.10f} rad/s (as given: 12)")
    print(f"crank turns = {(crank.angle[-1] - crank.angle[0]) / (2 * math.pi):.4f}")
    print(f"rocker swing = {math.degrees(np.ptp(rocker.angle)):.4f} deg (closed form 39.9600)")
    print(f"max coupler length error = {coupler_error:.3e} m")
    print(f"energy = {r.energy[0]:.6f} J (kinetic + gravity, datum y = 0)")
    print(f"energy drift = {np.ptp(r.energy):.3e} J")
    print(f"max |Phi| = {r.residual.max():.3e} m")
    print(f"steps = {r.stats['steps']}")
    if args.picture:
        draw(r, args.picture, trace=[("coupler", (0.0, 0.0))])
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
