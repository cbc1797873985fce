"""Vibration modes about a static equilibrium (mb.modes), against closed forms:

- a uniform rod pinned at one end (compound pendulum): omega = sqrt(3 g / 2 L),
  the mode a turn about the pin (centre of mass moving L/2 per radian);
- a double pendulum of two equal uniform rods: omega^2 = (g / L)(3 -+ 6 / sqrt 7)
  (from the linearized Lagrange equations; e.g. Meirovitch, Elements of
  Vibration Analysis, the double compound pendulum);
- N equal masses on a line joined by springs k, fixed at one end, free at the
  other: omega_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1))); with a damper c
  beside every spring the damping is proportional to the stiffness
  (C = (c/k) K), so zeta_j = c omega_j / (2 k) exactly;
- the rod upright: unstable, growing as exp(sqrt(3 g / 2 L) t);
- a rigid body hanging on a ball joint, centre of mass l below it,
  principal inertias I1, I2 (horizontal axes), I3: omega^2 = m g l / (I1 + m l^2)
  and m g l / (I2 + m l^2), and a spin about the vertical nothing resists.
"""

import math

import numpy as np
import pytest

import lagmb as mb

G = 9.81


def hanging_rod(L=1.3, mass=2.0, upright=False):
    m = mb.Model(gravity=(0.0, -G))
    sign = 1.0 if upright else -1.0
    rod = m.add_body("rod", mass, mass * L**2 / 12, position=(0.0, sign * L / 2), angle=sign * math.pi / 2)
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m


def test_a_compound_pendulum_swings_at_sqrt_3g_over_2L_turning_about_its_pin():
    L = 1.3
    modes = mb.modes(hanging_rod(L))
    assert len(modes) == 1 and modes.kinds == ["vibration"]
    assert modes.omega[0] == pytest.approx(math.sqrt(1.5 * G / L), rel=1e-12)
    assert modes.frequencies[0] == pytest.approx(modes.omega[0] / (2 * math.pi), rel=1e-15)
    assert modes.damping_ratios[0] == 0.0
    # (x, y, angle) of the rod: a turn of 1 rad moves the centre L/2 sideways, not up
    np.testing.assert_allclose(np.abs(modes.shapes[0]), [L / 2, 0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(np.sort(np.abs(modes.eigenvalues.imag)), [modes.omega[0]] * 2, rtol=1e-12)


def test_a_double_pendulum_of_two_rods_has_the_two_closed_form_frequencies():
    L, mass = 1.3, 1.0
    m = mb.Model(gravity=(0.0, -G))
    upper = m.add_body("upper", mass, mass * L**2 / 12, position=(0.0, -L / 2), angle=-math.pi / 2)
    lower = m.add_body("lower", mass, mass * L**2 / 12, position=(0.0, -1.5 * L), angle=-math.pi / 2)
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("elbow", upper, lower, at=(0.0, -L))
    modes = mb.modes(m)
    expected = np.sqrt(G / L * np.array([3 - 6 / math.sqrt(7), 3 + 6 / math.sqrt(7)]))
    np.testing.assert_allclose(modes.omega, expected, rtol=1e-12)
    assert len(modes) == 2 and modes.shapes.shape == (2, 6)
    # upside down: both modes unstable, still listed by frequency ascending
    upright = mb.Model(gravity=(0.0, G))
    upper = upright.add_body("upper", mass, mass * L**2 / 12, position=(0.0, -L / 2), angle=-math.pi / 2)
    lower = upright.add_body("lower", mass, mass * L**2 / 12, position=(0.0, -1.5 * L), angle=-math.pi / 2)
    upright.add_revolute("shoulder", upright.ground, upper, at=(0.0, 0.0))
    upright.add_revolute("elbow", upper, lower, at=(0.0, -L))
    falling = mb.modes(upright)
    assert falling.kinds == ["unstable", "unstable"]
    np.testing.assert_allclose(falling.omega, expected, rtol=1e-12)


def spring_chain(n, k, c, mass):
    """n blocks on horizontal guides 1 m apart, the first tied to a wall at
    x = 0 by a spring-damper, each to the next by another."""
    m = mb.Model(gravity=(0.0, 0.0))
    previous, anchor = m.ground, (0.0, 0.0)
    for j in range(1, n + 1):
        block = m.add_body(f"block{j}", mass, 0.01, position=(float(j), 0.0))
        m.add_translational(f"guide{j}", m.ground, block, at=(float(j), 0.0), axis=(1.0, 0.0))
        m.add_spring_damper(f"spring{j}", previous, anchor, block, (float(j), 0.0), stiffness=k, damping=c)
        previous, anchor = block, (float(j), 0.0)
    return m


def test_a_spring_chain_has_its_closed_form_frequencies_and_stiffness_proportional_damping():
    n, k, c, mass = 4, 400.0, 2.0, 1.5
    modes = mb.modes(spring_chain(n, k, c, mass))
    j = np.arange(1, n + 1)
    omega = 2 * math.sqrt(k / mass) * np.sin((2 * j - 1) * math.pi / (2 * (2 * n + 1)))
    np.testing.assert_allclose(modes.omega, omega, rtol=1e-12)
    np.testing.assert_allclose(modes.damping_ratios, c * omega / (2 * k), rtol=1e-10)
    # the damped eigenvalues: -zeta omega +- i omega sqrt(1 - zeta^2)
    zeta = c * omega / (2 * k)
    damped = np.concatenate([-zeta * omega + 1j * omega * np.sqrt(1 - zeta**2),
                             -zeta * omega - 1j * omega * np.sqrt(1 - zeta**2)])
    np.testing.assert_allclose(np.sort_complex(modes.eigenvalues), np.sort_complex(damped), rtol=1e-10)
    # the lowest mode moves every block the same way, the far end most
    x = modes.shapes[0][[3 * i for i in range(n)]]
    assert np.all(x > 0) and x[-1] == pytest.approx(1.0) and np.all(np.diff(x) > 0)


def test_an_upright_rod_has_one_unstable_mode_growing_at_sqrt_3g_over_2L():
    L = 0.8
    model = hanging_rod(L, upright=True)
    modes = mb.modes(model)
    assert modes.kinds == ["unstable"] and modes.omega_squared[0] < 0
    assert modes.omega[0] == pytest.approx(math.sqrt(1.5 * G / L), rel=1e-12)
    assert max(modes.eigenvalues.real) == pytest.approx(math.sqrt(1.5 * G / L), rel=1e-12)
    assert mb.modes(model, at=mb.equilibrium(model, allow_unstable=True)).omega[0] == modes.omega[0]


def test_a_body_on_a_ball_joint_swings_about_both_horizontal_axes_and_spins_freely():
    mass, l, inertia = 3.0, 0.4, (0.05, 0.06, 0.08)
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    bob = m.add_body("bob", mass, inertia, position=(0.0, 0.0, -l))
    m.add_spherical("ball", m.ground, bob, at=(0.0, 0.0, 0.0))
    modes = mb.modes(m)
    assert len(modes) == 3 and modes.kinds == ["rigid-body", "vibration", "vibration"]
    expected = sorted(math.sqrt(mass * G * l / (I + mass * l**2)) for I in inertia[:2])
    np.testing.assert_allclose(modes.omega[1:], expected, rtol=1e-10)
    assert math.isnan(modes.damping_ratios[0])


def test_a_fully_driven_mechanism_has_no_modes_and_bad_input_is_named():
    model = hanging_rod()
    model.drive_joint("motor", "pin", 0.0)
    assert len(mb.modes(model)) == 0
    with pytest.raises(mb.ModelError, match="at must be an equilibrium"):
        mb.modes(hanging_rod(), at=(0.0, 1.0))
    with pytest.raises(mb.ModelError, match="another model"):
        mb.modes(hanging_rod(), at=mb.equilibrium(hanging_rod()))
