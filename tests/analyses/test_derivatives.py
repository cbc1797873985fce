"""Every element kind's derivatives against finite differences, planar and spatial.

The integrator's Newton matrix and the acceleration equation use, per kind,
the constraint Jacobian Phi_q, its derivative (Phi_q^T w)_q, the velocity
Jacobian d(Phi_q v + Phi_t)/dq, gamma, and the force derivatives Q_q and
Q_v. Each is checked at a random state (not on the constraint manifold: the
formulas hold everywhere) against central differences of the lower-order
quantity, to 1e-6 relative to the largest entry. gamma is checked through
its definition: along the straight path q(s) = q + s v, t(s) = t + s,
d2/ds2 Phi(q(s), t(s)) = -gamma.
"""

import numpy as np
import pytest

import lagmb as mb

H = 1e-6


def every_kind():
    """One model holding every joint, driver and force kind (17 equations on
    17 coordinates, none redundant)."""
    m = mb.Model(gravity=(0.3, -9.81))
    a = m.add_body("a", mass=1.0, inertia=0.1, position=(0.5, 0.1), angle=0.3)
    b = m.add_body("b", mass=2.0, inertia=0.2, position=(1.5, -0.2), angle=-0.4)
    c = m.add_body("c", mass=0.5, inertia=0.05, position=(0.8, 1.2), angle=1.1)
    d = m.add_body("d", mass=1.5, inertia=0.3, position=(2.0, 1.0), angle=0.2)
    e = m.add_body("e", mass=0.7, inertia=0.07, position=(3.1, 0.4), angle=-0.9)
    p = m.add_particle("p", mass=0.3, position=(2.5, -1.0))
    m.add_revolute("rev", m.ground, a, at=(0.1, 0.0))
    m.add_translational("slide", a, b, at=(1.2, 0.0), axis=(1.0, 0.2))
    m.add_weld("weld", b, c)
    m.add_distance("link", a, (0.7, 0.3), d, (2.1, 0.8))
    m.add_pin_in_slot("slot", c, d, at=(1.9, 1.1), axis=(0.3, 1.0))
    m.add_gear("gear", d, e, ratio=-2.0)
    m.add_rack_pinion("rack", e, b, radius=0.2, axis=(1.0, 0.0))
    m.add_revolute("prev", p, e, at=(2.5, -1.0))
    m.drive_joint("motor", "rev", mb.Harmonic(0.5, 3.0, 0.2, 0.1))
    m.drive_joint("push", "slide", mb.Polynomial([0.0, 0.1, -0.3, 0.05]))
    m.drive_body("lift", d, "y", mb.Spline([0.0, 0.5, 1.0, 2.0], [1.0, 1.3, 0.9, 1.1]))
    m.drive_body("turn", e, "angle", mb.SmoothStep(0.1, 0.9, -0.9, 0.4))
    m.add_spring_damper("spring", a, (0.6, 0.2), e, (3.0, 0.5), stiffness=50.0, damping=3.0,
                        free_length=2.0, force=mb.Harmonic(1.0, 2.0))
    m.add_spring_damper("tether", m.ground, (2.0, -2.0), p, (2.5, -1.0), stiffness=20.0, damping=1.0)
    m.add_rotational_spring_damper("torsion", b, d, stiffness=7.0, damping=0.4, torque=mb.Linear(0.3))
    m.add_force("push_local", c, (1.0, mb.Linear(-2.0, 0.5)), point=(1.0, 1.3), local=True)
    m.add_force("push_global", d, (-3.0, 2.0), point=(2.2, 0.9))
    m.add_torque("twist", b, mb.Harmonic(2.0, 1.0))
    return m


def quaternion(axis, angle):
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return (np.cos(angle / 2), *(np.sin(angle / 2) * axis))


def every_spatial_kind():
    """One spatial model holding every spatial joint, driver and force kind,
    bodies in general orientations with full inertia tensors."""
    m = mb.Model(dimension=3, gravity=(0.2, -0.3, -9.81))
    tensor = ((0.3, 0.02, -0.01), (0.02, 0.25, 0.03), (-0.01, 0.03, 0.2))
    b = [m.add_body(name, 1.0 + 0.3 * k, tensor if k % 2 else (0.1 + 0.02 * k, 0.15, 0.2 - 0.01 * k),
                    (0.4 * k, 0.1 * k, 0.2 - 0.05 * k), orientation=quaternion((1, 2 - k, 0.5 * k), 0.3 + 0.2 * k),
                    velocity=(0.1, -0.2, 0.3), angular_velocity=(0.5, -0.1, 0.2 * k))
         for k, name in enumerate("abcdefgh")]
    m.add_spherical("ball", m.ground, b[0], at=(-0.1, 0.0, 0.3))
    m.add_revolute("hinge", b[0], b[1], at=(0.2, 0.05, 0.2), axis=(0.3, 1.0, 0.2))
    m.add_translational("prism", b[1], b[2], at=(0.6, 0.15, 0.12), axis=(1.0, -0.2, 0.4))
    m.add_cylindrical("cyl", b[2], b[3], at=(1.0, 0.25, 0.1), axis=(0.1, 0.3, 1.0))
    m.add_universal("cross", b[3], b[4], at=(1.4, 0.35, 0.05), axis_i=(1.0, 0.0, 0.0), axis_j=(0.0, 0.6, 0.8))
    m.add_planar("plane", b[4], b[5], at=(1.8, 0.45, 0.0), normal=(0.2, 0.1, 1.0))
    m.add_weld("weld", b[5], b[6])
    m.add_distance("link", m.ground, (3.0, 1.0, 0.0), b[7], (2.9, 0.8, -0.1))
    m.drive_joint("motor", "hinge", mb.Harmonic(0.5, 3.0, 0.2, 0.1))
    m.drive_joint("push", "prism", mb.Polynomial([0.0, 0.1, -0.3, 0.05]))
    m.drive_joint("screw", "cyl", mb.Linear(0.2))
    m.drive_body("lift", b[7], "z", mb.SmoothStep(0.1, 0.9, -0.15, 0.1))
    m.add_spring_damper("spring", b[0], (0.1, 0.1, 0.3), b[4], (1.5, 0.3, 0.0), stiffness=50.0, damping=3.0,
                        free_length=1.0, force=mb.Harmonic(1.0, 2.0))
    m.add_rotational_spring_damper("torsion", "hinge", stiffness=7.0, damping=0.4, torque=mb.Linear(0.3))
    m.add_rotational_spring_damper("twist_cyl", "cyl", stiffness=2.0, damping=0.1, free_angle=0.2)
    m.add_servo("servo", "hinge", target=mb.Harmonic(0.3, 2.0, 0.1), kp=40.0, kd=2.0, feedforward=mb.Linear(0.2))
    m.add_servo("servo_held", "prism", target=1.0, kp=500.0, kd=5.0, limit=3.0)  # (saturated: +-3 N)
    m.add_bushing("mount", b[6], b[7], at=(2.6, 0.7, -0.1), stiffness=(100.0, 200.0, 300.0),
                  damping=(1.0, 2.0, 3.0), rotational_stiffness=(10.0, 20.0, 30.0),
                  rotational_damping=(0.1, 0.2, 0.3))
    m.add_force("push_local", b[2], (1.0, mb.Linear(-2.0, 0.5), 0.3), point=(0.9, 0.2, 0.1), local=True)
    m.add_force("push_global", b[3], (-3.0, 2.0, 1.0), point=(1.1, 0.4, 0.2))
    m.add_torque("turn_local", b[5], (0.2, mb.Harmonic(2.0, 1.0), -0.1), local=True)
    m.add_torque("turn_global", b[1], (0.0, 0.5, -0.3))
    # an arm on body c turns with the prism's slide: one row over the bodies
    # (b, c) and (c, arm), c in both halves
    arm = m.add_body("arm", 0.7, tensor, (0.8, 0.3, 0.4), orientation=quaternion((0.2, 1, 0.3), 0.4),
                     angular_velocity=(0.1, 0.2, -0.3))
    m.add_revolute("elbow", b[2], arm, at=(0.7, 0.2, 0.3), axis=(0.2, 0.4, 1.0))
    m.add_joint_coupling("gang", "elbow", leader="prism", multiplier=3.0, offset=0.01)
    m.add_joint_friction("drag", "prism", viscous=2.0, preload=0.5, slip_velocity=0.1)
    m.add_joint_friction("bearing", "hinge", viscous=0.2, preload=0.3, slip_velocity=0.5)
    # a ball on body h pressed 0.1 m into a plane on body d, slipping (elastic: at the least impact
    # speed a contact has outside a run its damping would cancel the force at these speeds)
    ball = m.add_shape(b[7], "sphere", (0.2,), (2.8, 0.7, -0.15), role="collision")
    table = m.add_shape(b[3], "plane", (), (2.8, 0.7, -0.25), quaternion((1, 0.5, 0), 0.2), role="collision")
    m.add_contact("touch", ball, table, stiffness=1e4, restitution=1.0, friction=0.3, slip_velocity=0.5)
    return m


MODELS = {"planar": every_kind, "spatial": every_spatial_kind}


@pytest.fixture(scope="module", params=sorted(MODELS))
def state(request):
    m = MODELS[request.param]()
    core = m.compiled()
    rng = np.random.default_rng(7)
    q0, _ = core.initial_state()
    q = q0 + 0.05 * rng.standard_normal(q0.size)
    v = rng.standard_normal(q0.size)
    w = rng.standard_normal(core.n_constraints)
    return core, q, v, w, 0.37


def fd(f, x, h=H):
    x = np.asarray(x, dtype=float)
    cols = []
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = h
        cols.append((np.asarray(f(x + e)) - np.asarray(f(x - e))) / (2 * h))
    return np.array(cols).T


def close(a, b, rel=1e-6):
    scale = max(1.0, np.abs(b).max())
    assert np.abs(a - b).max() <= rel * scale, np.abs(a - b).max()


def test_model_holds_every_kind():
    core, t = every_kind().compiled(), 0.37
    q = core.initial_state()[0]
    kinds = {core.element_kind(n) for n in ["rev", "slide", "weld", "link", "slot", "gear", "rack",
                                             "motor", "push", "lift", "spring", "torsion",
                                             "push_local", "twist"]}
    assert kinds == {"revolute", "translational", "weld", "distance", "pin_in_slot", "gear",
                     "rack_pinion", "angle_driver", "slide_driver", "coordinate_driver",
                     "spring_damper", "rotational_spring_damper", "force", "torque"}
    assert core.n_constraints == 2 + 2 + 3 + 1 + 1 + 1 + 1 + 2 + 4
    # the kernels checked here evaluate every row (a run keeps the rows it
    # drops as redundant in its own Data); none of this model's is dependent
    assert core.rank(q, t)["dependent_rows"] == []


def test_spatial_model_holds_every_spatial_kind():
    from lagmb.registry import SPATIAL_KINDS

    m = every_spatial_kind()
    core = m.compiled()
    used = {core.element_kind(kw["name"]) for method, kw in m.elements} - {"body"}
    declared = {k.name for k in SPATIAL_KINDS if k.role != "body"}
    # the drivers and joint kinds a builder picks (angle or slide) are the ones in the core; a
    # stop's event function is the joint's coordinate, checked here through its driver
    # (and its impacts in tests/elements/test_stops.py)
    assert declared - {"spatial_joint_driver", "spatial_body_driver", "spatial_stop"} <= used
    assert {"spatial_angle_driver", "spatial_slide_driver", "spatial_position_driver"} <= used
    q = core.initial_state()[0]
    assert core.rank(q, 0.0)["dependent_rows"] == []


def test_constraint_jacobian(state):
    core, q, v, w, t = state
    close(core.constraint_jacobian(q, t), fd(lambda x: core.constraint_values(x, t)[0], q))


def test_phi_t(state):
    core, q, v, w, t = state
    dphi_dt = fd(lambda s: core.constraint_values(q, s[0])[0], [t])[:, 0]
    close(core.constraint_values(q, t)[1], dphi_dt)


def test_hessian_contraction(state):
    core, q, v, w, t = state
    close(core.constraint_hessian(q, w, t), fd(lambda x: core.constraint_jacobian(x, t).T @ w, q))


def test_velocity_jacobian(state):
    core, q, v, w, t = state
    g = lambda x: core.constraint_jacobian(x, t) @ v + core.constraint_values(x, t)[1]
    close(core.gamma(q, v, t)[1], fd(g, q))


def test_gamma_is_minus_the_second_derivative_along_a_straight_path(state):
    core, q, v, w, t = state
    h = 1e-4
    phi = lambda s: core.constraint_values(q + s * v, t + s)[0]
    second = (phi(h) - 2 * phi(0.0) + phi(-h)) / h**2
    gamma = core.gamma(q, v, t)[0]
    assert np.abs(-second - gamma).max() <= 1e-5 * max(1.0, np.abs(gamma).max())


def test_force_derivatives(state):
    core, q, v, w, t = state
    Q, Q_q, Q_v = core.forces(q, v, t)
    close(Q_q, fd(lambda x: core.forces(x, v, t)[0], q))
    close(Q_v, fd(lambda x: core.forces(q, x, t)[0], v))


def test_mass_derivative(state):
    """(M(q) a)_q against differences of M(q) a; zero for a planar model."""
    core, q, v, w, t = state
    a = np.random.default_rng(3).standard_normal(q.size)
    close(core.mass_derivative(q, a), fd(lambda x: core.mass_matrix(x)[0] @ a, q))


def test_mass_inverse(state):
    """M(q)^-1 M(q) = I, also off the normalization (|p| != 1)."""
    core, q, v, w, t = state
    M, M_inv = core.mass_matrix(q)
    close(M_inv @ M, np.eye(q.size), rel=1e-12)


def test_kinetic_energy_is_half_v_M_v_where_the_euler_parameters_are_consistent():
    """M_p adds 4 jbar p p^T to 4 G^T J' G: on |p| = 1 with p^T p' = 0 it
    adds nothing to v^T M v / 2."""
    core = every_spatial_kind().compiled()
    q, v = core.initial_state()
    assert core.kinetic_energy(q, v) == pytest.approx(0.5 * v @ core.mass_matrix(q)[0] @ v, rel=1e-13)
