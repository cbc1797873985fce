"""An inverted pendulum on a cart balanced by a linear-quadratic regulator
designed on lagmb's own linearization (mb.linearize + SciPy).

The model is examples/cart_pole.py's: a 1 kg cart on a rail, a uniform
1 m, 0.1 kg pole hinged on it, the horizontal force "push" on the cart an
input. mb.linearize gives the motion about the upright equilibrium as
x' = A x + B u in the states (cart.x, pole.angle, der(cart.x),
der(pole.angle)); scipy.linalg.solve_continuous_are gives the Riccati
solution P and the gain K = R^-1 B^T P that minimizes the integral of
x^T Q x + u^T R u. Every 10 ms the controller reads the state and sets

    F = -K (x - x_upright)

(held between samples, as a digital controller does). Started 0.6 rad
from upright, the LQR holds the pole within 2e-4 rad of upright and the
cart within 2e-3 m of x = 0 from 8 s on, pushing at most 27 N. The PD
controller of examples/cart_pole.py, from the same start, keeps the pole
up too but has not settled in 10 s (still 8e-3 rad and 0.1 m off). Both
lose the pole from 1.3 rad (the push they ask for grows without bound).

    python examples/cart_pole_lqr.py [--plot]
"""

import argparse
import math
import sys
from pathlib import Path

import numpy as np
from scipy import linalg

import lagmb as mb

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cart_pole import balance, cart_pole  # noqa: E402  (the model and the PD loop)

PERIOD = 0.01  # s, the controller's sampling period
WEIGHTS = dict(x=10.0, angle=100.0, x_rate=1.0, angle_rate=10.0, push=1.0)


def lqr_gain(model, weights=WEIGHTS):
    """The LQR gain K (1 x 4) and the linear system it is designed on, about
    the upright equilibrium of `model`."""
    lin = mb.linearize(model, inputs=["push"])
    assert lin.states == ["cart.x", "pole.angle", "der(cart.x)", "der(pole.angle)"]
    Q = np.diag([weights["x"], weights["angle"], weights["x_rate"], weights["angle_rate"]])
    R = np.array([[weights["push"]]])
    P = linalg.solve_continuous_are(lin.A, lin.B, Q, R)
    K = np.linalg.solve(R, lin.B.T @ P)
    return K, lin


def state_of(sim, lin):
    """The deviation of the Simulator's state from the operating point, in
    the linear system's states (independent coordinates and their rates)."""
    rows = lin.basis.argmax(axis=0)  # each independent coordinate's own row of q
    return np.concatenate([sim.q[rows] - lin.q[rows], sim.v[rows] - lin.v[rows]])


def balance_lqr(theta0=0.6, t_end=10.0, **options):
    """Runs the LQR loop from a tilt of theta0 (rad) to t_end; returns the
    Simulator and the gain."""
    K, lin = lqr_gain(cart_pole(theta0=0.0))
    sim = mb.Simulator(cart_pole(theta0=theta0), **options)
    for k in range(round(t_end / PERIOD)):
        sim.set_input("push", float(-(K @ state_of(sim, lin))[0]))
        sim.advance((k + 1) * PERIOD)
    return sim, K


def draw(result, path, **kwargs):
    """The mechanism at one output with traced paths (lagmb.plotting.picture, needs matplotlib)."""
    from lagmb.plotting import picture
    picture(result, path, size=(640, 480), **kwargs)
    print(f"picture written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH",
                        help="draw the cart and pole at 1 s with the pole's tip's path to PATH (.png)")
    parser.add_argument("--plot", action="store_true", help="show tilt and push against time (pyplot)")
    args = parser.parse_args(argv)
    K, lin = lqr_gain(cart_pole(theta0=0.0))
    print("open loop eigenvalues:", np.round(lin.eigenvalues, 4))
    print("LQR gain K =", np.round(K, 3), "(N per m, rad, m/s, rad/s)")
    print("closed loop eigenvalues:", np.round(np.linalg.eigvals(lin.A - lin.B @ K), 4))
    sim, _ = balance_lqr(rtol=1e-6)
    r = sim.result()
    tilt = r.body("pole").angle - math.pi / 2
    push = r.input("push")
    print(f"LQR from 0.6 rad: largest tilt after 8 s = {np.max(np.abs(tilt[r.t >= 8.0])):.2e} rad, "
          f"cart at 10 s = {sim.body('cart').position[0]:.2e} m, largest push = {np.max(np.abs(push)):.1f} N")
    pd_sim = balance(cart_pole(theta0=0.6), t_end=10.0, rtol=1e-6)
    pd = pd_sim.result()
    pd_tilt = pd.body("pole").angle - math.pi / 2
    print(f"PD from 0.6 rad: largest tilt after 8 s = {np.max(np.abs(pd_tilt[pd.t >= 8.0])):.2e} rad, "
          f"cart at 10 s = {pd_sim.body('cart').position[0]:.2e} m")
    if args.picture:
        draw(r, args.picture, time=1.0, trace=[("pole", (0.5, 0.0))])
    if args.plot:
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(2, 1, sharex=True)
        axes[0].plot(r.t, tilt, label="LQR")
        axes[0].plot(pd.t, pd_tilt, label="PD (examples/cart_pole.py)")
        axes[0].set_ylabel("pole tilt (rad)")
        axes[0].legend()
        axes[1].plot(r.t, push)
        axes[1].set_ylabel("push (N)")
        axes[1].set_xlabel("t (s)")
        plt.show()


if __name__ == "__main__":
    main()
