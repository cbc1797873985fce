"""The registry of element kinds (lagmb/model/registry.hpp, lagmb.registry).

Every kind is declared once, in C++; the Python methods, the scene schema,
the plotting roles and the element reference of docs/modelling.md are read
from that declaration. These tests walk the registry, every kind of it,
planar (dimension 2) and spatial (dimension 3, ``Model(dimension=3)``): a
kind without an example model here, a derivative check, a scene round trip,
a plotting role or a documentation entry fails them.
"""

import inspect
import pathlib

import numpy as np
import pytest

import lagmb as mb
from lagmb import registry
from lagmb.scene import load_scene
from lagmb.scene.schema import ELEMENTS, SPATIAL_ELEMENTS

from builders import lagmb_command
import paths  # noqa: E402  (tests/paths.py)

ROOT = pathlib.Path(paths.ROOT)


# --- one small model per kind: the planar kinds ----------------------------


def _pendulum(m=None):
    m = m or mb.Model(gravity=(0.0, -9.81))
    rod = m.add_body("rod", 1.0, 1 / 12, position=(0.5, 0.0))
    return m, rod


def _slider():
    m = mb.Model(gravity=(0.0, -9.81))
    block = m.add_body("block", 2.0, 0.1, position=(1.0, 0.0))
    rail = m.add_translational("rail", m.ground, block, at=(1.0, 0.0), axis=(1.0, 0.0))
    return m, block, rail


def example_body():
    m, rod = _pendulum()
    return m, rod


def example_particle():
    m = mb.Model(gravity=(0.0, -9.81))
    return m, m.add_particle("bob", 0.5, position=(1.0, -1.0), velocity=(0.2, 0.0))


def example_revolute():
    m, rod = _pendulum()
    return m, m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))


def example_translational():
    m, _, rail = _slider()
    return m, rail


def example_weld():
    m, rod = _pendulum()
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    tip = m.add_body("tip", 0.2, 0.01, position=(1.0, 0.0))
    return m, m.add_weld("glue", rod, tip)


def example_distance():
    m = mb.Model(gravity=(0.0, -9.81))
    bob = m.add_particle("bob", 1.0, position=(0.0, -1.0))
    return m, m.add_distance("string", m.ground, (0.0, 0.0), bob, (0.0, -1.0), length=1.0)


def example_pin_in_slot():
    m, rod = _pendulum()
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    follower = m.add_body("follower", 0.3, 0.01, position=(0.5, 0.5))
    m.add_revolute("hinge", m.ground, follower, at=(0.5, 1.0))
    return m, m.add_pin_in_slot("slot", rod, follower, at=(0.5, 0.0), axis=(1.0, 0.0))


def example_gear():
    m = mb.Model()
    a = m.add_body("a", 1.0, 0.1, position=(0.0, 0.0), angular_velocity=1.0)
    b = m.add_body("b", 1.0, 0.1, position=(0.3, 0.0))
    m.add_revolute("pa", m.ground, a, at=(0.0, 0.0))
    m.add_revolute("pb", m.ground, b, at=(0.3, 0.0))
    return m, m.add_gear("mesh", a, b, ratio=-2.0)


def example_rack_pinion():
    m, block, _ = _slider()
    pinion = m.add_body("pinion", 0.5, 0.01, position=(1.0, 0.1))
    m.add_revolute("axle", m.ground, pinion, at=(1.0, 0.1))
    return m, m.add_rack_pinion("teeth", pinion, block, radius=0.1, axis=(1.0, 0.0))


def example_joint_driver():
    m, rod = _pendulum()
    pin = m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m, m.drive_joint("motor", pin, mb.Linear(1.0))


def example_body_driver():
    m, block, _ = _slider()
    return m, m.drive_body("push", block, "x", mb.Harmonic(0.1, 2.0, offset=1.0))


def example_spring_damper():
    m, block, _ = _slider()
    return m, m.add_spring_damper("spring", m.ground, (0.0, 0.0), block, (1.0, 0.0), stiffness=100.0,
                                  damping=1.0, free_length=0.8, force=mb.Constant(2.0))


def example_rotational_spring_damper():
    m, rod = _pendulum()
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m, m.add_rotational_spring_damper("coil", m.ground, rod, stiffness=20.0, damping=0.5,
                                             free_angle=0.1, torque=mb.Linear(0.5))


def example_force():
    m, block, _ = _slider()
    return m, m.add_force("push", block, (1.0, mb.Linear(2.0)), point=(1.1, 0.0), local=True)


def example_torque():
    m, rod = _pendulum()
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m, m.add_torque("twist", rod, mb.Harmonic(1.0, 3.0))


def example_joint_friction():
    m, rod = _pendulum()
    pin = m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m, m.add_joint_friction("drag", pin, mu=0.2, viscous=0.01, pin_radius=0.01)


def example_contact():
    m = mb.Model(gravity=(0.0, -9.81))
    ball = m.add_body("ball", 1.0, 0.004, position=(0.0, 0.11))
    return m, m.add_contact("floor", ball, (0.0, 0.11), 0.1, m.ground, (0.0, 0.0), (1.0, 0.0),
                            stiffness=1e6, restitution=0.8, friction=0.3)


def example_stop():
    m, rod = _pendulum()
    pin = m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m, m.add_stop("limit", pin, lower=-1.0, upper=1.0, restitution=0.5)


# --- spatial kinds: Model(dimension=3), gravity along -z --------------------
# The same method names add the spatial kinds (a spatial Model dispatches by
# its dimension); each example is named after its registry kind
# (example_planar: the spatial planar joint).

ROD = (1e-3, 1 / 12, 1 / 12)  # a 1 m, 1 kg rod along its own x axis


def _spatial_model():
    return mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))


def _spatial_pendulum():
    m = _spatial_model()
    rod = m.add_body("rod", 1.0, ROD, position=(0.5, 0.0, 0.0))
    return m, rod


def _spatial_hinge():
    """The rod on a hinge about y at the origin: it swings down from level."""
    m, rod = _spatial_pendulum()
    hinge = m.add_revolute("hinge", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    return m, rod, hinge


def _spatial_slider():
    m = _spatial_model()
    block = m.add_body("block", 2.0, (0.1, 0.1, 0.1), position=(1.0, 0.0, 0.0))
    rail = m.add_translational("rail", m.ground, block, at=(1.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0))
    return m, block, rail


def example_spatial_body():
    m = _spatial_model()
    return m, m.add_body("brick", 1.0, (0.01, 0.02, 0.03), position=(0.0, 0.0, 1.0),
                         angular_velocity=(0.5, 1.0, 2.0))


def example_spherical():
    m, rod = _spatial_pendulum()
    return m, m.add_spherical("ball", m.ground, rod, at=(0.0, 0.0, 0.0))


def example_spatial_revolute():
    m, _, hinge = _spatial_hinge()
    return m, hinge


def example_cylindrical():
    """A sleeve on an inclined shaft, its centre off the axis: it slides
    down and swings about the shaft."""
    m = _spatial_model()
    sleeve = m.add_body("sleeve", 0.5, (0.01, 0.01, 0.005), position=(0.0, 0.2, 0.0))
    return m, m.add_cylindrical("shaft", m.ground, sleeve, at=(0.0, 0.0, 0.0), axis=(1.0, 0.0, -0.5))


def example_spatial_translational():
    m, _, rail = _spatial_slider()
    return m, rail


def example_universal():
    m, rod = _spatial_pendulum()
    return m, m.add_universal("cross", m.ground, rod, at=(0.0, 0.0, 0.0), axis_i=(1.0, 0.0, 0.0),
                              axis_j=(0.0, 1.0, 0.0))


def example_planar():
    """A puck on an inclined table (the spatial planar joint): it slides on
    and down the plane."""
    m = _spatial_model()
    puck = m.add_body("puck", 0.5, (0.01, 0.01, 0.02), position=(0.0, 0.0, 0.0), velocity=(1.0, 0.0, 0.0))
    return m, m.add_planar("table", m.ground, puck, at=(0.0, 0.0, 0.0), normal=(0.0, 0.3, 1.0))


def example_spatial_weld():
    m, rod, _ = _spatial_hinge()
    tip = m.add_body("tip", 0.2, (1e-3, 1e-3, 1e-3), position=(1.0, 0.0, 0.0))
    return m, m.add_weld("glue", rod, tip)


def example_spatial_distance():
    m = _spatial_model()
    bob = m.add_body("bob", 1.0, (1e-3, 1e-3, 1e-3), position=(0.0, 0.0, -1.0), velocity=(0.5, 0.0, 0.0))
    return m, m.add_distance("string", m.ground, (0.0, 0.0, 0.0), bob, (0.0, 0.0, -1.0), length=1.0)


def example_spatial_joint_driver():
    m, _, hinge = _spatial_hinge()
    return m, m.drive_joint("motor", hinge, mb.Linear(1.0))


def example_spatial_body_driver():
    m, block, _ = _spatial_slider()
    return m, m.drive_body("push", block, "x", mb.Harmonic(0.1, 2.0, offset=1.0))


def example_spatial_spring_damper():
    m, block, _ = _spatial_slider()
    return m, m.add_spring_damper("spring", m.ground, (0.0, 0.0, 0.0), block, (1.0, 0.0, 0.0), stiffness=100.0,
                                  damping=1.0, free_length=0.8, force=mb.Constant(2.0))


def example_spatial_rotational_spring_damper():
    m, _, hinge = _spatial_hinge()
    return m, m.add_rotational_spring_damper("coil", hinge, stiffness=20.0, damping=0.5, free_angle=0.1,
                                             torque=mb.Linear(0.5))


def example_spatial_joint_servo():
    m, _, hinge = _spatial_hinge()
    return m, m.add_servo("servo", hinge, target=mb.Input(0.2, "aim"), kp=20.0, kd=1.0, limit=5.0)


def example_spatial_stop():
    m, _, hinge = _spatial_hinge()
    return m, m.add_stop("limit", hinge, lower=-1.0, upper=1.0, restitution=0.5)


def example_joint_coupling():
    """Two rods hinged to the ground side by side: the second turns twice as
    far as the first, the other way."""
    m, rod, hinge = _spatial_hinge()
    other = m.add_body("other", 1.0, (1e-3, 1.0 / 12.0, 1.0 / 12.0), position=(0.5, 1.0, 0.0))
    second = m.add_revolute("second", m.ground, other, at=(0.0, 1.0, 0.0), axis=(0.0, 1.0, 0.0))
    return m, m.add_joint_coupling("gears", second, leader=hinge, multiplier=-2.0)


def example_spatial_joint_friction():
    m, _, hinge = _spatial_hinge()
    return m, m.add_joint_friction("bearing", hinge, viscous=0.2, preload=0.1)


def example_bushing():
    """A block hung from the ground by a bushing above its centre: it sags."""
    m = _spatial_model()
    block = m.add_body("block", 2.0, (0.1, 0.1, 0.1), position=(0.0, 0.0, -1.0))
    return m, m.add_bushing("mount", m.ground, block, at=(0.0, 0.0, -0.9), stiffness=(1e3, 1e3, 1e3),
                            damping=(10.0, 10.0, 10.0), rotational_stiffness=(50.0, 50.0, 50.0),
                            rotational_damping=(0.5, 0.5, 0.5))


def example_spatial_force():
    m, block, _ = _spatial_slider()
    return m, m.add_force("push", block, (1.0, mb.Linear(2.0), 0.0), point=(1.1, 0.0, 0.0), local=True)


def example_spatial_torque():
    m, rod, _ = _spatial_hinge()
    return m, m.add_torque("twist", rod, (0.0, mb.Harmonic(1.0, 3.0), 0.0))


def example_spatial_contact():
    """A ball dropped onto the ground plane from just above it: it bounces."""
    m = _spatial_model()
    ball = m.add_body("ball", 0.5, (1e-3, 1e-3, 1e-3), position=(0.0, 0.0, 0.051))
    floor = m.add_shape(m.ground, "plane", (), role="collision")
    sphere = m.add_shape(ball, "sphere", (0.05,), (0.0, 0.0, 0.051), role="collision")
    return m, m.add_contact("bounce", sphere, floor, stiffness=1e6, restitution=0.8, friction=0.3)


EXAMPLES = {name[len("example_"):]: f for name, f in dict(globals()).items() if name.startswith("example_")}

#: Where each kind's derivatives (Phi_q, its derivatives, gamma, Q_q, Q_v,
#: or the event function's gradient) are checked against finite
#: differences. Kinds in tests/analyses/test_derivatives.py are found in the model of
#: their dimension there, every_kind() (planar) or every_spatial_kind()
#: (spatial; it holds every spatial kind), with their rows or forces among
#: those checked (test_every_kind_has_a_derivative_check).
DERIVATIVE_CHECKS = {
    "joint_friction": "tests/elements/test_friction.py::test_friction_force_derivatives",
    "contact": "tests/elements/test_contact.py::test_contact_derivatives_match_finite_differences",
    # a stop's gradient ds/dq is the direction of its impulse: the speeds
    # before and after impacts match closed forms (1e-6) on a revolute and a
    # translational stop; its s(q) is drive_joint's, which
    # test_derivatives.py checks by finite differences
    "stop": "tests/elements/test_stops.py::test_slider_hits_translational_stop",
    # its s(q) is the spatial drive_joint's (test_derivatives.py); its impacts
    # equal the planar stop's on the same pendulum
    "spatial_stop": "tests/elements/test_stops.py::test_a_spatial_stop_acts_as_the_planar_one",
}


def kinds():
    """Every kind's name, planar and spatial."""
    return [k.name for k in registry.ALL_KINDS]


def _derivative_model(dimension):
    """The model of tests/analyses/test_derivatives.py whose derivatives are checked
    for kinds of this dimension (its `state` fixture runs on each of MODELS)."""
    from analyses import test_derivatives

    build = test_derivatives.every_kind if dimension == 2 else test_derivatives.every_spatial_kind
    assert build in test_derivatives.MODELS.values()
    m = build()
    assert m.dimension == dimension
    return m


def _kind_of(model, method):
    """The registry kind a method adds to this model (by its dimension)."""
    return (registry.BY_METHOD if model.dimension == 2 else registry.SPATIAL_BY_METHOD)[method].name


def _without(model, names):
    """The model rebuilt without the elements named."""
    other = mb.Model(gravity=model.gravity, dimension=model.dimension)
    for method, kw in model.elements:
        if kw["name"] not in names:
            getattr(other, method)(**kw)
    return other


def test_every_kind_has_an_example():
    assert sorted(EXAMPLES) == sorted(kinds())
    assert {k.dimension for k in registry.ALL_KINDS} == {2, 3}  # the walk takes both


@pytest.mark.parametrize("kind", kinds())
def test_example_holds_its_kind_and_runs(kind):
    """The example adds the element with its kind's method, and the model
    simulates for a moment (a body alone falls)."""
    m, handle = EXAMPLES[kind]()
    assert handle.kind == kind
    assert handle.role == registry.BY_NAME[kind].role
    assert (registry.BY_NAME[kind].method, handle.name) in [(meth, kw["name"]) for meth, kw in m.elements]
    r = mb.simulate(m, 0.02, n_out=3)
    assert np.isfinite(r.q).all()


@pytest.mark.parametrize("kind", kinds())
def test_a_kind_reads_the_effort_it_declares(kind):
    """A kind whose registry entry says what Result.effort reads of it
    (Kind.effort) gives that reading in its example's run, one column or
    its effort_components' many, finite; a kind without one (a body, a
    joint, a contact) is refused with a ModelError naming the element."""
    m, handle = EXAMPLES[kind]()
    declared = registry.BY_NAME[kind]
    r = mb.simulate(m, 0.02, n_out=3)
    if not declared.effort:
        with pytest.raises(mb.ModelError, match=f"'{handle.name}'"):
            r.effort(handle.name)
        return
    e = r.effort(handle)
    assert e.shape == ((3,) if not declared.effort_components else (3, len(declared.effort_components)))
    assert np.isfinite(e).all()
    assert declared.effort.split()[0] == "the" and ("(N" in declared.effort)


@pytest.mark.parametrize("kind", kinds())
def test_every_kind_has_a_derivative_check(kind):
    """The kind is in the model of its dimension that tests/analyses/test_derivatives.py
    checks against finite differences, its rows among the constraint
    equations there (joints, drivers) or its force changing the forces
    there; or DERIVATIVE_CHECKS names the test that checks it."""
    k = registry.BY_NAME[kind]
    m = _derivative_model(k.dimension)
    names = {kw["name"] for method, kw in m.elements if _kind_of(m, method) == kind}
    if names:
        core = m.compiled()
        if k.role in ("joint", "driver"):
            assert names & {core.constraint_name_of_row(r) for r in range(core.n_constraints)}, kind
        elif k.role == "force":  # at a random state, as there
            q0, _ = core.initial_state()
            rng = np.random.default_rng(7)
            q, v = q0 + 0.05 * rng.standard_normal(q0.size), rng.standard_normal(q0.size)
            Q = core.forces(q, v, 0.37)[0]
            assert np.abs(Q - _without(m, names).compiled().forces(q, v, 0.37)[0]).max() > 0.0, kind
        else:
            assert all(core.has(name) for name in names), kind
        return
    where = DERIVATIVE_CHECKS.get(kind)
    function = "every_kind()" if k.dimension == 2 else "every_spatial_kind()"
    assert where, f"{kind}: no derivative check (add it to {function} in tests/analyses/test_derivatives.py)"
    path, _, test = where.partition("::")
    source = (ROOT / path.split(":")[0]).read_text()
    assert not test or f"def {test}(" in source, where


@pytest.mark.parametrize("kind", kinds())
def test_every_kind_round_trips_through_a_scene(kind, tmp_path):
    m, handle = EXAMPLES[kind]()
    path = tmp_path / f"{kind}.toml"
    mb.save_scene(m, path)
    back = load_scene(path).model
    assert (back.dimension, back.gravity) == (m.dimension, m.gravity)
    assert [meth for meth, _ in back.elements] == [meth for meth, _ in m.elements]
    mine = dict(m.elements)[registry.BY_NAME[kind].method]
    theirs = dict(back.elements)[registry.BY_NAME[kind].method]
    for key, value in mine.items():
        other = theirs[key]
        if isinstance(value, (mb.TimeFunction,)):
            assert [value(t) for t in (0.0, 0.3)] == [other(t) for t in (0.0, 0.3)], key
        elif isinstance(value, tuple) and any(isinstance(v, mb.TimeFunction) for v in value):
            for a, b in zip(value, other):
                assert (a(0.3) if callable(a) else a) == (b(0.3) if callable(b) else b), key
        else:
            assert value == other, key


@pytest.mark.parametrize("kind", kinds())
def test_a_joint_kind_declares_the_coordinate_it_has(kind):
    """A joint kind with an angle or slide gives it (coordinate() next to its
    equations) and its registry entry names it; drivers, stops and friction
    find it there, never by the joint's kind."""
    m, handle = EXAMPLES[kind]()
    declared = registry.BY_NAME[kind].coordinate
    coordinate = m.compiled().joint_coordinate(handle.name)
    assert (coordinate is not None) == bool(declared)
    if coordinate is not None:
        assert coordinate["turns"] == ("angle" in declared)
        assert coordinate["slides"] == ("slide" in declared)
    assert {k.name for k in registry.ALL_KINDS if k.coordinate} == {
        "revolute", "translational", "spatial_revolute", "cylindrical", "spatial_translational"}


@pytest.mark.parametrize("kind", kinds())
def test_an_element_of_a_compiled_model_knows_its_kind(kind):
    """Result, the viewer and linearize ask the compiled model what an
    element was added as (registry.kind_of), not the name of its kind."""
    m, handle = EXAMPLES[kind]()
    core = m.compiled()
    assert registry.kind_of(core, handle.name) is registry.BY_NAME[kind]
    assert registry.is_driver(core, handle.name) == (registry.BY_NAME[kind].role == "driver")
    with pytest.raises(mb.ModelError, match="no body or element named 'nothing'"):
        registry.kind_of(core, "nothing")


@pytest.mark.parametrize("kind", kinds())
def test_every_kind_has_a_plotting_role(kind):
    """Drawings and summaries count an element by its role: a pendulum with
    a stop is "1 body, 1 joint, 1 stop"."""
    from lagmb import _drawing

    m, handle = EXAMPLES[kind]()
    role = registry.BY_NAME[kind].role
    assert role in registry.ROLES
    r = mb.simulate(m, 0.01, n_out=2)
    scene = _drawing.Scene(r)
    assert handle.name in scene.by_role[role]
    one, many = registry.ROLE_WORDS[role]
    n = len(scene.by_role[role])
    assert f"{n} {one if n == 1 else many}" in scene.summary().split(", ")


def test_the_modelling_reference_is_the_registry():
    """docs/modelling.md ends with the element reference that
    `python -m lagmb.registry` prints; regenerate it after changing a kind."""
    text = (ROOT / "docs" / "modelling.md").read_text()
    begin, end = "<!-- element reference: begin -->\n", "<!-- element reference: end -->"
    assert begin in text and end in text
    assert text.split(begin, 1)[1].split(end, 1)[0] == registry.markdown()
    for k in registry.ALL_KINDS:
        assert f"### {'' if k.dimension == 2 else 'spatial '}`{k.method}` ({k.name}:" in text


def test_lagmb_info_kinds_prints_the_reference():
    out = lagmb_command("info", "--kinds", timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout == registry.markdown()
    refused = lagmb_command("info", "--kinds", "--methods", timeout=120)
    assert refused.returncode == 2 and "--kinds" in refused.stderr


def test_methods_scene_schema_and_handles_come_from_the_registry():
    """Planar and spatial kinds share a method where they share a name
    (add_revolute); its signature shows the planar kind's parameters, its
    docstring both kinds'."""
    for k in registry.ALL_KINDS:
        method = getattr(mb.Model, k.method)
        shown = registry.BY_METHOD.get(k.method, k)
        params = list(inspect.signature(method).parameters)
        assert params == ["self", "name"] + [p.name for p in shown.params]
        assert " ".join(k.doc.split()) in " ".join(method.__doc__.split())
        for p in k.params:
            assert f"{p.name}: {registry.describe(p)}" in method.__doc__
        schema = ELEMENTS if k.dimension == 2 else SPATIAL_ELEMENTS
        assert schema[k.method].table == k.table and schema[k.method].type == k.type
    assert mb.handles.KINDS == {k.method: (k.name, k.role) for k in registry.KINDS}


def test_a_pendulum_with_a_stop_is_summarised_by_role():
    from lagmb import _drawing

    m, _ = example_stop()
    scene = _drawing.Scene(mb.simulate(m, 0.01, n_out=2))
    assert scene.summary() == "1 body, 1 joint, 1 stop"


def test_every_parameter_type_is_one_entry_checked_everywhere():
    """The types of parameters are one table in C++ (param_types()): every
    type a kind uses is in it, and each has its check in the Python API and
    its value kind in scene files."""
    from lagmb import _core
    from lagmb.model import _CHECKS
    from lagmb.scene.schema import _VALUE_OF

    names = [t["name"] for t in _core.param_types()]
    assert len(names) == len(set(names))
    assert {p.type for k in registry.ALL_KINDS for p in k.params} <= set(names)
    assert set(_CHECKS) == set(names)
    assert set(_VALUE_OF) == set(names)
    assert all(t["takes"] for t in _core.param_types())


def test_unknown_kind_and_parameter_are_model_errors():
    from lagmb import _core

    spec = _core.ModelSpec()
    with pytest.raises(mb.ModelError, match="no element kind 'hinge'.*revolute"):
        spec.add("hinge", "h", {})
    with pytest.raises(mb.ModelError, match="body has no parameter 'colour'"):
        spec.add("body", "b", {"mass": 1.0, "inertia": 1.0, "colour": 1.0})
    with pytest.raises(mb.ModelError, match="body 'b': 'mass' is required"):
        spec.add("body", "b", {"inertia": 1.0})
    assert len(spec) == 0
