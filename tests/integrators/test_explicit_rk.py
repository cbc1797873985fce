"""The explicit Runge-Kutta method (formulation "projection", integrator
"erk": ARKODE ERKStep, Prince-Dormand 8(7) by default) against independent
references: N-link chains against the minimal-coordinate SciPy solution
(references.RodChain, DOP853 at 1e-12), the four-bar loop against GGL at
tight tolerance (positions and reactions), a stop's impact against its
closed form. After every accepted step q and v are projected, so the
constraints hold to rounding; its counts show why it exists: a few
high-order steps where BDF takes many."""

import math

import numpy as np
import pytest
from scipy.special import ellipk

import lagmb as mb
from builders import rod_chain
from references import RodChain
from elements.test_fourbar import four_bar
from elements.test_stops import pendulum

ERK = dict(formulation="projection", integrator="erk")
T_OUT = [0.0, 0.25, 0.5, 0.75, 1.0]


def _wrap(a):
    return np.angle(np.exp(1j * np.asarray(a)))


@pytest.mark.parametrize("n", [8, 32])
def test_chain_matches_the_minimal_coordinate_reference(n):
    """Centres within 1e-7 m and angles within 1e-7 rad of the reference at
    five times over 1 s (rtol 1e-10); |Phi| stays at rounding level."""
    r = mb.simulate(rod_chain(n), t_out=T_OUT, rtol=1e-10, atol=1e-12, **ERK)
    ref = RodChain(n)
    theta, _ = ref.solve(T_OUT)
    for k, t in enumerate(T_OUT):
        centres = ref.centres(theta[k])
        q = r.q[k].reshape(n, 3)
        assert np.max(np.abs(q[:, :2] - centres)) <= 1e-7, t
        assert np.max(np.abs(_wrap(q[:, 2] - theta[k]))) <= 1e-7, t
    assert r.residual.max() <= 1e-12


def test_few_steps_where_bdf_takes_many():
    """On the 32-link chain over 1 s at rtol 1e-8 (counts, not times): ERK
    takes under a fifth of the steps of GGL (measured 82 against 780)."""
    m = rod_chain(32)
    erk = mb.simulate(m, t_end=1.0, rtol=1e-8, atol=1e-10, n_out=2, **ERK)
    ggl = mb.simulate(m, t_end=1.0, rtol=1e-8, atol=1e-10, n_out=2, formulation="ggl")
    assert erk.stats["steps"] * 5 < ggl.stats["steps"]
    assert erk.stats["projections"] >= erk.stats["steps"]


def test_four_bar_positions_and_reactions_agree_with_ggl():
    """The closed loop over 2 s: positions within 1e-7 (measured 1.2e-8, the
    size of either method's own error at rtol 1e-11) and the four joint
    reactions within 1e-6 of their largest magnitude of GGL's; the loop stays
    closed to rounding."""
    model = four_bar()
    opts = dict(t_end=2.0, n_out=21, rtol=1e-11, atol=1e-13)
    erk = mb.simulate(model, **opts, **ERK)
    ggl = mb.simulate(model, **opts)
    assert np.max(np.abs(erk.q - ggl.q)) <= 1e-7
    for joint in ("A", "B", "C", "D"):
        ref = ggl.reaction(joint)
        assert np.max(np.abs(erk.reaction(joint) - ref)) <= 1e-6 * np.max(np.abs(ref)), joint
    assert erk.residual.max() <= 1e-12


def test_stop_impact_at_the_closed_form_time():
    """A pendulum released horizontal reaches its stop at the quarter period
    sqrt(2 / (3 g)) K(1/2) with speed sqrt(3 g), and rebounds with e times it
    (1e-6 relative): events work with ERK too. ARKODE locates roots on its
    cubic interpolant, so the time is good to 1e-6 s here (measured 7.3e-8),
    not the 1e-8 s of the BDF methods."""
    e = 0.5
    r = mb.simulate(pendulum(e), t_end=0.9, rtol=1e-10, atol=1e-12, n_out=91, **ERK)
    t_star = math.sqrt(2.0 / (3.0 * 9.81)) * float(ellipk(0.5))
    w = math.sqrt(3.0 * 9.81)
    first = r.events[0]
    assert first["element"] == "stop" and first["kind"] == "impact"
    assert abs(first["t"] - t_star) <= 1e-6
    assert abs(first["speed_before"] + w) <= 1e-6 * w
    assert abs(first["speed_after"] - e * w) <= 1e-6 * w


def test_orders_without_a_table_are_refused():
    """ERKStep has tables of orders 2 to 6 and 8: max_order 7 (or 1, 9) is a
    ModelError naming the orders; a lower order runs."""
    m = rod_chain(2)
    for order in (1, 7, 9):
        with pytest.raises(mb.ModelError, match="orders 2, 3, 4, 5, 6 and 8|max_order"):
            mb.simulate(m, t_end=0.1, max_order=order, **ERK)
    # (two outputs: ERK steps to every output, 101 of them would set the steps)
    r4 = mb.simulate(m, t_end=0.1, max_order=4, rtol=1e-8, atol=1e-10, n_out=2, **ERK)
    r8 = mb.simulate(m, t_end=0.1, rtol=1e-8, atol=1e-10, n_out=2, **ERK)
    assert r4.stats["steps"] > r8.stats["steps"]


def test_the_schur_complement_is_analysed_once_and_its_factor_grows_linearly():
    """The right-hand sides solve M qdd + Phi_q^T lam = Q, Phi_q qdd = gamma
    through S = Phi_q M^-1 Phi_q^T: its pattern is analysed once per run,
    and the nonzeros of its Cholesky factor per link are the same for 100
    and 1,000 links (within 1 %): the solve is linear in the chain's length."""
    per_link = []
    for n in (100, 1000):
        r = mb.simulate(rod_chain(n), t_end=0.002, n_out=2, **ERK)
        assert r.stats["symbolic_analyses"] == 1
        assert r.stats["augmented_factorizations"] >= r.stats["residual_evals"] > 0
        per_link.append(r.stats["factor_nonzeros"] / n)
    assert per_link[0] > 0
    assert abs(per_link[1] - per_link[0]) <= 0.01 * per_link[0], per_link


def spinning_rod(rate=5.0, offset=0.5, mass=1.0, inertia=1.0 / 12.0):
    """A body turning freely about a pin at the origin, no gravity, no force:
    its centre `offset` from the pin, turning at `rate` for ever. Its
    accelerations depend on its angle alone (the pin's reaction is
    centripetal), so every Runge-Kutta stage integrates its angle exactly and
    the rest is a quadrature."""
    m = mb.Model(gravity=(0.0, 0.0))
    rod = m.add_body("rod", mass=mass, inertia=inertia, position=(offset, 0.0), angle=0.0,
                     velocity=(0.0, offset * rate), angular_velocity=rate)
    pin = m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m, rod, pin


def _kinetic_energy(r, body, mass, inertia):
    return 0.5 * mass * np.sum(r.body(body).velocity ** 2, axis=1) + 0.5 * inertia * r.body(body).angular_velocity ** 2


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_a_freely_spinning_rod_keeps_its_rate_and_energy(rtol):
    """A 1 m, 1 kg rod spinning at 5 rad/s about its end for 30 s (24 turns)
    with one output at the end, so the error estimate alone bounds the steps:
    the energy 4.1667 J and the rate within 10 rtol of exact (measured: 1.7e-9 and 4e-9 at rtol 1e-6, 2e-11 and 5e-11 at
    1e-10). Fehlberg 7(8), the former order-8 pair, estimated 0 for this
    quadrature: its steps grew to 18 s, its energy went 2.8 % off at any
    rtol and its projection failed at t = 25."""
    m, rod, _ = spinning_rod()
    r = mb.simulate(m, t_end=30.0, rtol=rtol, n_out=2, **ERK)
    energy = _kinetic_energy(r, rod, 1.0, 1.0 / 12.0)
    assert energy[0] == pytest.approx(25.0 / 6.0, rel=1e-15)
    assert abs(energy[-1] / energy[0] - 1.0) <= 10.0 * rtol
    assert abs(r.body(rod).angular_velocity[-1] - 5.0) <= 10.0 * rtol * 5.0
    assert r.stats["steps"] >= 100  # (24 turns: not a step of seconds)


def test_auto_takes_the_explicit_method_and_gets_the_spinning_rod_and_a_wheel_right():
    """The default method on the rod and on a wheel (radius 0.3 m, its centre
    0.1 m off its axle) over 30 s: energy within 1e-8 of the start at the
    default rtol 1e-6 (measured 1.6e-9 on the wheel; it lost 21 % before),
    and the same through one Simulator.advance."""
    for offset, inertia in [(0.5, 1.0 / 12.0), (0.1, 0.5 * 0.3 ** 2)]:
        m, rod, _ = spinning_rod(offset=offset, inertia=inertia)
        r = mb.simulate(m, t_end=30.0, n_out=2)
        assert r.stats["method"] == "projection-erk"
        energy = _kinetic_energy(r, rod, 1.0, inertia)
        assert abs(energy[-1] / energy[0] - 1.0) <= 1e-8
    m, rod, _ = spinning_rod()
    sim = mb.Simulator(m)
    sim.advance(30.0)
    assert sim.result().body(rod).angular_velocity[-1] == pytest.approx(5.0, rel=1e-7)


def test_a_stop_a_hundred_radians_away_is_struck_at_its_closed_form_time():
    """Turning at 5 rad/s, the rod reaches its upper limit of 100 rad at
    t = 20 s exactly and rebounds at -e times 5 rad/s (e = 0.5); struck at
    19.898 s under the former pair."""
    m, rod, pin = spinning_rod()
    m.add_stop("stop", pin, lower=-7.0, upper=100.0, restitution=0.5)
    r = mb.simulate(m, t_end=25.0)
    impact = r.events[0]
    assert impact["kind"] == "impact" and impact["label"] == "upper"
    assert impact["t"] == pytest.approx(20.0, abs=1e-6)
    assert r.body(rod).angular_velocity[-1] == pytest.approx(-2.5, rel=1e-6)
