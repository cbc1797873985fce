"""The motion linearized about an operating point (mb.linearize), each check
against something independent of it:

- a uniform rod pinned at one end: theta'' = -(3 g / 2 L) theta, its centre
  moving L/2 per radian, the pin pushing it sideways with -(3/4) m g theta;
- a double pendulum of two rods: the closed-form frequencies, and at a
  moving state the Jacobian of the closed-form equations of motion in the
  two angles (by central differences);
- a chain of spring-damped blocks: the analytic damped eigenvalues;
- a four-bar (a closed loop) hanging still: the frequency of a small
  oscillation of lagmb's own simulation, to 1e-6;
- a body on a ball joint (spatial): the two swing frequencies and the free
  spin;
- a cart-pole upright: the textbook linear model, and the descriptor form's
  finite eigenvalues equal to the minimal form's.
"""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import lagmb as mb
from analyses.test_modes import hanging_rod, spring_chain  # the same pinned rod and spring chain
import paths  # noqa: E402  (tests/paths.py)

G = 9.81
EXAMPLES = Path(paths.EXAMPLES)


def by_frequency(values):
    """Eigenvalues in a fixed order: by magnitude, then imaginary part."""
    values = np.asarray(values)
    return values[np.lexsort((values.imag, np.round(np.abs(values), 6)))]


def test_a_pinned_rod_linearizes_to_theta_dd_equal_minus_3g_over_2L_theta_with_its_reaction():
    L, mass = 1.3, 2.0
    lin = mb.linearize(hanging_rod(L, mass), outputs=["rod.x", "rod.y", "pin.reaction.x", "pin.reaction.y",
                                                      "pin.angle", "der(rod.angle)"])
    assert lin.states == ["rod.angle", "der(rod.angle)"]
    np.testing.assert_allclose(lin.A, [[0.0, 1.0], [-1.5 * G / L, 0.0]], atol=1e-12)
    assert lin.B.shape == (2, 0) and lin.D.shape == (6, 0)
    np.testing.assert_allclose(np.abs(lin.eigenvalues.imag), math.sqrt(1.5 * G / L), rtol=1e-12)
    # the mode: the centre moves L/2 sideways per radian, not up; the pin
    # pushes it back with m a_x = m (L/2) theta'' = -(3/4) m g theta
    np.testing.assert_allclose(lin.C, [[L / 2, 0], [0, 0], [-0.75 * mass * G, 0], [0, 0], [1, 0], [0, 1]],
                               atol=1e-8)
    np.testing.assert_allclose(lin.y0[[0, 1, 2, 3]], [0.0, -L / 2, 0.0, mass * G], atol=1e-10)


def two_rods(L=1.3, mass=1.0, angles=(-math.pi / 2, -math.pi / 2), rates=(0.0, 0.0)):
    """A double pendulum of two uniform rods; angles of the rods from +x."""
    m = mb.Model(gravity=(0.0, -G))
    a1, a2 = angles
    e1, e2 = np.array([math.cos(a1), math.sin(a1)]), np.array([math.cos(a2), math.sin(a2)])
    upper = m.add_body("upper", mass, mass * L**2 / 12, position=tuple(L / 2 * e1), angle=a1)
    lower = m.add_body("lower", mass, mass * L**2 / 12, position=tuple(L * e1 + L / 2 * e2), angle=a2)
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("elbow", upper, lower, at=tuple(L * e1))
    return m


def two_rods_state(L, a, w):
    """(q, v) of two_rods for angles a and rates w."""
    e = [np.array([math.cos(x), math.sin(x)]) for x in a]
    n = [np.array([-math.sin(x), math.cos(x)]) for x in a]
    q = np.r_[L / 2 * e[0], a[0], L * e[0] + L / 2 * e[1], a[1]]
    v = np.r_[L / 2 * w[0] * n[0], w[0], L * w[0] * n[0] + L / 2 * w[1] * n[1], w[1]]
    return q, v


def two_rods_accelerations(L, mass, a, w):
    """The closed-form equations of motion of two uniform rods in their
    absolute angles (Lagrange): M(a) a'' = f(a, a')."""
    c, s = math.cos(a[0] - a[1]), math.sin(a[0] - a[1])
    M = mass * L**2 * np.array([[1 / 3 + 1, 0.5 * c], [0.5 * c, 1 / 3]])
    f = -mass * L**2 * 0.5 * s * np.array([w[1] ** 2, -w[0] ** 2]) \
        - mass * G * L * np.array([1.5 * math.cos(a[0]), 0.5 * math.cos(a[1])])
    return np.linalg.solve(M, f)


def test_a_double_pendulum_has_the_closed_form_frequencies_in_any_coordinates():
    L = 1.3
    model = two_rods(L)
    expected = np.sqrt(G / L * np.array([3 - 6 / math.sqrt(7), 3 + 6 / math.sqrt(7)]))
    for coordinates in ("independent", "orthonormal", ["lower.angle", "upper.x"]):
        lin = mb.linearize(model, coordinates=coordinates)
        np.testing.assert_allclose(np.sort(np.abs(lin.eigenvalues.imag))[::2], expected, rtol=1e-10)
        np.testing.assert_allclose(lin.eigenvalues.real, 0.0, atol=1e-10)
    assert mb.linearize(model).states[:2] == ["upper.angle", "lower.angle"]
    assert mb.linearize(model, coordinates="orthonormal").states == ["z1", "z2", "der(z1)", "der(z2)"]


def test_at_a_moving_state_A_is_the_jacobian_of_the_equations_of_motion_in_the_two_angles():
    L, mass = 1.1, 0.7
    a, w = np.array([-1.1, 0.4]), np.array([1.3, -2.2])
    model = two_rods(L, mass, angles=tuple(a), rates=tuple(w))
    q, v = two_rods_state(L, a, w)
    lin = mb.linearize(model, at=(q, v, 0.0))
    assert lin.states == ["upper.angle", "lower.angle", "der(upper.angle)", "der(lower.angle)"]
    expected = np.zeros((4, 4))
    expected[:2, 2:] = np.eye(2)
    h = 1e-6
    for j in range(4):
        x = np.r_[a, w]
        plus, minus = x.copy(), x.copy()
        plus[j] += h
        minus[j] -= h
        expected[2:, j] = (two_rods_accelerations(L, mass, plus[:2], plus[2:])
                           - two_rods_accelerations(L, mass, minus[:2], minus[2:])) / (2 * h)
    np.testing.assert_allclose(lin.A, expected, rtol=1e-7, atol=1e-7)
    # and its accelerations are the closed form's
    np.testing.assert_allclose(lin.a[[2, 5]], two_rods_accelerations(L, mass, a, w), rtol=1e-12)
    with pytest.raises(mb.ModelError, match="not a static equilibrium"):
        lin.descriptor()


def test_a_spring_damper_chain_has_the_analytic_damped_eigenvalues_in_both_forms():
    n, k, c, mass = 4, 400.0, 2.0, 1.5
    lin = mb.linearize(spring_chain(n, k, c, mass))
    assert lin.states[:n] == [f"block{j}.x" for j in range(1, n + 1)]
    j = np.arange(1, n + 1)
    omega = 2 * math.sqrt(k / mass) * np.sin((2 * j - 1) * math.pi / (2 * (2 * n + 1)))
    zeta = c * omega / (2 * k)
    damped = np.concatenate([-zeta * omega + 1j * omega * np.sqrt(1 - zeta**2),
                             -zeta * omega - 1j * omega * np.sqrt(1 - zeta**2)])
    np.testing.assert_allclose(by_frequency(lin.eigenvalues), by_frequency(damped), rtol=1e-10)
    descriptor = lin.descriptor()
    assert descriptor.E.shape == (2 * 3 * n + 2 * n, 2 * 3 * n + 2 * n)
    np.testing.assert_allclose(by_frequency(descriptor.eigenvalues), by_frequency(damped), rtol=1e-8)


def four_bar(crank_angle):
    """examples/four_bar.toml's linkage (ground pivots (0, 0) and (4, 0),
    crank 1 m, coupler 3.5 m, rocker 3 m, bars of 1 kg/m) at rest with the
    crank at crank_angle (rad) and the coupler below the pivots."""
    A, D = np.array([0.0, 0.0]), np.array([4.0, 0.0])
    B = A + np.array([math.cos(crank_angle), math.sin(crank_angle)])
    d = np.linalg.norm(D - B)
    along = (3.5**2 - 3.0**2 + d**2) / (2 * d)
    across = math.sqrt(3.5**2 - along**2)
    u = (D - B) / d
    C = B + along * u - across * np.array([-u[1], u[0]])  # the lower branch
    m = mb.Model(gravity=(0.0, -G))
    bodies = []
    for name, p0, p1 in (("crank", A, B), ("coupler", B, C), ("rocker", D, C)):
        length = float(np.linalg.norm(p1 - p0))
        centre = 0.5 * (p0 + p1)
        angle = math.atan2(*(p1 - p0)[::-1])
        bodies.append(m.add_body(name, length, length**3 / 12, position=tuple(centre), angle=angle))
    crank, coupler, rocker = bodies
    m.add_revolute("A", m.ground, crank, at=tuple(A))
    m.add_revolute("B", crank, coupler, at=tuple(B))
    m.add_revolute("C", coupler, rocker, at=tuple(C))
    m.add_revolute("D", m.ground, rocker, at=tuple(D))
    return m


def test_a_hanging_four_bar_oscillates_at_the_linearized_frequency():
    model = four_bar(-1.2)
    eq = mb.equilibrium(model)
    assert eq.stable
    lin = mb.linearize(model, at=eq)
    assert lin.states == ["crank.angle", "der(crank.angle)"]
    omega = abs(lin.eigenvalues[0].imag)
    # lagmb's own simulation of a small swing: released 1e-4 rad from the equilibrium
    period = 2 * math.pi / omega
    r = mb.simulate(four_bar(eq.q[2] + 1e-4), 3.2 * period, rtol=1e-11, atol=1e-13, n_out=4001, method="ggl")
    rate = r.body("crank").angular_velocity
    up = np.nonzero((rate[:-1] < 0) & (rate[1:] >= 0))[0]
    crossings = r.t[up] - rate[up] * (r.t[up + 1] - r.t[up]) / (rate[up + 1] - rate[up])
    assert len(crossings) >= 3
    measured = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    assert measured == pytest.approx(period, rel=1e-6)


def test_a_body_on_a_ball_joint_swings_at_its_two_frequencies_and_spins_freely():
    mass, l, inertia = 3.0, 0.4, (0.05, 0.06, 0.08)
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    bob = m.add_body("bob", mass, inertia, position=(0.0, 0.0, -l))
    m.add_spherical("ball", m.ground, bob, at=(0.0, 0.0, 0.0))
    lin = mb.linearize(m, outputs=["bob.x", "bob.y", "ball.reaction.z"])
    assert lin.states[:3] == ["bob.e1", "bob.e2", "bob.e3"]
    expected = sorted(math.sqrt(mass * G * l / (I + mass * l**2)) for I in inertia[:2])
    values = lin.eigenvalues
    np.testing.assert_allclose(values[:2], 0.0, atol=1e-6)  # the spin about the vertical (a double 0)
    np.testing.assert_allclose(np.abs(values.imag[2:])[::2], expected, rtol=1e-10)
    # a tilt e1 (a turn 2 e1 about x) swings the bob toward +y, l per radian
    np.testing.assert_allclose(lin.C[:, 0], [0.0, 2 * l, 0.0], atol=1e-8)
    assert lin.y0[2] == pytest.approx(mass * G, rel=1e-12)
    np.testing.assert_allclose(by_frequency(lin.descriptor().eigenvalues)[2:], by_frequency(values)[2:],
                               rtol=1e-8)


def cart_pole():
    sys.path.insert(0, str(EXAMPLES))
    try:
        from cart_pole import cart_pole as build
    finally:
        sys.path.remove(str(EXAMPLES))
    return build(theta0=0.0)


def test_a_cart_pole_upright_has_the_textbook_linear_model():
    model = cart_pole()
    lin = mb.linearize(model, outputs=["pole.angle", "hinge.reaction.y"])
    assert lin.states == ["cart.x", "pole.angle", "der(cart.x)", "der(pole.angle)"]
    assert lin.inputs == ["push"]
    assert lin.equilibrium is not None and lin.equilibrium.stable is False
    # cart M, pole m of half-length l and inertia I about its centre (textbook:
    # Ogata; the pole's angle from upright positive toward -x)
    M, m, l, I = 1.0, 0.1, 0.5, 0.1 / 12
    den = (M + m) * (I + m * l**2) - (m * l) ** 2
    A = np.zeros((4, 4))
    A[:2, 2:] = np.eye(2)
    A[2, 1] = (m * l) ** 2 * G / den
    A[3, 1] = (M + m) * m * G * l / den
    B = np.array([0.0, 0.0, (I + m * l**2) / den, m * l / den])
    np.testing.assert_allclose(lin.A, A, atol=1e-12)
    np.testing.assert_allclose(lin.B[:, 0], B, rtol=1e-12, atol=1e-15)
    # the hinge carries the pole's weight; pushing the cart changes it at once
    assert lin.y0[1] == pytest.approx(m * G, rel=1e-12)
    assert lin.D.shape == (2, 1) and lin.D[0, 0] == 0.0
    ss = lin.to_scipy()
    np.testing.assert_array_equal(ss.A, lin.A)
    np.testing.assert_array_equal(ss.B, lin.B)
    np.testing.assert_allclose(np.sort(lin.descriptor().eigenvalues.real), np.sort(lin.eigenvalues.real),
                               atol=1e-6)
    held = mb.linearize(model, inputs=[])
    assert held.B.shape == (4, 0) and held.to_scipy().B.shape == (4, 1)
    # pushing 1 N: not at rest (the cart accelerates at B's (I + m l^2) / den), so no descriptor form
    pushed = mb.linearize(model, at=(lin.q, lin.v, 0.0), input_values={"push": 1.0})
    assert pushed.a[0] == pytest.approx((I + m * l**2) / den, rel=1e-12)
    with pytest.raises(mb.ModelError, match="not a static equilibrium"):
        pushed.descriptor()
    with pytest.raises(mb.ModelError, match="input_values with at=None"):
        mb.linearize(model, input_values={"push": 1.0})
    with pytest.raises(mb.ModelError, match=r"no input 'pull'.*push"):
        mb.linearize(model, at=(lin.q, lin.v), input_values={"pull": 1.0})


def test_bad_input_is_named():
    model = hanging_rod()
    with pytest.raises(mb.ModelError, match=r"no output 'rod\.z'.*rod\.x"):
        mb.linearize(model, outputs=["rod.z"])
    with pytest.raises(mb.ModelError, match="reaction's components are x, y, torque"):
        mb.linearize(model, outputs=["pin.reaction.z"])
    with pytest.raises(mb.ModelError, match=r"no input 'push'.*\(none\)"):
        mb.linearize(model, inputs=["push"])
    with pytest.raises(mb.ModelError, match="not a consistent state"):
        mb.linearize(model, at=(np.zeros(3), np.zeros(3)))
    with pytest.raises(mb.ModelError, match="coordinates must be"):
        mb.linearize(model, coordinates="minimal")
    with pytest.raises(mb.ModelError, match="give 1 different coordinates"):
        mb.linearize(model, coordinates=["rod.x", "rod.angle"])
    with pytest.raises(mb.ModelError, match="do not determine the motion"):
        mb.linearize(model, coordinates=["rod.y"])
    with pytest.raises(mb.ModelError, match="at must be None, an Equilibrium"):
        mb.linearize(model, at=3.0)
    rubbing = hanging_rod()
    rubbing.add_joint_friction("rub", "pin", mu=0.1, pin_radius=0.01)
    with pytest.raises(mb.ModelError, match="joint friction \\('rub'\\)"):
        mb.linearize(rubbing)
    driven = hanging_rod()
    driven.drive_joint("motor", "pin", mb.Input(0.0, name="angle"))
    with pytest.raises(mb.ModelError, match="input 'angle' drives the motion of 'motor'"):
        mb.linearize(driven, at=mb.equilibrium(driven))
    assert mb.linearize(driven, inputs=[], outputs=["motor.effort"]).A.shape == (0, 0)
    # the operating point's numbers are checked, each by name (issue 39)
    for bad, said in (("1.0", r"input 'angle' must be a number, got '1\.0'"),
                      (float("inf"), "input 'angle' must be finite, got inf")):
        with pytest.raises(mb.ModelError, match=said):
            mb.linearize(driven, at=(np.zeros(3), np.zeros(3)), inputs=[], input_values={"angle": bad})
    with pytest.raises(mb.ModelError, match=r"input_values must be a dict \{input name: value\}, got \[\('angle'"):
        mb.linearize(driven, at=(np.zeros(3), np.zeros(3)), inputs=[], input_values=[("angle", 1.0)])
    with pytest.raises(mb.ModelError, match="linearize: q must be a sequence of finite numbers, got 'abc'"):
        mb.linearize(model, at=("abc", np.zeros(3)))
    with pytest.raises(mb.ModelError, match="linearize: t must be a number, got 'now'"):
        mb.linearize(model, at=(np.zeros(3), np.zeros(3), "now"))
    for which in ("inputs", "outputs"):  # (a TypeError from list() before)
        with pytest.raises(mb.ModelError, match=f"linearize: {which} must be a list of {which[:-1]} names, got 5"):
            mb.linearize(model, **{which: 5})


def test_a_model_whose_drivers_move_has_no_equilibrium_to_linearize_about_and_says_so():
    """at=None asks for mb.equilibrium, a state at rest; a driver that moves
    has none: the message names it and says to give at=(q, v, t) instead of
    calling a state nobody gave inconsistent (issue 39)."""
    model = hanging_rod()
    model.add_body("idle", 1.0, 1.0, position=(3.0, 0.0))
    model.add_revolute("idle_pin", model.ground, "idle", at=(3.0, 0.0))
    model.drive_joint("held", "idle_pin", 0.0)  # a driver at rest is no reason: not named
    model.drive_joint("motor", "pin", mb.Linear(2.0, start=-math.pi / 2))  # from where the rod hangs
    with pytest.raises(mb.ModelError, match=r"linearize: the model has no equilibrium to linearize about: its "
                                            r"drivers 'motor' move at t = 0 .*give at=\(q, v, t\)"):
        mb.linearize(model)
    # a state of the motion is what it takes (fully driven: no states left)
    r = mb.simulate(model, 0.5)
    assert mb.linearize(model, at=(r.q[-1], r.v[-1], r.t[-1])).A.shape == (0, 0)
    # given an equilibrium of it anyway, the message names the equations its state breaks
    with pytest.raises(mb.ModelError, match=r"at is not a consistent state .* in the equations of 'motor'"):
        mb.linearize(model, at=mb.equilibrium(model))


def test_the_lqr_example_designed_on_the_linearization_balances_the_pole_from_0_6_rad():
    sys.path.insert(0, str(EXAMPLES))
    try:
        import cart_pole_lqr as example
    finally:
        sys.path.remove(str(EXAMPLES))
    K, lin = example.lqr_gain(cart_pole())
    # the closed loop of the linear model is stable; the open loop is not
    assert max(lin.eigenvalues.real) > 3.9
    assert max(np.linalg.eigvals(lin.A - lin.B @ K).real) < -0.5
    sim, _ = example.balance_lqr(theta0=0.6, t_end=10.0, rtol=1e-6)
    r = sim.result()
    tilt = r.body("pole").angle - math.pi / 2
    late = r.t >= 8.0
    assert np.max(np.abs(tilt[late])) < 2e-4
    assert np.max(np.abs(r.body("cart").position[late, 0])) < 2e-3
    assert np.max(np.abs(r.input("push"))) < 27.0
