"""Handles everywhere: every add_* / drive_* of mb.Model returns a handle of
what it added; the handle prints as its name and goes wherever that name
goes (joints of stops, friction and drivers; r.reaction, r.effort, r.body,
...). A handle of another model, or of the wrong role (a driver where a
joint belongs), is refused with a ModelError saying what was expected.
"""

import inspect

import numpy as np
import pytest

import lagmb as mb


def pendulum():
    """A horizontal rod pinned at the origin, released under gravity."""
    m = mb.Model(gravity=(0.0, -9.81))
    rod = m.add_body("rod", mass=1.0, inertia=1 / 12, position=(0.5, 0.0))
    pin = m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m, rod, pin


# --- the user story ----------------------------------------------------------


def test_a_joint_handle_limits_brakes_and_reports_its_joint():
    """``pin = m.add_revolute(...); m.add_stop("s", pin, ...)`` used to fail
    with "joint must be a joint name, got None"."""
    m, rod, pin = pendulum()
    stop = m.add_stop("s", pin, lower=-0.5, restitution=0.8)
    friction = m.add_joint_friction("f", pin, mu=0.2, pin_radius=0.01)
    r = mb.simulate(m, t_end=0.6, n_out=31)

    np.testing.assert_array_equal(r.reaction(pin), r.reaction("pin"))
    np.testing.assert_array_equal(r.reaction(pin, frame="joint"), r.reaction("pin", frame="joint"))
    np.testing.assert_array_equal(r.multipliers(pin), r.multipliers("pin"))
    np.testing.assert_array_equal(r.friction(friction), r.friction("f"))
    np.testing.assert_array_equal(r.friction_power(friction), r.friction_power("f"))
    np.testing.assert_array_equal(r.body(rod).angle, r.body("rod").angle)
    np.testing.assert_array_equal(r.point(rod, (0.5, 0.0)), r.point("rod", (0.5, 0.0)))
    # the rod hit the stop: events name it as the handle prints
    impacts = [e for e in r.events if e["kind"] == "impact"]
    assert impacts and impacts[0]["element"] == str(stop) == "s"
    assert r.body(rod).angle.min() >= -0.5 - 1e-6


def test_a_driver_handle_gives_its_effort():
    m, rod, pin = pendulum()
    motor = m.drive_joint("motor", pin, mb.Linear(2.0))
    r = mb.simulate(m, t_end=0.5, n_out=11)
    np.testing.assert_array_equal(r.effort(motor), r.effort("motor"))
    np.testing.assert_array_equal(r.reaction(motor), r.reaction("motor"))
    # a body driver too, on a free block
    m = mb.Model()
    block = m.add_body("block", mass=2.0, inertia=0.1)
    push = m.drive_body("push", block, "x", mb.Polynomial([0.0, 0.0, 0.5]))  # x = t^2 / 2
    m.drive_body("hold_y", block, "y", 0.0)
    m.drive_body("hold_angle", block, "angle", 0.0)
    r = mb.simulate(m, t_end=1.0, n_out=5)
    np.testing.assert_allclose(r.effort(push), 2.0, rtol=1e-9)  # F = m a


def test_equilibrium_accepts_handles():
    m, rod, pin = pendulum()
    m.add_rotational_spring_damper("spring", m.ground, rod, stiffness=20.0)
    eq = mb.equilibrium(m)
    assert eq.body(rod).angle == eq.body("rod").angle
    np.testing.assert_array_equal(eq.reaction(pin), eq.reaction("pin"))


def test_model_questions_and_scene_output_accept_handles(tmp_path):
    m, rod, pin = pendulum()
    motor = m.drive_joint("motor", pin, mb.Linear(1.0))
    assert m.outline(rod) == m.outline("rod")
    path = tmp_path / "p.toml"
    mb.save_scene(m, path, {"t_end": 0.1}, {"reactions": [pin], "efforts": [motor]})
    scene = mb.load_scene(path)
    assert scene.output["reactions"] == ["pin"] and scene.output["efforts"] == ["motor"]


def test_animate_traces_a_body_given_by_its_handle(tmp_path):
    pytest.importorskip("PIL")
    pytest.importorskip("matplotlib")
    from lagmb import plotting

    m, rod, pin = pendulum()
    r = mb.simulate(m, t_end=0.2, n_out=5)
    out = plotting.animate(r, str(tmp_path / "p.gif"), max_frames=3, trace=(rod, (0.5, 0.0)))
    assert (tmp_path / "p.gif").exists() and out


# --- every add_* / drive_* returns a handle ------------------------------------

def _add_everything(m):
    """One example call of each add_* / drive_* method, by method name.
    The model need not run: each element only has to be accepted."""
    g = m.ground
    bodies = {}

    def body(name, x):
        bodies[name] = m.add_body(name, mass=1.0, inertia=0.1, position=(x, 0.0))
        return bodies[name]

    a, b, c, d, e, f = (body(n, x) for n, x in zip("abcdef", range(1, 7)))
    p = m.add_particle("p", mass=1.0, position=(0.0, -1.0))
    return {
        "add_body": lambda: body("body", 9.0),
        "add_particle": lambda: m.add_particle("particle", mass=1.0, position=(0.0, -2.0)),
        "add_revolute": lambda: m.add_revolute("revolute", g, a, at=(0.0, 0.0)),
        "add_translational": lambda: m.add_translational("translational", g, b, at=(2.0, 0.0),
                                                         axis=(1.0, 0.0)),
        "add_weld": lambda: m.add_weld("weld", b, c),
        "add_distance": lambda: m.add_distance("distance", a, (1.0, 0.0), p, (0.0, -1.0)),
        "add_pin_in_slot": lambda: m.add_pin_in_slot("pin_in_slot", g, d, at=(4.0, 0.0),
                                                     axis=(0.0, 1.0)),
        "add_gear": lambda: m.add_gear("gear", a, e, ratio=-2.0),
        "add_rack_pinion": lambda: m.add_rack_pinion("rack_pinion", f, g, radius=0.5,
                                                     axis=(1.0, 0.0)),
        "drive_joint": lambda: m.drive_joint("joint_driver", "revolute", 0.0),
        "drive_body": lambda: m.drive_body("body_driver", c, "angle", 0.0),
        "add_stop": lambda: m.add_stop("stop", "translational", lower=-1.0),
        "add_contact": lambda: m.add_contact("contact", e, (5.0, 0.0), 0.1, g, (0.0, -3.0),
                                             (1.0, 0.0), stiffness=1e6, restitution=0.5),
        "add_spring_damper": lambda: m.add_spring_damper("spring_damper", g, (0.0, 1.0), a,
                                                         (1.0, 0.0), stiffness=10.0),
        "add_rotational_spring_damper": lambda: m.add_rotational_spring_damper(
            "rotational_spring_damper", g, a, stiffness=1.0),
        "add_force": lambda: m.add_force("force", p, (0.0, 1.0)),
        "add_torque": lambda: m.add_torque("torque", a, 1.0),
        "add_joint_friction": lambda: m.add_joint_friction("joint_friction", "revolute", mu=0.1,
                                                           pin_radius=0.01),
    }


def _add_everything_spatial(m):
    """The same for a spatial model (Model(dimension=3))."""
    g = m.ground
    bodies = {}

    def body(name, x):
        bodies[name] = m.add_body(name, mass=1.0, inertia=(0.1, 0.1, 0.1), position=(x, 0.0, 0.0))
        return bodies[name]

    a, b, c, d, e, f = (body(n, x) for n, x in zip("abcdef", range(1, 7)))
    return {
        "add_body": lambda: body("body", 9.0),
        "add_spherical": lambda: m.add_spherical("spherical", g, a, at=(0.0, 0.0, 0.0)),
        "add_revolute": lambda: m.add_revolute("revolute", a, b, at=(1.5, 0.0, 0.0), axis=(0.0, 0.0, 1.0)),
        "add_translational": lambda: m.add_translational("translational", g, c, at=(3.0, 0.0, 0.0),
                                                         axis=(1.0, 0.0, 0.0)),
        "add_cylindrical": lambda: m.add_cylindrical("cylindrical", c, d, at=(3.5, 0.0, 0.0), axis=(1.0, 0.0, 0.0)),
        "add_universal": lambda: m.add_universal("universal", d, e, at=(4.5, 0.0, 0.0), axis_i=(0.0, 1.0, 0.0),
                                                 axis_j=(0.0, 0.0, 1.0)),
        "add_planar": lambda: m.add_planar("planar", g, f, at=(6.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0)),
        "add_weld": lambda: m.add_weld("weld", e, bodies["body"]),
        "add_distance": lambda: m.add_distance("distance", a, (1.0, 0.0, 0.0), f, (6.0, 0.0, 0.0)),
        "drive_joint": lambda: m.drive_joint("joint_driver", "revolute", 0.0),
        "drive_body": lambda: m.drive_body("body_driver", f, "z", 0.0),
        "add_spring_damper": lambda: m.add_spring_damper("spring_damper", g, (0.0, 1.0, 0.0), a,
                                                         (1.0, 0.0, 0.0), stiffness=10.0),
        "add_rotational_spring_damper": lambda: m.add_rotational_spring_damper(
            "rotational_spring_damper", "revolute", stiffness=1.0),
        "add_servo": lambda: m.add_servo("servo", "revolute", target=0.1, kp=1.0, kd=0.1),
        "add_bushing": lambda: m.add_bushing("bushing", b, c, at=(2.5, 0.0, 0.0), stiffness=(1.0, 1.0, 1.0)),
        "add_force": lambda: m.add_force("force", a, (0.0, 1.0, 0.0)),
        "add_torque": lambda: m.add_torque("torque", a, (1.0, 0.0, 0.0)),
        "add_stop": lambda: m.add_stop("stop", "translational", lower=-1.0, upper=1.0),
        "add_joint_coupling": lambda: m.add_joint_coupling("joint_coupling", "translational", leader="revolute"),
        "add_joint_friction": lambda: m.add_joint_friction("joint_friction", "revolute", viscous=0.1),
        "add_contact": lambda: m.add_contact("contact", m.add_shape(a, "sphere", (0.1,), (1.0, 0.0, 0.0), role="collision"),
                                             m.add_shape(g, "plane", (), role="collision"), stiffness=1e6,
                                             restitution=0.5),
    }


def _public_add_and_drive_methods(dimension=2):
    """Model's add_* / drive_* methods that take elements in a model of this dimension."""
    from lagmb.registry import BY_METHOD, SPATIAL_BY_METHOD

    kinds = BY_METHOD if dimension == 2 else SPATIAL_BY_METHOD
    names = [name for name, f in inspect.getmembers(mb.Model, inspect.isfunction)
             if name.startswith(("add_", "drive_")) and name not in ("add_frame", "add_shape", "add_joint_alias")]
    # each from the registry (frames, shapes and joint aliases are no part of the equations: no elements)
    assert set(names) == set(BY_METHOD) | set(SPATIAL_BY_METHOD)
    return sorted(name for name in names if name in kinds)


def test_every_spatial_add_and_drive_method_returns_a_handle_and_planar_ones_are_refused():
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
    examples = _add_everything_spatial(m)
    methods = _public_add_and_drive_methods(3)
    assert set(examples) == set(methods)
    for method in examples:
        h = examples[method]()
        assert isinstance(h, mb.Handle) and h.model is m and m.elements[-1][0] == method
        assert repr(h) == f"<lagmb {h.kind} {h.name!r}>"
    with pytest.raises(mb.ModelError, match="add_gear: gear elements are planar only; this model has dimension 3"):
        m.add_gear("gear", "a", "b", ratio=2.0)
    with pytest.raises(mb.ModelError, match="spherical elements are spatial only; this model has dimension 2"):
        mb.Model().add_spherical("ball", "ground", "a", at=(0.0, 0.0, 0.0))


def test_every_add_and_drive_method_returns_a_handle_printed_as_its_name(capsys):
    """Walks Model's add_* / drive_* methods: a new kind of element without a
    handle (or without an example here) fails this test."""
    m = mb.Model(gravity=(0.0, -9.81))
    examples = _add_everything(m)
    methods = _public_add_and_drive_methods()
    assert len(methods) >= 18
    missing = sorted(set(methods) - set(examples))
    assert not missing, f"add an example call of {missing} to _add_everything"
    assert set(examples) == set(methods)
    roles = set()
    for method in examples:  # in the order written (joints before what refers to them)
        h = examples[method]()
        assert isinstance(h, mb.Handle), f"{method} returned {h!r}"
        name = m.elements[-1][1]["name"]
        assert m.elements[-1][0] == method
        assert str(h) == name and h.name == name and f"{h}" == name and f"{h:>30}" == f"{name:>30}"
        print(h)
        assert capsys.readouterr().out == name + "\n"
        assert repr(h) == f"<lagmb {h.kind} {name!r}>"
        assert h.model is m
        roles.add(h.role)
    assert roles == {"body", "joint", "driver", "force", "friction", "stop", "contact"}
    assert isinstance(m.ground, mb.Body) and str(m.ground) == "ground"
    assert repr(m.add_body("wheel", mass=1.0, inertia=0.1)) == "<lagmb body 'wheel'>"
    assert repr(m.add_particle("bob", mass=1.0, position=(0.0, 5.0))) == "<lagmb particle 'bob'>"
    assert all(isinstance(b, mb.Body) for b in m.bodies)


def test_handles_compare_by_model_and_name_never_equal_to_strings():
    m, rod, pin = pendulum()
    again = mb.Handle("pin", m, "revolute", "joint")
    assert again == pin and hash(again) == hash(pin) and len({pin, again}) == 1
    assert pin != "pin" and "pin" != pin  # documented: compare pin.name == "pin"
    assert pin.name == "pin" and str(pin) == "pin"
    assert rod == m.bodies[0] and rod != pin
    other, other_rod, other_pin = pendulum()
    assert other_pin != pin and other_rod != rod
    with pytest.raises(AttributeError):
        pin.name = "renamed"


# --- refusals -----------------------------------------------------------------

def test_a_handle_from_another_model_is_refused_naming_both():
    m, rod, pin = pendulum()
    other, other_rod, other_pin = pendulum()
    alien = other.add_body("alien", mass=1.0, inertia=0.1)
    with pytest.raises(mb.ModelError, match="another model") as e:
        m.add_stop("limit", other_pin, lower=-1.0)
    message = str(e.value)
    assert "stop 'limit'" in message and "'pin'" in message
    assert f"0x{id(other):x}" in message and f"0x{id(m):x}" in message  # both models
    with pytest.raises(mb.ModelError, match=r"revolute 'bridge': body_j .*'alien'.* another model"):
        m.add_revolute("bridge", rod, alien, at=(1.0, 0.0))
    r = mb.simulate(m, t_end=0.1, n_out=3)
    for ask in (lambda: r.reaction(other_pin), lambda: r.body(other_rod),
                lambda: r.point(other_rod, (0.0, 0.0)), lambda: mb.equilibrium(m).reaction(other_pin)):
        with pytest.raises(mb.ModelError, match="another model"):
            ask()
    with pytest.raises(mb.ModelError, match="another model"):
        mb.save_scene(m, "never-written.toml", output={"reactions": [other_pin]})


@pytest.mark.parametrize("ask, expected, given", [
    (lambda m, h: m["m"].add_stop("s", h["motor"], lower=-1.0), "a joint", "joint_driver 'motor'"),
    (lambda m, h: m["m"].add_joint_friction("f", h["rod"], mu=0.1), "a joint", "body 'rod'"),
    (lambda m, h: m["m"].drive_joint("d", h["spring"], 0.0), "a joint", "rotational_spring_damper"),
    (lambda m, h: m["m"].add_revolute("x", h["pin"], h["rod"], at=(0.0, 0.0)), "a body", "revolute"),
    (lambda m, h: m["m"].add_torque("t", h["motor"], 1.0), "a body", "joint_driver"),
    (lambda m, h: m["r"].effort(h["rod"]), "a joint or a driver or a stop", "body 'rod'"),
    (lambda m, h: m["r"].reaction(h["spring"]), "a joint or a driver", "rotational_spring_damper"),
    (lambda m, h: m["r"].friction(h["pin"]), "a joint friction", "revolute 'pin'"),
    (lambda m, h: m["r"].body(h["motor"]), "a body", "joint_driver 'motor'"),
])
def test_a_handle_of_the_wrong_role_is_refused_saying_what_was_expected(ask, expected, given):
    m, rod, pin = pendulum()
    spring = m.add_rotational_spring_damper("spring", m.ground, rod, stiffness=1.0)
    motor = m.drive_joint("motor", pin, mb.Linear(1.0))
    r = mb.simulate(m, t_end=0.1, n_out=3)
    handles = {"rod": rod, "pin": pin, "spring": spring, "motor": motor}
    with pytest.raises(mb.ModelError, match=f"expected {expected} ") as e:
        ask({"m": m, "r": r}, handles)
    assert given in str(e.value)


def test_something_neither_name_nor_handle_is_refused():
    m, rod, pin = pendulum()
    with pytest.raises(mb.ModelError, match=r"stop 's': joint: expected a joint .*got None"):
        m.add_stop("s", None, lower=-1.0)
    with pytest.raises(mb.ModelError, match="expected a body"):
        m.add_revolute("x", 3, rod, at=(0.0, 0.0))
    r = mb.simulate(m, t_end=0.1, n_out=3)
    with pytest.raises(mb.ModelError, match="expected a joint or a driver"):
        r.reaction(object())


def test_what_a_model_has_is_an_attribute_and_the_old_call_warns():
    """One rule (as MuJoCo's and numpy's): what a model has is an
    attribute (bodies, elements, parameters, parameter_info,
    coordinate_names, frames, shapes), what is computed a method
    (degrees_of_freedom(), assemble(), rank()). The method spelling of an
    attribute (m.elements(), m.parameters(): before 0.1.0's release; and
    m.bodies(), which was a TypeError) still gives the same value, with a
    DeprecationWarning naming the attribute."""
    import pickle

    m = mb.Model(gravity=(0.0, -9.81))
    rod = m.add_body("rod", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    assert [b.name for b in m.bodies] == ["rod"]
    assert [method for method, _ in m.elements] == ["add_body", "add_revolute"]
    assert m.parameters["rod.mass"] == 1.0 and m.coordinate_names == ["rod.x", "rod.y", "rod.angle"]
    assert {p["name"] for p in m.parameter_info} == set(m.parameters)
    assert m.degrees_of_freedom() == 1
    for name in ("bodies", "elements", "parameters", "parameter_info", "coordinate_names", "frames", "shapes"):
        with pytest.warns(DeprecationWarning, match=f"Model.{name} is an attribute .*: write m.{name}, not "
                                                    rf"m.{name}\(\)"):
            called = getattr(m, name)()
        assert called == getattr(m, name) and type(called) in (list, dict)
    # (what pickles or goes to JSON is the plain list or dict)
    assert type(pickle.loads(pickle.dumps(m.parameters))) is dict
    assert type(pickle.loads(pickle.dumps(m.elements))) is list
