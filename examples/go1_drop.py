"""A quadruped robot dropped onto the ground comes to rest on it.

    python examples/go1_drop.py [--picture go1.png] [--gif go1.gif]

Unitree Go1 from example-robot-data's URDF (pip install example-robot-data,
or the robots extra) on a floating base, its joint limits on, its joints
free (no motors), is let go 0.35 m above a floor: load_urdf(...,
ground=-0.35) adds the plane and a contact between it and each of the
robot's collision shapes (boxes, cylinders, sphere feet; mb.urdf.
GROUND_CONTACT: k = 1e7 N/m^1.5, e = 0.5, friction 0.8). It lands on its
feet, its legs fold onto their limits and its body comes down on the floor.

At rest, the floor carries the robot's weight: the contacts' normal forces
add up to m g, and no shape is deeper than the whole weight would press a
single point, (m g / k)^(2/3).
"""

import argparse
import os
import site
import sys
import sysconfig
import time
import warnings

import numpy as np

import lagmb as mb

G = 9.81


def go1_urdf():
    """Go1's URDF in the example-robot-data package (None if absent)."""
    for base in sorted({sysconfig.get_paths()["purelib"], *site.getsitepackages()}):
        path = os.path.join(base, "cmeel.prefix", "share", "example-robot-data", "robots", "go1_description",
                            "urdf", "go1.urdf")
        if os.path.isfile(path):
            return path
    return None


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", metavar="PATH", help="draw the robot at rest at 3 s to PATH (.png)")
    parser.add_argument("--gif", metavar="PATH", help="write an animation to PATH (.gif)")
    args = parser.parse_args(argv)
    path = go1_urdf()
    if path is None:
        print("example-robot-data is not installed: pip install example-robot-data")
        return 1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)  # (inertias the file rounds: load_urdf's warning)
        model = mb.load_urdf(path, floating_base=True, ground=-0.35)
    contacts = [kw["name"] for method, kw in model.elements if method == "add_contact"]
    start = time.perf_counter()
    r = mb.simulate(model, 3.0, rtol=1e-6, atol=1e-8, n_out=301)
    wall = time.perf_counter() - start
    weight = G * sum(kw["mass"] for method, kw in model.elements if method == "add_body")
    readings = [r.contact(name) for name in contacts]
    print(f"bodies = {len(model.bodies)}")
    print(f"contacts = {len(contacts)}")
    print(f"largest speed at 3 s = {np.abs(r.v[-1]).max():.3e}")
    print(f"normal forces / weight = {sum(c.normal_force[-1] for c in readings) / weight:.9f}")
    print(f"deepest at rest = {max(c.penetration[-1] for c in readings):.3e} m")
    print(f"whole weight on one point = {(weight / mb.urdf.GROUND_CONTACT['stiffness']) ** (2 / 3):.3e} m")
    print(f"deepest during the run = {max(c.penetration.max() for c in readings):.3e} m")
    print(f"trunk height at rest = {r.body('base').position[-1, 2] + 0.35:.4f} m above the floor")
    print(f"onsets = {sum(e['label'] == 'onset' for e in r.events)}")
    print(f"steps = {r.stats['steps']}")
    print(f"wall time = {wall:.2f} s")
    if args.picture:
        from lagmb.plotting import picture
        picture(r, args.picture, view=(15.0, -50.0), title="Unitree Go1 (example-robot-data) at rest on the floor")
        print(f"picture written to {args.picture}")
    if args.gif:
        from lagmb.plotting import animate
        animate(r, args.gif, view=(15.0, -50.0))
        print(f"animation written to {args.gif}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
