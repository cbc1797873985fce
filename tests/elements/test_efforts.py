"""What every element that applies a force reads in a run (Result.effort,
Simulator.effort): a servo's torque after its limit, a spring-damper's force,
a rotational spring's torque, a bushing's six, applied forces and torques as
applied, joint friction; each against the closed form of its law evaluated
on the run's own states, or against the statics it holds (a pendulum, the
Panda's gravity torques from Pinocchio) (issue 56)."""

import math
import os
import warnings

import numpy as np
import pytest

import lagmb as mb

G = 9.81


def servo_pendulum(**servo):
    """A 1 kg bob 0.5 m below a horizontal hinge (axis +y) with a servo on
    it: hanging at angle theta the weight's torque about +y is -m g l
    sin(theta), so a servo holding it at rest applies +m g l sin(theta)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    theta0 = servo.pop("theta0")
    m.add_body("bob", mass=1.0, inertia=(1e-3, 1e-3, 1e-3),
               position=(-0.5 * math.sin(theta0), 0.0, -0.5 * math.cos(theta0)))
    hinge = m.add_revolute("hinge", "ground", "bob", at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0), angle=theta0)
    m.add_servo("servo", hinge, **servo)
    return m


def test_a_servo_holding_a_pendulum_reads_the_weights_torque():
    """kp = 50 N m/rad toward 0.6 rad, started there: the bob sags to theta
    where kp (0.6 - theta) = m g l sin(theta) and rests; the servo's effort
    reads m g l sin(theta) there (to 1e-9 N m), equal to kp (0.6 - theta),
    and along the way kp (theta* - theta) - kd theta' (its unsaturated law)."""
    kp, kd = 50.0, 8.0
    r = mb.simulate(servo_pendulum(theta0=0.6, target=0.6, kp=kp, kd=kd), 6.0, n_out=61, rtol=1e-11, atol=1e-13)
    path, tau = r.joint("hinge"), r.effort("servo")
    assert tau.shape == (61,)
    assert np.max(np.abs(tau - (kp * (0.6 - path.angle) - kd * path.rate))) <= 1e-9
    theta = path.angle[-1]
    assert abs(path.rate[-1]) <= 1e-10
    assert tau[-1] == pytest.approx(1.0 * G * 0.5 * math.sin(theta), abs=1e-9)
    assert 0.4 < theta < 0.6


def test_a_saturated_servo_reads_its_limit():
    """Aimed at 2 rad from 1.2 rad with a 2 N m limit, below the 4.6 N m the
    weight needs there: the bob falls until m g l sin(theta) = 2 N m (a
    rotational damper on the hinge takes out the swing) and the servo reads
    its limit, 2 N m, all the way (its demand kp (2 - theta) - kd theta'
    stays above it); the damper reads -c theta', 0 at rest."""
    m = servo_pendulum(theta0=1.2, target=2.0, kp=50.0, kd=1.0, limit=2.0)
    m.add_rotational_spring_damper("damper", "hinge", damping=0.5)
    r = mb.simulate(m, 20.0, n_out=41, rtol=1e-10, atol=1e-12)
    path = r.joint("hinge")
    assert np.all(r.effort("servo") == 2.0)
    assert np.max(np.abs(r.effort("damper") + 0.5 * path.rate)) <= 1e-12
    assert path.angle[-1] == pytest.approx(math.asin(2.0 / (G * 0.5)), abs=1e-6)
    assert abs(r.effort("damper")[-1]) <= 1e-6


def test_a_simulator_reads_a_servo_now():
    """Simulator.effort is Result.effort at the simulator's time: the servo's
    torque with its target an input set from outside."""
    m = servo_pendulum(theta0=0.0, target=mb.Input(0.0, "aim"), kp=50.0, kd=8.0)
    sim = mb.Simulator(m, rtol=1e-10, atol=1e-12)
    sim.set_input("aim", 0.3)
    sim.advance(0.25)
    now = sim.effort("servo")
    path = sim.joint("hinge")
    assert isinstance(now, float)
    assert now == pytest.approx(50.0 * (0.3 - path.angle) - 8.0 * path.rate, abs=1e-9)
    assert sim.result().effort("servo")[-1] == pytest.approx(now, abs=1e-12)


def oscillator(dimension):
    """A 2 kg body on a spring-damper from a point of the ground, pulled by
    an actuator force f(t) = 3 sin(5 t), moving along the line (x) from a
    stretch of 0.1 m; in the plane also a rotational spring-damper to the
    ground, set turning."""
    m = mb.Model(dimension=dimension)
    origin, start = ((0.0, 0.0), (1.1, 0.0)) if dimension == 2 else ((0.0, 0.0, 0.0), (1.1, 0.0, 0.0))
    if dimension == 2:
        m.add_body("block", mass=2.0, inertia=0.1, position=start, velocity=(0.3, 0.0), angular_velocity=2.0)
        m.add_rotational_spring_damper("twist", "ground", "block", stiffness=4.0, damping=0.2, free_angle=0.1,
                                       torque=mb.Harmonic(0.5, 3.0))
    else:
        m.add_body("block", mass=2.0, inertia=(0.1, 0.1, 0.1), position=start, velocity=(0.3, 0.0, 0.0))
    m.add_spring_damper("spring", "ground", origin, "block", start, stiffness=80.0, damping=1.5, free_length=1.0,
                        force=mb.Harmonic(3.0, 5.0))
    return m


@pytest.mark.parametrize("dimension", [2, 3])
def test_a_spring_damper_reads_its_force(dimension):
    """F = -k (L - L0) - c L' + f(t) (> 0 pushing the points apart), with L
    and L' = d . d' / L from the run's positions and velocities, at every
    output (to 1e-12 N); in the plane the rotational one reads -k (phi -
    phi0) - c phi' + tau(t)."""
    r = mb.simulate(oscillator(dimension), 2.0, n_out=41, rtol=1e-10, atol=1e-12)
    body = r.body("block")
    d, v = body.position, body.velocity
    L = np.linalg.norm(d, axis=1)
    Ld = np.einsum("ki,ki->k", d, v) / L
    exact = -80.0 * (L - 1.0) - 1.5 * Ld + 3.0 * np.sin(5.0 * r.t)
    assert r.effort("spring").shape == (41,)
    assert np.max(np.abs(r.effort("spring") - exact)) <= 1e-12
    assert np.ptp(r.effort("spring")) > 1.0
    if dimension == 2:
        exact = -4.0 * (body.angle - 0.1) - 0.2 * body.angular_velocity + 0.5 * np.sin(3.0 * r.t)
        assert np.max(np.abs(r.effort("twist") - exact)) <= 1e-12


def test_a_spatial_rotational_spring_reads_its_torque():
    """About a revolute's axis: T = -k (theta - theta0) - c theta' + tau(t),
    theta counting turns (the wheel spins through several)."""
    m = mb.Model(dimension=3)
    m.add_body("wheel", mass=1.0, inertia=(0.1, 0.1, 0.2), position=(0.0, 0.0, 0.0), angular_velocity=(0, 0, 30.0))
    axle = m.add_revolute("axle", "ground", "wheel", at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    m.add_rotational_spring_damper("coil", axle, stiffness=0.5, damping=0.01, free_angle=0.2, torque=0.05)
    r = mb.simulate(m, 3.0, n_out=31, rtol=1e-10, atol=1e-12)
    path = r.joint("axle")
    assert path.angle.max() > 4 * math.pi
    exact = -0.5 * (path.angle - 0.2) - 0.01 * path.rate + 0.05
    assert np.max(np.abs(r.effort("coil") - exact)) <= 1e-10


def test_a_bushing_reads_its_force_and_torque():
    """A body on a bushing at its centre of mass to the ground (no gravity),
    set sliding along x and turning about z: its frame's axes are the global
    ones, so the six read -k x - c x' along x (0 along y, z) and -k_r sin(psi)
    - c_r cos(psi) psi' about z (rho_z = sin(psi), psi the turn), to 1e-10."""
    m = mb.Model(dimension=3)
    m.add_body("mount", mass=3.0, inertia=(0.2, 0.2, 0.2), position=(0.0, 0.0, 0.0), velocity=(0.4, 0.0, 0.0),
               angular_velocity=(0.0, 0.0, 1.5))
    m.add_bushing("bush", "ground", "mount", at=(0.0, 0.0, 0.0), stiffness=(300.0, 300.0, 300.0),
                  damping=(2.0, 2.0, 2.0), rotational_stiffness=(5.0, 5.0, 5.0), rotational_damping=(0.1, 0.1, 0.1))
    r = mb.simulate(m, 1.0, n_out=21, rtol=1e-11, atol=1e-13)
    body, e = r.body("mount"), r.effort("bush")
    assert e.shape == (21, 6)
    psi = np.arctan2(body.rotation[:, 1, 0], body.rotation[:, 0, 0])
    psid = body.angular_velocity[:, 2]
    assert np.max(np.abs(e[:, 0] - (-300.0 * body.position[:, 0] - 2.0 * body.velocity[:, 0]))) <= 1e-10
    assert np.max(np.abs(e[:, [1, 2, 3, 4]])) <= 1e-10
    assert np.max(np.abs(e[:, 5] - (-5.0 * np.sin(psi) - 0.1 * np.cos(psi) * psid))) <= 1e-10


def test_applied_forces_read_as_applied():
    """A force given in the body's axes reads in global axes, turned with the
    body (A(phi) F' in the plane, R F' in space), and a torque as given;
    a force fed by an mb.Input reads the value the Simulator set."""
    m = mb.Model()
    m.add_body("disc", mass=1.0, inertia=0.5, position=(0.0, 0.0), angular_velocity=1.0)
    m.add_force("thrust", "disc", (2.0, 0.0), local=True)
    m.add_torque("twist", "disc", mb.Harmonic(0.3, 2.0))
    r = mb.simulate(m, 2.0, n_out=21)
    phi = r.body("disc").angle
    assert r.effort("thrust").shape == (21, 2)
    assert np.max(np.abs(r.effort("thrust") - 2.0 * np.column_stack([np.cos(phi), np.sin(phi)]))) <= 1e-14
    assert np.max(np.abs(r.effort("twist") - 0.3 * np.sin(2.0 * r.t))) <= 1e-15

    s = mb.Model(dimension=3)
    s.add_body("drone", mass=1.0, inertia=(0.1, 0.2, 0.3), position=(0.0, 0.0, 0.0), angular_velocity=(0.5, 1.0, 0.2))
    s.add_force("lift", "drone", (0.0, 0.0, mb.Input(4.0, "lift")), point=(0.1, 0.0, 0.0), local=True)
    s.add_torque("yaw", "drone", (0.0, 0.0, 0.1), local=True)
    sim = mb.Simulator(s)
    sim.advance(0.5)
    sim.set_input("lift", 6.0)
    sim.advance(1.0)
    r = sim.result()
    R = r.body("drone").rotation
    assert r.effort("lift").shape == (len(r.t), 3)
    lift = np.where(r.t > 0.5, 6.0, 4.0)
    assert np.max(np.abs(r.effort("lift") - lift[:, None] * R[:, :, 2])) <= 1e-14
    assert np.max(np.abs(r.effort("yaw") - 0.1 * R[:, :, 2])) <= 1e-15
    assert sim.effort("lift") == pytest.approx(6.0 * R[-1, :, 2], abs=1e-14)


def test_joint_friction_reads_its_torque():
    """Planar joint friction reads what Result.friction reads; spatial joint
    friction -F0 s' / sqrt(s'^2 + v_s^2) - c s' from the joint's rate."""
    m = mb.Model(gravity=(0.0, -G))
    m.add_body("rod", mass=1.0, inertia=0.1, position=(0.5, 0.0))
    m.add_revolute("pin", "ground", "rod", at=(0.0, 0.0))
    m.add_joint_friction("rub", "pin", mu=0.2, pin_radius=0.01, viscous=0.05)
    r = mb.simulate(m, 1.0, n_out=11)
    assert np.array_equal(r.effort("rub"), r.friction("rub"))

    s = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    s.add_body("rod", mass=1.0, inertia=(0.1, 0.1, 0.1), position=(0.5, 0.0, 0.0))
    s.add_revolute("pin", "ground", "rod", at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    s.add_joint_friction("rub", "pin", viscous=0.05, preload=0.1, slip_velocity=0.01)
    r = mb.simulate(s, 1.0, n_out=11)
    rate = r.joint("pin").rate
    exact = -0.1 * rate / np.sqrt(rate ** 2 + 0.01 ** 2) - 0.05 * rate
    assert np.max(np.abs(r.effort("rub") - exact)) <= 1e-14


def test_what_has_no_effort_says_where_its_force_is():
    """A joint's force is its reaction, a contact's Result.contact: asking
    their effort names the element and where to look. Drivers and stops
    read as before, through the same core function."""
    m = mb.Model(gravity=(0.0, -G))
    m.add_body("rod", mass=1.0, inertia=0.1, position=(0.5, 0.0))
    pin = m.add_revolute("pin", "ground", "rod", at=(0.0, 0.0))
    m.add_stop("limit", pin, lower=-0.3)
    r = mb.simulate(m, 1.0, n_out=11)
    for given in ("pin", pin):
        with pytest.raises(mb.ModelError, match="Result.effort: 'pin' is a revolute, which has no effort .* "
                                                "a joint's force is its reaction"):
            r.effort(given)
    with pytest.raises(mb.ModelError, match="Result.effort: element: expected .* got <lagmb body 'rod'>"):
        r.effort(m.bodies[0])
    ball = mb.Model(gravity=(0.0, -G))
    ball.add_body("ball", mass=1.0, inertia=0.01, position=(0.0, 0.1))
    ball.add_contact("bounce", "ball", (0.0, 0.1), 0.1, "ground", (0.0, 0.0), (1.0, 0.0), stiffness=1e6,
                     restitution=0.8)
    with pytest.raises(mb.ModelError, match="'bounce' is a contact: its forces are Result.contact"):
        mb.simulate(ball, 0.1, n_out=3).effort("bounce")
    lam = r.multipliers("limit")
    assert np.array_equal(r.effort("limit"), lam[:, 1] - lam[:, 0])
    assert r.effort("limit")[-1] > 0.0  # resting on its lower limit: pushing up along the angle


# --- the Panda holding a pose: its servos' efforts are the gravity torques ---------------------------------

def test_the_pandas_servos_hold_it_against_its_gravity_torques():
    """The Panda (example-robot-data) with a servo on each joint (kp 2000 N
    m/rad or N/m, kd 100) toward its pose sags a little and comes to rest;
    there each servo's effort equals Pinocchio's generalized gravity
    (computeGeneralizedGravity) at the joint values reached, to 1e-7 N m."""
    pin = pytest.importorskip("pinocchio", reason="the robots extra (pin) is not installed")
    from formats import urdf_robots

    relpath = "panda_description/urdf/panda.urdf"
    pose = {f"panda_joint{k}": a for k, a in enumerate((0.3, -0.5, 0.2, -2.0, 0.1, 1.6, 0.7), start=1)}
    pose.update(panda_finger_joint1=0.02, panda_finger_joint2=0.02)
    model = urdf_robots.load(relpath, positions=pose)
    js = mb.JointSpace(model)
    for joint in js.joints:
        model.add_servo(f"{joint}_servo", joint, target=pose[joint], kp=2000.0, kd=100.0)
    r = mb.simulate(model, 4.0, n_out=5, rtol=1e-10, atol=1e-12)
    pm = urdf_robots.pinocchio_model(relpath)
    pd = pm.createData()
    q = pin.neutral(pm)
    for jid in range(1, pm.njoints):
        path = r.joint(pm.names[jid])
        q[pm.joints[jid].idx_q] = (path.slide if "finger" in pm.names[jid] else path.angle)[-1]
        assert abs(path.rate[-1]) <= 1e-9
    gravity = pin.computeGeneralizedGravity(pm, pd, q)
    for jid in range(1, pm.njoints):
        name = pm.names[jid]
        assert r.effort(f"{name}_servo")[-1] == pytest.approx(gravity[pm.joints[jid].idx_v], abs=1e-7)
    assert np.max(np.abs(gravity)) > 10.0  # (the shoulder holds the arm's weight)


def test_a_saved_run_holds_the_efforts_asked_for(tmp_path):
    """Result.save writes force elements' efforts too: one column NAME.effort,
    or NAME.effort.x, NAME.effort.y for an applied force's components (.csv),
    and an array effort_NAME (.npz); read back exactly."""
    m = mb.Model()
    m.add_body("disc", mass=1.0, inertia=0.5, position=(0.0, 0.0), angular_velocity=1.0)
    m.add_force("thrust", "disc", (2.0, 0.0), local=True)
    m.add_torque("twist", "disc", 0.3)
    r = mb.simulate(m, 1.0, n_out=5)
    r.save(tmp_path / "run.csv", efforts=["thrust", "twist"])
    header, *rows = (tmp_path / "run.csv").read_text().splitlines()
    columns = header.split(",")
    assert columns[-3:] == ["thrust.effort.x", "thrust.effort.y", "twist.effort"]
    table = np.array([[float(x) for x in row.split(",")] for row in rows])
    assert np.array_equal(table[:, -3:-1], r.effort("thrust")) and np.array_equal(table[:, -1], r.effort("twist"))
    r.save(tmp_path / "run.npz", efforts=["thrust"])
    assert np.array_equal(np.load(tmp_path / "run.npz")["effort_thrust"], r.effort("thrust"))
