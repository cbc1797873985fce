"""MuJoCo models (mb.load_mjcf), checked against MuJoCo and lagmb's own.

tests/data/four_bar.xml closes a four-bar with an equality `connect`; it
must move as the four-bar built by hand in the plane. tests/data/chain.xml
is a tree of hinges and a slide in general orientations (contacts
disabled); its joint accelerations must equal MuJoCo's mj_forward.
tests/data/floating_tree.xml (a free base with two branches of ball, hinge
and slide joints, a second free body) and tests/data/ball_chain.xml (a
fixed-base chain of ball joints, a hinge and a slide) take every joint kind
load_mjcf reads: at random states their accelerations, mapped to MuJoCo's
joint space, must equal mj_forward's qacc.
"""

import math
import os
import warnings

import numpy as np
import pytest

import lagmb as mb

mujoco = pytest.importorskip("mujoco", reason="the mjcf extra (mujoco) is not installed")

from paths import DATA  # noqa: E402
FOUR_BAR = os.path.join(DATA, "four_bar.xml")
CHAIN = os.path.join(DATA, "chain.xml")
FLOATING_TREE = os.path.join(DATA, "floating_tree.xml")
BALL_CHAIN = os.path.join(DATA, "ball_chain.xml")


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


def _E(p):
    """E(p) (3 x 4): omega = 2 E(p) p' in global axes (lagmb's Euler parameters p = (w, x, y, z))."""
    w, x, y, z = p
    return np.array([[-x, w, -z, y], [-y, z, w, -x], [-z, -y, x, w]])


def _random_state(m, d, rng):
    """MuJoCo's qpos and qvel at random: hinges within a turn, slides within
    0.5 m of their reference, ball and free joints at random unit quaternions,
    free bodies within 1 m of their reference position; rates within 2 rad/s
    or m/s."""
    for j in range(m.njnt):
        a, kind = m.jnt_qposadr[j], m.jnt_type[j]
        if kind == mujoco.mjtJoint.mjJNT_FREE:
            d.qpos[a:a + 3] = m.qpos0[a:a + 3] + rng.uniform(-1.0, 1.0, 3)
            a += 3
        if kind in (mujoco.mjtJoint.mjJNT_FREE, mujoco.mjtJoint.mjJNT_BALL):
            p = rng.normal(size=4)
            d.qpos[a:a + 4] = p / np.linalg.norm(p)
        elif kind == mujoco.mjtJoint.mjJNT_SLIDE:
            d.qpos[a] = m.qpos0[a] + rng.uniform(-0.5, 0.5)
        else:
            d.qpos[a] = rng.uniform(-np.pi, np.pi)
    d.qvel[:] = rng.uniform(-2.0, 2.0, m.nv)


def _lagmb_state(model, m, d):
    """lagmb's (q, v) of MuJoCo's state in d (after mj_forward): each lagmb
    body is a MuJoCo body with a joint and the jointless bodies below it, at
    their common centre of mass, its axes the MuJoCo body's (xquat), its
    velocity that of the centre of mass from MuJoCo's body velocity."""
    group = {0: 0}
    for b in range(1, m.nbody):
        group[b] = b if m.body_jntnum[b] else group[int(m.body_parentid[b])]
    ids = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, body.name) for body in model.bodies]
    q, v = np.zeros(7 * len(ids)), np.zeros(7 * len(ids))
    for k, b in enumerate(ids):
        members = [c for c in range(1, m.nbody) if group[c] == b]
        com = sum(m.body_mass[c] * d.xipos[c] for c in members) / sum(m.body_mass[c] for c in members)
        motion = np.zeros(6)  # (angular, linear at the body origin), world axes
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_XBODY, b, motion, 0)
        omega = motion[:3]
        p = d.xquat[b] / np.linalg.norm(d.xquat[b])
        q[7 * k:7 * k + 7] = np.concatenate([com, p])
        v[7 * k:7 * k + 7] = np.concatenate([motion[3:] + np.cross(omega, com - d.xpos[b]), 0.5 * _E(p).T @ omega])
    return q, v, group, {b: k for k, b in enumerate(ids)}


def _mujoco_accelerations(m, d, q, v, qdd, group, slot):
    """lagmb's accelerations qdd as MuJoCo's qacc: a hinge's is the relative
    angular acceleration along its axis, a slide's the second derivative of
    the child's position along the axis in the parent's axes, a ball's the
    derivative of the relative angular velocity in the child's axes
    (R^T (alpha_c - alpha_p + omega_c x omega_p)); a free joint's the
    acceleration of the body origin (world axes) and the angular acceleration
    in the body's axes."""
    def motion(b):  # position, axes, velocity, angular velocity, acceleration, angular acceleration
        if b == 0:
            zero = np.zeros(3)
            return zero, np.eye(3), zero, zero, zero, zero
        k = slot[b]
        p = q[7 * k + 3:7 * k + 7]
        w, x, y, z = p
        R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
        return (q[7 * k:7 * k + 3], R, v[7 * k:7 * k + 3], 2.0 * _E(p) @ v[7 * k + 3:7 * k + 7],
                qdd[7 * k:7 * k + 3], 2.0 * _E(p) @ qdd[7 * k + 3:7 * k + 7])

    qacc = np.zeros(m.nv)
    for j in range(m.njnt):
        b, i, kind = int(m.jnt_bodyid[j]), int(m.jnt_dofadr[j]), m.jnt_type[j]
        r, R, vc, wc, ac, alc = motion(b)
        rp, _, vp, wp, ap, alp = motion(group[int(m.body_parentid[b])])
        if kind == mujoco.mjtJoint.mjJNT_HINGE:
            qacc[i] = d.xaxis[j] @ (alc - alp)
        elif kind == mujoco.mjtJoint.mjJNT_SLIDE:
            e, ed, edd = r - rp, vc - vp, ac - ap
            qacc[i] = d.xaxis[j] @ (edd - np.cross(alp, e) - 2.0 * np.cross(wp, ed) + np.cross(wp, np.cross(wp, e)))
        elif kind == mujoco.mjtJoint.mjJNT_BALL:
            qacc[i:i + 3] = R.T @ (alc - alp + np.cross(wc, wp))
        else:
            e = d.xpos[b] - r
            qacc[i:i + 3] = ac + np.cross(alc, e) + np.cross(wc, np.cross(wc, e))
            qacc[i + 3:i + 6] = R.T @ alc
    return qacc


def _largest_difference_to_mj_forward(path, seed, states=5):
    """The largest difference between lagmb's accelerations (mapped to
    MuJoCo's joint space) and mj_forward's qacc over `states` random states,
    relative to the largest |qacc|; contacts disabled in MuJoCo. Each state
    given to lagmb holds its joints to 1e-12 (positions and velocities), and
    each hinge's and slide's value and rate (JointSpace.motion) are MuJoCo's
    qpos (a hinge's modulo a turn) and qvel."""
    model = mb.load_mjcf(path, contacts="ignore")
    core = model.compiled()
    js = mb.JointSpace(model)
    m = mujoco.MjModel.from_xml_path(path)
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    d = mujoco.MjData(m)
    # the reference configuration: lagmb's initial state is MuJoCo's at qpos0
    mujoco.mj_forward(m, d)
    q, v, group, slot = _lagmb_state(model, m, d)
    q0, v0 = core.initial_state()
    for k in range(len(model.bodies)):
        np.testing.assert_allclose(q0[7 * k:7 * k + 3], q[7 * k:7 * k + 3], atol=1e-12)
        assert abs(abs(q0[7 * k + 3:7 * k + 7] @ q[7 * k + 3:7 * k + 7]) - 1.0) < 1e-12
    assert not np.any(v0)
    rng = np.random.default_rng(seed)
    worst = 0.0
    for _ in range(states):
        _random_state(m, d, rng)
        mujoco.mj_forward(m, d)
        q, v, group, slot = _lagmb_state(model, m, d)
        assert core.residual(np.zeros(1), q[None], np.zeros((0, 0)))[0] < 1e-12
        assert core.velocity_residual(np.zeros(1), q[None], v[None], np.zeros((0, 0)))[0] < 1e-12
        for j in range(m.njnt):
            if m.jnt_type[j] in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE):
                value, rate, _ = js.motion(mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j), q, v)
                off = value - d.qpos[m.jnt_qposadr[j]]
                if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE:
                    off = math.remainder(off, 2 * math.pi)
                assert abs(off) < 1e-12 and abs(rate - d.qvel[m.jnt_dofadr[j]]) < 1e-12
        qdd, _ = mb.solve_accelerations(model, q, v)
        qacc = _mujoco_accelerations(m, d, q, v, qdd, group, slot)
        worst = max(worst, np.abs(qacc - d.qacc).max() / np.abs(d.qacc).max())
    return worst


@pytest.mark.parametrize("path, bodies, seed", [
    (CHAIN, ["l1", "l2", "l3", "l4"], 1),
    (FLOATING_TREE, ["base", "lid", "upper_a", "lower_a", "finger_a", "upper_b", "lower_b", "puck", "puck_arm"], 2),
    (BALL_CHAIN, ["link1", "link2", "link3", "link4"], 3),
], ids=["chain", "floating_tree", "ball_chain"])
def test_trees_of_every_joint_kind_have_mujocos_accelerations(path, bodies, seed):
    """Hinge, slide, ball and free joints (a free base with two branches, a
    second free body, a fixed-base chain of balls), frames turned by quat,
    euler (two sequences, degrees and radians), axisangle, xyaxes and zaxis,
    inertial frames off the body origin and turned, joints off the body
    origin, hinge and slide refs, jointless bodies merged into their parents
    (and into the ground), hinge damping, gravity off the vertical: at 5
    random states lagmb's accelerations are mj_forward's qacc to 1e-9 of the
    largest (seen 5e-14; 2e-13 over 200 states)."""
    model = mb.load_mjcf(path)
    assert [b.name for b in model.bodies] == bodies
    assert _largest_difference_to_mj_forward(path, seed) < 1e-9


@pytest.mark.parametrize("path, change, left_out", [
    (FLOATING_TREE, ('<flag contact="disable"/>', '<flag contact="disable" gravity="disable"/>'), "gravity"),
    (FLOATING_TREE, ('<flag contact="disable"/>', '<flag contact="disable" damper="disable"/>'), "elbow_a_damping"),
    (FOUR_BAR, ('<option gravity="0 0 -9.81"/>', '<option gravity="0 0 -9.81"><flag equality="disable"/></option>'),
     "equality0"),
    (FOUR_BAR, ('<option gravity="0 0 -9.81"/>', '<option gravity="0 0 -9.81"><flag constraint="disable"/></option>'),
     "equality0"),
], ids=["gravity", "damper", "equality", "constraint"])
def test_what_mujocos_flags_disable_lagmb_leaves_out(tmp_path, path, change, left_out):
    """<option><flag gravity|damper|equality|constraint="disable"/>: MuJoCo
    leaves out gravity, joint damping or the equality constraints, and so
    does lagmb (it read them before: 0.48, 6.8 and 0.90 of the largest qacc
    apart); the accelerations are mj_forward's to 1e-9."""
    text = open(path).read()
    assert change[0] in text
    path = tmp_path / os.path.basename(path)
    path.write_text(text.replace(*change))
    model = mb.load_mjcf(path, contacts="ignore")
    if left_out == "gravity":
        assert tuple(model.gravity) == (0.0, 0.0, 0.0)
    else:
        assert left_out not in [values["name"] for _, values in model.elements]
    assert _largest_difference_to_mj_forward(str(path), 5) < 1e-9


CHAIN_TEXT = open(CHAIN).read() if os.path.isfile(CHAIN) else ""
PLUGIN_SENSOR = ('<extension><plugin plugin="mujoco.sensor.touch_grid"/></extension><sensor><plugin name="touch" '
                 'plugin="mujoco.sensor.touch_grid" objtype="site" objname="s"><config key="size" value="7 7"/>'
                 '<config key="fov" value="45 45"/><config key="gamma" value="0"/><config key="nchannel" value="3"/>'
                 '</plugin></sensor>')
WORLD = '</worldbody>'
J1 = '<joint name="j1" type="hinge" axis="0 0 1"/>'
J3 = '<joint name="j3" type="slide" axis="1 0 0.2"/>'
TOOL = '<geom type="sphere" size="0.03" mass="0.2"/>'


def _with(joint, attributes):
    """(joint, the joint with attributes): a change of one joint element."""
    return joint, joint.replace("/>", f" {attributes}/>")


#: (id, file, changes (old, new) to its text, the words of the refusal)
REFUSALS = [
    ("tendon", CHAIN, [(WORLD, WORLD + '<tendon><fixed name="t"><joint joint="j1" coef="1"/></fixed></tendon>')],
     "tendon 't': tendons are not supported"),
    ("actuator", CHAIN, [(WORLD, WORLD + '<actuator><motor name="m" joint="j1"/></actuator>')],
     "actuator 'm': actuators are not supported yet"),
    ("flex", CHAIN, [(WORLD, '<flexcomp name="f" type="grid" count="3 1 1" spacing="0.1 0.1 0.1" mass="1" '
                             'radius="0.01" dim="1"/>' + WORLD)],
     "flex 'f': flexes (deformable bodies) are not supported"),
    ("plugin", CHAIN, [(TOOL, TOOL + '<site name="s" size="0.01"/>'), (WORLD, WORLD + PLUGIN_SENSOR)],
     "plugin 'plugin0': plugins are not supported"),
    ("density", CHAIN, [("<option ", '<option density="1.2" ')],
     "option density=1.2 viscosity=0: fluid forces are not supported"),
    ("viscosity", CHAIN, [("<option ", '<option viscosity="0.01" ')],
     "option density=0 viscosity=0.01: fluid forces are not supported"),
    ("gravcomp", CHAIN, [('<body name="l2"', '<body name="l2" gravcomp="1"')],
     "body 'l2': gravity compensation (gravcomp) is not supported"),
    ("two joints", CHAIN, [(J3, J3 + '<joint name="j3b" type="hinge" axis="1 0 0"/>')],
     "body 'l3' has 2 joints"),
    ("quadratic joint equality", CHAIN,
     [(WORLD, WORLD + '<equality><joint joint1="j1" joint2="j2" polycoef="0 1 0.5 0 0"/></equality>')],
     "equality 'equality0': a joint equality with polycoef beyond the linear term (0 1 0.5 0 0)"),
    ("connect between sites", CHAIN,
     [(TOOL, TOOL + '<site name="s"/>'), (J1, J1 + '<site name="s0"/>'),
      (WORLD, WORLD + '<equality><connect name="c" site1="s0" site2="s"/></equality>')],
     "equality 'c': only connect and weld between bodies and joint equalities are read"),
    ("weld relpose", FOUR_BAR,
     [('<connect body1="coupler" body2="rocker" anchor="1 0 0.5"/>',
       '<weld name="w" body1="coupler" body2="rocker" relpose="0.1 0 0 1 0 0 0"/>')],
     "equality 'w': MuJoCo holds its bodies elsewhere than where they are in the reference configuration"),
    ("armature", CHAIN, [_with(J1, 'armature="0.1"')], "joint 'j1': armature is not supported yet"),
    ("frictionloss", CHAIN, [_with(J1, 'frictionloss="0.1"')], "joint 'j1': frictionloss is not supported yet"),
    ("stiffness", CHAIN, [_with(J1, 'stiffness="2"')], "joint 'j1': stiffness is not supported yet"),
    ("nonlinear stiffness", CHAIN, [_with(J1, 'stiffness="0 2"')], "joint 'j1': stiffness is not supported yet"),
    ("springdamper", CHAIN, [_with(J1, 'springdamper="0.5 0.3"')], "joint 'j1': stiffness is not supported yet"),
    ("range", CHAIN, [_with(J1, 'range="-1 1"')], "joint 'j1': limits (range) are not read yet"),
    ("nonlinear damping", CHAIN, [_with(J1, 'damping="0.5 0.2"')],
     "joint 'j1': nonlinear damping (damping with more than one coefficient) is not supported"),
    ("ball damping", FLOATING_TREE,
     [('<joint name="knee_b" type="ball"', '<joint name="knee_b" type="ball" damping="0.3"')],
     "joint 'knee_b': damping of a ball joint is not supported yet"),
    ("free damping", FLOATING_TREE, [('<freejoint name="root"/>', '<joint name="root" type="free" damping="0.4"/>')],
     "joint 'root': damping of a free joint is not supported yet"),
    ("compiler", CHAIN, [('<body name="l1"', '<bodyy name="l1"')], "MuJoCo's compiler refused it"),
]


@pytest.mark.parametrize("source, changes, words", [pytest.param(*case[1:], id=case[0]) for case in REFUSALS])
def test_what_lagmb_does_not_read_is_refused_by_name(tmp_path, source, changes, words):
    """Each refusal names the file and the MuJoCo element (before, fluid
    forces, gravcomp, nonlinear damping and stiffness, a free joint's damping
    and a weld's relpose loaded, with other accelerations than MuJoCo's, and
    a flex was refused as a body with 3 joints)."""
    text = open(source).read()
    for old, new in changes:
        assert old in text
        text = text.replace(old, new, 1)
    path = tmp_path / "bad.xml"
    path.write_text(text)
    with pytest.raises(mb.MjcfError) as error:
        mb.load_mjcf(path, contacts="ignore")
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


def test_an_explicit_contact_pair_is_named(tmp_path):
    """Geoms that collide only as a <contact><pair> (contype and
    conaffinity 0) are named too (before: loaded without a word); with
    <flag constraint="disable"/> MuJoCo has no contacts and nothing is said."""
    text = (CHAIN_TEXT.replace('<flag contact="disable"/>', "").replace("<geom ", '<geom contype="0" conaffinity="0" ')
            .replace('<geom contype="0" conaffinity="0" type="sphere"', '<geom name="tip" contype="0" conaffinity="0" '
                     'type="sphere"')
            .replace("</worldbody>", '<geom name="floor" type="plane" size="2 2 0.1" contype="0" conaffinity="0"/>'
                     '</worldbody><contact><pair geom1="floor" geom2="tip"/></contact>'))
    path = tmp_path / "pair.xml"
    path.write_text(text)
    with pytest.warns(mb.MjcfWarning, match="2 geoms collide in MuJoCo: 'floor', 'tip'"):
        mb.load_mjcf(path)
    path.write_text(text.replace("<option ", '<option><flag constraint="disable"/></option><option '))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert mb.load_mjcf(path).bodies


def test_contacts_takes_warn_ignore_error_or_simulate():
    with pytest.raises(mb.ModelError, match="contacts must be 'warn', 'ignore', 'error' or 'simulate'"):
        mb.load_mjcf(CHAIN, contacts="yes")


def test_a_slides_damping_is_mujocos(tmp_path):
    """A slide's damping (a translational joint's viscous friction in
    lagmb): the accelerations are mj_forward's to 1e-9 at random states."""
    path = tmp_path / "chain.xml"
    path.write_text(CHAIN_TEXT.replace(*_with(J3, 'damping="0.5"')))
    model = mb.load_mjcf(path, contacts="ignore")
    assert ("add_joint_friction", dict(name="j3_damping", joint="j3", viscous=0.5, preload=0.0,
                                       slip_velocity=0.001)) in model.elements
    assert _largest_difference_to_mj_forward(str(path), 4) < 1e-9


def test_a_joint_equality_couples_two_joints(tmp_path):
    """<joint joint1="j2" joint2="j1" polycoef="0.1 -0.5 0 0 0">: MuJoCo's
    j2 - j2_0 = 0.1 - 0.5 (j1 - j1_0) (values from qpos0), in lagmb a joint
    coupling j2 = -0.5 j1 + (j2_0 + 0.1 + 0.5 j1_0) that holds in a run; one
    joint alone (joint2 left out) is held at j1_0 + a0 by a driver."""
    text = CHAIN_TEXT.replace(WORLD, WORLD + '<equality><joint name="gear" joint1="j2" joint2="j1" '
                              'polycoef="0 -0.5 0 0 0"/></equality>')
    path = tmp_path / "geared.xml"
    path.write_text(text)
    model = mb.load_mjcf(path, contacts="ignore")
    m = mujoco.MjModel.from_xml_path(str(path))
    j1_0, j2_0 = (math.remainder(float(m.qpos0[m.jnt_qposadr[m.joint(n).id]]), 2 * math.pi) for n in ("j1", "j2"))
    coupling = [kw for method, kw in model.elements if method == "add_joint_coupling"]
    assert coupling == [dict(name="gear", joint="j2", leader="j1", multiplier=-0.5,
                             offset=pytest.approx(j2_0 + 0.5 * j1_0, abs=1e-15))]
    r = mb.simulate(model, 0.5, rtol=1e-9, n_out=6)
    assert r.joint("j2").angle == pytest.approx(-0.5 * r.joint("j1").angle + j2_0 + 0.5 * j1_0, abs=1e-8)
    held = tmp_path / "held.xml"
    held.write_text(CHAIN_TEXT.replace(WORLD, WORLD + '<equality><joint name="lock" joint1="j1"/></equality>'))
    locked = mb.load_mjcf(held, contacts="ignore")
    r = mb.simulate(locked, 0.3, rtol=1e-9, n_out=4)
    assert r.joint("j1").angle == pytest.approx(np.full(4, j1_0), abs=1e-9)


# --- names and arguments (issue 39) ----------------------------------------------------------------------

def _names(model):
    return [values["name"] for _, values in model.elements]


def test_a_body_and_a_joint_may_share_a_name(tmp_path):
    """MuJoCo keeps bodies and joints apart (before: refused as "duplicate
    name 'l2'"): the joint is l2_joint, quietly (documented), and moves as
    MuJoCo's; a body named ground, a joint named like the damping lagmb
    makes, an equality named like a body, and an unnamed joint whose name
    lagmb makes (joint0) beside a body called so get their kind or a
    number added, each change named in one MjcfWarning."""
    path = tmp_path / "shared.xml"
    path.write_text(CHAIN_TEXT.replace('name="j2"', 'name="l2"'))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model = mb.load_mjcf(path, contacts="ignore")
    assert _names(model) == ["l1", "l2", "l3", "l4", "j1", "l2_joint", "j3", "j4"]
    assert _largest_difference_to_mj_forward(str(path), 2) < 1e-9
    text = (CHAIN_TEXT.replace('name="l3"', 'name="ground"').replace('name="j3"', 'name="j1_damping"')
            .replace(J1, '<joint type="hinge" axis="0 0 1" damping="0.1"/>').replace('name="l4"', 'name="joint0"')
            .replace(WORLD, WORLD + '<equality><joint name="l1" joint1="j1_damping"/></equality>'))
    path.write_text(text)
    with pytest.warns(mb.MjcfWarning) as caught:
        model = mb.load_mjcf(path, contacts="ignore")
    assert _names(model) == ["l1", "l2", "ground_body", "joint0", "joint0_2", "joint0_2_damping", "j2",
                             "j1_damping", "j4", "l1_equality"]
    message = str(caught[0].message)
    for change in ("body 'ground' is 'ground_body' (the ground has the name 'ground')",
                   "equality 'l1' is 'l1_equality' (body 'l1' has the name 'l1')",
                   "joint 0 (unnamed) is 'joint0_2' (body 'joint0' has the name 'joint0')"):
        assert change in message


def test_lagmbs_damping_name_taken_by_a_joint_gets_a_number(tmp_path):
    path = tmp_path / "damped.xml"
    path.write_text(CHAIN_TEXT.replace(*_with(J1, 'damping="0.1"')).replace('name="j2"', 'name="j1_damping"'))
    with pytest.warns(mb.MjcfWarning, match="the damping of joint 'j1' is 'j1_damping_2' \\(joint 'j1_damping' has "
                                            "the name 'j1_damping'\\)"):
        model = mb.load_mjcf(path, contacts="ignore")
    assert ("add_joint_friction", "j1_damping_2") in [(method, kw["name"]) for method, kw in model.elements]


@pytest.mark.parametrize("path, contacts, words", [
    (5, "warn", "load_mjcf: path must be a file name (a str or os.PathLike), got 5"),
    (None, "warn", "load_mjcf: path must be a file name (a str or os.PathLike), got None"),
    (CHAIN + "\0.xml", "warn", "holds a NUL character"),
    (CHAIN, np.array(["warn", "error"]), "load_mjcf: contacts must be 'warn', 'ignore', 'error' or 'simulate', got array("),
    (CHAIN, None, "load_mjcf: contacts must be 'warn', 'ignore', 'error' or 'simulate', got None"),
])
def test_bad_arguments_are_named(path, contacts, words):
    """A path that is no file name (before: TypeError), one holding a NUL
    (MuJoCo read the file named by the part before it), contacts given an
    array (before: ValueError of its truth): an MjcfError naming the
    argument."""
    with pytest.raises(mb.MjcfError) as error:
        mb.load_mjcf(path, contacts=contacts)
    assert words in str(error.value)


@pytest.mark.parametrize("change, words", [
    (('<body name="l2" pos="0.4 0 0"', '<body name="l2" pos="1e200 0 0"'), "body 'l2': its position, mass or inertia"),
    (('mass="2"', 'mass="1e300"'), "body 'l1': its position, mass or inertia"),
    (('<body name="tool" pos="0.15 0 0">', '<body name="tool" pos="1e100 0 0">'),
     "body 'l4': its inertia about its centre of mass (1.06947e+199 kg m^2) is beyond"),
])
def test_values_too_large_for_a_model_are_refused_at_load(tmp_path, change, words):
    """Past 1e150 (a square overflows; before: RuntimeWarnings and a
    ModelError about a NaN inertia, or a failed first run): an MjcfError
    naming the body."""
    path = tmp_path / "far.xml"
    assert change[0] in CHAIN_TEXT
    path.write_text(CHAIN_TEXT.replace(*change))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(mb.MjcfError) as error:
            mb.load_mjcf(path, contacts="ignore")
    assert words in str(error.value) and "beyond what a model can hold" in str(error.value)


DROP_TEXT = """<mujoco>
  <option gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1" friction="0.6"/>
    <body name="ball" pos="0 0 0.3">
      <freejoint/>
      <geom name="ball" type="sphere" size="0.1" mass="1" friction="0.4"/>
    </body>
    <body name="crate" pos="0.5 0 0.2" euler="0 0 30">
      <freejoint/>
      <geom name="crate" type="box" size="0.1 0.15 0.1" mass="2"/>
    </body>
    <body name="stick" pos="-0.5 0 0.2" euler="0 90 0">
      <freejoint/>
      <geom name="stick" type="capsule" size="0.05 0.2" mass="1"/>
      <body name="tip" pos="0 0 0.3">
        <joint name="hinge" type="hinge" axis="0 1 0"/>
        <geom name="tip" type="sphere" size="0.04" mass="0.2"/>
      </body>
    </body>
  </worldbody>
  <contact><exclude body1="ball" body2="crate"/></contact>
</mujoco>"""


def test_contacts_simulate_pairs_the_geoms_mujoco_would(tmp_path):
    """contacts="simulate": a shape per colliding geom at its pose and a
    contact (GEOM1_GEOM2) for each pair MuJoCo tests: the floor with each
    body's geom; the ball with the stick and the tip, not with the crate
    (an <exclude>); the stick not with its child the tip (filterparent);
    the crate and the stick (box-capsule, which lagmb has no contact for)
    left out with a warning naming them. Friction is the larger of the
    geoms', `contact` sets the rest; the run rests each body on the floor at
    its Hertz height, as a model built by hand does."""
    path = tmp_path / "drop.xml"
    path.write_text(DROP_TEXT)
    with pytest.warns(mb.MjcfWarning, match="leaves out geoms 'crate' and 'stick' \\(box-capsule\\)"):
        m = mb.load_mjcf(path, contacts="simulate", contact={"stiffness": 1e6, "restitution": 0.3})
    contacts = {kw["name"]: kw for method, kw in m.elements if method == "add_contact"}
    assert sorted(contacts) == ["ball_stick", "ball_tip", "crate_tip", "floor_ball", "floor_crate", "floor_stick",
                                "floor_tip"]
    assert contacts["floor_ball"]["friction"] == 0.6 and contacts["ball_stick"]["friction"] == 1.0
    assert contacts["floor_ball"]["stiffness"] == 1e6 and contacts["floor_ball"]["restitution"] == 0.3
    assert [s.kind for s in m.shapes] == ["plane", "sphere", "box", "capsule", "sphere"]
    r = mb.simulate(m, 1.5, rtol=1e-9, atol=1e-11, n_out=3)
    assert abs(r.body("ball").position[-1, 2] - (0.1 - (9.81 / 1e6) ** (2 / 3))) <= 1e-9
    assert abs(r.body("crate").position[-1, 2] - (0.1 - (2 * 9.81 / 4e6) ** (2 / 3))) <= 1e-9
    with pytest.raises(mb.MjcfError, match="contact .* goes with contacts='simulate'"):
        mb.load_mjcf(path, contact={"stiffness": 1e6})
