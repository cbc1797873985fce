"""Stops that hold: the active set of unilateral rows (docs/methods.md, "The active set, step by step").

A joint that comes to rest on its limit is captured: the limit becomes a
joint equation whose multiplier is the stop's force (Result.effort), until
the stop would have to pull, where it is released. Every check is against a
closed form (none from lagmb):
- a block dropped h = 1 m onto a floor stop with restitution e hits at
  t0 = sqrt(2 h / g) with v0 = g t0; bounce k leaves at e^k v0 and lasts
  2 e^k v0 / g, so the bounces end at T = t0 (1 + e) / (1 - e); resting, the
  stop carries m g; an impact takes exactly (1 - e^2) m v^2 / 2;
- a uniform rod (J_O = m L^2 / 3) pinned at one end and released level
  turns by theta in t(theta) = int_0^theta dphi / sqrt(3 g sin(phi) / L);
  resting on a stop at -beta it needs the torque m g (L / 2) cos(beta);
  a torque k t lifts it off at t = m g (L / 2) cos(beta) / k.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

import lagmb as mb
import builders

G = 9.81
FORMULATIONS = ["ggl", "index1", "index3", "projection", "projection-erk", "ali3p"]
# how each is asked for (ali3p: a fixed step, no error control)
METHOD = {"projection-erk": dict(formulation="projection", integrator="erk"),
          "ali3p": dict(formulation="ali3p", step=1e-4)}
# where each finds an impact (index-3 BDF resolves event times to O(tol / h)
# only; CVODE's projection locates the shortest bounces less well)
TIME_TOL = {"ggl": 1e-8, "index1": 1e-8, "index3": 1e-6, "projection": 1e-6, "projection-erk": 1e-8,
            "ali3p": 1e-6}
# the accumulation point: the bounces left when a rebound is captured add up
# to capture_time (1e-6 s) at most; the formulations' own event times add to it
REST_TOL = {"ggl": 2e-6, "index1": 2e-6, "index3": 5e-5, "projection": 5e-5, "projection-erk": 5e-5,
            "ali3p": 1e-5}


def run(model, formulation, t_end, **kw):
    """The model run by a formulation of FORMULATIONS at tight tolerances."""
    if formulation == "ali3p":
        return mb.simulate(model, t_end=t_end, **METHOD[formulation], **kw)
    method = METHOD.get(formulation, dict(formulation=formulation))
    return mb.simulate(model, t_end=t_end, rtol=1e-10, atol=1e-12, **method, **kw)


def drop(e, h=1.0, mass=2.0, **stop):
    """A block on a vertical rail, its floor stop h below."""
    m = mb.Model(gravity=(0.0, -G))
    block = m.add_body("block", mass=mass, inertia=0.1, position=(0.0, 0.0))
    m.add_translational("rail", m.ground, block, at=(0.0, 0.0), axis=(0.0, 1.0))
    m.add_stop("floor", "rail", lower=-h, restitution=e, **stop)
    return m


def fall_time(beta, L=1.0):
    """Time for the level rod to fall to the angle -beta (closed form, quadrature)."""
    return quad(lambda phi: 1.0 / math.sqrt(3.0 * G * math.sin(phi) / L), 0.0, beta)[0]


@pytest.mark.parametrize("formulation", FORMULATIONS)
@pytest.mark.parametrize("e", [0.0, 0.5])
def test_a_dropped_block_bounces_to_rest_on_its_stop(formulation, e):
    """Impacts at the closed-form times with rebound -e times the impact speed
    (1e-12: the energy lost is exactly (1 - e^2) m v^2 / 2); one capture, at
    T = t0 (1 + e) / (1 - e) (2e-6 s for ggl); then the slide holds the limit
    to 1e-10 m and the stop carries m g to 1e-9; energy is never gained."""
    mass, h = 2.0, 1.0
    t0 = math.sqrt(2.0 * h / G)
    v0 = G * t0
    T = t0 * (1.0 + e) / (1.0 - e)
    r = run(drop(e, h, mass), formulation, T + 0.3, n_out=301)
    impacts = [x for x in r.events if x["kind"] == "impact"]
    captures = [x for x in r.events if x["kind"] == "capture"]
    assert [x["kind"] for x in r.events[-1:]] == ["capture"] and len(captures) == 1
    assert r.stats["captures"] == 1 and r.stats["releases"] == 0 and r.stats["impacts"] == len(impacts)
    t_k, v_k = t0, v0
    for x in impacts:
        if v_k < 1e-3 * v0:  # (the last, shortest bounces: the event times' error grows)
            break
        assert abs(x["t"] - t_k) <= TIME_TOL[formulation]
        assert abs(x["speed_before"] + v_k) <= 1e-5 * v0
        t_k += 2.0 * e * v_k / G
        v_k *= e
    for x in impacts[:-1]:
        assert abs(x["speed_after"] + e * x["speed_before"]) <= 1e-12 * abs(x["speed_before"])
    # the last rebound is captured (it ends at 0), or the flight it starts is
    # too short to resolve and the block is captured within it
    last = impacts[-1]
    assert abs(last["speed_after"]) <= 1e-12 or captures[0]["t"] - last["t"] <= 2.0 * last["speed_after"] / G
    assert abs(captures[0]["t"] - T) <= REST_TOL[formulation]
    resting = r.t > captures[0]["t"]
    slide = r.joint("rail").slide
    assert np.max(np.abs(slide[resting] + h)) <= 1e-10
    assert np.min(slide) >= -h - 1e-9
    assert np.max(np.abs(r.effort("floor")[resting] - mass * G)) <= 1e-9 * mass * G
    assert np.all(r.effort("floor")[~resting] == 0.0)
    assert np.all(np.diff(r.energy) <= 1e-9 * mass * G * h)
    assert abs(r.energy[-1] - (-mass * G * h)) <= 1e-9 * mass * G * h


def test_a_lively_bounce_series_ends_at_its_accumulation_point():
    """e = 0.9: some 150 bounces, the capture at T = 19 t0 (2e-6 s), not
    a Zeno guard; then the block rests on the limit (1e-10 m)."""
    t0 = math.sqrt(2.0 / G)
    T = 19.0 * t0
    r = mb.simulate(drop(0.9), t_end=T + 0.2, rtol=1e-10, atol=1e-12, n_out=51)
    capture = [x for x in r.events if x["kind"] == "capture"]
    assert len(capture) == 1 and abs(capture[0]["t"] - T) <= 2e-6
    assert np.max(np.abs(r.joint("rail").slide[r.t > T] + 1.0)) <= 1e-10


def test_rest_speed_captures_the_first_slow_rebound():
    """rest_speed = 0.2 m/s, e = 0.5: the rebounds are e^k v0 (v0 = 4.43 m/s);
    the first below 0.2 m/s (k = 5, 0.138 m/s) is captured at its impact time
    t0 + sum_{i=1..4} 2 e^i v0 / g (1e-8 s)."""
    t0 = math.sqrt(2.0 / G)
    v0 = G * t0
    k = next(k for k in range(1, 20) if 0.5**k * v0 < 0.2)
    t_capture = t0 + sum(2.0 * 0.5**i * v0 / G for i in range(1, k))
    r = mb.simulate(drop(0.5, rest_speed=0.2), t_end=1.4, rtol=1e-10, atol=1e-12)
    assert [x["kind"] for x in r.events] == ["impact"] * k + ["capture"]
    assert abs(r.events[-1]["t"] - t_capture) <= 1e-8


@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_a_pendulum_rests_on_its_stop_with_the_static_torque(formulation):
    """The level rod falls onto a plastic stop at -pi/4: the impact at
    t(pi/4) (closed form, 1e-8 s; index3 1e-6) is a capture; afterwards the
    angle is the limit to 1e-10 rad and the stop's torque the static
    m g (L/2) cos(pi/4) to 1e-9 relative; the pin's reaction carries the weight."""
    beta = math.pi / 4
    m = builders.pendulum(g=G)
    m.add_stop("stop", "pin", lower=-beta, restitution=0.0)
    r = run(m, formulation, 1.0, n_out=101)
    assert [x["kind"] for x in r.events] == ["impact", "capture"]
    assert abs(r.events[0]["t"] - fall_time(beta)) <= TIME_TOL[formulation]
    resting = r.t > r.events[0]["t"]
    assert np.max(np.abs(r.joint("pin").angle[resting] + beta)) <= 1e-10
    static = G * 0.5 * math.cos(beta)
    assert np.max(np.abs(r.effort("stop")[resting] - static)) <= 1e-9 * static
    # the pin and the stop together hold the rod: the pin's force is the weight
    assert np.max(np.abs(r.reaction("pin")[resting, 1] - G)) <= 1e-8 * G


def test_a_torque_ramp_releases_the_stop_at_the_closed_form_time():
    """The rod starts at rest on its stop at -pi/4 (captured at t = 0); a
    torque k t lifts it off where k t = m g (L/2) cos(pi/4) (1e-8 s); until
    then the stop's torque is the static torque minus k t (1e-9), after it 0,
    and the rod rises off the limit."""
    beta, k = math.pi / 4, 2.0
    m = builders.pendulum(g=G, angle=-beta)
    m.add_stop("stop", "pin", lower=-beta)
    m.add_torque("lift", "rod", torque=lambda t: k * t)
    static = G * 0.5 * math.cos(beta)
    t_release = static / k
    r = mb.simulate(m, t_end=t_release + 0.5, rtol=1e-10, atol=1e-12, n_out=201)
    assert [x["kind"] for x in r.events] == ["capture", "release"]
    assert r.events[0]["t"] == 0.0
    assert abs(r.events[1]["t"] - t_release) <= 1e-8
    before = r.t < t_release
    assert np.max(np.abs(r.effort("stop")[before] - (static - k * r.t[before]))) <= 1e-9 * static
    assert np.all(r.effort("stop")[r.t > t_release] == 0.0)
    assert r.joint("pin").angle[-1] > -beta + 1e-3


def test_two_stops_capture_and_release_at_one_instant():
    """Two identical rods, each on its own pin and stop, fall together: both
    stops capture at one instant and release at one instant under identical
    torque ramps (the events come in pairs at equal times)."""
    beta, k = math.pi / 4, 2.0
    m = mb.Model(gravity=(0.0, -G))
    for side in ("a", "b"):
        x = 0.0 if side == "a" else 3.0
        rod = m.add_body(f"rod_{side}", mass=1.0, inertia=1.0 / 12.0, position=(x + 0.5, 0.0))
        m.add_revolute(f"pin_{side}", m.ground, rod, at=(x, 0.0))
        m.add_stop(f"stop_{side}", f"pin_{side}", lower=-beta)
        m.add_torque(f"lift_{side}", rod, torque=lambda t: k * max(t - 1.0, 0.0))
    r = mb.simulate(m, t_end=3.5, rtol=1e-10, atol=1e-12)
    kinds = [(x["kind"], x["element"]) for x in r.events]
    assert kinds == [("impact", "stop_a"), ("impact", "stop_b"), ("capture", "stop_a"), ("capture", "stop_b"),
                     ("release", "stop_a"), ("release", "stop_b")]
    times = [x["t"] for x in r.events]
    assert times[0] == times[1] == times[2] == times[3] and times[4] == times[5]
    assert abs(times[4] - (1.0 + G * 0.5 * math.cos(beta) / k)) <= 1e-8


def test_a_captured_stop_in_a_closed_loop():
    """A four-bar (crank 1, coupler 2, rocker 2, ground 2) falls under
    gravity onto a stop on its crank: captured, it holds the loop still
    (crank angle at the limit to 1e-10, every body at rest, the loop closed to
    1e-10) and its torque balances the loop's weight: the power-free
    (virtual work) check P = effort * 1 + sum m g . v_i = 0 for the velocities
    of a unit crank rate."""
    m = mb.Model(gravity=(0.0, -G))
    crank = m.add_body("crank", mass=1.0, inertia=1.0 / 12.0, position=(0.0, 0.5), angle=math.pi / 2, angular_velocity=-1.0)
    coupler = m.add_body("coupler", mass=2.0, inertia=2.0 * 4.0 / 12.0, position=(1.0, 1.0))
    rocker = m.add_body("rocker", mass=2.0, inertia=2.0 * 4.0 / 12.0, position=(2.0, 0.0), angle=math.pi / 2)
    m.add_revolute("A", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, coupler, at=(0.0, 1.0))
    m.add_revolute("C", coupler, rocker, at=(2.0, 1.0))
    m.add_revolute("D", rocker, m.ground, at=(2.0, -1.0))
    m.add_stop("stop", "A", lower=math.pi / 2 - 0.3, upper=math.pi / 2 + 0.3)  # (the crank's angle)
    r = mb.simulate(m, t_end=3.0, rtol=1e-10, atol=1e-12, n_out=301)
    capture = [x for x in r.events if x["kind"] == "capture"]
    assert capture and not [x for x in r.events if x["kind"] == "release" and x["t"] > capture[-1]["t"]]
    resting = r.t > capture[-1]["t"]
    limit = math.pi / 2 + (-0.3 if capture[-1]["label"] == "lower" else 0.3)
    assert np.max(np.abs(r.joint("A").angle[resting] - limit)) <= 1e-10
    assert np.max(np.abs(r.v[resting])) <= 1e-8
    assert np.max(r.residual[resting]) <= 1e-10
    # virtual work: the stop's torque along the crank angle s is dV/ds,
    # V = sum m_i g h_i, the heights from the loop's closed-form geometry
    # (C on the perpendicular bisector of BD; the branch the run is on)
    a = r.q[-1, 2]  # the crank's angle
    D = np.array([2.0, -1.0])
    C_run = 2.0 * r.q[-1, 6:8] - D  # (only to choose the branch)

    def heights(angle):
        B = np.array([math.cos(angle), math.sin(angle)])
        mid, half = 0.5 * (B + D), 0.5 * np.linalg.norm(D - B)
        normal = np.array([-(D - B)[1], (D - B)[0]]) / (2.0 * half)
        C = min((mid + s * math.sqrt(4.0 - half**2) * normal for s in (1.0, -1.0)),
                key=lambda c: np.linalg.norm(c - C_run))
        return np.array([0.5 * B[1], 0.5 * (B + C)[1], 0.5 * (C + D)[1]])

    d = 1e-6
    dV = np.array([1.0, 2.0, 2.0]) * G @ (heights(a + d) - heights(a - d)) / (2.0 * d)
    assert abs(r.effort("stop")[-1] - dV) <= 1e-6 * G


def test_stops_that_depend_on_each_other_close_one_row():
    """Two fingers on vertical rails, coupled (finger 2 mirrors finger 1, as a
    URDF <mimic>), each with a stop 0.1 m down: they fall together (g, from
    rest: t = sqrt(2 d / g)), and at the stops the two rows are dependent: one
    closes and holds both (the other's gap follows it), its force the two
    fingers' weight, 0.7 g (1e-9), with no chatter (one capture, no release)."""
    m = mb.Model(dimension=3, gravity=(0.0, -G, 0.0))
    f1 = m.add_body("f1", 0.5, (0.01, 0.01, 0.01), position=(0.1, 0.0, 0.0))
    f2 = m.add_body("f2", 0.2, (0.01, 0.01, 0.01), position=(-0.1, 0.0, 0.0))
    m.add_translational("finger1", m.ground, f1, at=(0.1, 0, 0), axis=(0, 1, 0))
    m.add_translational("finger2", m.ground, f2, at=(-0.1, 0, 0), axis=(0, 1, 0))
    m.add_joint_coupling("mirror", "finger2", leader="finger1", multiplier=1.0)
    m.add_stop("stop1", "finger1", lower=-0.1)
    m.add_stop("stop2", "finger2", lower=-0.1)
    r = mb.simulate(m, t_end=1.0, rtol=1e-10, atol=1e-12, n_out=101)
    t_hit = math.sqrt(2.0 * 0.1 / G)
    captures = [x for x in r.events if x["kind"] == "capture"]
    assert len(captures) == 1 and r.stats["releases"] == 0
    assert abs(captures[0]["t"] - t_hit) <= 1e-8
    resting = r.t > t_hit
    for joint in ("finger1", "finger2"):
        assert np.max(np.abs(r.joint(joint).slide[resting] + 0.1)) <= 1e-10
    held = r.effort("stop1") + r.effort("stop2")
    assert np.max(np.abs(held[resting] - 0.7 * G)) <= 1e-9 * 0.7 * G


def test_a_simulator_releases_at_an_input_jump_and_restores_a_held_stop():
    """A rod resting on its stop at -pi/4 in a Simulator: a lifting torque
    input of 5 N m (above the static 3.47 N m) releases it at the instant the
    input jumps (not a step later); a state saved while the stop held it,
    restored, holds it again at once: the stop's torque the static one (1e-9),
    no new capture logged."""
    beta = math.pi / 4
    static = G * 0.5 * math.cos(beta)
    m = builders.pendulum(g=G, angle=-beta)
    m.add_stop("stop", "pin", lower=-beta)
    m.add_torque("lift", "rod", torque=mb.Input(0.0, name="lift"))
    sim = mb.Simulator(m, rtol=1e-10, atol=1e-12)
    sim.advance(0.5)
    held = sim.state()
    sim.set_input("lift", 5.0)
    sim.advance(0.8)
    r = sim.result()
    assert [(x["kind"], x["t"]) for x in r.events] == [("capture", 0.0), ("release", 0.5)]
    assert r.joint("pin").angle[-1] > -beta + 1e-3
    sim.set_state(held)
    sim.advance(1.0)
    r = sim.result()
    assert [x["kind"] for x in r.events] == ["capture"]
    after = r.t >= 0.5
    assert np.max(np.abs(r.effort("stop")[after] - static)) <= 1e-9 * static
    assert np.max(np.abs(r.joint("pin").angle[after] + beta)) <= 1e-10


def test_linearized_about_a_rest_on_a_stop_the_held_joint_is_fixed():
    """A double pendulum at rest with its upper rod on a stop at -pi/4 and
    the lower rod hanging: linearized with the stop held, the upper joint is
    fixed and the motion is the lower rod's about the elbow, omega^2 =
    (m g L/2) / (m L^2/3) = 3 g / (2 L) (1e-9 relative); with the stop open
    (not held) the model has its two degrees of freedom. A stop not at a
    limit cannot be held (ModelError naming its gaps)."""
    beta = math.pi / 4
    c, s = math.cos(beta), math.sin(beta)
    m = mb.Model(gravity=(0.0, -G))
    upper = m.add_body("upper", mass=1.0, inertia=1.0 / 12.0, position=(0.5 * c, -0.5 * s), angle=-beta)
    lower = m.add_body("lower", mass=1.0, inertia=1.0 / 12.0, position=(c, -s - 0.5), angle=-math.pi / 2)
    m.add_revolute("shoulder", m.ground, upper, at=(0.0, 0.0))
    m.add_revolute("elbow", upper, lower, at=(c, -s))
    stop = m.add_stop("stop", "shoulder", lower=-beta)
    q = np.array([0.5 * c, -0.5 * s, -beta, c, -s - 0.5, -math.pi / 2])
    held = mb.linearize(m, at={"q": q, "v": np.zeros(6), "held": [stop]})
    assert held.A.shape == (2, 2)
    # eigenvalues +-i omega: their product is omega^2
    assert abs(np.prod(np.linalg.eigvals(held.A)).real - 1.5 * G) <= 1e-9 * 1.5 * G
    free = mb.linearize(m, at={"q": q, "v": np.zeros(6)})
    assert free.A.shape == (4, 4)
    m2 = mb.Model(gravity=(0.0, -G))
    rod = m2.add_body("rod", mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0))
    m2.add_revolute("pin", m2.ground, rod, at=(0.0, 0.0))
    m2.add_stop("stop", "pin", lower=-beta)
    # (issue 56: said as "tangent_at: held: ...", the core's function, not linearize's argument)
    with pytest.raises(mb.ModelError, match=r"^linearize: at\['held'\]: stop 'stop' is at neither limit.*lower 0.785"):
        mb.linearize(m2, at={"q": np.array([0.5, 0.0, 0.0]), "v": np.zeros(3), "held": ["stop"]})
    with pytest.raises(mb.ModelError, match=r"^linearize: at\['held'\]: .*'pin'.*not a stop"):
        mb.linearize(m2, at={"q": np.array([0.5, 0.0, 0.0]), "v": np.zeros(3), "held": ["pin"]})


def test_an_open_stop_leaves_the_modes_and_the_linearization_alone():
    """A stop the equilibrium does not reach (lower limit -2 rad, the rod
    hanging at -pi/2) changes no linearization: the rod's one mode, omega^2 =
    3 g / (2 L) (1e-9), and a 2-state linear system about a moving state."""
    m = builders.pendulum(g=G, angle=-0.3)
    m.add_stop("stop", "pin", lower=-2.0, upper=2.0)
    assert abs(mb.modes(m).omega[0] ** 2 - 1.5 * G) <= 1e-9 * 1.5 * G
    r = mb.simulate(m, t_end=0.1)
    assert mb.linearize(m, at=(r.q[-1], r.v[-1], r.t[-1])).A.shape == (2, 2)


def test_lagmb_info_counts_a_stop_s_rows_apart_from_the_equations(tmp_path, capsys):
    """A pendulum with a stop: 2 constraint equations (the pin's) and the
    stop's 2 rows named apart; 1 degree of freedom."""
    scene = tmp_path / "stopped.toml"
    scene.write_text(builders.pendulum_scene() + '\n[[stops]]\nname = "stop"\njoint = "pin"\nlower = -1.0\n')
    status, out, err = builders.lagmb_main(capsys, "info", scene)
    assert status == 0, err
    lines = out.splitlines()
    assert "constraint equations: 2 (and 2 rows of stops, held only while a joint rests on a limit)" in lines
    assert "degrees of freedom: 1" in lines
