"""MuJoCo models (mb.load_mjcf), checked against MuJoCo and lagmb's own.

tests/data/four_bar.xml closes a four-bar with an equality `connect`; it
must move as the four-bar built by hand in the plane. tests/data/chain.xml
is a tree of hinges and a slide in general orientations (contacts
disabled); its joint accelerations must equal MuJoCo's mj_forward.
"""

import os
import warnings

import numpy as np
import pytest

import lagmb as mb

mujoco = pytest.importorskip("mujoco", reason="the mjcf extra (mujoco) is not installed")

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
FOUR_BAR = os.path.join(DATA, "four_bar.xml")
CHAIN = os.path.join(DATA, "chain.xml")


def test_a_closed_loop_in_mjcf_moves_as_the_hand_built_four_bar():
    """The crank, coupler and rocker of four_bar.xml (capsules, MuJoCo's
    inertias), the loop closed by connect: over 1 s the crank angle equals
    that of the planar four-bar built with lagmb's add_revolute from the same
    masses and inertias to 1e-9 rad (the x-z plane is the x-y plane with
    y = -z)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.RedundantConstraintWarning)  # parallel hinges + a ball: one repeats
        model = mb.load_mjcf(FOUR_BAR, contacts="ignore")
        assert [b.name for b in model.bodies] == ["crank", "coupler", "rocker"]
        r = mb.simulate(model, 1.0, n_out=11, rtol=1e-11, atol=1e-13)
    m = mujoco.MjModel.from_xml_path(FOUR_BAR)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    plane = mb.Model(gravity=(0.0, 9.81))

    def body(name, b):
        R = d.ximat[b].reshape(3, 3)
        inertia_y = (R @ np.diag(m.body_inertia[b]) @ R.T)[1, 1]
        x, _, z = d.xipos[b]
        return plane.add_body(name, m.body_mass[b], inertia_y, position=(x, -z))

    crank, coupler, rocker = body("crank", 1), body("coupler", 2), body("rocker", 3)
    plane.add_revolute("A", plane.ground, crank, at=(0.0, 0.0))
    plane.add_revolute("B", crank, coupler, at=(0.5, 0.0))
    plane.add_revolute("D", plane.ground, rocker, at=(1.5, 0.0))
    plane.add_revolute("C", coupler, rocker, at=(1.5, -0.5))
    by_hand = mb.simulate(plane, 1.0, n_out=11, rtol=1e-11, atol=1e-13)
    assert np.ptp(r.joint("A").angle) > 1.0
    np.testing.assert_allclose(r.joint("A").angle, by_hand.joint("A").angle, atol=1e-9)


def test_a_tree_has_mujocos_joint_accelerations():
    """chain.xml (hinges, a slide, bodies turned by euler and quat, a joint
    off its body's origin, a body without joint merged into its parent): at
    5 random states the joint accelerations equal MuJoCo's qacc to 1e-8 of
    the largest."""
    model = mb.load_mjcf(CHAIN)
    js = mb.JointSpace(model)
    assert [b.name for b in model.bodies] == ["l1", "l2", "l3", "l4"] and js.joints == ["j1", "j2", "j3", "j4"]
    m = mujoco.MjModel.from_xml_path(CHAIN)
    d = mujoco.MjData(m)
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) for j in range(m.njnt)]
    rng = np.random.default_rng(4)
    for _ in range(5):
        d.qpos[:], d.qvel[:] = rng.uniform(-1.0, 1.0, m.nq), rng.uniform(-1.0, 1.0, m.nv)
        mujoco.mj_forward(m, d)
        q, v, _ = js.coordinates(dict(zip(names, d.qpos)), dict(zip(names, d.qvel)))
        qdd, _ = mb.solve_accelerations(model, q, v)
        scale = max(1.0, np.abs(d.qacc).max())
        for j, name in enumerate(names):
            assert abs(js.motion(name, q, v, qdd)[2] - d.qacc[j]) <= 1e-8 * scale, name


CHAIN_TEXT = open(CHAIN).read() if os.path.isfile(CHAIN) else ""


@pytest.mark.parametrize("change, words", [
    (('</worldbody>', '</worldbody><tendon><fixed name="t"><joint joint="j1" coef="1"/></fixed></tendon>'),
     "tendon 't': tendons are not supported"),
    (('</worldbody>', '</worldbody><actuator><motor name="m" joint="j1"/></actuator>'),
     "actuator 'm': actuators are not supported yet"),
    (('<joint name="j2" type="hinge" axis="0 1 0" pos="0 0 0"/>',
      '<joint name="j2" type="hinge" axis="0 1 0" pos="0 0 0"/><joint name="j2b" type="hinge" axis="1 0 0"/>'),
     "body 'l2' has 2 joints"),
    (('</worldbody>', '</worldbody><equality><joint joint1="j1" joint2="j2"/></equality>'),
     "equality 'equality0': only connect and weld"),
    (('<joint name="j1" type="hinge" axis="0 0 1"/>', '<joint name="j1" type="hinge" axis="0 0 1" armature="0.1"/>'),
     "joint 'j1': armature is not supported yet"),
    (('<body name="l1"', '<bodyy name="l1"'), "MuJoCo's compiler refused it"),
])
def test_what_lagmb_does_not_read_is_refused_by_name(tmp_path, change, words):
    path = tmp_path / "bad.xml"
    path.write_text(CHAIN_TEXT.replace(*change))
    with pytest.raises(mb.MjcfError) as error:
        mb.load_mjcf(path)
    assert words in str(error.value) and str(path) in str(error.value)


def test_contacts_are_named_not_simulated(tmp_path):
    """Geoms that collide in MuJoCo: a warning names them (contacts="warn"),
    contacts="error" refuses, contacts="ignore" loads quietly."""
    path = tmp_path / "contacts.xml"
    path.write_text(CHAIN_TEXT.replace('<flag contact="disable"/>', ""))
    with pytest.warns(mb.MjcfWarning, match="contacts between geoms are not simulated"):
        mb.load_mjcf(path)
    with pytest.raises(mb.MjcfError, match="geoms collide"):
        mb.load_mjcf(path, contacts="error")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert mb.load_mjcf(path, contacts="ignore").bodies
