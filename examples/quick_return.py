"""Whitworth quick-return mechanism (as on a shaping machine).

    python examples/quick_return.py [--picture quick_return-picture.png] [--plot quick_return.png]

    crank   O2-P, r = 0.1 m, turned at a constant 2 pi rad/s (one turn per
            second) about O2 = (0, 0) by the driver "motor"
    lever   a slotted bar 0.3 m long pivoted at its centre O4 = (0, 0.04); the
            crank pin P runs in its slot (pin-in-slot joint "slot")
    link    Q-R, 0.4 m, from the lever's end Q (0.15 m from O4, on the other
            side of O4 from P) to the ram
    ram     slides on a horizontal guide through O4 (translational "guide")

O2O4 = 0.04 m is shorter than the crank, so the lever turns fully too, but not
uniformly: it is fast while P passes below O4 and slow while P is above.
O4-Q-R is an in-line slider-crank whose crank is the lever, so the ram's
stroke is 2 x 0.15 = 0.3 m, with its ends where the lever is horizontal, i.e.
where P is level with O4: sin(theta2) = 0.04 / 0.1, theta2 = 23.58 deg and
156.42 deg. The crank covers 180 + 2 x 23.58 = 227.16 deg during one stroke
(the working stroke) and 132.84 deg during the other (the quick return):
time ratio 227.16 / 132.84 = 1.710.
"""

import argparse
import math

import numpy as np

import lagmb as mb

G = 9.81
R_CRANK, O4, HALF_LEVER, LINK = 0.1, np.array([0.0, 0.04]), 0.15, 0.4
OMEGA = 2 * math.pi


def build():
    P = np.array([0.0, R_CRANK])                  # crank at 90 deg
    Q = O4 + np.array([0.0, -HALF_LEVER])         # lever vertical, slot upwards
    Rp = np.array([math.sqrt(LINK**2 - HALF_LEVER**2), O4[1]])
    m = mb.Model(gravity=(0.0, -G))
    crank = m.add_body("crank", mass=1.0, inertia=R_CRANK**2 / 12, position=0.5 * P,
                       angle=math.pi / 2, angular_velocity=OMEGA)
    lever = m.add_body("lever", mass=2.0, inertia=2.0 * 0.3**2 / 12, position=O4, angle=math.pi / 2)
    link = m.add_body("link", mass=1.0, inertia=LINK**2 / 12, position=0.5 * (Q + Rp),
                      angle=math.atan2(Rp[1] - Q[1], Rp[0] - Q[0]))
    ram = m.add_body("ram", mass=3.0, inertia=0.01, position=Rp)
    m.add_revolute("O2", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("O4", m.ground, lever, at=O4)
    m.add_pin_in_slot("slot", lever, crank, at=P, axis=(0.0, 1.0))
    m.add_revolute("Q", lever, link, at=Q)
    m.add_revolute("R", link, ram, at=Rp)
    m.add_translational("guide", m.ground, ram, at=Rp, axis=(1.0, 0.0))
    m.drive_joint("motor", "O2", mb.Linear(OMEGA, start=math.pi / 2))
    return m


def turning_times(t, v, a):
    """Where v changes sign: the root of the cubic Hermite interpolant of v
    (from v and a = dv/dt at both ends of the bracketing output interval),
    by Newton's method; error O(h^4). Returns the times and the index of the
    output just before each."""
    times, index = [], []
    for k in np.nonzero(v[:-1] * v[1:] < 0)[0]:
        h = t[k + 1] - t[k]
        v0, v1, d0, d1 = v[k], v[k + 1], a[k] * h, a[k + 1] * h
        s = v0 / (v0 - v1)
        for _ in range(20):
            p = ((2 * s**3 - 3 * s**2 + 1) * v0 + (s**3 - 2 * s**2 + s) * d0
                 + (-2 * s**3 + 3 * s**2) * v1 + (s**3 - s**2) * d1)
            dp = ((6 * s**2 - 6 * s) * v0 + (3 * s**2 - 4 * s + 1) * d0
                  + (-6 * s**2 + 6 * s) * v1 + (3 * s**2 - 2 * s) * d1)
            s -= p / dp
        times.append(t[k] + s * h)
        index.append(k)
    return np.array(times), np.array(index)


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
                        help="draw the mechanism at 1.2 s with the ram's path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)

    model = build()
    r = mb.simulate(model, t_end=1.2, rtol=1e-10, atol=1e-12, n_out=1201)
    ram = r.body("ram")
    x, v, a = ram.position[:, 0], ram.velocity[:, 0], ram.acceleration[:, 0]
    (t1, t2, *_), (k1, k2, *_) = turning_times(r.t, v, a)
    # ram position at the turning times (second-order Taylor step)
    x1 = x[k1] + v[k1] * (t1 - r.t[k1]) + 0.5 * a[k1] * (t1 - r.t[k1])**2
    x2 = x[k2] + v[k2] * (t2 - r.t[k2]) + 0.5 * a[k2] * (t2 - r.t[k2])**2
    slow, quick = t2 - t1, 1.0 - (t2 - t1)
    theta2 = math.asin(O4[1] / R_CRANK)

    print("Whitworth quick return: crank 0.1 m at one turn per second, lever pivot 0.04 m above")
    print(f"degrees of freedom = {model.degrees_of_freedom()}")
    print(f"ram turns at t1 = {t1:.10f} s (closed form {(math.pi / 2 - theta2) / OMEGA:.10f})")
    print(f"ram turns at t2 = {t2:.10f} s (closed form {(1.5 * math.pi + theta2) / OMEGA:.10f})")
    print(f"stroke = {abs(x2 - x1):.10f} m (closed form 2 x 0.15 = 0.3)")
    print(f"working stroke time = {max(slow, quick):.10f} s")
    print(f"return stroke time = {min(slow, quick):.10f} s")
    print(f"time ratio = {max(slow, quick) / min(slow, quick):.10f} "
          f"(closed form {(math.pi + 2 * theta2) / (math.pi - 2 * theta2):.10f})")
    print(f"max ram speed = {np.abs(v).max():.6f} m/s")
    print(f"max motor torque = {np.abs(r.effort('motor')).max():.6f} N m")
    print(f"max slot force = {np.abs(r.reaction('slot', frame='joint')[:, 1]).max():.6f} N")
    print(f"max |Phi| = {r.residual.max():.3e} m")
    if args.picture:
        draw(r, args.picture, trace="ram")
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
