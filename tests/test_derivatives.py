"""Every element kind's derivatives against finite differences.

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


@pytest.fixture(scope="module")
def state():
    m = every_kind()
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


def test_model_holds_every_kind(state):
    core, q, _, _, t = state
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
