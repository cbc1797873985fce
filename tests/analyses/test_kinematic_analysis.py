"""Kinematic analysis and inverse dynamics of fully driven mechanisms.

A model with 0 degrees of freedom (every motion prescribed by drivers) is
solved from its constraints alone: positions by Newton on Phi(q, t) = 0,
velocities from Phi_q v = -Phi_t, accelerations from Phi_q a = gamma and,
for inverse dynamics, the multipliers from M a + Phi_q^T lam = Q.

References: the closed-form slider-crank kinematics of test_drivers.py
(slider x = r cos th + sqrt(l^2 - r^2 sin^2 th) and its derivatives), the
motor torque from the power balance tau omega = d(KE)/dt + (gravity power)
evaluated on those closed forms, and the dynamic (DAE) run of the same model
at rtol 1e-10 (analysis="dynamic").
"""

import math

import numpy as np
import pytest

import lagmb as mb
from elements.test_drivers import (G, J_ROD, M_CRANK, M_ROD, M_SLIDER, OMEGA, THETA0,
                                   slider_crank, slider_crank_kinematics)

T_END, N_OUT = 0.5, 101


@pytest.fixture(scope="module")
def auto_run():
    return mb.simulate(slider_crank(), t_end=T_END, n_out=N_OUT)


@pytest.fixture(scope="module")
def dynamic_run():
    return mb.simulate(slider_crank(), t_end=T_END, n_out=N_OUT, rtol=1e-10, atol=1e-12,
                       analysis="dynamic")


def test_auto_picks_inverse_dynamics_without_integrating(auto_run, dynamic_run):
    """0 DOF and all masses > 0: "auto" runs the kinematic analysis with
    inverse dynamics; no DAE step is taken (steps == 0), every output took
    at least one Newton iteration, and the square Jacobian (the independent
    rows of Phi_q) was factorized fewer times than there were solves
    (reused); the augmented matrix only for the assembly at t0. The dynamic
    run did integrate."""
    s = auto_run.stats
    assert s["analysis"] == "inverse_dynamics"
    assert s["steps"] == 0
    assert s["kinematic_solves"] >= N_OUT
    assert s["newton_iterations"] >= N_OUT
    # the Jacobian's LU is made now and then and reused in between
    assert 1 <= s["lu_factorizations"] < s["kinematic_solves"]
    assert s["augmented_factorizations"] <= 5
    assert dynamic_run.stats["analysis"] == "dynamic" and dynamic_run.stats["steps"] > 0


def test_positions_closed_form_and_dynamic(auto_run, dynamic_run):
    """Slider x, rod angle, and their rates vs the closed form (1e-11 in
    positions, 1e-9 relative in rates); all coordinates vs the dynamic run
    at rtol 1e-10 to 1e-8."""
    r = auto_run
    ref = slider_crank_kinematics(THETA0 + OMEGA * r.t, OMEGA)
    x = r.body("slider").position[:, 0]
    np.testing.assert_allclose(x, ref["x"], rtol=0, atol=1e-11)
    np.testing.assert_allclose(r.body("rod").angle, ref["psi"], rtol=0, atol=1e-11)
    np.testing.assert_allclose(r.body("slider").velocity[:, 0], ref["xd"], rtol=0,
                               atol=1e-9 * np.max(np.abs(ref["xd"])))
    np.testing.assert_allclose(r.body("slider").acceleration[:, 0], ref["xdd"], rtol=0,
                               atol=1e-9 * np.max(np.abs(ref["xdd"])))
    np.testing.assert_allclose(r.body("rod").angular_acceleration, ref["psidd"], rtol=0,
                               atol=1e-9 * np.max(np.abs(ref["psidd"])))
    assert np.max(np.abs(r.q - dynamic_run.q)) < 1e-8
    assert np.max(r.residual) < 1e-12


def _motor_torque_reference(t):
    """tau omega = sum_i (m_i a_i . v_i + J_i alpha_i omega_i) + g sum_i m_i v_iy
    on the closed-form motion (the crank turns at constant omega and the
    slider does not turn: J_CRANK and J_SLIDER do no work)."""
    k = slider_crank_kinematics(THETA0 + OMEGA * t, OMEGA)
    power = (M_CRANK * np.sum(k["crank_a"] * k["crank_v"], axis=1)
             + M_ROD * np.sum(k["rod_a"] * k["rod_v"], axis=1) + J_ROD * k["psidd"] * k["psid"]
             + M_SLIDER * np.sum(k["slider_a"] * k["slider_v"], axis=1)
             + G * (M_CRANK * k["crank_v"][:, 1] + M_ROD * k["rod_v"][:, 1]))
    return power / OMEGA


def test_driver_torque_inverse_dynamics(auto_run, dynamic_run):
    """The motor torque from inverse dynamics agrees with the dynamic run to
    1e-6 of its peak and with the power balance on the closed form to 1e-9."""
    tau = auto_run.effort("motor")
    peak = np.max(np.abs(tau))
    assert np.max(np.abs(tau - dynamic_run.effort("motor"))) < 1e-6 * peak
    assert np.max(np.abs(tau - _motor_torque_reference(auto_run.t))) < 1e-9 * peak
    # equations of motion hold for the reported state: M a + Phi_q^T lam = Q
    for k in (0, 37, N_OUT - 1):
        a, lam = mb.solve_accelerations(slider_crank(), auto_run.q[k], auto_run.v[k], auto_run.t[k])
        np.testing.assert_allclose(auto_run.a[k], a, rtol=0, atol=1e-9 * np.max(np.abs(a)))
        np.testing.assert_allclose(auto_run.lam[k], lam, rtol=0, atol=1e-9 * np.max(np.abs(lam)))


def massless_slider_crank():
    """The slider-crank of test_drivers.py with every mass and inertia 0."""
    m = slider_crank()
    massless = mb.Model(gravity=m.gravity)
    for method, kw in m.elements:
        if method == "add_body":
            kw.update(mass=0.0, inertia=0.0)
        getattr(massless, method)(**kw)
    return massless


def test_massless_mechanism_kinematics_only():
    """All bodies massless: "auto" picks "kinematic"; q, v, a vs the closed
    form (1e-11 in positions, 1e-9 relative in rates); the multipliers were
    not computed, so r.lam, r.reaction and r.effort raise KinematicOnlyError
    saying the run was kinematic only."""
    r = mb.simulate(massless_slider_crank(), t_end=T_END, n_out=51)
    assert r.stats["analysis"] == "kinematic" and r.stats["steps"] == 0
    ref = slider_crank_kinematics(THETA0 + OMEGA * r.t, OMEGA)
    np.testing.assert_allclose(r.body("slider").position[:, 0], ref["x"], rtol=0, atol=1e-11)
    np.testing.assert_allclose(r.body("rod").angle, ref["psi"], rtol=0, atol=1e-11)
    np.testing.assert_allclose(r.body("rod").velocity, ref["rod_v"], rtol=0,
                               atol=1e-9 * np.max(np.abs(ref["rod_v"])))
    np.testing.assert_allclose(r.body("rod").acceleration, ref["rod_a"], rtol=0,
                               atol=1e-9 * np.max(np.abs(ref["rod_a"])))
    np.testing.assert_allclose(r.body("crank").acceleration, ref["crank_a"], rtol=0,
                               atol=1e-9 * np.max(np.abs(ref["crank_a"])))
    for ask in (lambda: r.lam, lambda: r.reaction("O"), lambda: r.effort("motor")):
        with pytest.raises(mb.KinematicOnlyError, match="kinematic"):
            ask()
    assert issubclass(mb.KinematicOnlyError, ValueError)


def test_kinematic_needs_zero_dof():
    """A pendulum (1 DOF) with analysis="kinematic" or "inverse_dynamics":
    ModelError naming the degree of freedom count; "auto" integrates it."""
    m = mb.Model(gravity=(0.0, -9.81))
    rod = m.add_body("rod", 1.0, 1 / 12, position=(0.5, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    for analysis in ("kinematic", "inverse_dynamics"):
        with pytest.raises(mb.ModelError, match=r"1 degree\(s\) of freedom"):
            mb.simulate(m, t_end=0.1, analysis=analysis)
    r = mb.simulate(m, t_end=0.1, n_out=3)
    assert r.stats["analysis"] == "dynamic" and r.stats["steps"] > 0
    with pytest.raises(mb.ModelError, match=r"unknown analysis 'static' \(the choices are auto, dynamic, "
                                            r"kinematic, inverse_dynamics\)"):
        mb.simulate(m, t_end=0.1, analysis="static")


def test_massless_body_refused_in_dynamic_run():
    """A massless body without inertia on a pin turns with nothing to
    follow it: a dynamic run (explicit, or "auto" at DOF > 0) raises
    ModelError naming the body and suggesting analysis="kinematic". A fully
    driven massless mechanism is determined by its drivers: a dynamic run
    (the augmented system's LU; before issue 41 refused) moves as the
    kinematic analysis does."""
    m = mb.Model(gravity=(0.0, -9.81))
    rod = m.add_body("ghost", 0.0, 0.0, position=(0.5, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    with pytest.raises(mb.ModelError, match="ghost") as info:
        mb.simulate(m, t_end=0.1)
    assert 'analysis="kinematic"' in str(info.value)
    dynamic = mb.simulate(massless_slider_crank(), t_end=0.1, n_out=11, analysis="dynamic", rtol=1e-10, atol=1e-12)
    kinematic = mb.simulate(massless_slider_crank(), t_end=0.1, n_out=11)
    np.testing.assert_allclose(dynamic.q, kinematic.q, rtol=0, atol=1e-8)
    with pytest.raises(mb.ModelError, match="mass must be positive"):
        m.add_body("negative", -1.0, 0.1)


def test_driver_through_toggle_stops_with_partial_result():
    """The slider of tests/hard/test_lockup.py pushed at 0.1 m/s into the
    toggle at t* = (r + l - sqrt(l^2 - r^2)) / 0.1: the kinematic analysis
    stops within 1e-6 s of t* (not later than rounding, 1e-9 s) with SimulationError naming the analysis,
    the singular Jacobian and the driver; the partial result holds the
    outputs before (slider exactly on its driver) and still no DAE step."""
    from hard.test_lockup import SPEED, T_TOGGLE, X0, slider_pushed_to_toggle

    with pytest.raises(mb.SimulationError) as info:
        mb.simulate(slider_pushed_to_toggle(), t_end=2.0, n_out=201)
    e = info.value
    assert T_TOGGLE - 1e-6 <= e.t <= T_TOGGLE + 1e-9
    msg = str(e)
    assert "kinematic analysis" in msg and "singular" in msg and "'push'" in msg
    p = e.result
    assert p.stats["steps"] == 0 and p.stats["analysis"] == "inverse_dynamics"
    assert T_TOGGLE - 0.01 <= p.t[-1] <= e.t
    np.testing.assert_allclose(p.body("slider").position[:, 0], X0 + SPEED * p.t, rtol=0, atol=1e-12)


def test_coarse_outputs_stay_on_branch():
    """Two outputs 1.6 crank turns (10 rad) apart: sub-steps of at most
    0.25 rad keep the mechanism on its assembly branch (slider to the right)
    and the rod angle continuous, matching the closed form."""
    r = mb.simulate(slider_crank(), t_out=[0.0, 1.0])
    ref = slider_crank_kinematics(THETA0 + OMEGA * r.t, OMEGA)
    np.testing.assert_allclose(r.body("slider").position[:, 0], ref["x"], rtol=0, atol=1e-11)
    np.testing.assert_allclose(r.body("rod").angle, ref["psi"], rtol=0, atol=1e-11)  # no 2 pi jump
    assert r.stats["kinematic_solves"] >= OMEGA * 1.0 / 0.25  # sub-steps of at most 0.25 rad of crank
    assert math.isclose(r.body("crank").angle[-1], THETA0 + OMEGA, abs_tol=1e-12)


def test_inverse_dynamics_with_joint_friction():
    """Coulomb friction in the crank-rod pin takes its load from the pin's
    own reaction, so the inverse-dynamic multipliers solve a fixed point.
    The motor torque must agree with the dynamic run of the same driven
    model (DAE with the friction in its residual, rtol 1e-10) to 1e-6 of its
    peak, differ from the frictionless torque (the friction is felt), and
    close the power balance on the closed-form motion with the friction law
    written out in the test to 1e-9 of its peak."""
    def model():
        m = slider_crank()
        m.add_joint_friction("B_friction", "B", mu=0.3, pin_radius=0.02)
        return m
    kin = mb.simulate(model(), t_end=T_END, n_out=N_OUT)
    dyn = mb.simulate(model(), t_end=T_END, n_out=N_OUT, rtol=1e-10, atol=1e-12, analysis="dynamic")
    assert kin.stats["analysis"] == "inverse_dynamics"
    tau, tau_dyn = kin.effort("motor"), dyn.effort("motor")
    peak = np.max(np.abs(tau))
    assert np.max(np.abs(tau - tau_dyn)) < 1e-6 * peak
    frictionless = mb.simulate(slider_crank(), t_end=T_END, n_out=N_OUT).effort("motor")
    assert np.max(np.abs(tau - frictionless)) > 1e-3 * peak
    # independent of lagmb's friction code: the power balance on the closed-form
    # motion, tau omega = (power without friction) - T_f (omega_rod - omega_crank),
    # with the law written out here, T_f = -mu r N sd / sqrt(sd^2 + v_s^2),
    # N = sqrt(|R_B|^2 + F_s^2) - F_s from the run's own pin reaction
    k = slider_crank_kinematics(THETA0 + OMEGA * kin.t, OMEGA)
    sd = k["psid"] - OMEGA
    load = np.sqrt(np.sum(kin.reaction("B")[:, :2] ** 2, axis=1) + 1e-12) - 1e-6
    friction_torque = -0.3 * 0.02 * load * sd / np.sqrt(sd**2 + 1e-6)
    balance = (_motor_torque_reference(kin.t) * OMEGA - friction_torque * sd) / OMEGA
    assert np.max(np.abs(tau - balance)) < 1e-9 * peak
