"""Slider-crank driven at constant speed: kinematics and the motor torque.

    python examples/slider_crank.py [--picture slider_crank-picture.png] [--plot slider_crank.png]

Crank O-B (r = 0.1 m, 1 kg) turns at a constant 10 rad/s about the ground
pivot O = (0, 0); the connecting rod B-C (l = 0.3 m, 2 kg) drives the slider C
(0.5 kg) along a horizontal guide through O. The crank starts at 90 deg.

The motor is a driver on the crank's ground pivot ("motor" on revolute "O":
crank angle = pi/2 + 10 t); with it the mechanism has no degree of freedom
left and its motion is pure kinematics:

    x_C = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta))

so the slider is at r + l = 0.4 m when the crank points along +x (outer dead
centre) and at l - r = 0.2 m at 180 deg (inner dead centre). r.effort("motor")
is the torque that keeps the speed constant against inertia and gravity; over
a whole turn it does no net work (the mechanism returns to the same state).
"""

import argparse
import math

import numpy as np

import lagmb as mb

R, L, OMEGA, G = 0.1, 0.3, 10.0, 9.81
THETA0 = math.pi / 2


def build():
    B = np.array([0.0, R])
    C = np.array([math.sqrt(L**2 - R**2), 0.0])
    m = mb.Model(gravity=(0.0, -G))
    crank = m.add_body("crank", mass=1.0, inertia=1.0 * R**2 / 12, position=0.5 * B,
                       angle=THETA0, angular_velocity=OMEGA)
    rod = m.add_body("rod", mass=2.0, inertia=2.0 * L**2 / 12, position=0.5 * (B + C),
                     angle=math.atan2(C[1] - B[1], C[0] - B[0]))
    slider = m.add_body("slider", mass=0.5, inertia=1e-4, position=C)
    m.add_revolute("O", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, rod, at=B)
    m.add_revolute("C", rod, slider, at=C)
    m.add_translational("guide", m.ground, slider, at=C, axis=(1.0, 0.0))
    m.drive_joint("motor", "O", mb.Linear(OMEGA, start=THETA0))
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
                        help="draw the mechanism with the rod's midpoint path to PATH (.png)")
    parser.add_argument("--plot", metavar="PATH", help="write time histories to PATH (.png, .pdf)")
    args = parser.parse_args(argv)

    turn = 2 * math.pi / OMEGA
    t_inner = (math.pi - THETA0) / OMEGA        # crank at 180 deg
    t_outer = (2 * math.pi - THETA0) / OMEGA    # crank at 360 deg
    t_out = np.union1d(np.linspace(0.0, turn, 2001), [t_inner, t_outer])
    model = build()
    r = mb.simulate(model, t_out=t_out, rtol=1e-10, atol=1e-12)

    x = r.body("slider").position[:, 0]
    v = r.body("slider").velocity[:, 0]
    tau = r.effort("motor")
    i_in = int(np.argmin(abs(r.t - t_inner)))
    i_out = int(np.argmin(abs(r.t - t_outer)))
    work = float(np.sum(0.5 * (tau[1:] * OMEGA + tau[:-1] * OMEGA) * np.diff(r.t)))

    print("slider-crank, r = 0.1 m, l = 0.3 m, crank at a constant 10 rad/s, one turn")
    print(f"degrees of freedom = {model.degrees_of_freedom()} (the motor takes the last one)")
    print(f"slider at outer dead centre = {x[i_out]:.10f} m (closed form r + l = {R + L:.1f})")
    print(f"slider at inner dead centre = {x[i_in]:.10f} m (closed form l - r = {L - R:.1f})")
    print(f"stroke = {x.max() - x.min():.8f} m (closed form 2 r = {2 * R:.1f})")
    print(f"max slider speed = {np.abs(v).max():.6f} m/s")
    print(f"max motor torque = {np.abs(tau).max():.6f} N m")
    print(f"motor work over one turn = {work:.3e} J")
    print(f"max |Phi| = {r.residual.max():.3e} m")
    if args.picture:
        draw(r, args.picture, trace=[("rod", (0.0, 0.0))])
    if args.plot:
        plot(r, args.plot)


if __name__ == "__main__":
    main()
