"""What the URDF tests share: example-robot-data's robots directory and
files, the files lagmb does not read, loading a robot as Pinocchio builds
it, Pinocchio's model of the same file, joint names and random states, and
writing a file of our own."""

import os
import site
import sysconfig
import warnings

import numpy as np
import pytest

import lagmb as mb

pin = pytest.importorskip("pinocchio", reason="the robots extra (pin) is not installed")


def robots_dir():
    bases = {sysconfig.get_paths()["purelib"], *site.getsitepackages()}
    for base in sorted(bases):
        path = os.path.join(base, "cmeel.prefix", "share", "example-robot-data", "robots")
        if os.path.isdir(path):
            return path
    return None


ROBOTS = robots_dir()
if ROBOTS is None:
    pytest.skip("example-robot-data is not installed", allow_module_level=True)

URDFS = sorted(os.path.relpath(os.path.join(d, f), ROBOTS) for d, _, files in os.walk(ROBOTS)
               for f in files if f.endswith(".urdf"))

#: The files lagmb does not read, and the words of the error that says why.
SKIPPED = {
    "ur_description/urdf/ur3.urdf": "the robot has no links",
    # (flying robots: on a fixed base nothing moves; they load with floating_base=True)
    "hector_description/robots/quadrotor_base.urdf": "nothing moves: the root link is the ground",
    "iris_description/robots/iris_simple.urdf": "nothing moves: the root link and the links fixed to it",
}

GRAVITY = (0.0, 0.0, -9.81)


def load(relpath, **options):
    """A robot of example-robot-data as Pinocchio builds it. What lagmb warns
    of in some of the files (inertias that break the triangle inequality or
    have a negative moment, <origin> in <link>, meshes not found, mimics of
    joints the file does not have, joints held because no mass moves with
    them) is checked by the tests of those warnings below; here the robots
    are compared, and the warnings are expected."""
    options = dict(dict(limits=False, dynamics=False, mimic=False), **options)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        return mb.load_urdf(os.path.join(ROBOTS, relpath), **options)


def pinocchio_model(relpath, floating_base=False, js=None):
    """Pinocchio's model of the file. With `js` (lagmb's JointSpace of the
    same file loaded by `load`) it is the model lagmb builds: the joints
    lagmb holds because no mass or inertia moves with them (Romeo's
    fingers, iCub's neck_yaw) or because load_urdf's `hold` says so (human's
    X joints that can reach a gimbal lock) locked at 0, where `load` builds
    the robot, and a body whose inertia tensor is not positive semi-definite (Romeo's
    hips in romeo_laas_small.urdf, whose merged links add no mass) given
    the moments lagmb builds instead (test_an_inertia_no_body_has_is_built_
    with_the_nearest_a_body_has checks them)."""
    from lagmb.urdf.inertias import nearest_rigid_moments

    path = os.path.join(ROBOTS, relpath)
    model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating_base else \
        pin.buildModelFromUrdf(path)
    model.gravity.linear[:] = GRAVITY
    if js is not None:
        for jid in range(1, model.njoints):
            inertia = model.inertias[jid]
            moments, axes = np.linalg.eigh(inertia.inertia)
            if moments.min() < -1e-9 * np.abs(moments).max():
                model.inertias[jid] = pin.Inertia(inertia.mass, inertia.lever,
                                                  axes @ np.diag(nearest_rigid_moments(moments)) @ axes.T)
        held = [jid for jid in range(1, model.njoints) if model.joints[jid].shortname() != "JointModelFreeFlyer"
                and lagmb_name(js, model.names[jid]) not in js.joints]
        if held:
            model = pin.buildReducedModel(model, held, pin.neutral(model))
    return model


def lagmb_name(js, name):
    """A URDF joint's name in lagmb (a joint named like a link is NAME_joint)."""
    return name if name in js.joints else f"{name}_joint"


def random_state(pm, js, rng):
    """Joint values and rates, uniform in [-1, 1] (rad, m, rad/s, m/s), as
    {lagmb joint: value} and as Pinocchio's (q, v) (a continuous joint is
    (cos, sin) there)."""
    positions, rates = {}, {}
    q, v = pin.neutral(pm), np.zeros(pm.nv)
    for jid in range(1, pm.njoints):
        joint = pm.joints[jid]
        if joint.shortname() == "JointModelFreeFlyer":
            continue
        x, xd = rng.uniform(-1.0, 1.0, 2)
        name = lagmb_name(js, pm.names[jid])
        positions[name], rates[name] = x, xd
        if joint.nq == 1:
            q[joint.idx_q] = x
        else:  # unbounded revolute
            q[joint.idx_q:joint.idx_q + 2] = (np.cos(x), np.sin(x))
        v[joint.idx_v] = xd
    return positions, rates, q, v


#: human.urdf's middle joints whose chains reach a gimbal lock with the
#: defaults (neck, shoulders: within the limits; hips: 1.3e-6 rad beyond).
HUMAN_LOCKS = ["left_hip_X", "left_shoulder_X", "middle_cervical_X", "right_hip_X", "right_shoulder_X"]


def write(tmp_path, text, name="robot.urdf"):
    path = tmp_path / name
    path.write_text(text)
    return path


def names(model):
    """The names of a model's elements, in the order they were added."""
    return [values["name"] for _, values in model.elements]
