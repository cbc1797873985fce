"""Fuzzed stops: random mechanisms with joint limits obey the laws of stops.

Hypothesis draws mechanisms with stops (tests/fuzz/fuzz_stops.py: planar and
spatial pendulums, chains, sliders on inclined and vertical rails, a
four-bar; one or two stops per joint with random limits, restitution
0..0.95, dampers, drivers, torques from time functions and inputs that jump
in a Simulator; every formulation with events) and runs each in the
mechanism fuzzer's worker subprocess (tests/fuzz/fuzz_mechanisms.py), so that a
crash or a hang fails one example, not pytest. Every run either succeeds
and keeps the laws of fuzz_stops.stop_problems (no joint beyond its limit,
no energy gained, no impacts piled on the output times, a closed stop's
force pushing and an open one's 0, the result check of the mechanism fuzzer:
finite, joints held), or raises one of lagmb's exceptions (refusals are
counted by message and printed; most runs must succeed). A broken law is a
failure of its own kind (one exception class per law), so hypothesis
shrinks each to a minimal mechanism and reports them all.

- test_fuzz_stops_default: the default suite, a fixed seed, DEFAULT_EXAMPLES
  examples (about 10 s); it leaves out the features of fs.KNOWN_BUGS and
  counts (prints) the runs that break only the laws of fs.KNOWN_LAWS.
- test_fuzz_stops_long: @pytest.mark.fuzz, LAGMB_FUZZ_STOP_EXAMPLES (1000)
  examples from LAGMB_FUZZ_SEED; run with ``python3 -m pytest -m fuzz
  tests/fuzz/test_fuzz_stops.py`` or ``make test-fuzz``. LAGMB_FUZZ_STOPS_KNOWN=1
  draws the known bugs' features too and fails on every broken law (to
  see whether a fix holds).
- the findings, shrunk, as explicit tests: xfail(strict=True) while the core
  breaks them (they pass, and must then lose the mark, once it is fixed;
  then drop their entry from KNOWN_BUGS or KNOWN_LAWS).

The draws are deterministic for a seed as long as the same modules are
loaded (hypothesis mixes in constants of the loaded code); the laws must
hold for every draw, so the default run passes whatever it draws.
"""

import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fuzz_stops as fs  # noqa: E402
import laws  # noqa: E402  (the law fuzzers' runner)

DEFAULT_EXAMPLES = 300
DEFAULT_SEED = 41
TIMEOUT = 30.0  # s per op: a healthy run takes well under 1 s


def _check(n, rng_seed):
    known_bugs = bool(os.environ.get("LAGMB_FUZZ_STOPS_KNOWN"))
    laws.check(fs.stop_cases(known_bugs=known_bugs), n, rng_seed, TIMEOUT, fs, known_bugs, "runs with stops")


def test_fuzz_stops_default():
    """DEFAULT_EXAMPLES random mechanisms with stops (seed DEFAULT_SEED), in the default suite."""
    _check(DEFAULT_EXAMPLES, DEFAULT_SEED)


@pytest.mark.fuzz
def test_fuzz_stops_long(request):
    """LAGMB_FUZZ_STOP_EXAMPLES (1000) random mechanisms with stops, selected with -m fuzz."""
    if "fuzz" not in (request.config.getoption("markexpr", "") or ""):
        pytest.skip("long fuzz run: select it with -m fuzz")
    _check(int(os.environ.get("LAGMB_FUZZ_STOP_EXAMPLES", "1000")), int(os.environ.get("LAGMB_FUZZ_SEED", "20240611")))


# --- the findings, shrunk (the core breaks them today; see fuzz_stops.KNOWN_BUGS) ---

import math  # noqa: E402

import numpy as np  # noqa: E402

import lagmb as mb  # noqa: E402

G = 9.81


def _drop(e, h=0.3):
    """A 2 kg block on a vertical rail, its floor stop h below (restitution e)."""
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", mass=2.0, inertia=0.1, position=(0.0, 0.0))
    m.add_translational("rail", m.ground, block, at=(0.0, 0.0), axis=(0.0, 1.0))
    m.add_stop("floor", "rail", lower=-h, restitution=e)
    return m


def _known(reason):
    return pytest.mark.xfail(strict=True, reason=reason)


@pytest.mark.parametrize("formulation, options", [
    ("ggl", {}), ("index1", {}),
    ("projection", {"integrator": "erk"}), ("auto", {}),
    ("index3", {}), ("projection", {}),
])
def test_a_pressed_bounce_series_is_captured(formulation, options):
    """The block falls h = 0.3 m onto its stop (e = 0.3): it hits at
    t0 = sqrt(2 h / g) and the bounces, e^k shorter each, end at
    T = t0 (1 + e) / (1 - e) = 0.459 s; there it is captured (one capture,
    a dozen impacts: e^12 < 1e-6) and rests on the limit (1e-8 m) with the
    stop carrying m g. Found by the fuzzer on a spatial pendulum: index3
    and projection (BDF) log 7,000-15,000 impacts in 0.7 s (30,000-80,000 in
    1.5 s) and sink 1e-4 m through the stop."""
    e, h = 0.3, 0.3
    t0 = math.sqrt(2.0 * h / G)
    T = t0 * (1.0 + e) / (1.0 - e)
    r = mb.simulate(_drop(e, h), t_end=0.7, n_out=71, rtol=1e-8, atol=1e-10, formulation=formulation,
                    max_steps=20000, **options)
    assert r.stats["impacts"] <= 30
    assert r.stats["captures"] == 1 and abs(r.events[-1]["t"] - T) <= 1e-4
    slide = r.joint("rail").slide
    assert np.min(slide) >= -h - 1e-8
    resting = r.t > T + 1e-3
    assert np.max(np.abs(r.effort("floor")[resting] - 2.0 * G)) <= 1e-6 * 2.0 * G


@pytest.mark.parametrize("formulation, options", [
    ("ggl", {}), ("index1", {}), ("index3", {}), ("projection", {}), ("projection", {"integrator": "adams"}),
    ("projection", {"integrator": "erk"}), ("auto", {}),
])
def test_a_rod_between_close_limits_comes_to_rest_on_the_lower(formulation, options):
    """A uniform rod (m = 1, L = 1) pinned at one end, at a0 = pi/8 above
    level and turning up at 2 rad/s between limits a0 - 0.1 and a0 + 0.05
    (e = 0.1): it strikes the upper limit, falls onto the lower and is
    captured there (gravity presses it on); it rests on the limit (1e-8 rad)
    with the stop's torque the static m g (L/2) cos(a0 - 0.1) (1e-6), never
    beyond a limit, never gaining energy. Found by the fuzzer: the explicit
    run logged an impact at every output time and sank 0.8 rad through;
    then it was found 1.2e-4 rad beyond at one output (the projection onto
    the joint put the rebounding rod just beyond its limit, so its next
    crossing in the first step showed no sign change)."""
    a0 = math.pi / 8
    lower = a0 - 0.1
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5 * math.cos(a0), 0.5 * math.sin(a0)),
                     angle=a0, velocity=(-math.sin(a0), math.cos(a0)), angular_velocity=2.0)
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    m.add_stop("stop", "pin", lower=lower, upper=a0 + 0.05, restitution=0.1)
    r = mb.simulate(m, t_end=3.0, n_out=61, rtol=1e-8, atol=1e-10, formulation=formulation, max_steps=20000,
                    **options)
    angle = r.joint("pin").angle
    assert np.min(angle) >= lower - 1e-8 and np.max(angle) <= a0 + 0.05 + 1e-8
    assert r.stats["captures"] == 1 and r.stats["releases"] == 0 and r.stats["impacts"] <= 20
    resting = r.t > r.events[-1]["t"]
    assert np.max(np.abs(angle[resting] - lower)) <= 1e-8
    static = G * 0.5 * math.cos(lower)
    assert np.max(np.abs(r.effort("stop")[resting] - static)) <= 1e-6 * static
    assert np.max(np.diff(r.energy)) <= 1e-6 * G


@pytest.mark.parametrize("amplitude", [20.0, 10.0])
def test_a_short_release_is_not_stepped_over(amplitude):
    """A rod (m = 2, L = 1) rests on its upper stop at pi - 0.1 (pointing
    left, gravity pressing it on with m g (L/2) cos(0.1) = 9.76 N m); a
    torque A sin(4 t) lifts it off where A sin(4 t) = -9.76 N m, at
    t = (pi + asin(9.76 / A)) / 4 (1e-6 s): A = 20 after 0.91 s; A = 10
    after 1.12 s, for 0.11 s only. Until then the stop pushes (its effort
    <= 0 along the upper gap). Found by the fuzzer (a harmonic torque): the
    0.11 s release fell inside one step at rest, where the force is read at
    the steps' ends only; a closed row's force is now looked at inside a
    step where a parabola through its ends and middle comes near 0."""
    a = math.pi - 0.1
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", mass=2.0, inertia=2.0 / 12.0, position=(0.5 * math.cos(a), 0.5 * math.sin(a)), angle=a)
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    m.add_stop("stop", "pin", upper=a)
    m.add_torque("shake", rod, mb.Harmonic(amplitude, 4.0))
    r = mb.simulate(m, t_end=2.0, n_out=201, rtol=1e-8, atol=1e-10, formulation="ggl")
    pressed = 2.0 * G * 0.5 * math.cos(0.1)
    t_release = (math.pi + math.asin(pressed / amplitude)) / 4.0
    assert np.max(r.effort("stop")) <= 1e-6 * pressed
    releases = [x["t"] for x in r.events if x["kind"] == "release"]
    assert releases and abs(releases[0] - t_release) <= 1e-6


@pytest.mark.parametrize("formulation, options", [
    ("ggl", {}), ("index1", {}), ("index3", {}), ("projection", {}),
    ("projection", {"integrator": "erk"}), ("projection", {"integrator": "adams"}),
])
def test_a_release_after_a_long_rest_is_found(formulation, options):
    """A spatial pendulum (m = 0.5 kg, its centre a = 0.177 m out along x
    and down along z) on a revolute about y rests on its upper stop at
    0.05 rad, gravity pressing it on with m g a (cos 0.05 - sin 0.05) =
    0.823 N m; a torque sin(4 t) about y lifts it off at
    t = (pi + asin(0.823)) / 4 = 1.027 s (1e-8 s). Found by the fuzzer: at
    rest nothing bounds the step, one step spanned 0.83 s to 1.5 s and
    the 0.3 s in which the stop would have pulled went unseen (the force
    was read at the steps' ends; the stop held it on its limit until the
    end, pulling 0.17 N m)."""
    a = 0.176777
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    bob = m.add_body("bob", mass=0.5, inertia=(0.0104167,) * 3, position=(a, 0.0, -a))
    m.add_revolute("pin", m.ground, bob, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    m.add_stop("stop", "pin", lower=-0.05, upper=0.05, restitution=0.0)
    m.add_torque("shake", bob, (0.0, mb.Harmonic(1.0, 4.0), 0.0))
    r = mb.simulate(m, t_end=1.5, n_out=151, rtol=1e-8, atol=1e-10, formulation=formulation, **options)
    pressed = 0.5 * G * a * (math.cos(0.05) - math.sin(0.05))
    t_release = (math.pi + math.asin(pressed)) / 4.0
    assert [x["kind"] for x in r.events][:3] == ["impact", "capture", "release"]
    assert abs(r.events[2]["t"] - t_release) <= 1e-8
    closed = (r.t > r.events[1]["t"]) & (r.t < t_release)
    assert np.max(r.effort("stop")[closed]) <= 1e-6 * pressed  # it pushes (along -angle at an upper stop)
    assert np.max(r.joint("pin").angle) <= 0.05 + 1e-8


@pytest.mark.parametrize("formulation, options", [
    ("projection", {"integrator": "adams"}), ("projection", {}), ("ggl", {}), ("projection", {"integrator": "erk"}),
    ("index3", {}),
])
def test_a_release_soon_after_a_capture_is_found(formulation, options):
    """A level rod (m = 1, L = 1) falls 0.05 rad onto its lower stop and is
    captured at 0.088 s; gravity presses it on with m g (L/2) cos(0.05) =
    4.899 N m, and a torque 5 sin(4 t) lifts it off at
    t = asin(4.899 / 5) / 4 = 0.342 s (1e-8 s). Found by the fuzzer: at rest
    CVODE's second step after the capture reached the end of the run
    (0.16 s to 3 s, 40 times the first, before the force's history bounded
    it), and the release waited for the next one at 1.9 s; while a closed
    stop's force moves, a step is now at most 4 times the last."""
    m = mb.Model(gravity=(0.0, -G))
    rod = m.add_body("rod", mass=1.0, inertia=0.0833333, position=(0.5, 0.0))  # (as drawn: its steps)
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    m.add_stop("stop", "pin", lower=-0.05)
    m.add_torque("shake", rod, mb.Harmonic(5.0, 4.0))
    r = mb.simulate(m, t_end=3.0, n_out=151, rtol=1e-8, atol=1e-10, formulation=formulation, **options)
    t_release = math.asin(G * 0.5 * math.cos(0.05) / 5.0) / 4.0
    assert [x["kind"] for x in r.events][:3] == ["impact", "capture", "release"]
    assert abs(r.events[2]["t"] - t_release) <= 1e-8


@pytest.mark.parametrize("formulation, options", [
    ("ggl", {}), ("projection", {}), ("projection", {"integrator": "adams"}), ("projection", {"integrator": "erk"}),
])
def test_a_release_just_after_a_simulators_target_is_found(formulation, options):
    """A level rod (m = 1, L = 1) on its lower stop at 0, gravity pressing
    it on with 4.905 N m; a torque 5 sin(4 t) lifts it off at
    t = asin(4.905 / 5) / 4 = 0.344 s (1e-8 s), for 0.1 s. A Simulator
    advanced to 0.3 s, then 0.6 s: the same events and outputs as one run
    to 0.6 s. Found by the fuzzer: the release was found inside the step
    that passed 0.3 s, beyond the target, and dropped (the next advance
    went on from the step's end): the stop pulled 0.09 N m until the end."""
    def model():
        m = mb.Model(gravity=(0.0, -G))
        rod = m.add_body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0))
        m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
        m.add_stop("stop", "pin", lower=0.0, restitution=0.0)
        m.add_torque("shake", rod, mb.Harmonic(5.0, 4.0))
        return m

    sim = mb.Simulator(model(), rtol=1e-8, atol=1e-10, formulation=formulation, output_interval=0.01, **options)
    sim.advance(0.3)
    sim.advance(0.6)
    r = sim.result()
    whole = mb.simulate(model(), t_end=0.6, n_out=61, rtol=1e-8, atol=1e-10, formulation=formulation, **options)
    assert [x["kind"] for x in r.events] == [x["kind"] for x in whole.events]
    releases = [x["t"] for x in r.events if x["kind"] == "release"]
    assert len(releases) == 1 and abs(releases[0] - math.asin(G * 0.5 / 5.0) / 4.0) <= 1e-8
    assert np.min(r.effort("stop")) >= -1e-6 * G * 0.5  # it pushes (along +angle at a lower stop)
    assert np.allclose(r.t, whole.t, rtol=0.0, atol=1e-12)
    assert np.max(np.abs(r.joint("pin").angle - whole.joint("pin").angle)) <= 1e-6


@pytest.mark.parametrize("formulation, options", [
    ("projection", {"integrator": "adams"}), ("projection", {}), ("ggl", {}),
])
def test_a_simulators_long_steps_at_rest_do_not_step_over_a_release(formulation, options):
    """A rod on its lower stop at 0.589 rad, gravity pressing it on and a
    torque 5 sin(4 t) lifting it off, released, landing at 0.92 s and
    released again at 1.81 s: a Simulator advanced to 0.9, 1.5 and 2.1 s
    logs the events of one run to 2.1 s. Found by the fuzzer: the
    Simulator's steps pass its targets, and at rest one CVODE step ran
    from 1.47 s to 3.12 s (4 times the one before, the force's cubic term
    over the last steps looking small) over the release; a step now ends
    at most where the parabola through the force, carried on, reaches 0."""
    def model():
        m = mb.Model(gravity=(0.0, -G))
        a = 0.589049
        rod = m.add_body("rod", mass=1.0, inertia=0.0833333, position=(0.5 * math.cos(a), 0.5 * math.sin(a)), angle=a)
        m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
        m.add_stop("stop", "pin", lower=a)
        m.add_torque("shake", rod, mb.Harmonic(5.0, 4.0))
        return m

    sim = mb.Simulator(model(), rtol=1e-8, atol=1e-10, formulation=formulation, output_interval=0.01, **options)
    for t in (0.9, 1.5, 2.1):
        sim.advance(t)
    chunks = sim.result()
    whole = mb.simulate(model(), t_end=2.1, n_out=211, rtol=1e-8, atol=1e-10, formulation=formulation, **options)
    assert [x["kind"] for x in chunks.events] == [x["kind"] for x in whole.events]
    assert [x["kind"] for x in whole.events][-1] == "release"
    assert max(abs(x["t"] - y["t"]) for x, y in zip(chunks.events, whole.events)) <= 1e-8


def test_a_drivers_jump_keeps_the_other_joints_within_their_limits():
    """A level two-rod arm: the shoulder driven by an input, the elbow with
    an upper stop at 0 where it starts (gravity folds it down, away from
    the stop). The input jumps to -0.6 rad (at t0 and after 0.1 s): the
    shoulder turns down at once, and the elbow must stay at or below 0 (the
    forearm turned with the upper arm, or an impact), never beyond its
    limit (1e-8 rad). Found by the fuzzer (a driver's input in a Simulator)."""
    for first in (0.0, 0.1):
        m = mb.Model(gravity=(0.0, -G))
        upper = m.add_body("upper", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0))
        fore = m.add_body("fore", mass=1.0, inertia=1.0 / 12.0, position=(1.5, 0.0))
        m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
        m.add_revolute("elbow", upper, fore, at=(1.0, 0.0))
        m.add_stop("stop", "elbow", upper=0.0)
        m.drive_joint("motor", "shoulder", mb.Input(0.0))
        sim = mb.Simulator(m, rtol=1e-8, atol=1e-10, formulation="ggl", output_interval=0.01)
        if first:
            sim.advance(first)
        sim.set_input("motor", -0.6)
        sim.advance(first + 0.2)
        assert np.max(sim.result().joint("elbow").angle) <= 1e-8


def test_a_drivers_jump_does_not_push_a_joint_through_its_stop():
    """A level chain of three rods, the shoulder driven by an input, stops
    on the elbow (upper 0.05 rad) and the wrist (upper 0.15 rad, e = 0.05),
    which the wrist strikes twice while the chain falls. The input jumps to
    -0.3 rad at 0.15 s: the positions are projected onto the new driver's
    value, which turns the elbow beyond its limit; held on it, the
    projection turned the wrist 0.65 rad beyond its own. Both must stay
    within their limits (1e-8 rad) at every output. Found by the fuzzer (a
    driver's input in a Simulator): the projection now holds every stop it
    puts beyond its limit, and projects again."""
    m = mb.Model(gravity=(0.0, -G))
    parent = m.ground
    for i in range(3):
        rod = m.add_body(f"rod{i}", mass=1.0, inertia=1.0 / 12.0, position=(i + 0.5, 0.0))
        m.add_revolute(f"j{i}", parent, rod, at=(float(i), 0.0))
        parent = rod
    m.add_stop("wrist_stop", "j2", upper=0.15, restitution=0.05)
    m.add_stop("elbow_stop", "j1", upper=0.05)
    m.drive_joint("motor", "j0", mb.Input(0.0))
    sim = mb.Simulator(m, rtol=1e-8, atol=1e-10, formulation="ggl", output_interval=0.01)
    sim.advance(0.15)
    sim.set_input("motor", -0.3)
    sim.advance(0.45)
    r = sim.result()
    assert np.max(r.joint("j1").angle) <= 0.05 + 1e-8
    assert np.max(r.joint("j2").angle) <= 0.15 + 1e-8
    assert np.allclose(r.joint("j0").angle[r.t > 0.15], -0.3, rtol=0.0, atol=1e-8)


@pytest.mark.parametrize("formulation", ["index3", "ggl", "index1", "projection"])
def test_a_released_elbow_leaves_its_stop_without_a_chatter(formulation):
    """A level double pendulum in space (rods of 1 m, 1 kg, revolutes
    about y), its elbow with a lower stop at -0.05 rad: the elbow strikes
    it (plastic, captured) while the arm falls, and the swing releases it.
    After the release the elbow leaves at rest; the run logs a handful of
    events. Found by the fuzzer: under index 3 the release was followed by
    500 impacts within 2e-4 s at speeds of 1e-8 rad/s (its velocities
    after a first step of 1e-9 s come from positions: their error is
    1e-16 / h), each restarting at such a step; a row left open at rest now
    reads as inside until a step ends off the limit, and crosses at -1e-10."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    upper = m.add_body("upper", mass=1.0, inertia=(1.0 / 12.0,) * 3, position=(0.5, 0.0, 0.0))
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    fore = m.add_body("fore", mass=1.0, inertia=(1.0 / 12.0,) * 3, position=(1.5, 0.0, 0.0))
    m.add_revolute("elbow", upper, fore, at=(1.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    m.add_stop("stop", "elbow", lower=-0.05)
    r = mb.simulate(m, t_end=1.5, n_out=151, rtol=1e-8, atol=1e-10, formulation=formulation)
    kinds = [x["kind"] for x in r.events]
    assert kinds[:3] == ["impact", "capture", "release"] and len(kinds) <= 10
    assert np.min(r.joint("elbow").angle) >= -0.05 - 1e-8


@pytest.mark.parametrize("formulation", ["ggl", "index3", "index1", "projection"])
def test_a_block_pressed_from_rest_is_captured_not_bounced(formulation):
    """A block (2 kg) on a level rail in space, starting on its upper stop
    (e = 0.2), a bob (1 kg, centre 0.5 m out, I = 0.1 kg m^2) hinged to it
    and released level: while the bob swings down its pull presses the
    block on the stop, from 0 at the start (the hinge force is vertical
    there); when the bob hangs straight down the pull turns and the stop
    lets go, at t = int_0^(pi/2) dtheta / sqrt(2 m g c sin(theta) / I_O)
    (the block held: a compound pendulum). One impact (at the speed that
    reads as at rest), a capture, a release at that time (1e-8 s; index 3,
    whose event times are O(tol / h) only, 1e-6 s). Found
    by the fuzzer: 452 impacts at 1e-9 m/s, each rebounding at 2e-10 m/s
    (e times it) and returning at once; a rebound slower than at rest
    reads is now captured."""
    from scipy.integrate import quad

    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    block = m.add_body("block", mass=2.0, inertia=(0.1, 0.1, 0.1), position=(0.0, 0.0, 0.0))
    m.add_translational("rail", m.ground, block, at=(0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0))
    bob = m.add_body("bob", mass=1.0, inertia=(0.01, 0.1, 0.1), position=(0.5, 0.0, 0.0))
    m.add_revolute("hinge", block, bob, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    m.add_stop("stop", "rail", upper=0.0, restitution=0.2)
    r = mb.simulate(m, t_end=0.6, n_out=61, rtol=1e-10, atol=1e-12, formulation=formulation)
    I_O, c = 0.1 + 0.5 ** 2, 0.5
    t_release = quad(lambda th: 1.0 / math.sqrt(2.0 * G * c * math.sin(th) / I_O), 0.0, math.pi / 2.0)[0]
    assert [x["kind"] for x in r.events] == ["impact", "capture", "release"]
    assert abs(r.events[0]["speed_before"]) <= 1e-8
    assert abs(r.events[2]["t"] - t_release) <= (1e-6 if formulation == "index3" else 1e-8)
    assert np.max(r.joint("rail").slide) <= 1e-8


@pytest.mark.parametrize("formulation, options", [
    ("projection", {"integrator": "adams"}), ("projection", {}), ("projection", {"integrator": "erk"}), ("ggl", {}),
])
def test_a_long_step_strikes_the_limit_it_grazes_before_the_one_it_reaches(formulation, options):
    """A block on a vertical rail between stops at 0 and 0.05 m (e = 0),
    thrown up from the lower at 1 m/s: it would rise 0.051 m, so it
    strikes the upper at t1 = (1 - sqrt(1 - 2 g 0.05)) / g and, stopped
    there, falls onto the lower at t1 + sqrt(2 0.05 / g) (1e-8 s). Found by
    the fuzzer: Adams integrates the parabola exactly in one step of 0.17 s
    that ends at the lower stop's root; the upper one, crossed and left
    within it, was looked for only in steps without a root (0.95 mm
    beyond)."""
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", mass=2.0, inertia=0.1, position=(0.0, 0.0), velocity=(0.0, 1.0))
    m.add_translational("rail", m.ground, block, at=(0.0, 0.0), axis=(0.0, 1.0))
    m.add_stop("stop", "rail", lower=0.0, upper=0.05)
    r = mb.simulate(m, t_end=0.5, n_out=51, rtol=1e-8, atol=1e-10, formulation=formulation, **options)
    t_upper = (1.0 - math.sqrt(1.0 - 2.0 * G * 0.05)) / G
    t_lower = t_upper + math.sqrt(2.0 * 0.05 / G)
    impacts = [(x["label"], x["t"]) for x in r.events if x["kind"] == "impact"]
    assert [label for label, _ in impacts] == ["upper", "lower"]
    assert abs(impacts[0][1] - t_upper) <= 1e-8 and abs(impacts[1][1] - t_lower) <= 1e-8
    assert np.max(r.joint("rail").slide) <= 0.05 + 1e-8


@pytest.mark.parametrize("formulation", ["index3", "ggl", "projection"])
def test_two_stops_on_one_limit_let_go_without_a_chatter(formulation):
    """A level chain of three rods thrown down, two stops with the same
    lower limit (-1.2 rad) on its shoulder: both are struck at once (one
    closes, its twin rests open on the limit: they depend on each other)
    and the swing back releases the closed one. Its twin, at rest on the
    limit and open, must not strike it at its velocity's rounding: a
    handful of events. Found by the fuzzer: under index 3, 467 events,
    278 within a microsecond."""
    m = mb.Model(gravity=(0.0, -G))
    parent = m.ground
    for i in range(3):
        v = (0.0, -1.5) if i == 0 else (0.0, -3.0)
        rod = m.add_body(f"rod{i}", mass=1.0, inertia=1.0 / 12.0, position=(i + 0.5, 0.0), velocity=v,
                         angular_velocity=-3.0 if i == 0 else 0.0)
        m.add_revolute(f"j{i}", parent, rod, at=(float(i), 0.0))
        parent = rod
    m.add_stop("stop", "j0", lower=-1.2)
    m.add_stop("twin", "j0", lower=-1.2)
    r = mb.simulate(m, t_end=1.5, n_out=151, rtol=1e-8, atol=1e-10, formulation=formulation)
    assert [x["kind"] for x in r.events if x["kind"] != "impact"] == ["capture", "release"]
    assert len(r.events) <= 12
    assert np.min(r.joint("j0").angle) >= -1.2 - 1e-8


def test_a_grazing_swing_strikes_its_stop():
    """A bob hanging from a cart on a level rail (the cart pushed at
    2 m/s), its hinge with an upper stop 0.1 rad above the start: where the
    swing reaches the limit it strikes it (an impact), and the hinge never
    passes it by more than 1e-8 rad. Found by the fuzzer (the default seed):
    at t = 2.48 s the hinge was 3.9e-6 rad beyond, with no event (the root
    functions compare signs at the steps' ends; a crossing in and out
    within one step is now found on the step's interpolant)."""
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", mass=0.5, inertia=0.1, position=(0.0, 0.0), velocity=(-2.0, 0.0))
    m.add_translational("rail", m.ground, block, at=(0.0, 0.0), axis=(1.0, 0.0))
    bob = m.add_body("bob", mass=1.0, inertia=0.0208333, position=(0.0487718, -0.245196), angle=-1.37445)
    m.add_revolute("hinge", block, bob, at=(0.0, 0.0))
    m.add_stop("stop", "hinge", upper=-1.27445, restitution=0.15)
    r = mb.simulate(m, t_end=3.0, n_out=151, rtol=1e-8, atol=1e-10, formulation="ggl")
    assert np.max(r.joint("hinge").angle) <= -1.27445 + 1e-8
    strikes = [x for x in r.events if x["kind"] == "impact"]
    assert strikes and all(x["speed_before"] < 0.0 < x["speed_after"] for x in strikes)


def test_adjacent_stops_settle_without_a_pile_of_impacts():
    """A chain of four rods under a constant torque with stops on three
    joints (two of them adjacent, e = 0.75 and 0.15): where the adjacent
    stops meet at rest they close (a capture), as the acceleration-level
    complementarity problem decides; a run logs at most a few hundred
    events. Found by the fuzzer: 682 events, 636 of them impacts at speed 0
    piled within microseconds of t = 1.99 s (capture_time 1e-8 makes 1108)."""
    m = mb.Model(gravity=(0.0, -G))
    b0 = m.add_body("b0", mass=0.5, inertia=0.0416667, position=(-0.191344, -0.461939), angle=-1.9635,
                    velocity=(2.77163, -1.14806), angular_velocity=6.0)
    m.add_revolute("j0", m.ground, b0, at=(0.0, 0.0))
    b1 = m.add_body("b1", mass=0.5, inertia=0.0104167, position=(-0.632688, -0.923877), angle=3.14159,
                    velocity=(5.54327, -2.29613), angular_velocity=0.0)
    m.add_revolute("j1", b0, b1, at=(-0.382688, -0.923878))
    b2 = m.add_body("b2", mass=1.0, inertia=0.333333, position=(-0.327118, -0.0924067), angle=0.981748,
                    velocity=(5.54327, -2.29613), angular_velocity=0.0)
    m.add_revolute("j2", b1, b2, at=(-0.882688, -0.923876))
    b3 = m.add_body("b3", mass=2.0, inertia=0.666667, position=(1.05992, 0.183493), angle=-0.589049,
                    velocity=(5.54327, -2.29613), angular_velocity=0.0)
    m.add_revolute("j3", b2, b3, at=(0.228452, 0.739063))
    m.add_stop("stop0", "j0", lower=-2.3135, upper=-1.9635, restitution=0.25)
    m.add_stop("stop1", "j2", lower=-2.85984, restitution=0.75)
    m.add_stop("stop2", "j1", lower=3.90509, upper=5.10509, restitution=0.15)
    m.add_torque("torque", b1, 5.0)
    r = mb.simulate(m, t_end=3.0, n_out=151, rtol=1e-8, atol=1e-10, formulation="ggl")
    assert len(r.events) <= fs.MAX_EVENTS
    assert not [x for x in r.events if x["kind"] == "impact" and x["speed_before"] == 0.0]


@pytest.mark.parametrize("formulation", ["ggl", "index1", "projection", "index3"])
def test_a_stop_pressed_by_a_swinging_chain_settles(formulation):
    """A spatial chain of three rods released level, a stop (0 .. 0.1 rad,
    e = 0.3) on its middle joint: the bounces on the lower limit shrink by e
    each, so a series ends (a capture, or the joint leaves) within a few
    dozen impacts. Found by the fuzzer: 597 events, later 2,500, the
    rebounds staying at 1e-6 rad/s: flights 4e-13 rad high, below the
    positions' error, each return striking 3.3 times as fast as the rebound
    before it (1 / e); a return more than twice as fast as its rebound is
    now taken as the unresolved end of the series (captured)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    b0 = m.add_body("b0", mass=1.0, inertia=(0.0833333,) * 3, position=(0.5, 0.0, 0.0))
    m.add_revolute("j0", m.ground, b0, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    b1 = m.add_body("b1", mass=2.0, inertia=(0.0416667,) * 3, position=(1.23097, 0.0, -0.0956709))
    m.add_revolute("j1", b0, b1, at=(1.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    b2 = m.add_body("b2", mass=2.0, inertia=(0.666667,) * 3, position=(0.53806, -0.270598, 0.0792563))
    m.add_revolute("j2", b1, b2, at=(1.46194, 0.0, -0.191342), axis=(0.0, 1.0, 1.0))
    m.add_stop("stop", "j1", lower=0.0, upper=0.1, restitution=0.3)
    r = mb.simulate(m, t_end=1.5, n_out=151, rtol=1e-8, atol=1e-10, formulation=formulation)
    assert len(r.events) <= 30
    assert 0.0 - 1e-8 <= np.min(r.joint("j1").angle) and np.max(r.joint("j1").angle) <= 0.1 + 1e-8


@pytest.mark.parametrize("formulation, options", [
    ("projection", {}), ("ggl", {}), ("projection", {"integrator": "erk"}), ("index3", {}),
])
def test_a_bounce_series_lower_than_the_positions_error_ends(formulation, options):
    """A spatial double pendulum, its elbow between stops at -0.05 (e = 0)
    and 0.05 rad (e = 0.55), a constant torque swinging it into the upper:
    each series of bounces shrinks by e and ends (captured), a few dozen
    impacts each. Found by the fuzzer: under projection-BDF, 4,469 impacts,
    each rebound at 9.7e-5 rad/s returning at 1.8e-4 (1/e times it): the
    flights were 1e-10 rad high, below what the positions resolve (rtol
    1e-8), and CVODE's first step after each restart spanned the flight;
    a return faster than its rebound from a flight lower than the positions'
    accuracy now ends the series."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    upper = m.add_body("upper", mass=0.5, inertia=(0.0104167,) * 3, position=(0.23097, 0.0427853, 0.0855706))
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0, 0.0), axis=(0.0, 2.0, -1.0))
    fore = m.add_body("fore", mass=0.5, inertia=(0.0104167,) * 3, position=(0.71194, 0.0855706, 0.171141))
    m.add_revolute("elbow", upper, fore, at=(0.46194, 0.0855706, 0.171141), axis=(0.0, 0.0, 1.0))
    m.add_stop("bouncy", "elbow", upper=0.05, restitution=0.55)
    m.add_stop("dead", "elbow", lower=-0.05)
    m.add_torque("push", fore, (0.0, 5.0, 0.0))
    r = mb.simulate(m, t_end=1.5, n_out=151, rtol=1e-8, atol=1e-10, formulation=formulation, **options)
    assert len(r.events) <= 120
    angle = r.joint("elbow").angle
    assert np.min(angle) >= -0.05 - 1e-8 and np.max(angle) <= 0.05 + 1e-8


def test_a_four_bar_starting_on_two_stops_runs():
    """A four-bar (crank 1, coupler 2, rocker 2, ground 2) starts with its
    crank on its upper stop, turning into it, and its rocker on its own:
    the loop has one degree of freedom, so the two rows are dependent and
    one impact stops both (docs/modelling.md: several crossings at one
    instant are solved together). The run goes on, every joint within its
    limits. Found by the fuzzer: refused at the start with a time of inf
    (with its inertias rounded to 6 digits, as here; with 1/12 and 2/3 to
    the last bit it runs)."""
    m = mb.Model(gravity=(0.0, -G))
    crank = m.add_body("crank", mass=1.0, inertia=0.0833333, position=(0.0, 0.5), angle=1.5708,
                         angular_velocity=2.0)
    coupler = m.add_body("coupler", mass=2.0, inertia=0.666667, position=(1.0, 1.0))
    rocker = m.add_body("rocker", mass=2.0, inertia=0.666667, position=(2.0, 0.0), angle=1.5708)
    m.add_revolute("A", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, coupler, at=(0.0, 1.0))
    m.add_revolute("C", coupler, rocker, at=(2.0, 1.0))
    m.add_revolute("D", rocker, m.ground, at=(2.0, -1.0))
    m.add_stop("stop0", "D", upper=-1.5708, restitution=0.35)
    m.add_stop("stop1", "D", lower=-1.7708, upper=-1.5208, restitution=0.05)
    m.add_stop("stop2", "A", upper=1.5708, restitution=0.05)
    m.add_stop("stop3", "B", lower=-2.3208, upper=-1.4708, restitution=0.05)
    r = mb.simulate(m, t_end=1.5, n_out=151, rtol=1e-8, atol=1e-10, formulation="ggl")
    assert np.max(r.joint("A").angle) <= 1.5708 + 1e-8 and np.max(r.joint("D").angle) <= -1.5708 + 1e-8


def test_a_failure_does_not_blame_an_open_stop():
    """Two free bodies joined by a spatial revolute, falling, a torque
    ramped in from t = 0.2 s: GGL fails at 0.2 s (a core failure that has
    nothing to do with stops: it fails the same without one). With a stop
    on the hinge, open all the while (the hinge stays near 0, its limits
    -1.2 and 0.75), the message must not name the stop as the cause. Found
    by the fuzzer."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    b0 = m.add_body("b0", mass=2.0, inertia=(0.666667,) * 3, position=(0.0, -0.707107, 0.707107),
                    angular_velocity=(0.0, -3.53553, -3.53553), velocity=(-5.0, 0.0, 0.0))
    b1 = m.add_body("b1", mass=1.0, inertia=(0.333333,) * 3, position=(0.707107, -0.914214, 0.914214))
    m.add_revolute("hinge", b0, b1, at=(0.0, -1.41421, 1.41421), axis=(0.0, 1.0, 1.0))
    m.add_stop("stop", "hinge", lower=-1.2, upper=0.75, restitution=0.35)
    m.add_torque("torque", b0, (0.0, mb.SmoothStep(0.2, 0.6, 0.0, 1.0), 0.0))
    try:
        mb.simulate(m, t_end=0.8, n_out=61, rtol=1e-8, atol=1e-10, formulation="ggl")
    except mb.SimulationError as e:
        assert "'stop'" not in str(e), str(e)
