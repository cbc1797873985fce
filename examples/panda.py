"""A Franka Emika Panda arm falling under gravity onto its joint limits, with damped joints.

    python examples/panda.py [--plot panda.png] [--gif panda.gif] [--picture arm.png]

The robot is example-robot-data's URDF (pip install example-robot-data, or
the `robots` extra), read by mb.load_urdf with its joint limits: 7 arm
joints and 2 finger slides, at rest, the arm straight up except the elbow
(joint 4), whose limits (-3.07, -0.07) rad exclude 0: load_urdf starts it
at their middle, -1.5708 rad. Each arm joint gets a viscous damper of
0.5 N m s/rad (the file's own tiny damping values are left out,
dynamics=False). The second finger mimics the first (the file's <mimic>,
a joint coupling). The limits are stops: the shoulder (joint 2) swings
onto its upper limit at 0.48 s with restitution 0 and is captured there,
and the limit holds the arm while the other joints swing on.

Prints the shoulder's stop torque at the end against the torque inverse
dynamics needs for the run's own joint motion there (mb.inverse_dynamics),
the largest distance any joint went beyond a limit, and the energy balance
of the 2 s fall: the energy the arm lost is the work of the dampers (the
integral of c w^2 over the joints) plus what the impacts took; after the
last impact the two are equal, as a captured stop does no work.
"""

import argparse
import os
import site
import sys
import sysconfig

import numpy as np

import lagmb as mb

DAMPING = 0.5  # N m s/rad at each arm joint
ARM = [f"panda_joint{k}" for k in range(1, 8)]
SHOULDER_STOP = "panda_joint2_limit"  # (load_urdf's stop of joint 2)


def panda_urdf():
    """The Panda's URDF in the example-robot-data package (None if absent)."""
    for base in sorted({sysconfig.get_paths()["purelib"], *site.getsitepackages()}):
        path = os.path.join(base, "cmeel.prefix", "share", "example-robot-data", "robots", "panda_description",
                            "urdf", "panda.urdf")
        if os.path.isfile(path):
            return path
    return None


def build(path):
    model = mb.load_urdf(path, dynamics=False)
    for joint in ARM:
        model.add_rotational_spring_damper(f"{joint}_damper", joint=joint, damping=DAMPING)
    return model


def limit_excursion(model, result):
    """The largest distance (rad or m) a joint went beyond one of its limits."""
    worst = 0.0
    for kind, stop in model.elements:
        if kind == "add_stop":
            path = result.joint(stop["joint"])
            s = path.angle if hasattr(path, "angle") else path.slide
            worst = max(worst, float(np.max(stop["lower"] - s)), float(np.max(s - stop["upper"])))
    return worst


def damper_work(result):
    """(k,) the work the dampers did from the start to each output: their
    power c w^2 integrated by the two-point Hermite rule, exact for a cubic
    between outputs (it uses the power's rate 2 c w w' from the run's own
    joint accelerations)."""
    rates = np.array([result.joint(joint).rate for joint in ARM])
    accelerations = np.array([result.joint(joint).acceleration for joint in ARM])
    power = DAMPING * np.sum(rates ** 2, axis=0)  # W, what the dampers take
    slope = 2.0 * DAMPING * np.sum(rates * accelerations, axis=0)
    h = np.diff(result.t)
    steps = 0.5 * h * (power[1:] + power[:-1]) + h * h / 12.0 * (slope[:-1] - slope[1:])
    return np.concatenate([[0.0], np.cumsum(steps)])


def plot(result, path):
    """The arm's joint angles against time (needs matplotlib)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        print(f"no plot: {e}")
        return
    fig, ax = plt.subplots(figsize=(7, 4), dpi=120)
    for joint in ARM:
        ax.plot(result.t, result.joint(joint).angle, label=joint.replace("panda_", ""))
    upper = next(stop["upper"] for kind, stop in result.model.elements if stop["name"] == SHOULDER_STOP)
    ax.axhline(upper, color="0.4", ls=":", lw=1, label="joint2's upper limit")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("joint angle (rad)")
    ax.set_title("Panda falling onto its joint limits, damped joints")
    ax.set_ylim(-2.6, 3.6)
    ax.legend(ncol=4, fontsize=8, loc="upper right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path)
    print(f"plot written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plot", metavar="PATH", help="write the joint angles to PATH (.png, .pdf)")
    parser.add_argument("--gif", metavar="PATH", help="write an animation to PATH (.gif)")
    parser.add_argument("--picture", metavar="PATH",
                        help="draw the arm with its collision meshes at 2 s to PATH")
    args = parser.parse_args(argv)
    path = panda_urdf()
    if path is None:
        print("example-robot-data is not installed: pip install example-robot-data")
        return 1
    model = build(path)
    r = mb.simulate(model, 2.0, n_out=2001, formulation="projection", integrator="erk", rtol=1e-9, atol=1e-11)
    print(f"bodies = {len(model.bodies)}")
    print(f"joints = {len(mb.JointSpace(model).joints)}")
    print(f"steps = {r.stats['steps']}")
    print(f"impacts = {r.stats['impacts']}")
    print(f"captures = {r.stats['captures']}")
    print(f"releases = {r.stats['releases']}")
    captured = next(e["t"] for e in r.events if e["element"] == SHOULDER_STOP and e["kind"] == "capture")
    print(f"shoulder captured on its limit at t = {captured:.6f} s")
    print(f"largest excursion beyond a limit = {limit_excursion(model, r):.3e} rad or m")
    joints = {joint: (r.joint(joint).angle[-1], r.joint(joint).rate[-1], r.joint(joint).acceleration[-1])
              for joint in ARM}
    print(f"shoulder stop torque at 2 s = {r.effort(SHOULDER_STOP)[-1]:.9f} N m")
    print(f"inverse dynamics shoulder torque = {mb.inverse_dynamics(model, joints)['panda_joint2']:.9f} N m")
    work = damper_work(r)
    lost = float(r.energy[0] - r.energy[-1])
    print(f"energy lost = {lost:.9f} J")
    print(f"damper work = {work[-1]:.9f} J")
    print(f"impact losses = {lost - work[-1]:.9f} J")
    last = np.searchsorted(r.t, max(e["t"] for e in r.events if e["kind"] == "impact"), side="right")
    print(f"energy lost after the last impact = {r.energy[last] - r.energy[-1]:.9f} J")
    print(f"damper work after the last impact = {work[-1] - work[last]:.9f} J")
    print(f"elbow angle at 2 s = {r.joint('panda_joint4').angle[-1]:.6f} rad")
    if args.plot:
        plot(r, args.plot)
    if args.picture:
        from lagmb.plotting import picture
        picture(r, args.picture, time=2.0,
                title="Franka Panda from URDF (example-robot-data), its shoulder on its limit")
        print(f"picture written to {args.picture}")
    if args.gif:
        from lagmb.plotting import animate
        animate(r, args.gif, view=(15.0, -60.0))
        print(f"animation written to {args.gif}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
