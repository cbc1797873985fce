"""Where a model is without a run (Model.poses, Model.pose,
Model.lowest_point): bodies, frames and shapes in global axes at the initial
configuration, at given coordinates or at given joint values, against closed
forms and Pinocchio's forward kinematics; the lowest collision point a floor
is put at (issue 56)."""

import math
import os
import warnings

import numpy as np
import pytest

import lagmb as mb

G = 9.81


def pendulum(theta0=0.0):
    """A 0.8 m rod hanging from a hinge about +y at (0, 0, 1), a frame at its
    tip: turned by theta about +y, the tip is at (-0.8 sin theta, 0, 1 - 0.8
    cos theta)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("rod", mass=1.0, inertia=(0.05, 0.05, 1e-3), position=(0.0, 0.0, 0.6))
    m.add_revolute("hinge", "ground", "rod", at=(0.0, 0.0, 1.0), axis=(0.0, 1.0, 0.0))
    m.add_frame("tip", "rod", (0.0, 0.0, 0.2))
    m.add_shape("rod", "sphere", (0.05,), position=(0.0, 0.0, 0.2), role="collision")
    return m


def tip(theta):
    return np.array([-0.8 * math.sin(theta), 0.0, 1.0 - 0.8 * math.cos(theta)])


@pytest.mark.parametrize("theta", [0.0, 0.4, -1.3, 2.9])
def test_a_pendulums_tip_is_where_its_angle_puts_it(theta):
    """By joint value (positions=) and by coordinates (q from the same
    forward kinematics): the tip frame's origin at the closed form (to
    1e-15 m), its axes the turn about +y, the rod's centre of mass halfway;
    the sphere on the tip lowest at the tip less its radius along gravity."""
    m = pendulum()
    at = m.poses(positions={"hinge": theta})
    assert at["tip"].position == pytest.approx(tip(theta), abs=1e-15)
    c, s = math.cos(theta), math.sin(theta)
    assert at["tip"].rotation == pytest.approx(np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]), abs=1e-15)
    assert at["rod"].position == pytest.approx((tip(theta) + np.array([0.0, 0.0, 1.0])) / 2, abs=1e-15)
    assert at.shapes[0].position == pytest.approx(tip(theta), abs=1e-15)
    q = mb.JointSpace(m).coordinates({"hinge": theta})[0]
    assert m.pose("tip", q).position == pytest.approx(tip(theta), abs=1e-15)
    lowest = m.lowest_point(positions={"hinge": theta})
    assert lowest == pytest.approx(tip(theta) - np.array([0.0, 0.0, 0.05]), abs=1e-15)
    assert m.lowest_point(positions={"hinge": theta}, direction=(1.0, 0.0, 0.0)) == \
        pytest.approx(tip(theta) + np.array([0.05, 0.0, 0.0]), abs=1e-15)


def test_the_initial_configuration_is_the_default_and_the_ground_is_the_origin():
    """No state given: where the model was built (add_body's values, before
    assembly); "ground" is the origin with the global axes; a shape added
    at a global position reads it back there (Model.shapes holds it in its
    body's axes, from the centre of mass)."""
    m = pendulum()
    m.add_shape("rod", "box", (0.1, 0.2, 0.3), position=(0.3, 0.0, 0.7),
                orientation=(math.cos(0.2), 0.0, 0.0, math.sin(0.2)))
    at = m.poses()
    assert at["rod"].position == pytest.approx((0.0, 0.0, 0.6), abs=0)
    assert at["ground"].position == pytest.approx((0.0, 0.0, 0.0), abs=0)
    assert np.array_equal(at["ground"].rotation, np.eye(3))
    assert at.shapes[1].position == pytest.approx((0.3, 0.0, 0.7), abs=1e-15)
    assert m.shapes[1].position == pytest.approx((0.3, 0.0, 0.1), abs=1e-15)  # (from the rod's centre of mass)
    assert at.shapes[1].rotation[:, 0] == pytest.approx((math.cos(0.4), math.sin(0.4), 0.0), abs=1e-15)
    # the box's corner lowest: its centre less half its edges along -z (it turns about z only)
    assert m.lowest_point() == pytest.approx((0.0, 0.0, 0.15), abs=1e-15)  # (the tip's sphere, lower)


def test_a_planar_models_bodies_at_given_coordinates():
    """In the plane: each body's centre of mass, angle and axes from q; a
    point in a body's axes through Pose.point."""
    m = mb.Model()
    m.add_body("crank", mass=1.0, inertia=0.1, position=(0.5, 0.0))
    m.add_particle("bead", mass=0.2, position=(1.0, 1.0))
    q = np.array([0.1, 0.2, 0.5, 1.5, -0.5])
    at = m.poses(q)
    assert at["crank"].angle == 0.5 and at["bead"].angle == 0.0
    assert at["crank"].point((1.0, 0.0)) == pytest.approx((0.1 + math.cos(0.5), 0.2 + math.sin(0.5)), abs=1e-15)
    assert at["bead"].position == pytest.approx((1.5, -0.5), abs=0)
    assert m.pose("crank").position == pytest.approx((0.5, 0.0), abs=0)


@pytest.mark.parametrize("call, words", [
    (lambda m: m.poses(q=[0.0]), "Model.poses: q must be 7 finite numbers"),
    (lambda m: m.poses(q=np.full(7, np.nan)), "q must be 7 finite numbers"),
    (lambda m: m.poses(q=np.zeros(7), positions={"hinge": 0.1}), "not both"),
    (lambda m: m.poses(positions={"elbow": 0.1}), "'elbow' are not joints of the tree"),
    (lambda m: m.poses(positions={"hinge": "up"}), r"positions\['hinge'\] must be a number"),
    (lambda m: m.pose("nothing"), "no body or frame named 'nothing'"),
    (lambda m: m.lowest_point(direction=(0, 0, 0)), "direction must be a nonzero vector"),
])
def test_bad_states_are_named(call, words):
    with pytest.raises(mb.ModelError, match=words):
        call(pendulum())


def test_a_model_without_gravity_or_collision_shapes_has_no_lowest_point():
    weightless = mb.Model(dimension=3)
    weightless.add_body("b", mass=1.0, inertia=(1, 1, 1), position=(0, 0, 0))
    weightless.add_shape("b", "sphere", (0.1,), role="collision")
    with pytest.raises(mb.ModelError, match="no gravity to say which way is down; give direction="):
        weightless.lowest_point()
    assert weightless.lowest_point(direction=(0, 0, -1)) == pytest.approx((0, 0, -0.1), abs=0)
    bare = mb.Model(dimension=3, gravity=(0, 0, -G))
    bare.add_body("b", mass=1.0, inertia=(1, 1, 1), position=(0, 0, 0))
    bare.add_shape("b", "sphere", (0.1,))  # (visual)
    with pytest.raises(mb.ModelError, match="no collision shapes on its bodies"):
        bare.lowest_point()
    with pytest.raises(mb.ModelError, match="shapes are spatial only"):
        mb.Model(gravity=(0, -G)).lowest_point()


@pytest.mark.parametrize("kind, size, expected", [
    ("box", (0.2, 0.4, 0.6), -0.3 * math.cos(0.3) - 0.2 * math.sin(0.3)),
    ("cylinder", (0.1, 0.6), -0.3 * math.cos(0.3) - 0.1 * math.sin(0.3)),
    ("capsule", (0.1, 0.6), -0.3 * math.cos(0.3) - 0.1),
])
def test_each_shape_kinds_lowest_point(kind, size, expected):
    """A shape turned 0.3 rad about x (its z axis tilted): the lowest
    point's height by hand (a box's corner: half its z edge times cos plus
    half its y edge times sin; a cylinder's rim; a capsule's end sphere)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("b", mass=1.0, inertia=(1, 1, 1), position=(0, 0, 0))
    c, s = math.cos(0.15), math.sin(0.15)
    m.add_shape("b", kind, size, orientation=(c, s, 0.0, 0.0), role="collision")
    assert m.lowest_point()[2] == pytest.approx(expected, abs=1e-15)


# --- robots: Pinocchio's forward kinematics, the Go1 on its floor -----------------------------------------

def robots():
    """Pinocchio and the URDF tests' loaders (formats/urdf_robots.py) (the test skips without the robots extra)."""
    pin = pytest.importorskip("pinocchio", reason="the robots extra (pin) is not installed")
    from formats import urdf_robots  # (skips without example-robot-data)

    return pin, urdf_robots


def test_the_pandas_hand_is_where_pinocchio_puts_it():
    """The Panda's hand and tool-centre frames (links merged into link 7's
    body) at three sets of joint values: Model.poses(positions=...) equals
    Pinocchio's framesForwardKinematics (oMf) to 1e-12 m and rad, and so
    does Model.pose at the coordinates of the same state."""
    pin, urdf_robots = robots()
    relpath = "panda_description/urdf/panda.urdf"
    model = urdf_robots.load(relpath)
    pm = urdf_robots.pinocchio_model(relpath)
    pd = pm.createData()
    rng = np.random.default_rng(56)
    js = mb.JointSpace(model)
    for _ in range(3):
        positions = {j: float(rng.uniform(-1.5, 1.5)) if "finger" not in j else float(rng.uniform(0, 0.04))
                     for j in js.joints}
        q = pin.neutral(pm)
        for jid in range(1, pm.njoints):
            q[pm.joints[jid].idx_q] = positions[pm.names[jid]]
        pin.framesForwardKinematics(pm, pd, q)
        at = model.poses(positions=positions)
        for frame in ("panda_hand", "panda_hand_tcp", "panda_link8"):
            placement = pd.oMf[pm.getFrameId(frame)]
            assert at[frame].position == pytest.approx(placement.translation, abs=1e-12)
            assert at[frame].rotation == pytest.approx(placement.rotation, abs=1e-12)
        lagmb_q = js.coordinates(positions)[0]
        assert model.pose("panda_hand_tcp", lagmb_q).position == \
            pytest.approx(pd.oMf[pm.getFrameId("panda_hand_tcp")].translation, abs=1e-12)


GO1 = "go1_description/urdf/go1.urdf"
#: Go1 standing: each leg's hip at 0, thigh 0.8 rad, calf -1.5 rad.
STAND = {f"{leg}_{joint}_joint": angle for leg in ("FR", "FL", "RR", "RL")
         for joint, angle in (("hip", 0.0), ("thigh", 0.8), ("calf", -1.5))}


def go1(urdf_robots, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        return mb.load_urdf(os.path.join(urdf_robots.ROBOTS, GO1), floating_base=True, **options)


def test_go1s_lowest_point_is_its_lowest_foot():
    """Go1 standing and in a crouch of random joint values: its lowest
    collision point is the bottom of its lowest foot sphere, worked out by
    hand from the file (each foot a sphere of radius 0.02 at its link's
    origin) and Pinocchio's placements of the foot frames (the free flyer
    where lagmb builds the trunk: at the origin); to 1e-12 m."""
    import xml.etree.ElementTree as ET

    pin, urdf_robots = robots()
    path = os.path.join(urdf_robots.ROBOTS, GO1)
    feet = {}
    for link in ET.parse(path).getroot().iter("link"):
        if link.get("name").endswith("_foot"):
            collision = link.find("collision")
            origin = [float(x) for x in collision.find("origin").get("xyz").split()]
            feet[link.get("name")] = (np.array(origin), float(collision.find("geometry/sphere").get("radius")))
    assert len(feet) == 4 and {r for _, r in feet.values()} == {0.02}
    pm = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    pd = pm.createData()
    model = go1(urdf_robots)
    rng = np.random.default_rng(56)
    crouch = {j: a + rng.uniform(-0.3, 0.3) for j, a in STAND.items()}
    for positions in (STAND, crouch):
        q = pin.neutral(pm)
        for jid in range(2, pm.njoints):
            q[pm.joints[jid].idx_q] = positions[pm.names[jid]]
        pin.framesForwardKinematics(pm, pd, q)
        bottoms = []
        for name, (origin, radius) in feet.items():
            placement = pd.oMf[pm.getFrameId(name)]
            bottoms.append(placement.translation + placement.rotation @ origin - (0.0, 0.0, radius))
            assert model.pose(name, positions=positions).position == pytest.approx(placement.translation, abs=1e-12)
        lowest = model.lowest_point(positions=positions)
        assert lowest[2] == pytest.approx(min(b[2] for b in bottoms), abs=1e-12)
        assert min(np.linalg.norm(lowest - b) for b in bottoms) <= 1e-12


def test_go1_put_on_the_floor_its_lowest_point_gives_starts_on_its_feet():
    """The use a robot user wants: load Go1 standing, read its lowest point,
    load it again with the floor there (load_urdf(ground=z)): at t = 0 its
    four feet touch (penetration 0 to 1e-15 m, every other shape above the
    floor), and over 0.05 s of its weight coming down (no motors: the legs
    give) they press in less than (m g / k)^(2/3), the depth of its whole
    weight on one foot."""
    _, urdf_robots = robots()
    z = go1(urdf_robots, positions=STAND).lowest_point()[2]
    model = go1(urdf_robots, positions=STAND, ground=z)
    r = mb.simulate(model, 0.05, n_out=6)
    contacts = [values["name"] for method, values in model.elements if method == "add_contact"]
    depth = {name: r.contact(name).penetration for name in contacts}
    feet = [name for name in contacts if name.endswith("_foot_ground")]
    assert len(feet) == 4
    assert all(abs(depth[name][0]) <= 1e-15 for name in feet)
    assert max(depth[name][0] for name in contacts if name not in feet) < -1e-3
    assert all((r.contact(name).state[1:] != "open").all() for name in feet)
    weight = sum(values["mass"] for method, values in model.elements if method == "add_body") * G
    assert max(d.max() for d in depth.values()) <= (weight / 1e7) ** (2.0 / 3.0)
