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
  and m g l / (I2 + m l^2), and a spin about the vertical nothing resists;
- the sparse path (count=k: the k lowest modes by shift-invert Lanczos) against
  the dense one, and a chain of N rigid rods against the continuous hanging
  chain (Daniel Bernoulli 1732; Rayleigh, Theory of Sound, sec. 162):
  omega_k = (j_{0,k} / 2) sqrt(g / L), j_{0,k} the zeros of the Bessel J0.
"""

import math
import sys

import numpy as np
import pytest

import lagmb as mb
from lagmb import linear

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
    # tol: a fraction of the largest omega^2 (issue 39: NaN and -1 were taken)
    for bad, said in ((float("nan"), "tol must be finite, got nan"), (-1, "tol must be positive and finite, got -1"),
                      (0.0, "tol must be positive"), (1.0, "tol must be below 1"), ("1e-9", "tol must be a number")):
        with pytest.raises(mb.ModelError, match=f"modes: {said}"):
            mb.modes(hanging_rod(), tol=bad)


# --- the sparse path: count=k -------------------------------------------------


def hanging_chain(n, length=1.0, mass=1.0, g=G):
    """n equal uniform rods (length / n each, total mass `mass`) hanging from a
    pin at the origin, each pinned to the next; gravity -g in y (g < 0:
    upside down)."""
    m = mb.Model(gravity=(0.0, -g))
    l, mi = length / n, mass / n
    previous = m.ground
    for k in range(n):
        rod = m.add_body(f"rod{k}", mi, mi * l**2 / 12, position=(0.0, -(k + 0.5) * l), angle=-math.pi / 2)
        m.add_revolute(f"pin{k}", previous, rod, at=(0.0, -k * l))
        previous = rod
    return m


def same_up_to_sign(a, b, atol):
    """Rows of a equal rows of b, each up to its sign."""
    for x, y in zip(a, b):
        s = 1.0 if np.dot(x, y) >= 0 else -1.0
        np.testing.assert_allclose(x, s * y, rtol=0, atol=atol)


def test_the_sparse_path_finds_the_dense_paths_lowest_modes_of_a_40_rod_chain():
    model = hanging_chain(40, length=10.0)
    eq = mb.equilibrium(model)
    dense = mb.modes(model, at=eq)
    sparse = mb.modes(model, at=eq, count=5)
    assert len(dense) == 40 and len(sparse) == 5
    np.testing.assert_allclose(sparse.omega, dense.omega[:5], rtol=1e-9)
    np.testing.assert_allclose(sparse.frequencies, dense.frequencies[:5], rtol=1e-9)
    assert sparse.kinds == dense.kinds[:5] == ["vibration"] * 5
    # largest entry +1 in both: the same vectors (the sign only where two entries tie)
    same_up_to_sign(sparse.shapes, dense.shapes[:5], atol=1e-9)
    np.testing.assert_array_equal(sparse.damping_ratios, np.zeros(5))
    np.testing.assert_allclose(np.sort(sparse.eigenvalues.imag), np.sort(np.r_[sparse.omega, -sparse.omega]),
                               rtol=1e-12)
    assert sparse.equilibrium is eq
    # upside down: every mode unstable; the slowest-growing first, as dense
    upright = hanging_chain(40, length=10.0, g=-G)
    eq = mb.equilibrium(upright, allow_unstable=True)
    dense, sparse = mb.modes(upright, at=eq), mb.modes(upright, at=eq, count=3)
    assert sparse.kinds == ["unstable"] * 3
    np.testing.assert_allclose(sparse.omega_squared, dense.omega_squared[:3], rtol=1e-9)
    same_up_to_sign(sparse.shapes, dense.shapes[:3], atol=1e-9)


def free_spring_chain(n, k, c, mass):
    """spring_chain without the wall: n blocks on guides, each tied to the
    next by a spring k and a damper c; the whole chain slides freely."""
    m = mb.Model(gravity=(0.0, 0.0))
    previous = None
    for j in range(1, n + 1):
        block = m.add_body(f"block{j}", mass, 0.01, position=(float(j), 0.0))
        m.add_translational(f"guide{j}", m.ground, block, at=(float(j), 0.0), axis=(1.0, 0.0))
        if previous is not None:
            m.add_spring_damper(f"spring{j}", previous, (j - 1.0, 0.0), block, (float(j), 0.0), stiffness=k, damping=c)
        previous = block
    return m


def test_the_sparse_path_finds_a_rigid_body_mode_and_stiffness_proportional_damping():
    """A free-free chain: omega_j = 2 sqrt(k/m) sin(j pi / (2N)), j = 0 .. N - 1
    (j = 0 the chain sliding as a whole), and zeta_j = c omega_j / (2 k) as
    C = (c/k) K: the shift just below 0 keeps the zero eigenvalue apart."""
    n, k, c, mass = 40, 400.0, 2.0, 1.5
    model = free_spring_chain(n, k, c, mass)
    modes = mb.modes(model, count=5)
    omega = 2 * math.sqrt(k / mass) * np.sin(np.arange(5) * math.pi / (2 * n))
    assert modes.kinds == ["rigid-body"] + ["vibration"] * 4
    assert abs(modes.omega_squared[0]) < 1e-10
    np.testing.assert_allclose(modes.omega[1:], omega[1:], rtol=1e-10)
    np.testing.assert_allclose(modes.shapes[0][0::3], np.ones(n), atol=1e-10)  # every block the same way
    assert math.isnan(modes.damping_ratios[0])
    zeta = c * omega[1:] / (2 * k)
    np.testing.assert_allclose(modes.damping_ratios[1:], zeta, rtol=1e-9)
    # the reduced system's eigenvalues: these modes' own (proportional damping), 0 twice for the slide
    damped = -zeta * omega[1:] + 1j * omega[1:] * np.sqrt(1 - zeta**2)
    expected = np.sort_complex(np.concatenate([damped, damped.conj(), [0.0, 0.0]]))
    np.testing.assert_allclose(np.sort_complex(modes.eigenvalues), expected, atol=1e-9)
    dense = mb.modes(model, count=None)
    np.testing.assert_allclose(modes.omega[1:], dense.omega[1:5], rtol=1e-9)


def test_a_chain_of_200_rods_swings_like_the_continuous_hanging_chain():
    """The hanging chain of length L (Bernoulli; Rayleigh, Theory of Sound,
    sec. 162): omega_k = (j_{0,k} / 2) sqrt(g / L). N rigid rods (inertia
    m l^2 / 12) are that chain restricted to shapes straight between the
    pins: its kinetic energy and its potential, the integral of
    T(s) u'(s)^2 / 2 with the tension T linear in s, are the continuous
    chain's exactly for such shapes. So the rods are the linear finite
    elements of the chain with a consistent mass: by Rayleigh's principle
    their frequencies lie above the chain's, and closer as 1/N^2. For
    L = 100 m, N = 200 the first two are 7.7e-7 and 2.6e-5 above (about
    0.031 / N^2 and 1.03 / N^2); asserted: above, within 1e-6 and 3e-5,
    and four times closer than with N = 100 (to 1%)."""
    special = pytest.importorskip("scipy.special")
    length = 100.0
    exact = special.jn_zeros(0, 2) / 2 * math.sqrt(G / length)
    errors = {}
    for n in (100, 200):
        model = hanging_chain(n, length=length)
        modes = mb.modes(model, at=mb.equilibrium(model, stability=False), count=2)
        assert modes.kinds == ["vibration"] * 2
        errors[n] = modes.omega / exact - 1
    assert np.all(errors[200] > 0)
    assert errors[200][0] < 1e-6 and errors[200][1] < 3e-5
    np.testing.assert_allclose(errors[100] / errors[200], 4.0, rtol=0.01)


def test_a_model_of_more_than_600_coordinates_gets_its_10_lowest_modes_sparsely(monkeypatch):
    model = hanging_chain(201, length=100.0)  # 603 coordinates
    modes = mb.modes(model)
    assert len(modes) == 10 and modes.shapes.shape == (10, 603)
    assert modes.equilibrium.stable is None  # found without the dense stability check
    assert np.all(np.diff(modes.omega) > 0)
    np.testing.assert_allclose(modes.omega[:3], mb.modes(model, at=modes.equilibrium, count=3).omega, rtol=1e-10)
    # the rule, on small chains: more than SPARSE_ABOVE coordinates (600) is sparse, that many dense
    monkeypatch.setattr(linear, "SPARSE_ABOVE", 60)
    assert len(mb.modes(hanging_chain(20))) == 20 and len(mb.modes(hanging_chain(21))) == 10


def test_few_degrees_of_freedom_take_the_sparse_path_too():
    """count close to the number of degrees of freedom (too few for Lanczos):
    every mode from a sparse basis of the motions allowed, the lowest kept."""
    L, mass = 1.3, 1.0
    m = mb.Model(gravity=(0.0, -G))
    upper = m.add_body("upper", mass, mass * L**2 / 12, position=(0.0, -L / 2), angle=-math.pi / 2)
    lower = m.add_body("lower", mass, mass * L**2 / 12, position=(0.0, -1.5 * L), angle=-math.pi / 2)
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("elbow", upper, lower, at=(0.0, -L))
    dense = mb.modes(m)
    for count in (1, 2):
        sparse = mb.modes(m, count=count)
        np.testing.assert_allclose(sparse.omega, dense.omega[:count], rtol=1e-12)
        same_up_to_sign(sparse.shapes, dense.shapes[:count], atol=1e-12)
        by_frequency = lambda values: values[np.argsort(values.imag)]  # noqa: E731 - real parts 0 (to 1e-16)
        np.testing.assert_allclose(by_frequency(sparse.eigenvalues), by_frequency(dense.eigenvalues[:2 * count]),
                                   rtol=0, atol=1e-12)
    # a ball joint: the free spin (rigid-body) first, then the slower swing
    mass, l, inertia = 3.0, 0.4, (0.05, 0.06, 0.08)
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    bob = m.add_body("bob", mass, inertia, position=(0.0, 0.0, -l))
    m.add_spherical("ball", m.ground, bob, at=(0.0, 0.0, 0.0))
    modes = mb.modes(m, count=2)
    assert modes.kinds == ["rigid-body", "vibration"]
    assert modes.omega[1] == pytest.approx(math.sqrt(mass * G * l / (inertia[1] + mass * l**2)), rel=1e-10)


def test_the_sparse_path_in_space_where_the_euler_parameters_leave_M_singular():
    """Spatial bodies' M has a null direction (along the Euler parameters,
    taken up by their unit-length rows): Lanczos with the M inner product in
    shift-invert mode still finds the dense path's modes. 15 bodies on
    universal joints (30 degrees of freedom)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    previous = m.ground
    for k in range(15):
        body = m.add_body(f"b{k}", 1.0, (0.05, 0.06, 0.01), position=(0.0, 0.0, -(k + 0.5)))
        m.add_universal(f"u{k}", previous, body, at=(0.0, 0.0, -k), axis_i=(1.0, 0.0, 0.0), axis_j=(0.0, 1.0, 0.0))
        previous = body
    eq = mb.equilibrium(m)
    dense, sparse = mb.modes(m, at=eq), mb.modes(m, at=eq, count=4)
    np.testing.assert_allclose(sparse.omega, dense.omega[:4], rtol=1e-9)
    same_up_to_sign(sparse.shapes, dense.shapes[:4], atol=1e-8)  # two swings 2e-4 apart: shapes less sharp


def test_count_is_checked_and_scipy_is_needed_only_for_the_sparse_path(monkeypatch):
    model = hanging_rod()
    for bad in (0, -1):
        with pytest.raises(mb.ModelError, match="count must be at least 1"):
            mb.modes(model, count=bad)
    for bad in (1.5, "3", True):
        with pytest.raises(mb.ModelError, match="count must be a whole number"):
            mb.modes(model, count=bad)
    with pytest.raises(mb.ModelError, match="count 2 is more than the 1 degree of freedom"):
        mb.modes(model, count=2)
    assert len(mb.modes(model, count=1.0)) == 1
    driven = hanging_rod()
    driven.drive_joint("motor", "pin", 0.0)
    with pytest.raises(mb.ModelError, match="more than the 0 degrees of freedom"):
        mb.modes(driven, count=1)
    # a follower force: its tangent stiffness is not symmetric, as on the dense path
    chain = hanging_chain(40, length=10.0)
    chain.add_force("push", "rod39", (0.3, 0.0), point=(0.0, -10.0), local=True)
    eq = mb.equilibrium(chain, allow_unstable=True)
    for count in (None, 5):
        with pytest.raises(mb.ModelError, match="not symmetric"):
            mb.modes(chain, at=eq, count=count)
    monkeypatch.setitem(sys.modules, "scipy", None)
    with pytest.raises(mb.ModelError, match="needs SciPy"):
        mb.modes(model, count=1)
    assert len(mb.modes(model)) == 1  # dense: NumPy only
