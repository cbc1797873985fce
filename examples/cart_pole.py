"""An inverted pendulum on a cart, held upright by a PD controller that sets
the cart force every 10 ms (lagmb.Simulator driven from Python).

The cart (1 kg) slides on a horizontal rail; the pole (a uniform rod of
1 m and 0.1 kg) is hinged on it and starts 0.1 rad from the vertical. The
force on the cart is an input (mb.Input); every 10 ms the controller reads
the state and sets

    F = -(k_p theta + k_d theta') + k_x x + k_v x'

theta the pole's tilt from the vertical (positive: leaning to -x): pushing
the cart under the pole rights it, the small cart terms bring the cart back
to x = 0. The force is held between samples (a zero-order hold, as a digital
controller does); each change restarts the integrator there.

    python examples/cart_pole.py [--plot]
"""

import argparse
import math

import numpy as np

import lagmb as mb

GAINS = dict(k_p=40.0, k_d=8.0, k_x=1.0, k_v=2.0)  # N/rad, N s/rad, N/m, N s/m
PERIOD = 0.01  # s, the controller's sampling period


def cart_pole(theta0=0.1, pole_length=1.0, pole_mass=0.1, cart_mass=1.0):
    """The model: the cart on a rail, the pole tilted theta0 (rad) toward -x,
    the force "push" on the cart an input (initially 0)."""
    m = mb.Model(gravity=(0.0, -9.81))
    cart = m.add_body("cart", mass=cart_mass, inertia=0.01, position=(0.0, 0.0))
    # the pole's axis along its body x: angle pi/2 is upright
    half = 0.5 * pole_length
    pole = m.add_body("pole", mass=pole_mass, inertia=pole_mass * pole_length**2 / 12,
                      position=(-half * math.sin(theta0), half * math.cos(theta0)), angle=math.pi / 2 + theta0)
    m.add_translational("rail", m.ground, cart, at=(0.0, 0.0), axis=(1.0, 0.0))
    m.add_revolute("hinge", cart, pole, at=(0.0, 0.0))
    m.add_force("push", cart, force=(mb.Input(0.0), 0.0))
    return m


def tilt(sim):
    """The pole's tilt from the vertical (rad) and its rate (rad/s)."""
    pole = sim.body("pole")
    return pole.angle - math.pi / 2, pole.angular_velocity


def balance(model, t_end=10.0, gains=GAINS, control=True, **options):
    """Runs the controller loop to t_end; returns the Simulator. With
    control=False the force stays 0 (the pole falls)."""
    sim = mb.Simulator(model, **options)
    for k in range(round(t_end / PERIOD)):
        if control:
            theta, rate = tilt(sim)
            cart = sim.body("cart")
            x, xdot = cart.position[0], cart.velocity[0]
            force = -(gains["k_p"] * theta + gains["k_d"] * rate) + gains["k_x"] * x + gains["k_v"] * xdot
            sim.set_input("push", force)
        sim.advance((k + 1) * PERIOD)
    return sim


def draw(result, path, **kwargs):
    """The mechanism at one output with traced paths (lagmb.plotting.picture, needs matplotlib)."""
    from lagmb.plotting import picture
    picture(result, path, size=(640, 480), **kwargs)
    print(f"picture written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH",
                        help="draw the cart and pole at 1 s with the pole's tip's path to PATH (.png)")
    parser.add_argument("--plot", action="store_true", help="show the tilt against time (pyplot)")
    args = parser.parse_args(argv)
    sim = balance(cart_pole(), rtol=1e-6)
    r = sim.result()
    theta = r.body("pole").angle - math.pi / 2
    print(f"largest tilt = {np.max(np.abs(theta)):.4f} rad (start 0.1)")
    print(f"largest tilt after 2 s = {np.max(np.abs(theta[r.t >= 2.0])):.2e} rad")
    print(f"cart position at 10 s = {sim.body('cart').position[0]:.4f} m")
    print(f"controller samples = {sim.stats['input_changes']}, integrator steps = {sim.stats['steps']}")
    falling = balance(cart_pole(), t_end=3.0, control=False).result()
    print(f"largest tilt in 3 s without control = {np.max(np.abs(falling.body('pole').angle - math.pi / 2)):.3f} rad")
    if args.picture:
        draw(r, args.picture, time=1.0, trace=[("pole", (0.5, 0.0))])
    if args.plot:
        import matplotlib.pyplot as plt

        plt.plot(r.t, theta)
        plt.xlabel("t (s)")
        plt.ylabel("pole tilt (rad)")
        plt.show()


if __name__ == "__main__":
    main()
