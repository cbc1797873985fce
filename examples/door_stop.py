"""A door swinging shut against its stop, bouncing and coming to rest on it.

    python examples/door_stop.py [--picture door_stop-picture.png] [--plot door_stop.png]

A door (a uniform leaf 0.9 m wide, 30 kg: I = m w^2 / 3 = 8.1 kg m^2 about
its hinge), seen from above, is held open at 1.2 rad and let go. A
counterweight closer pulls it shut with a constant torque of 20 N m. The
stop on the hinge (add_stop, lower limit 0, restitution 0.5) makes each
impact send the door back at half the speed it arrived with; the bounces
shrink geometrically and pile up at a finite time, where the stop captures
the door: from then on the limit holds as a joint equation and the stop's
torque, r.effort("door_stop"), holds the door against the closer.

Closed forms, with alpha = closer torque / I: the first impact at
t1 = sqrt(2 theta0 / alpha) with speed alpha t1; the k-th at
t1 + 2 t1 (e + ... + e^(k-1)) with speed e^(k-1) alpha t1; rest at the
bounces' accumulation point T = t1 (1 + e) / (1 - e); after it the stop's
torque is the closer's, 20 N m, and the door's kinetic energy is 0: every
joule of the closer's work, torque x theta0, was taken by the impacts.
"""

import argparse
import math
import sys

import lagmb as mb

WIDTH, MASS = 0.9, 30.0        # m, kg
OPEN = 1.2                     # rad, where the door is let go
CLOSER = 20.0                  # N m, pulling shut
RESTITUTION = 0.5
INERTIA = MASS * WIDTH ** 2 / 3.0  # kg m^2 about the hinge


def build():
    m = mb.Model()  # seen from above: no gravity in the plane of the door's swing
    door = m.add_body("door", mass=MASS, inertia=MASS * WIDTH ** 2 / 12.0,
                      position=(0.5 * WIDTH * math.cos(OPEN), 0.5 * WIDTH * math.sin(OPEN)), angle=OPEN)
    hinge = m.add_revolute("hinge", m.ground, door, at=(0.0, 0.0))
    m.add_torque("closer", door, -CLOSER)
    m.add_stop("door_stop", hinge, lower=0.0, restitution=RESTITUTION)
    return m


def plot(result, path):
    """The door's angle, the stop's torque and the kinetic energy, one under
    the other (lagmb.plotting.plot_result, which needs matplotlib)."""
    from lagmb.plotting import plot_result

    plot_result(result, path, what=("coordinates", "efforts", "energy"))
    print(f"plot written to {path}")


def draw(result, path, **kwargs):
    """The mechanism at one output with traced paths (lagmb.plotting.picture, needs matplotlib)."""
    from lagmb.plotting import picture
    picture(result, path, size=(640, 480), **kwargs)
    print(f"picture written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH",
                        help="draw the door at 4 s with its edge's path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)
    r = mb.simulate(build(), t_end=4.0, n_out=2001, rtol=1e-10, atol=1e-12)
    alpha = CLOSER / INERTIA
    t1 = math.sqrt(2.0 * OPEN / alpha)
    rest = t1 * (1.0 + RESTITUTION) / (1.0 - RESTITUTION)
    impacts = [e for e in r.events if e["kind"] == "impact"]
    capture = next(e for e in r.events if e["kind"] == "capture")
    print(f"first impact time = {impacts[0]['t']:.10f} s (closed form {t1:.10f})")
    print(f"first impact speed = {-impacts[0]['speed_before']:.10f} rad/s (closed form {alpha * t1:.10f})")
    worst_time = worst_speed = 0.0
    for k, event in enumerate(impacts):
        t_k = t1 + 2.0 * t1 * sum(RESTITUTION ** j for j in range(1, k + 1))
        worst_time = max(worst_time, abs(event["t"] - t_k))
        worst_speed = max(worst_speed, abs(-event["speed_before"] - RESTITUTION ** k * alpha * t1))
        if k < 4:
            print(f"impact {k + 1}: t = {event['t']:.10f} s (closed form {t_k:.10f}), rebound ratio "
                  f"{event['speed_after'] / -event['speed_before']:.10f}")
    print(f"impacts = {len(impacts)}")
    print(f"largest impact time error = {worst_time:.3e} s")
    print(f"largest impact speed error = {worst_speed:.3e} rad/s")
    print(f"capture time = {capture['t']:.10f} s")
    print(f"rest time closed form = {rest:.10f} s")
    angle = r.joint("hinge").angle
    print(f"lowest angle = {angle.min():.3e} rad")
    print(f"angle at 4 s = {angle[-1]:.3e} rad")
    print(f"stop torque at 4 s = {r.effort('door_stop')[-1]:.10f} N m (the closer's {CLOSER:g})")
    print(f"kinetic energy at 4 s = {0.5 * INERTIA * r.joint('hinge').rate[-1] ** 2:.3e} J")
    lost = sum(0.5 * INERTIA * (e["speed_before"] ** 2 - e["speed_after"] ** 2) for e in impacts)
    print(f"energy the impacts took = {lost:.10f} J")
    print(f"closer work = {CLOSER * OPEN:.10f} J")
    if args.picture:
        draw(r, args.picture, trace=[("door", (0.5 * WIDTH, 0.0))])
    if args.plot:
        plot(r, args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
