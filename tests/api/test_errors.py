"""Bad input gets a clear exception that names the element and the value.

docs/design.md section 6.  Modelling errors raise mb.ModelError (a ValueError);
bad simulation settings raise ValueError naming the setting; solver trouble
raises mb.SimulationError (not a ValueError) carrying .t (time reached) and
.result (partial Result or None); a model whose initial positions cannot be
made consistent raises mb.AssemblyError (a SimulationError) whose message
names the violated joints.  Every case checks the type and that the
offending name (and, for numbers, the value) appears in the message.
"""

import math
import re
import warnings

import numpy as np
import pytest

import lagmb as mb
from builders import pendulum


def _rod_kwargs(**over):
    kw = dict(mass=1.0, inertia=1.0 / 12.0, position=(0.5, 0.0), angle=0.0)
    kw.update(over)
    return kw


def test_exception_hierarchy():
    """ModelError is a ValueError; SimulationError is not (it is not the
    caller's input that is wrong); AssemblyError is a SimulationError."""
    assert issubclass(mb.ModelError, ValueError)
    assert issubclass(mb.SimulationError, Exception)
    assert not issubclass(mb.SimulationError, ValueError)
    assert issubclass(mb.AssemblyError, mb.SimulationError)


# --------------------------------------------------------------------------
# Bodies
# --------------------------------------------------------------------------

@pytest.mark.parametrize(
    "over, words",
    [
        (dict(mass=-2.5), ["mass", "-2.5"]),
        (dict(mass=math.nan), ["mass", "nan"]),
        (dict(inertia=-0.25), ["inertia", "-0.25"]),
        (dict(position=(math.nan, 0.0)), ["position", "nan"]),
        (dict(position=(0.0, math.inf)), ["position", "inf"]),
        (dict(angle=-math.inf), ["angle", "inf"]),
    ],
    ids=["negative-mass", "nan-mass", "negative-inertia",
         "nan-position", "inf-position", "inf-angle"],
)
def test_bad_body_parameters(over, words):
    """A body named "wheel" with a bad number: ModelError whose message
    contains "wheel", the parameter name and the offending value
    (case-insensitive for nan/inf)."""
    m = mb.Model(gravity=(0.0, -9.81))
    with pytest.raises(mb.ModelError, match="wheel") as info:
        m.add_body("wheel", **_rod_kwargs(**over))
    msg = str(info.value).lower()
    for w in words:
        assert w.lower() in msg, f"{w!r} not in {msg!r}"


def test_duplicate_body_name():
    """Two bodies called "link": the second one is refused, naming "link"."""
    m = mb.Model()
    m.add_body("link", **_rod_kwargs())
    with pytest.raises(mb.ModelError, match="link"):
        m.add_body("link", **_rod_kwargs(position=(1.5, 0.0)))


# --------------------------------------------------------------------------
# Joints
# --------------------------------------------------------------------------

def test_duplicate_joint_name():
    """Two revolutes called "hinge": the second is refused, naming "hinge"."""
    m = mb.Model()
    a = m.add_body("upper", **_rod_kwargs())
    b = m.add_body("lower", **_rod_kwargs(position=(1.5, 0.0)))
    m.add_revolute("hinge", m.ground, a, at=(0.0, 0.0))
    with pytest.raises(mb.ModelError, match="hinge"):
        m.add_revolute("hinge", a, b, at=(1.0, 0.0))


def test_joint_name_clashes_with_body_name():
    """Names are unique across all elements: a revolute may not be called
    like an existing body ("arm")."""
    m = mb.Model()
    arm = m.add_body("arm", **_rod_kwargs())
    with pytest.raises(mb.ModelError, match="arm"):
        m.add_revolute("arm", m.ground, arm, at=(0.0, 0.0))


def test_body_name_clashes_with_joint_name():
    """... and a body may not take the name of an existing joint ("pivot")."""
    m = mb.Model()
    arm = m.add_body("arm", **_rod_kwargs())
    m.add_revolute("pivot", m.ground, arm, at=(0.0, 0.0))
    with pytest.raises(mb.ModelError, match="pivot"):
        m.add_body("pivot", **_rod_kwargs(position=(1.5, 0.0)))


def test_revolute_between_body_and_itself():
    """A joint from "arm" to "arm" constrains nothing (Phi_q rows vanish) and
    is refused, naming the joint "selfie"."""
    m = mb.Model()
    arm = m.add_body("arm", **_rod_kwargs())
    with pytest.raises(mb.ModelError, match="selfie"):
        m.add_revolute("selfie", arm, arm, at=(0.0, 0.0))


def test_revolute_with_body_from_another_model():
    """A body handle belongs to the model that created it: joining it in a
    different model is refused, naming the joint "bridge"."""
    other = mb.Model()
    alien = other.add_body("alien", **_rod_kwargs())
    m = mb.Model()
    with pytest.raises(mb.ModelError, match="bridge"):
        m.add_revolute("bridge", m.ground, alien, at=(0.0, 0.0))


def test_revolute_with_unknown_body_name():
    """Bodies may be given by name; an unknown one ("ghost") is refused,
    naming it."""
    m = mb.Model()
    m.add_body("arm", **_rod_kwargs())
    with pytest.raises(mb.ModelError, match="ghost"):
        m.add_revolute("hinge", m.ground, "ghost", at=(0.0, 0.0))


# --------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------

@pytest.fixture(scope="module")
def short_run():
    return mb.simulate(pendulum(), t_end=0.1, n_out=3, rtol=1e-8, atol=1e-10)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda r: r.body("nosuchbody"), "nosuchbody"),
        (lambda r: r.point("nosuchbody", (0.0, 0.0)), "nosuchbody"),
        (lambda r: r.reaction("nosuchjoint"), "nosuchjoint"),
    ],
    ids=["body", "point", "reaction"],
)
def test_unknown_name_in_result(short_run, call, name):
    """Asking a Result for an element that does not exist raises a KeyError
    or ValueError (ModelError) whose message names it."""
    with pytest.raises((KeyError, ValueError)) as info:
        call(short_run)
    assert name in str(info.value)


# --------------------------------------------------------------------------
# Simulation settings
# --------------------------------------------------------------------------

@pytest.mark.parametrize(
    "kwargs, word",
    [
        (dict(t_end=0.0), "t_end"),
        (dict(t_end=-1.0), "t_end"),
        (dict(t_end=1.0, rtol=0.0), "rtol"),
        (dict(t_end=1.0, rtol=-1e-6), "rtol"),
        (dict(t_end=1.0, atol=-1e-10), "atol"),
        (dict(t_end=1.0, t_out=[0.0, 0.6, 0.3, 1.0]), "t_out"),
        (dict(t_end=1.0, t_out=[0.0, 0.5, 0.5, 1.0]), "t_out"),
        (dict(t_end=1.0, formulation="index7"), "index7"),
    ],
    ids=["t_end-zero", "t_end-negative", "rtol-zero", "rtol-negative",
         "atol-negative", "t_out-decreasing", "t_out-repeated",
         "unknown-formulation"],
)
def test_bad_simulation_settings(kwargs, word):
    """Settings that make no sense are the caller's error: ValueError (not a
    SimulationError) naming the setting or the bad value."""
    with pytest.raises(ValueError, match=re.escape(word)):
        mb.simulate(pendulum(), **kwargs)


# --------------------------------------------------------------------------
# Assembly
# --------------------------------------------------------------------------

def _unassemblable():
    """Two 1 m rods pinned to the ground 3 m apart, "left_pin" at (0, 0) and
    "right_pin" at (3, 0), lying toward each other, and pinned to each other
    by "middle" at their free tips (local point (L/2, 0) on each).  The tips
    stay within 1 m of their ground pins, so they are always at least
    3 - 1 - 1 = 1 m apart: no configuration satisfies all three joints.
    ("middle" is given by local points: a revolute given by one global point
    in the initial configuration is satisfied there by construction.)"""
    m = mb.Model(gravity=(0.0, -9.81))
    left = m.add_body("left", **_rod_kwargs(position=(0.5, 0.0), angle=0.0))
    right = m.add_body("right", **_rod_kwargs(position=(2.5, 0.0), angle=math.pi))
    m.add_revolute("left_pin", m.ground, left, at=(0.0, 0.0))
    m.add_revolute("right_pin", m.ground, right, at=(3.0, 0.0))
    m.add_revolute("middle", left, right, local_i=(0.5, 0.0), local_j=(0.5, 0.0))
    return m


def test_unassemblable_model_raises_assembly_error():
    """The initial positions cannot be made consistent: AssemblyError (a
    SimulationError, not a ValueError) raised at the start time t = 0 (so
    .t == 0.0, to 1e-15), carrying .result, and naming at least one of the
    violated joints in its message."""
    with pytest.raises(mb.AssemblyError, match="left_pin|right_pin|middle") as info:
        mb.simulate(_unassemblable(), t_end=1.0, n_out=11, rtol=1e-8, atol=1e-10)
    err = info.value
    assert isinstance(err, mb.SimulationError)
    assert not isinstance(err, ValueError)
    assert isinstance(err.t, float)
    assert abs(err.t - 0.0) <= 1e-15
    assert hasattr(err, "result")
    if err.result is not None:
        assert np.asarray(err.result.t).size <= 1


def test_a_loop_that_cannot_close_blames_the_joint_the_given_positions_break():
    """A four-bar of three 1 m links whose ground pivot D is 10 m away: no
    configuration closes it. The given positions break D alone; where
    Newton stops, the violation is spread over the loop. AssemblyError
    blames D (first in .violated and in the message) and says what is
    still violated where Newton stopped."""
    m = mb.Model(gravity=(0.0, -9.81))
    crank = m.add_body("crank", 1.0, 0.1, (0.5, 0.0))
    coupler = m.add_body("coupler", 1.0, 0.1, (1.5, 0.0))
    rocker = m.add_body("rocker", 1.0, 0.1, (2.5, 0.0))
    m.add_revolute("A", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, coupler, at=(1.0, 0.0))
    m.add_revolute("C", coupler, rocker, at=(2.0, 0.0))
    m.add_revolute("D", rocker, m.ground, local_i=(0.5, 0.0), local_j=(10.0, 0.0))
    with pytest.raises(mb.AssemblyError) as failure:
        mb.simulate(m, 0.1)
    assert [name for name, _ in failure.value.violated] == ["D"]
    assert abs(failure.value.violated[0][1] - 7.0) < 1e-12  # |(10, 0) - (3, 0)|
    assert re.search(r"violated by the given positions: 'D' \(\|Phi\| = 7\); still violated where Newton "
                     r"stopped: '", str(failure.value))


def _crank_with_a_coupler_off_its_pin():
    """A crank pinned at the origin and a coupler whose pin point, given in
    the coupler's axes (0.6 m below its centre), is 0.45 m from the crank's
    end (local points: nothing makes them meet)."""
    m = mb.Model(gravity=(0.0, -9.81))
    crank = m.add_body("crank", 1.0, 0.1, (0.5, 0.0))
    coupler = m.add_body("coupler", 1.0, 0.1, (1.0, 1.0))
    m.add_revolute("A", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, coupler, local_i=(0.5, 0.0), local_j=(0.0, -0.6))
    return m


def test_assembly_that_moves_bodies_far_says_which_and_by_how_much():
    """The run starts from the assembled configuration, and an
    AssemblyWarning, pointing at the caller's line, names each body moved
    by more than 1e-3 of the mechanism's size or 1e-3 rad with the distance
    and the turn it was moved by (those of the run's first output); the
    Simulator and Model.assemble warn alike."""
    m = _crank_with_a_coupler_off_its_pin()
    with pytest.warns(mb.AssemblyWarning) as seen:
        r = mb.simulate(m, 0.1, n_out=3)
    assert seen[0].filename == __file__
    message = str(seen[0].message)
    for name, (x, y, angle) in (("crank", (0.5, 0.0, 0.0)), ("coupler", (1.0, 1.0, 0.0))):
        body = r.body(name)
        shift = math.hypot(body.position[0, 0] - x, body.position[0, 1] - y)
        assert shift > 0.05
        assert f"'{name}' by {shift:.3g} m and {abs(body.angle[0] - angle):.3g} rad" in message
    # the pin closed: the crank's end is the coupler's pin point
    assert np.abs(r.point("crank", (0.5, 0.0))[0] - r.point("coupler", (0.0, -0.6))[0]).max() < 1e-10
    with pytest.warns(mb.AssemblyWarning, match="'crank' by"):
        mb.Simulator(m)
    with pytest.warns(mb.AssemblyWarning, match="'coupler' by"):
        m.assemble()


def test_a_spatial_body_moved_by_assembly_is_named_with_its_turn():
    """In space the turn is the angle between the given and the assembled
    orientations, 2 acos |p0 . p1|."""
    m = mb.Model(dimension=3)
    m.add_body("bob", 1.0, (0.1, 0.1, 0.1), position=(1.0, 0.0, 0.0))
    m.add_spherical("ball", m.ground, "bob", at=(0.0, 0.0, 0.0))
    # a link of 1.5 m between the ground point (1, 1, 0) and the bob's far end, 1 m away
    m.add_distance("link", m.ground, (1.0, 1.0, 0.0), "bob", (2.0, 0.0, 0.0), length=1.5)
    with pytest.warns(mb.AssemblyWarning, match="'bob' by") as seen:
        r = mb.simulate(m, 0.1, n_out=3)
    p0, p1 = np.array([1.0, 0.0, 0.0, 0.0]), r.body("bob").orientation[0]
    shift = np.linalg.norm(r.body("bob").position[0] - (1.0, 0.0, 0.0))
    assert f"'bob' by {shift:.3g} m and {2 * math.acos(min(1.0, abs(p0 @ p1))):.3g} rad" in str(seen[0].message)


def test_a_consistent_model_assembles_without_a_word():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mb.simulate(pendulum(), 0.1, n_out=3)
        mb.Simulator(pendulum())


def test_a_redundant_joint_is_named_at_the_callers_line():
    m = pendulum()
    m.add_revolute("again", m.ground, "rod", at=(0.0, 0.0))
    with pytest.warns(mb.RedundantConstraintWarning) as seen:
        mb.simulate(m, 0.1, n_out=3)
    assert seen[0].filename == __file__


# --------------------------------------------------------------------------
# Solver trouble keeps what was computed
# --------------------------------------------------------------------------

def test_step_limit_raises_simulation_error_with_partial_result(capfd):
    """A run stopped by max_steps raises SimulationError carrying the time
    reached (0 < t < t_end) and a Result with the outputs before it, each of
    which is a valid state (|Phi| < 1e-9); SUNDIALS prints nothing.
    max_steps bounds the steps between two outputs: 200 do not reach 1 s."""
    m = pendulum()
    with pytest.raises(mb.SimulationError, match="max_steps") as info:
        mb.simulate(m, t_end=2.0, n_out=3, rtol=1e-8, atol=1e-10, max_steps=200, formulation="ggl")
    err = info.value
    assert 0.0 < err.t < 2.0
    partial = err.result
    assert isinstance(partial, mb.Result)
    assert 1 <= len(partial.t) < 3
    assert partial.t[-1] <= err.t
    assert partial.q.shape == (len(partial.t), 3)
    assert partial.lam.shape == (len(partial.t), 2)
    assert partial.residual.max() < 1e-9
    assert partial.stats["steps"] == 200
    out, errout = capfd.readouterr()
    assert out == "" and errout == ""


def test_integrator_failure_is_reported_with_time_and_diagnosis(capfd):
    """A particle on a 1 m link to the origin, its x driven as 0.5 + t: at
    t = 0.5 s the link is stretched straight and beyond that no position
    exists. The run fails there: SimulationError naming the solver, the time
    (0.4 < t < 0.6) and the step size, with the outputs before it kept and
    nothing printed by SUNDIALS."""
    m = mb.Model()
    bob = m.add_particle("bob", mass=1.0, position=(0.5, -math.sqrt(0.75)))
    m.add_distance("link", m.ground, (0.0, 0.0), bob, (0.5, -math.sqrt(0.75)))
    m.drive_body("pull", bob, "x", mb.Linear(1.0, start=0.5))
    with pytest.raises(mb.SimulationError, match=r"failed at t = .*step size") as info:
        # the integrator's failure: integrate it (0 DOF would pick the kinematic analysis)
        mb.simulate(m, t_end=1.0, n_out=101, rtol=1e-8, atol=1e-10, analysis="dynamic")
    assert 0.4 < info.value.t < 0.6
    partial = info.value.result
    assert partial is not None and 40 <= len(partial.t) <= 60
    assert partial.residual.max() < 1e-8
    assert capfd.readouterr().err == ""


def test_failure_on_a_long_chain_is_not_called_a_singular_position():
    """A 60-link chain with every joint driven, integrated with atol 1e-13 m
    although it is 60 m long and its Jacobian's condition number is ~1e3:
    IDA's Newton iteration cannot converge below rounding and the run stops
    at t = 0. A long chain is ill conditioned everywhere (sigma_min/sigma_max
    ~ 1/N), so the diagnosis must not call this a dead point: it says the
    conditioning is no worse than at the start and estimates the rounding
    floor for atol (1e-15 x largest coordinate x condition), which lies
    between the failing 1e-13 and the 1e-10 that runs."""
    m = mb.Model(gravity=(0.0, -9.81))
    prev = m.ground
    for k in range(60):
        rod = m.add_body(f"rod{k}", 1.0, 1 / 12, position=(k + 0.5, 0.0))
        m.add_revolute(f"pin{k}", prev, rod, at=(float(k), 0.0))
        m.drive_joint(f"motor{k}", f"pin{k}", mb.Harmonic(0.3, 2.0, phase=0.1 * k))
        prev = rod
    with pytest.raises(mb.SimulationError, match="no worse conditioned") as info:
        mb.simulate(m, t_end=0.1, n_out=3, rtol=1e-10, atol=1e-13, analysis="dynamic", formulation="ggl")
    assert "dead point" not in str(info.value)
    floor = float(re.search(r"rounding allows for this model: about ([-+\d.e]+)", str(info.value)).group(1))
    assert 1e-13 < floor < 1e-10
    with pytest.warns(mb.AssemblyWarning, match="59 bodies"):  # the drives' start angles fold the chain
        assert mb.simulate(m, t_end=0.1, n_out=3, rtol=1e-10, atol=1e-10, analysis="dynamic",
                           formulation="ggl").stats["steps"] > 0


@pytest.mark.parametrize("rtol", [1e-15, 0.0, -1e-6])
def test_rtol_beyond_double_precision_is_rejected(rtol):
    with pytest.raises(mb.ModelError, match="rtol"):
        mb.simulate(pendulum(), t_end=1.0, rtol=rtol)


def test_an_argument_of_the_other_dimension_says_where_it_belongs():
    """A planar add_revolute given a spatial revolute's axis: a ModelError
    that names the argument, says it is for spatial models and lists what
    the planar kind takes (not a bare TypeError from the signature)."""
    m = mb.Model()
    b = m.add_body("b", 1.0, 0.1)
    with pytest.raises(mb.ModelError, match=r"add_revolute: got an unexpected keyword argument 'axis'; 'axis' is "
                       r"for spatial models \(Model\(dimension=3\)\), this model has dimension 2\. It takes name, "
                       r"body_i, body_j, at, local_i, local_j"):
        m.add_revolute("r", m.ground, b, at=(0.0, 0.0), axis=(0.0, 0.0, 1.0))
    s = mb.Model(dimension=3)
    c = s.add_body("c", 1.0, (0.1, 0.1, 0.1))
    with pytest.raises(mb.ModelError, match="'local_i' is for planar models"):
        s.add_revolute("r", s.ground, c, at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0), local_i=(0.0, 0.0))
    with pytest.raises(mb.ModelError, match="add_body: missing a required argument: 'mass'. It takes name, mass"):
        m.add_body("d", mas=1.0, inertia=0.1)
    assert len(m.bodies) == 1  # nothing was added


# --------------------------------------------------------------------------
# Contacts that start deep, and stiffnesses no material has
# --------------------------------------------------------------------------

def ball_in_slope(depth, stiffness=1e7):
    """A 1 kg ball of radius 0.1 m started `depth` inside a 20 degree slope
    (its centre on the slope's normal through the origin)."""
    c, s = math.cos(math.radians(20.0)), math.sin(math.radians(20.0))
    tilt = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    centre = tuple((0.1 - depth) * tilt[:, 2])
    m = mb.Model(gravity=(0.0, 0.0, -9.81), dimension=3)
    m.add_body("ball", mass=1.0, inertia=(0.004, 0.004, 0.004), position=centre)
    slope = m.add_shape("ground", "plane", (), (0.0, 0.0, 0.0), tilt, role="collision")
    ball = m.add_shape("ball", "sphere", (0.1,), centre, role="collision")
    m.add_contact("on_slope", ball, slope, stiffness=stiffness, restitution=0.5, friction=0.5)
    return m


def test_a_ball_started_deep_in_a_slope_is_named_with_its_depth():
    """16 cm inside the slope (deeper than its radius) the contact presses
    with k d^1.5 = 6.4e5 N, 65,000 times the ball's weight: a
    DeepContactWarning at the caller's line names the contact, its two
    shapes, the depth and the force; index3 then fails at t = 0, and its
    message names them too (a Simulator's failure as well)."""
    with pytest.warns(mb.DeepContactWarning) as seen:
        with pytest.raises(mb.SimulationError, match="failed at t = 0") as info:
            mb.simulate(ball_in_slope(0.16), 1.0, method="index3")
    assert seen[0].filename == __file__
    text = str(seen[0].message)
    for words in ("'on_slope' 0.16 m deep", "a sphere on 'ball' and a plane on the ground", "6.4e+05 N",
                  "6.52e+04 times the bodies' weight"):
        assert words in text
    assert info.value.t == 0.0 and "It started with contacts deep (the deepest first): 'on_slope' 0.16 m deep" \
        in str(info.value)
    with pytest.warns(mb.DeepContactWarning, match="'on_slope' 0.16 m deep"):
        sim = mb.Simulator(ball_in_slope(0.16), method="index3")
    with pytest.raises(mb.SimulationError, match="'on_slope' 0.16 m deep"):
        sim.advance(1.0)


def test_a_contact_pressed_in_less_than_ten_weights_starts_without_a_word():
    """The ball pressed in 4 times the depth its whole weight W gives one
    point, (W / k)^(2/3), pushes with 4^1.5 = 8 W: no warning (the ball
    hops off); 5 times, 11 W: warned."""
    static = (9.81 / 1e7) ** (2 / 3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mb.simulate(ball_in_slope(4.0 * static), 0.01, n_out=3)
    with pytest.warns(mb.DeepContactWarning, match=r"11.2 times the bodies' weight"):
        mb.simulate(ball_in_slope(5.0 * static), 0.01, n_out=3)


@pytest.mark.parametrize("stiffness, words", [
    (1e30, "stiffness 1e+30 N/m^1.5 is stiffer than any material"), (2e13, "stiffness 2e+13 N/m^1.5 is stiffer"),
    (math.inf, "stiffness must be finite, got inf"), (math.nan, "stiffness must be finite, got nan"),
    (0.0, "stiffness must be positive and finite, got 0"),
])
def test_a_stiffness_no_material_has_is_refused(stiffness, words):
    """A contact's stiffness is at most 1e13 N/m^1.5 (Hertz's (4/3) E*
    sqrt(R) for diamond on diamond at R = 200 m), positive and finite: else
    a ModelError at add_contact naming the contact and the value, in space
    and in the plane."""
    with pytest.raises(mb.ModelError, match=re.escape(words)) as info:
        ball_in_slope(0.0, stiffness=stiffness)
    assert "'on_slope'" in str(info.value)
    m = pendulum()
    with pytest.raises(mb.ModelError, match=re.escape(words)) as info:
        m.add_contact("bump", "rod", (1.0, 0.0), 0.05, m.ground, (0.0, -2.0), (1.0, 0.0), stiffness=stiffness,
                      restitution=0.5)
    assert "'bump'" in str(info.value)


def test_a_collision_mesh_of_no_triangles_names_its_file(tmp_path):
    """Issue 56: an STL of 0 triangles as a contact's mesh raised numpy's
    "attempt to get argmax of an empty sequence"."""
    empty = tmp_path / "empty.stl"
    empty.write_text("solid empty\nendsolid empty\n")
    m = mb.Model(gravity=(0.0, 0.0, -9.81), dimension=3)
    m.add_body("gem", mass=1.0, inertia=(0.01, 0.01, 0.01), position=(0.0, 0.0, 0.2))
    gem = m.add_shape("gem", "mesh", (0.1, 0.1, 0.1), (0.0, 0.0, 0.2), mesh=str(empty), role="collision")
    floor = m.add_shape("ground", "plane", (), role="collision")
    with pytest.raises(mb.ModelError, match=r"^spatial contact 'floor': shape_a: the mesh '.*empty\.stl' has no "
                                            r"triangles \(0 in the file\)"):
        m.add_contact("floor", gem, floor, stiffness=1e6, restitution=0.5)
