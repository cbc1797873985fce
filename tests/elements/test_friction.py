"""Joint friction: Coulomb with the load from the joint's own reaction, plus viscous.

Law (docs/modelling.md, "Joint friction"): with sd the joint's relative rate,
F = -(mu rho N + F0) sd / sqrt(sd^2 + v_s^2) - c sd on the joint's second
body (a torque for a revolute, rho = r_pin, N = |joint force|; a force along
the axis for a translational, rho = 1, N = |normal force|), N smoothed as
sqrt(N^2 + F_s^2) - F_s.

References: the block on an incline against its closed-form acceleration
g (sin a - mu cos a) and the regularized law's creep speed (derived below);
the pendulum's energy balance dE/dt = F omega with F recomputed here from the
run's own reaction; a spring-mass on a viscous slider and a spinning disc
with viscous + preload friction against their closed-form solutions; the
derivatives against central finite differences.
"""

import math

import numpy as np
import pytest

import lagmb as mb
import builders

G = 9.81
ALPHA = 0.4  # incline angle (rad); tan(ALPHA) = 0.4228
V_S = 1e-3   # slip velocity of the regularized sign (m/s)
F_S = 1e-6   # load smoothing (N), the default
FORMULATIONS = ["ggl", "index3", "index1", "projection"]


def incline(mu, mass=2.0):
    """A block on a translational joint to the ground along the downhill
    direction (cos a, -sin a); gravity (0, -g); at rest."""
    m = mb.Model(gravity=(0.0, -G))
    b = m.add_body("block", mass=mass, inertia=0.1, position=(0.0, 0.0))
    m.add_translational("slide", m.ground, b, at=(0.0, 0.0), axis=(math.cos(ALPHA), -math.sin(ALPHA)))
    m.add_joint_friction("friction", "slide", mu=mu, slip_velocity=V_S)
    return m


def downhill(x):
    return x @ np.array([math.cos(ALPHA), -math.sin(ALPHA)])


@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_block_sticks_when_mu_above_tan_alpha(formulation):
    """mu = 0.6 > tan(a): a Coulomb block would stay. The regularized law
    lets it creep at the speed where friction balances gravity along the
    slope: m g sin a = mu N v / sqrt(v^2 + v_s^2), N = sqrt((m g cos a)^2 +
    F_s^2) - F_s (the normal reaction, unchanged by the friction), so
    rho = m g sin a / (mu N) and v_creep = v_s rho / sqrt(1 - rho^2)
    (0.99 v_s here). Starting from rest the speed rises to v_creep (time
    constant ~ v_s / (mu g cos a) = 0.2 ms) and may not pass it: asserted at
    every output to 1e-6 relative, and reached at the end to 1e-6."""
    mass, mu = 2.0, 0.6
    r = mb.simulate(incline(mu, mass), t_end=1.0, rtol=1e-8, atol=1e-10, n_out=201, formulation=formulation)
    N = math.hypot(mass * G * math.cos(ALPHA), F_S) - F_S
    rho = mass * G * math.sin(ALPHA) / (mu * N)
    v_creep = V_S * rho / math.sqrt(1.0 - rho**2)
    v = downhill(r.body("block").velocity)
    assert np.all(v <= v_creep * (1 + 1e-6))
    assert abs(v[-1] - v_creep) <= 1e-6 * v_creep
    # creep distance after 1 s: below v_creep * 1 s (about 1 mm)
    assert 0.0 < downhill(r.body("block").position)[-1] <= v_creep * 1.0


@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_block_slides_with_closed_form_acceleration(formulation):
    """mu = 0.2 < tan(a): a = g (sin a - mu cos a). The regularized sign
    differs from 1 by 1 - v/sqrt(v^2 + v_s^2) and the load by at most F_s, so
    at every output with v > 0.1 m/s: |a - a_exact| <= mu g cos a (1 -
    v/sqrt(v^2 + v_s^2)) + mu F_s / m + 1e-10 m/s^2 (a is solved from the
    augmented system at the output state, so no integration error enters)."""
    mass, mu = 2.0, 0.2
    r = mb.simulate(incline(mu, mass), t_end=1.0, rtol=1e-8, atol=1e-10, n_out=101, formulation=formulation)
    v = downhill(r.body("block").velocity)
    a = downhill(r.body("block").acceleration)
    a_exact = G * (math.sin(ALPHA) - mu * math.cos(ALPHA))
    fast = v > 0.1
    assert fast.sum() > 80
    bound = mu * G * math.cos(ALPHA) * (1 - v / np.sqrt(v**2 + V_S**2)) + mu * F_S / mass + 1e-10
    assert np.all(np.abs(a[fast] - a_exact) <= bound[fast])
    # the speed lags the closed form by no more than the start-up through |v| < 0.1
    assert abs(v[-1] - a_exact * r.t[-1]) <= 1e-3 * a_exact


def friction_pendulum(mu=0.3, r_pin=0.05, viscous=0.02, preload=0.01, omega0=0.0):
    """Uniform rod (L = 1 m, m = 1 kg) pinned to the ground at one end,
    horizontal; revolute friction in the pin."""
    m = builders.pendulum(g=G, angular_velocity=omega0)
    m.add_joint_friction("pin_friction", "pin", mu=mu, pin_radius=r_pin, viscous=viscous, preload=preload,
                         slip_velocity=V_S)
    return m


def revolute_friction_torque(F, omega, mu=0.3, r_pin=0.05, viscous=0.02, preload=0.01):
    """The law written out from the reaction force F (k, 2) and omega."""
    N = np.sqrt((F**2).sum(axis=1) + F_S**2) - F_S
    return -(mu * r_pin * N + preload) * omega / np.sqrt(omega**2 + V_S**2) - viscous * omega


def test_pendulum_loses_energy_at_the_friction_power():
    """dE/dt = T_f omega, T_f recomputed from the run's own pin reaction
    (r.reaction: the force on the rod). dE/dt by central differences of
    r.energy on a 1 ms output grid (error O(dt^2) ~ 1e-6 W) against T_f
    omega at the same outputs: to 2e-4 of max |T_f omega|. The total loss
    E(T) - E(0) against the trapezoidal integral of T_f omega: to 1e-6 of
    the loss. r.friction_power is the same quantity: to 1e-12."""
    r = mb.simulate(friction_pendulum(), t_end=2.0, rtol=1e-10, atol=1e-12, n_out=2001)
    omega = r.body("rod").angular_velocity
    T = revolute_friction_torque(r.reaction("pin")[:, :2], omega)
    P = T * omega
    assert np.all(P <= 0.0)
    E = r.energy
    dE = (E[2:] - E[:-2]) / (r.t[2:] - r.t[:-2])
    assert np.abs(dE - P[1:-1]).max() <= 2e-4 * np.abs(P).max()
    loss = E[-1] - E[0]
    work = np.trapezoid(P, r.t) if hasattr(np, "trapezoid") else np.trapz(P, r.t)
    assert loss < -0.1  # friction takes a visible part of the 4.9 J swing
    assert abs(loss - work) <= 1e-6 * abs(loss)
    assert np.abs(r.friction_power("pin_friction") - P).max() <= 1e-12 * np.abs(P).max()
    assert np.abs(r.friction("pin_friction") - T).max() <= 1e-12 * np.abs(T).max()


def test_every_formulation_agrees_on_the_friction_pendulum():
    """The same run with ggl, index3, index1 and projection (rtol 1e-10):
    the angle at t = 1.5 s agrees with ggl's to 1e-5 rad (index3, whose
    error test weighs positions through h^2-scaled multipliers, is the
    loosest at ~1e-6; the others agree to ~1e-9)."""
    angles = {}
    for form in FORMULATIONS:
        r = mb.simulate(friction_pendulum(), t_end=1.5, rtol=1e-10, atol=1e-12, n_out=3, formulation=form)
        angles[form] = r.body("rod").angle[-1]
    for form in FORMULATIONS[1:]:
        assert abs(angles[form] - angles["ggl"]) <= 1e-5, angles


def test_viscous_slider_is_a_damped_oscillator():
    """A block (m = 2 kg) on a horizontal translational joint, a spring
    (k = 50 N/m) to the ground, viscous joint friction c = 3 N s/m, no
    Coulomb part: m x'' + c x' + k x = 0, x(0) = 0.1 m, x'(0) = 0, whose
    closed form is x = e^(-z w t) (x0 cos(wd t) + z w x0 / wd sin(wd t)).
    Asserted to 1e-7 m over 3 s."""
    mass, k, c, x0 = 2.0, 50.0, 3.0, 0.1
    m = mb.Model()
    b = m.add_body("block", mass=mass, inertia=0.1, position=(x0, 0.0))
    m.add_translational("slide", m.ground, b, at=(x0, 0.0), axis=(1.0, 0.0))
    m.add_spring_damper("spring", m.ground, (-1.0, 0.0), b, (x0, 0.0), stiffness=k, free_length=1.0)
    m.add_joint_friction("friction", "slide", viscous=c)
    r = mb.simulate(m, t_end=3.0, rtol=1e-10, atol=1e-12, n_out=301)
    w = math.sqrt(k / mass)
    z = c / (2 * math.sqrt(k * mass))
    wd = w * math.sqrt(1 - z**2)
    t = r.t
    x = np.exp(-z * w * t) * (x0 * np.cos(wd * t) + z * w * x0 / wd * np.sin(wd * t))
    assert np.abs(r.body("block").position[:, 0] - x).max() <= 1e-7


def test_spinning_disc_with_preload_and_viscous_friction():
    """A disc (J = 0.5 kg m^2) spinning about its centre on a revolute to the
    ground: the pin carries no load (no gravity, centre at rest), so only the
    preload T0 = 0.2 N m and the viscous c = 0.3 N m s act: J w' = -T0 - c w
    while w >> v_s, so w = (w0 + T0/c) e^(-c t / J) - T0/c. With w0 = 5 rad/s
    it stays above 2.8 rad/s over 1 s; the sign's regularization is off by
    v_s^2 / (2 w^2) < 1e-7 relative. Asserted to 1e-6 rad/s."""
    J, T0, c, w0 = 0.5, 0.2, 0.3, 5.0
    m = mb.Model()
    d = m.add_body("disc", mass=1.0, inertia=J, position=(0.0, 0.0), angular_velocity=w0)
    m.add_revolute("axle", m.ground, d, at=(0.0, 0.0))
    m.add_joint_friction("bearing", "axle", mu=0.5, pin_radius=0.01, preload=T0, viscous=c,
                         slip_velocity=V_S)
    r = mb.simulate(m, t_end=1.0, rtol=1e-10, atol=1e-12, n_out=101)
    w = (w0 + T0 / c) * np.exp(-c * r.t / J) - T0 / c
    assert np.abs(r.body("disc").angular_velocity - w).max() <= 1e-6


# --- derivatives ---------------------------------------------------------------

H = 1e-6


def fd(f, x, h=H):
    cols = []
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.array(cols).T


def close(a, b, rel=1e-6):
    scale = max(1.0, np.abs(b).max())
    assert np.abs(a - b).max() <= rel * scale, np.abs(a - b).max()


@pytest.fixture(scope="module")
def friction_state():
    """Both kinds between moving bodies (the translational's axis turns with
    body a), with every term on: Coulomb (with the bearing-length moment
    term), preload, viscous; at a random state off the constraint manifold,
    random multipliers, and slip rates comparable to v_s (where the
    regularized sign bends most)."""
    m = mb.Model(gravity=(0.0, -G))
    a = m.add_body("a", mass=1.0, inertia=0.1, position=(0.5, 0.1), angle=0.3)
    b = m.add_body("b", mass=2.0, inertia=0.2, position=(1.5, -0.2), angle=-0.4)
    c = m.add_body("c", mass=0.5, inertia=0.05, position=(0.8, 1.2), angle=1.1)
    m.add_revolute("rev", a, c, at=(0.6, 0.7))
    m.add_translational("slide", a, b, at=(1.2, 0.0), axis=(1.0, 0.2))
    m.add_joint_friction("rev_friction", "rev", mu=0.4, pin_radius=0.03, viscous=0.1, preload=0.05,
                         slip_velocity=0.5)
    m.add_joint_friction("slide_friction", "slide", mu=0.3, bearing_length=0.2, viscous=0.7,
                         preload=0.2, slip_velocity=0.5, load_smoothing=0.1)
    core = m.compiled()
    rng = np.random.default_rng(11)
    q0, _ = core.initial_state()
    q = q0 + 0.05 * rng.standard_normal(q0.size)
    v = 0.5 * rng.standard_normal(q0.size)
    lam = 3.0 * rng.standard_normal(core.n_constraints)
    return core, q, v, lam


def test_friction_force_derivatives(friction_state):
    """Q_f,q, Q_f,v and Q_f,lam (the Newton-matrix terms) against central
    differences of Q_f, to 1e-6 relative to the largest entry."""
    core, q, v, lam = friction_state
    Q, Qq, Qv, Ql = core.friction_forces(q, v, lam)
    assert np.abs(Q).max() > 0.1
    close(Qq, fd(lambda x: core.friction_forces(x, v, lam)[0], q))
    close(Qv, fd(lambda x: core.friction_forces(q, x, lam)[0], v))
    close(Ql, fd(lambda x: core.friction_forces(q, v, x)[0], lam))


def test_friction_lam_derivative_sits_in_the_joint_rows_of_phi_q_transpose(friction_state):
    """Each joint's friction reads only its own multipliers and acts only on
    its own bodies: the nonzeros of Q_f,lam lie in the joint's columns (rows
    of Phi) and its bodies' coordinates, which is where Phi_q^T has that
    joint's entries, so the Newton matrix holds -Q_f,lam in those slots."""
    core, q, v, lam = friction_state
    Ql = core.friction_forces(q, v, lam)[3]
    allowed = np.zeros_like(Ql, dtype=bool)
    for joint, bodies in (("rev", ("a", "c")), ("slide", ("a", "b"))):
        row0, rows = core.constraint_rows(joint)
        for body in bodies:
            first, count = core.body_coordinates(body)
            allowed[first:first + count, row0:row0 + rows] = True
    assert np.count_nonzero(Ql) > 0
    assert not np.any((Ql != 0.0) & ~allowed)


def test_friction_power_is_force_times_slip_and_dissipative(friction_state):
    """Q_f . v equals the sum of F sd over the elements (the generalized
    force is F ds/dq), and is <= 0."""
    core, q, v, lam = friction_state
    Q = core.friction_forces(q, v, lam)[0]
    total = sum(np.prod(core.friction(n, q[None], v[None], lam[None])[0])
                for n in ("rev_friction", "slide_friction"))
    assert abs(Q @ v - total) <= 1e-12 * max(1.0, abs(total))
    assert Q @ v <= 0.0


# --- scene files and errors ----------------------------------------------------------------

def test_friction_in_a_scene_file_gives_the_same_run(tmp_path):
    """save_scene writes the friction, load_scene reads it back: the run is
    bit-identical to the Python-built model's."""
    m = friction_pendulum(omega0=1.0)
    path = tmp_path / "friction.toml"
    mb.save_scene(m, path)
    text = path.read_text()
    assert 'type = "joint_friction"' in text
    scene = mb.load_scene(path)
    r1 = mb.simulate(m, t_end=0.5, rtol=1e-8, n_out=11)
    r2 = mb.simulate(scene.model, t_end=0.5, rtol=1e-8, n_out=11)
    assert np.array_equal(r1.q, r2.q)


def test_scene_friction_key_errors(tmp_path):
    """Unknown key and bad values in a joint_friction table name file, table and key."""
    base = builders.pendulum_scene(inertia=0.1) + """
[[forces]]
type = "joint_friction"
name = "f"
joint = "pin"
"""
    path = tmp_path / "bad.toml"
    path.write_text(base + "mu = 0.2\npin_radius = 0.01\nfriction = 3\n")
    with pytest.raises(mb.ModelError, match="friction"):
        mb.load_scene(path)
    path.write_text(base + "mu = -0.2\npin_radius = 0.01\n")
    with pytest.raises(mb.ModelError, match="mu"):
        mb.load_scene(path)
    path.write_text(base.replace('joint = "pin"', 'joint = "nope"') + "mu = 0.2\n")
    with pytest.raises(mb.ModelError, match="nope"):
        mb.load_scene(path)


def test_bad_input_is_a_clear_error():
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", mass=1.0, inertia=0.1, position=(0.5, 0.0))
    box = m.add_body("box", mass=1.0, inertia=0.1, position=(1.5, 0.0))
    cart = m.add_body("cart", mass=1.0, inertia=0.1, position=(3.0, 0.0))
    p = m.add_particle("p", mass=1.0, position=(2.0, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    m.add_weld("weld", rod, box)
    m.add_revolute("ppin", box, p, at=(2.0, 0.0))
    m.add_translational("slide", m.ground, cart, at=(3.0, 0.0), axis=(1.0, 0.0))
    with pytest.raises(ValueError, match="'nope' is not a joint of this model"):
        m.add_joint_friction("f1", "nope", mu=0.1, pin_radius=0.01)
    with pytest.raises(ValueError, match="'weld' is a weld, not a revolute or translational joint"):
        m.add_joint_friction("f2", "weld", mu=0.1)
    with pytest.raises(ValueError, match="'rod' is a body"):
        m.add_joint_friction("f3", "rod", mu=0.1)
    with pytest.raises(ValueError, match=r"mu must be finite and >= 0, got -0.1"):
        m.add_joint_friction("f4", "pin", mu=-0.1, pin_radius=0.01)
    with pytest.raises(ValueError, match="viscous must be finite and >= 0"):
        m.add_joint_friction("f5", "pin", viscous=-1.0)
    with pytest.raises(ValueError, match="needs the pin radius"):
        m.add_joint_friction("f6", "pin", mu=0.1)
    with pytest.raises(ValueError, match="pin_radius applies to revolute joints"):
        m.add_joint_friction("f7", "slide", mu=0.1, pin_radius=0.01)
    with pytest.raises(ValueError, match="bearing_length applies to translational"):
        m.add_joint_friction("f8", "pin", mu=0.1, pin_radius=0.01, bearing_length=0.1)
    with pytest.raises(ValueError, match="slip_velocity must be positive"):
        m.add_joint_friction("f9", "pin", mu=0.1, pin_radius=0.01, slip_velocity=0.0)
    with pytest.raises(ValueError, match="it has no angle"):
        m.add_joint_friction("f10", "ppin", mu=0.1, pin_radius=0.01)
    with pytest.raises(ValueError, match="mu must be a number"):
        m.add_joint_friction("f11", "pin", mu="lots", pin_radius=0.01)
    with pytest.raises(ValueError, match="duplicate name 'pin'"):
        m.add_joint_friction("pin", "pin", mu=0.1, pin_radius=0.01)
    m.add_joint_friction("ok", "pin", mu=0.1, pin_radius=0.01)
    r = mb.simulate(m, t_end=0.1, n_out=3)
    with pytest.raises(ValueError, match="not a joint friction"):
        r.friction("pin")
    assert m.compiled().element_kind("ok") == "revolute_friction"


def test_friction_that_locks_the_augmented_system_is_reported():
    """mu r_pin far above the rod's l / (1.5): the friction torque changes the
    pin reaction faster than the reaction changes the torque, so the
    fixed-point iteration of the augmented system diverges; simulate and
    solve_accelerations raise SimulationError saying so (the pendulum starts
    turning, so the friction is on at t = 0)."""
    m = friction_pendulum(mu=50.0, r_pin=1.0, omega0=1.0)
    with pytest.raises(mb.SimulationError, match="joint friction.*do not converge.*Reduce mu"):
        mb.simulate(m, t_end=0.1)
    q, v = m.compiled().initial_state()
    with pytest.raises(mb.SimulationError, match="joint friction"):
        mb.solve_accelerations(m, q, v)
