"""A contact's restitution is its rebound: the damping of the contact law
(contact_law.hpp) is chosen so that an impact under the contact force alone
rebounds at exactly e times its speed.

References:
- the law alone, m d'' = -k d^1.5 (1 + c d'/v), d(0) = 0, d'(0) = v: with
  u = d / L, L = (m v^2 / k)^(2/5), and s = t v / L it is
  u'' = -u^1.5 (1 + c u'), u(0) = 0, u'(0) = 1, whose exit speed e(c) is
  one function of c; its phase plane separates into the closed form
  c (1 + e) = ln((1 + c) / (1 - c e)) (solved here with SciPy's brentq),
  checked against SciPy's solve_ivp (DOP853, rtol 1e-12) of the ODE;
- Flores et al. 2011's damping c = 8 (1 - e) / (5 e), lagmb's before issue
  56, rebounds at e(c) = 0.894, 0.7885, 0.470, 0.256 for e = 0.9, 0.8,
  0.5, 0.3 (the same ODE);
- a sphere hitting a plane and a disc hitting a line, without gravity,
  leave at e times the speed they came (1e-6);
- below 1e-3 m/s the damping is that of a 1e-3 m/s impact: an approach
  at v rebounds at e(c v / 1e-3).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import lagmb as mb

MIN_IMPACT_SPEED = 1e-3  # m/s (ContactLaw::kMinImpactSpeed)


def damping(e):
    """c with c (1 + e) = ln((1 + c) / (1 - c e)), c in (0, 1/e)."""
    if e == 1.0:
        return 0.0
    f = lambda c: math.log1p(c) - math.log1p(-c * e) - c * (1.0 + e)  # noqa: E731
    top = (1.0 - 1e-15) / e
    if f(top) <= 0.0:  # (small e: 1 - c e ~ (1 + c) exp(-(1 + c)) is below 1e-15)
        return top
    return brentq(f, 1e-3 * (1.0 - e), top, xtol=1e-300, rtol=1e-15)


def exit_speed(c, exponent=1.5):
    """The exit speed of u'' = -u^n (1 + c u') (the force 0 where it would
    pull), u(0) = 0, u'(0) = 1: SciPy DOP853 to the return of u to 0."""
    def f(s, y):
        force = y[0] ** exponent * (1.0 + c * y[1]) if y[0] > 0.0 else 0.0
        return [y[1], -max(force, 0.0)]

    def back(s, y):
        return y[0] if s > 1e-6 else 1.0
    back.terminal, back.direction = True, -1
    sol = solve_ivp(f, [0.0, 1e4], [0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-15, events=back)
    return -sol.y_events[0][0][1]


@pytest.mark.parametrize("e", [0.05, 0.3, 0.5, 0.8, 0.9, 0.99])
def test_the_damping_of_the_closed_form_rebounds_at_e(e):
    """The closed form's c, integrated (DOP853, rtol 1e-12): the exit speed
    is e to 1e-9, for the law's exponent 1.5 and for 1 (the closed form
    holds for any)."""
    c = damping(e)
    assert 0.0 < c < 1.0 / e
    assert abs(exit_speed(c) - e) <= 1e-9
    assert abs(exit_speed(c, exponent=1.0) - e) <= 1e-9


def test_flores_damping_rebounds_below_e():
    """Flores et al.'s c = 8 (1 - e) / (5 e) (lagmb's law before issue 56)
    rebounds at 0.8939, 0.7885, 0.4704, 0.2562 for e = 0.9, 0.8, 0.5, 0.3
    (the numbers the issue measured): more damping than the exact c."""
    for e, rebound in ((0.9, 0.89392069), (0.8, 0.78853913), (0.5, 0.47044478), (0.3, 0.25620791)):
        assert abs(exit_speed(8.0 * (1.0 - e) / (5.0 * e)) - rebound) <= 1e-8
        assert damping(e) < 8.0 * (1.0 - e) / (5.0 * e)


def _driven_into_floor(e, speed=0.1):
    """A disc (R = 0.1 m) whose height falls at `speed` from 0.01 m above
    the floor contact, its x and angle held."""
    m = mb.Model()
    b = m.add_body("ball", 1.0, 0.004, position=(0.0, 0.11))
    m.add_contact("floor", b, (0.0, 0.11), 0.1, m.ground, (0.0, 0.0), (1.0, 0.0), 1e6, e)
    m.drive_body("dx", b, "x", 0.0)
    m.drive_body("dphi", b, "angle", 0.0)
    m.drive_body("dy", b, "y", mb.Linear(-speed, start=0.11))
    return m


@pytest.mark.parametrize("e", [0.01, 0.3, 0.5, 0.8, 0.9, 0.999, 1.0])
def test_lagmb_damping_is_the_closed_forms(e):
    """Driven into the floor at its impact speed V, d' = V, so the driver
    holds F = k d^1.5 (1 + c): the c lagmb computed (model build, C++) is
    the closed form's to 1e-9 relative (2e-9 absolute: the force's 1e-9)."""
    r = mb.simulate(_driven_into_floor(e), t_end=0.15, n_out=16, rtol=1e-10, atol=1e-12)
    d = 0.1 - r.body("ball").position[:, 1]
    inside = d > 5e-4
    c = -r.effort("dy")[inside] / (1e6 * d[inside] ** 1.5) - 1.0
    assert np.count_nonzero(inside) >= 4
    np.testing.assert_allclose(c, damping(e), rtol=1e-9, atol=2e-9)


def sphere_at_plane(e, v, k=1e7, mass=1.0, R=0.1, gap=1e-3):
    m = mb.Model(gravity=(0.0, 0.0, 0.0), dimension=3)
    centre = (0.0, 0.0, R + gap)
    m.add_body("ball", mass=mass, inertia=(0.4 * mass * R * R,) * 3, position=centre, velocity=(0.0, 0.0, -v))
    floor = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), role="collision")
    ball = m.add_shape("ball", "sphere", (R,), centre, role="collision")
    m.add_contact("hit", ball, floor, stiffness=k, restitution=e)
    return m


def disc_at_line(e, v, k=1e7, mass=1.0, R=0.1, gap=1e-3):
    m = mb.Model(gravity=(0.0, 0.0))
    b = m.add_body("ball", mass=mass, inertia=0.5 * mass * R * R, position=(0.0, R + gap), velocity=(0.0, -v))
    m.add_contact("hit", b, (0.0, R + gap), R, m.ground, (0.0, 0.0), (1.0, 0.0), stiffness=k, restitution=e)
    return m


def rebound(build, e, v, **kwargs):
    """The run of a body launched at a surface at v without gravity: its
    speed after the contact over v, and the run."""
    m = build(e, v, **kwargs)
    # the contact lasts about (m / k)^0.4 v^-0.2 (Hertz), longer as e -> 0
    t_end = 1e-3 / v + 0.1
    r = mb.simulate(m, t_end, n_out=201, rtol=1e-11, atol=1e-14)
    return r.v[-1, 2 if build is sphere_at_plane else 1] / v, r


@pytest.mark.parametrize("build", [sphere_at_plane, disc_at_line])
@pytest.mark.parametrize("e", [0.3, 0.5, 0.8, 0.9, 1.0])
def test_a_body_rebounds_at_e_times_its_impact_speed(build, e):
    """A sphere at a plane (spatial) and a disc at a line (planar), no
    gravity: at 0.01, 1 and 10 m/s, and with 10 times the mass, each leaves
    at e times the speed it came, to 1e-6 (one contact: onset, release);
    its energy never rises (by 1e-8 of it: the integration's error, 6e-10
    where e = 1 at 10 m/s)."""
    for v, mass in ((0.01, 1.0), (1.0, 1.0), (10.0, 1.0), (1.0, 10.0)):
        ratio, r = rebound(build, e, v, mass=mass)
        assert [x["label"] for x in r.events] == ["onset", "release"]
        assert abs(ratio - e) <= 1e-6, (v, mass, ratio)
        energy = r.energy
        assert np.all(np.diff(energy) <= 1e-8 * energy[0])
        assert abs(energy[-1] - e * e * energy[0]) <= 2e-6 * energy[0]


def test_a_box_landing_flat_rebounds_at_e():
    """A 0.2 m cube (1 kg) landing flat at 1 m/s, no gravity or friction:
    its four lower corners touch at once and press alike (each a quarter
    of the mass), so it leaves at e times its speed (1e-6), without a turn."""
    a, e, v = 0.2, 0.5, 1.0
    m = mb.Model(gravity=(0.0, 0.0, 0.0), dimension=3)
    centre = (0.0, 0.0, a / 2 + 1e-3)
    m.add_body("box", mass=1.0, inertia=(a * a / 6,) * 3, position=centre, velocity=(0.0, 0.0, -v))
    floor = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), role="collision")
    box = m.add_shape("box", "box", (a, a, a), centre, role="collision")
    m.add_contact("floor", box, floor, stiffness=1e7, restitution=e)
    r = mb.simulate(m, 0.1, n_out=3, rtol=1e-11, atol=1e-14)
    assert [x["label"] for x in r.events].count("onset") == 4
    assert abs(r.body("box").velocity[-1, 2] / v - e) <= 1e-6
    assert np.abs(r.body("box").angular_velocity[-1]).max() <= 1e-9


@pytest.mark.parametrize("build", [sphere_at_plane, disc_at_line])
def test_a_small_restitution_is_exact_too(build):
    """e = 0.01 (practically no bounce; c = 1/e to 1e-16), 1e-3 and 1e-6:
    the rebound is e times the impact speed to 1e-6 of itself (the body
    creeps out, 9 s at e = 1e-6)."""
    for e in (0.01, 1e-3, 1e-6):
        r = mb.simulate(build(e, 1.0), 20.0, n_out=3, rtol=1e-11, atol=1e-14)
        assert [x["label"] for x in r.events] == ["onset", "release"]
        assert abs(r.v[-1, 2 if build is sphere_at_plane else 1] / e - 1.0) <= 1e-6


@pytest.mark.parametrize("build", [sphere_at_plane, disc_at_line])
def test_an_impact_slower_than_1_mm_per_s_is_damped_as_at_1_mm_per_s(build):
    """At 1e-4 m/s (below kMinImpactSpeed, 1e-3 m/s) the damping is c v /
    1e-3 in effect: the rebound ratio is the ODE's e(0.1 c) (1e-6), above e."""
    e, v = 0.5, 1e-4
    expected = exit_speed(damping(e) * v / MIN_IMPACT_SPEED)
    ratio, _ = rebound(build, e, v)
    assert expected > e + 0.1
    assert abs(ratio - expected) <= 1e-6


def test_restitution_zero_is_refused_with_what_gives_no_bounce():
    """e = 0 has no finite damping (c -> 1/e): a ModelError naming the
    contact and the value, and saying what gives practically no bounce;
    so does an e whose 1/e overflows (1e-310)."""
    for build in (sphere_at_plane, disc_at_line):
        with pytest.raises(mb.ModelError, match=r"'hit'.*restitution must be in \(0, 1\], got 0.*0\.01 rebounds at 1 %"):
            build(0.0, 1.0)
        with pytest.raises(mb.ModelError, match=r"'hit'.*restitution 1e-310 is too small.*0\.01 rebounds at 1 %"):
            build(1e-310, 1.0)
