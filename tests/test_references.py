"""Self-checks of the independent references (no lagmb needed).

If one of these fails, the reference is wrong and every lagmb test built on
it is meaningless; they run in well under a second.
"""

import math

import numpy as np
import pytest

from references import (
    GROUND,
    Revolute,
    RodChain,
    augmented_solve,
    body_energy,
    circle_intersection,
    compound_pendulum_period,
    hermite_root,
    revolute_jacobian,
    revolute_residuals,
    revolute_velocity_residuals,
    rod_pin_force,
)

G = 9.81


def test_single_rod_chain_is_the_compound_pendulum():
    """N = 1: (m L^2/4 + m L^2/12) thetadd = -m g (L/2) cos(theta), so
    thetadd = -3 g cos(theta) / (2 L) for any thetadot.  Tolerance 1e-13 g."""
    chain = RodChain(1)
    for theta, thetadot in [(0.0, 0.0), (0.3, 1.7), (-1.2, -4.0), (2.0, 0.5)]:
        thdd = chain.accelerations([theta], [thetadot])[0]
        assert abs(thdd + 1.5 * G * math.cos(theta)) <= 1e-13 * G


@pytest.mark.parametrize("n", [2, 5])
def test_chain_reference_conserves_energy(n):
    """The chain equations come from a Lagrangian, so T + V is constant along
    the DOP853 solution; at rtol = atol = 1e-12 the drift over 1 s must stay
    below 1e-10 of m g L."""
    chain = RodChain(n)
    theta, thetadot = chain.solve(np.linspace(0.0, 1.0, 51))
    E = chain.energy(theta, thetadot)
    assert np.abs(E - E[0]).max() <= 1e-10 * chain.m * G * chain.L


@pytest.mark.parametrize("n", [1, 2, 5])
def test_chain_reference_matches_cartesian_augmented_system(n):
    """Two independent formulations of the same chain must give the same
    accelerations at any state: the minimal absolute-angle equations, and
    the body-coordinate augmented system M qdd + Phi_q^T lam = Q,
    Phi_q qdd = gamma (with Phi_q and gamma written out by hand for
    revolutes).  The Cartesian accelerations follow from the minimal ones by
    r_k'' = L sum_i c_ki (thetadd_i n_i - thetadot_i^2 e_i).
    Also checks the hand-written Phi_q against central differences (1e-8)
    and Phi = 0, Phi_q v = 0 at states built from angles (1e-13).
    Agreement of accelerations to 1e-12 relative to g."""
    chain = RodChain(n)
    joints = chain.joints()
    rng = np.random.default_rng(1234 + n)
    for _ in range(5):
        theta = rng.uniform(-3.0, 3.0, n)
        thetadot = rng.uniform(-4.0, 4.0, n)
        q, v = chain.cartesian_state(theta, thetadot)
        assert np.abs(revolute_residuals(q, joints)).max() <= 1e-13
        assert np.abs(revolute_velocity_residuals(q, v, joints)).max() <= 1e-13

        Jm = revolute_jacobian(q, joints, n)
        eps = 1e-7
        Jfd = np.column_stack([
            (revolute_residuals(q + eps * e, joints)[0]
             - revolute_residuals(q - eps * e, joints)[0]) / (2 * eps)
            for e in np.eye(3 * n)])
        assert np.abs(Jm - Jfd).max() <= 1e-8

        qdd, _ = augmented_solve(q, v, [chain.m] * n, [chain.inertia] * n, joints)
        thdd = chain.accelerations(theta, thetadot)
        e = np.stack([np.cos(theta), np.sin(theta)], axis=-1)
        nv = np.stack([-np.sin(theta), np.cos(theta)], axis=-1)
        rdd = chain.L * chain.c @ (thdd[:, None] * nv - (thetadot**2)[:, None] * e)
        qdd_min = np.column_stack([rdd, thdd]).ravel()
        assert np.abs(qdd - qdd_min).max() <= 1e-12 * G


def test_rod_pin_force_matches_multipliers():
    """The closed-form pin force of the rod released from horizontal equals
    -lam of the augmented system (force on the rod = -Phi_q^T lam, whose
    translational part is -lam for a ground pin) at states on the energy
    curve thetadot^2 = 3 g sin(theta)/L.  Also the two textbook values:
    m g/4 up at release, 5/2 m g up at the bottom.  Tolerance 1e-12 m g."""
    chain = RodChain(1)
    for theta in np.linspace(0.0, math.pi, 13):
        phidot = -math.sqrt(max(3.0 * G * math.sin(theta), 0.0))
        q, v = chain.cartesian_state([-theta], [phidot])
        _, lam = augmented_solve(q, v, [1.0], [1.0 / 12.0], chain.joints())
        assert np.abs(-lam - rod_pin_force(theta)).max() <= 1e-12 * G
    assert np.abs(rod_pin_force(0.0) - [0.0, G / 4]).max() <= 1e-12 * G
    assert np.abs(rod_pin_force(math.pi / 2) - [0.0, 2.5 * G]).max() <= 1e-12 * G


def test_period_formula_matches_direct_integration():
    """T = 4 sqrt(2L/(3g)) K(m = sin^2(pi/4)); the rod released horizontal
    reaches phi = -pi (phidot = 0) at T/2.  Integrate
    phidd = -3 g cos(phi)/(2L) with DOP853 at 1e-13 and locate phidot = 0
    with an event: relative agreement 1e-10.  Also the small-amplitude limit
    T -> 2 pi sqrt(2L/(3g)) (1e-6 at amplitude 1e-3)."""
    from scipy.integrate import solve_ivp

    T = compound_pendulum_period(math.pi / 2)

    def turn(t, y):
        return y[1]

    turn.terminal = True
    turn.direction = 1
    sol = solve_ivp(lambda t, y: [y[1], -1.5 * G * math.cos(y[0])], (0.0, 3.0),
                    [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13,
                    events=turn)
    t_half = sol.t_events[0][0]
    assert abs(t_half - T / 2) <= 1e-10 * T
    assert abs(sol.y_events[0][0][0] + math.pi) <= 1e-9

    T0 = 2 * math.pi * math.sqrt(2.0 / (3.0 * G))
    assert abs(compound_pendulum_period(1e-3) / T0 - 1.0) <= 1e-6


def test_hermite_root_locates_a_cosine_zero():
    """Cubic-Hermite root finder: zero of cos(t) at pi/2 on a 0.05 grid,
    error O(h^4) -> below 1e-7."""
    t = np.arange(0.0, 3.0, 0.05)
    assert abs(hermite_root(t, np.cos(t), -np.sin(t)) - math.pi / 2) <= 1e-7


def test_circle_intersection_and_body_energy():
    """Two-circle intersection lands on both circles (1e-14); body_energy of
    a body at rest at height y is m g y (1e-14)."""
    p = circle_intersection((0.5, 0.8), 3.5, (4.0, 0.0), 3.0, upper=True)
    assert abs(np.hypot(*(p - [0.5, 0.8])) - 3.5) <= 1e-14
    assert abs(np.hypot(*(p - [4.0, 0.0])) - 3.0) <= 1e-14
    E = body_energy([0.0, 2.0, 0.0], [0.0, 0.0, 0.0], [3.0], [1.0])
    assert abs(E[0] - 3.0 * G * 2.0) <= 1e-12
    # Ground on the j side of a revolute also works (used by the four-bar).
    jt = [Revolute(0, (0.5, 0.0), GROUND, (1.0, 0.0))]
    assert np.abs(revolute_residuals([0.5, 0.0, 0.0], jt)).max() <= 1e-15
