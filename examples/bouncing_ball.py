"""A ball bouncing on the floor: compliant contact with restitution.

    python examples/bouncing_ball.py [--picture bouncing_ball-picture.png] [--plot bouncing_ball.png]

A ball (radius 0.1 m, 1 kg) is dropped from rest with its centre 1 m above
the floor line y = 0. The contact "floor" (circle-line, Hunt-Crossley
damping whose rebound is exactly e, k = 1e7 N/m^1.5, e = 0.8) makes each
bounce leave at e times the speed it arrived with (0.2 to 0.5 % less:
gravity presses the ball down during each 4 ms contact, the more so as the
bounces slow), so the apex gap above the floor shrinks by about e^2 = 0.64
per bounce. Contact onset and release are events: the run
restarts there, and r.events lists them with the gap rate (speed) at each.

Closed forms for the ideal impact: first touch after sqrt(2 h / g) with
h = 0.9 m, at sqrt(2 g h) = 4.202 m/s; apex gaps h e^(2k).
"""

import argparse
import math

import lagmb as mb

G, R, H0, E, K = 9.81, 0.1, 1.0, 0.8, 1e7


def build():
    m = mb.Model(gravity=(0.0, -G))
    ball = m.add_body("ball", mass=1.0, inertia=0.4 * R * R, position=(0.0, H0))
    m.add_contact("floor", ball, (0.0, H0), R, m.ground, (0.0, 0.0), (1.0, 0.0), stiffness=K,
                  restitution=E)
    return m


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
                        help="draw the ball at the end with its centre's path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)
    r = mb.simulate(build(), t_end=2.5, rtol=1e-8, atol=1e-10, n_out=501)
    onsets = [e for e in r.events if e["label"] == "onset"]
    releases = [e for e in r.events if e["label"] == "release"]
    h = H0 - R
    print(f"first touch time = {onsets[0]['t']:.8f} s (ideal {math.sqrt(2 * h / G):.8f})")
    print(f"first impact speed = {-onsets[0]['speed_before']:.8f} m/s (ideal {math.sqrt(2 * G * h):.8f})")
    for k, (a, b) in enumerate(zip(onsets, releases)):
        ratio = b["speed_before"] / -a["speed_before"]
        apex = b["speed_before"] ** 2 / (2 * G)
        print(f"bounce {k}: restitution {ratio:.6f}, apex gap {apex:.6f} m")
    ratio = releases[0]["speed_before"] / -onsets[0]["speed_before"]
    print(f"effective restitution = {ratio:.8f}")
    print(f"contact events = {len(r.events)}")
    print(f"steps = {r.stats['steps']}")
    if args.picture:
        draw(r, args.picture, trace="ball", title="a ball bouncing on the floor: its centre's path")
    if args.plot:
        plot(r, args.plot, what=("coordinates", "energy"))


if __name__ == "__main__":
    main()
