"""Static equilibrium (mb.equilibrium) and runs that start from it.

References: closed forms (a mass on a spring under gravity: deflection
m g / k), the transcendental balance of a pendulum on a torsional spring,
k (theta - theta0) + m g l cos(theta) = 0, solved with
scipy.optimize.brentq to 1e-15, and the stiffness of the reduced potential
V(theta) along the unit-speed path in q: V''(theta) / |dq/dtheta|^2.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import lagmb as mb
import builders

G, MASS, K = 9.81, 2.0, 400.0


def test_block_on_vertical_spring():
    """A block on a vertical guide resting on a spring of free length l0
    anchored at the ground: y = l0 - m g / k (1e-12), the guide carries no
    vertical force, and the equilibrium is stable with stiffness k / 1 (the
    guide leaves only y free: eigenvalue k)."""
    l0 = 0.5
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", MASS, 0.01, position=(0.0, l0))
    m.add_translational("guide", m.ground, block, at=(0.0, l0), axis=(0.0, 1.0))
    m.add_spring_damper("spring", m.ground, (0.0, 0.0), block, (0.0, l0), stiffness=K)
    eq = mb.equilibrium(m)
    assert eq.stable
    assert abs(eq.body("block").position[1] - (l0 - MASS * G / K)) < 1e-12
    assert abs(eq.body("block").position[0]) < 1e-12 and abs(eq.body("block").angle) < 1e-12
    np.testing.assert_allclose(eq.reaction("guide"), [0.0, 0.0, 0.0], atol=1e-10)
    np.testing.assert_allclose(eq.stiffness_eigenvalues, [K], rtol=1e-10)


def test_particle_hanging_on_spring():
    """A particle hanging from a spring (2 DOF): y = -(l0 + m g / k), x = 0;
    stable: vertical stiffness k, lateral T / L with T = m g, L = l0 + m g / k."""
    l0 = 1.0
    m = mb.Model(gravity=(0.0, -G))
    bob = m.add_particle("bob", MASS, position=(0.0, -l0))
    m.add_spring_damper("spring", m.ground, (0.0, 0.0), bob, (0.0, -l0), stiffness=K)
    eq = mb.equilibrium(m)
    L = l0 + MASS * G / K
    np.testing.assert_allclose(eq.q, [0.0, -L], rtol=0, atol=1e-12)
    np.testing.assert_allclose(eq.stiffness_eigenvalues, sorted([MASS * G / L, K]), rtol=1e-9)
    assert eq.stable and eq.lam.size == 0


def torsion_pendulum(k, theta0=0.0, start=0.0, L=1.0, mass=1.0):
    """A uniform rod (length L, pin at its end at the origin, centre at
    l = L/2) on a rotational spring to the ground (stiffness k, free angle
    theta0), released at angle `start`."""
    m = builders.pendulum(L=L, m=mass, g=G, angle=start)
    m.add_rotational_spring_damper("spring", m.ground, "rod", stiffness=k, free_angle=theta0)
    return m


def test_pendulum_on_torsional_spring():
    """k (theta - theta0) + m g l cos(theta) = 0 (brentq reference, 1e-10);
    the pin carries the weight (0, m g) and the torque -l m g cos(theta)
    about the centre; reduced stiffness (k - m g l sin theta) / (1 + l^2)."""
    k, theta0, mass, l = 20.0, 0.3, 1.0, 0.5
    ref = brentq(lambda th: k * (th - theta0) + mass * G * l * math.cos(th), -math.pi / 2, math.pi / 2,
                 xtol=1e-15)
    eq = mb.equilibrium(torsion_pendulum(k, theta0))
    th = eq.body("rod").angle
    assert abs(th - ref) < 1e-10
    np.testing.assert_allclose(eq.body("rod").position, [l * math.cos(ref), l * math.sin(ref)], atol=1e-10)
    F = eq.reaction("pin")
    np.testing.assert_allclose(F, [0.0, mass * G, -l * mass * G * math.cos(ref)], rtol=0, atol=1e-9)
    assert eq.stable
    np.testing.assert_allclose(eq.stiffness_eigenvalues, [(k - mass * G * l * math.sin(ref)) / (1 + l * l)],
                               rtol=1e-9)
    assert eq.iterations <= 20 and eq.force_residual < 1e-9


def test_inverted_pendulum_is_unstable():
    """A rod standing upright on its pin (no spring) is in equilibrium but
    unstable: EquilibriumError (a ValueError) saying so and naming the rod;
    with allow_unstable=True it is returned with stable == False and
    reduced stiffness -m g l / (1 + l^2)."""
    m = torsion_pendulum(0.0, start=math.pi / 2)
    with pytest.raises(mb.EquilibriumError, match="unstable") as info:
        mb.equilibrium(m)
    assert "'rod'" in str(info.value) and isinstance(info.value, ValueError)
    eq = mb.equilibrium(m, allow_unstable=True)
    assert not eq.stable
    np.testing.assert_allclose(eq.stiffness_eigenvalues, [-G * 0.5 / 1.25], rtol=1e-9)
    assert abs(eq.body("rod").angle - math.pi / 2) < 1e-12


def test_without_the_stability_check_the_same_rest_state_and_stability_unknown():
    """stability=False (for models too large for the dense check) finds the
    same upright rod to the bit, says nothing of its stability (stable is
    None, no eigenvalues) and so does not refuse it."""
    m = torsion_pendulum(0.0, start=math.pi / 2)
    checked = mb.equilibrium(m, allow_unstable=True)
    unchecked = mb.equilibrium(m, stability=False)
    assert np.array_equal(unchecked.q, checked.q) and np.array_equal(unchecked.lam, checked.lam)
    assert unchecked.stable is None and unchecked.stiffness_eigenvalues.size == 0
    assert "stability not checked" in repr(unchecked)


def test_the_options_are_checked_by_name():
    """A string for a flag was read by its truth ("False" is true) and the
    stability check skipped or an unstable rest state returned (issue 39)."""
    m = torsion_pendulum(0.0, start=math.pi / 2)
    for name in ("allow_unstable", "stability"):
        for bad in ("False", 0, None):
            with pytest.raises(mb.ModelError, match=f"equilibrium: {name} must be True or False, got {bad!r}"):
                mb.equilibrium(m, **{name: bad})
    for bad, said in ((float("nan"), "tol must be finite"), (1.0, r"tol must be in \(0, 1\)"),
                      (0, "max_iterations must be in 1..")):
        with pytest.raises(mb.ModelError, match=said):
            mb.equilibrium(m, **({"max_iterations": bad} if "iterations" in said else {"tol": bad}))


def test_the_rows_left_out_as_redundant_are_named():
    """A parallelogram of three equal cranks hanging from the ground and a
    bar joining their ends: the third crank repeats a constraint the other
    two already impose (one row is redundant; it is left out and its
    multiplier is 0). A single pendulum leaves out none."""
    m = mb.Model(gravity=(0.0, -G))
    bar = m.add_body("bar", 1.0, 1 / 12, position=(1.0, -1.0))
    for k, x in enumerate((0.0, 1.0, 2.0)):
        crank = m.add_body(f"crank{k}", 1.0, 1 / 12, position=(x, -0.5), angle=-math.pi / 2)
        m.add_revolute(f"ground{k}", m.ground, crank, at=(x, 0.0))
        m.add_revolute(f"end{k}", crank, bar, at=(x, -1.0))
    eq = mb.equilibrium(m)
    assert len(eq.dropped_rows) == 1
    assert np.all(eq.lam[eq.dropped_rows] == 0.0)
    assert mb.equilibrium(torsion_pendulum(1.0)).dropped_rows == []


def test_free_body_has_no_equilibrium():
    """A body with no joint under gravity: EquilibriumError naming the body
    and its y coordinate with the unbalanced weight -m g."""
    m = mb.Model(gravity=(0.0, -G))
    m.add_body("rock", MASS, 0.1, position=(0.0, 1.0))
    with pytest.raises(mb.EquilibriumError, match="no static equilibrium") as info:
        mb.equilibrium(m)
    assert "body 'rock' y" in str(info.value)
    assert f"{-MASS * G:g}" in str(info.value)


def test_overwhelming_torque_has_no_equilibrium():
    """A pinned rod with a constant torque 3 m g l: gravity can balance at
    most m g l, so there is none; the error names the rod."""
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", 1.0, 1 / 12, position=(0.5, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    m.add_torque("motor", rod, 3 * G * 0.5)
    with pytest.raises(mb.EquilibriumError, match="no static equilibrium") as info:
        mb.equilibrium(m, max_iterations=50)
    assert "body 'rod'" in str(info.value)


def test_run_started_in_equilibrium_stays_at_rest():
    """start="equilibrium": the torsion pendulum released there stays put:
    max |q - q_eq| < 1e-9 over 1 s (rtol 1e-10), and the first output is
    the equilibrium itself."""
    m = torsion_pendulum(20.0, 0.3)
    eq = mb.equilibrium(m)
    r = mb.simulate(m, t_end=1.0, n_out=51, rtol=1e-10, atol=1e-12, start="equilibrium")
    assert r.stats["analysis"] == "dynamic"
    assert np.max(np.abs(r.q - eq.q)) < 1e-9
    assert np.max(np.abs(r.v)) < 1e-8
    given = mb.simulate(m, t_end=1.0, n_out=51, rtol=1e-8)
    assert np.max(np.abs(given.q - eq.q)) > 1e-2  # released elsewhere, it swings


def test_scene_keys_round_trip(tmp_path):
    """[simulation] analysis and start are written and read back, and a bad
    value is a SceneError naming the key."""
    m = torsion_pendulum(20.0, 0.3)
    settings = {"t_end": 0.2, "n_out": 5, "analysis": "dynamic", "start": "equilibrium"}
    path = tmp_path / "pendulum.toml"
    mb.save_scene(m, str(path), settings=settings)
    scene = mb.load_scene(str(path))
    assert scene.settings["analysis"] == "dynamic" and scene.settings["start"] == "equilibrium"
    r = scene.run()
    eq = mb.equilibrium(m)
    assert np.max(np.abs(r.q - eq.q)) < 1e-6
    path.write_text(path.read_text().replace('analysis = "dynamic"', 'analysis = "statics"'))
    with pytest.raises(mb.SceneError, match="analysis"):
        mb.load_scene(str(path))
