"""The editable model and the compiled one (lagmb/spec/spec.hpp).

mb.Model is a description (a ModelSpec in the core); compiled() gives the
immutable core Model that runs read. These tests check the split: the
compiled model stays what it was when the description changes, copies are
independent, a refused element leaves the description as it was, and a run
never changes the compiled model.
"""

import copy

import numpy as np
import pytest

import lagmb as mb
from lagmb import _core
from builders import pendulum


def test_compiled_model_is_built_once_and_kept_until_the_model_changes():
    m = pendulum()
    first = m.compiled()
    assert m.compiled() is first
    assert (first.n_coordinates, first.n_constraints) == (3, 2)
    tip = m.add_body("tip", 0.5, 0.01, position=(1.5, 0.0))
    m.add_revolute("elbow", "rod", tip, at=(1.0, 0.0))
    second = m.compiled()
    assert second is not first
    assert (second.n_coordinates, second.n_constraints) == (6, 4)
    # the first is immutable: what was compiled stays as it was
    assert (first.n_coordinates, first.n_constraints) == (3, 2)
    assert first.finalized and second.finalized



def test_each_element_is_built_once_to_describe_and_compile_a_model():
    """add() checks an element by building it into the model so far, and
    compiling finalizes that model: a 20-link chain's 40 elements are built
    40 times, not 80. Adding after a compile builds the description again
    (the compiled model is immutable), once; a model holding a Python
    function is built again when compiled (each compiled model owns its
    references to the callables)."""
    from builders import rod_chain

    m = rod_chain(20)
    spec = m._spec
    assert len(spec) == spec.element_builds == 40
    first = m.compiled()
    assert spec.element_builds == 40 and first.n_coordinates == 60
    m.add_body("extra", 1.0, 0.1, position=(30.0, 0.0))
    assert spec.element_builds == 40 + 41  # the 40 again, then the new one
    second = m.compiled()
    assert spec.element_builds == 81
    assert (first.n_coordinates, second.n_coordinates) == (60, 63)

    pushed = rod_chain(2)
    pushed.add_force("push", "rod1", (lambda t: 1.0, 0.0))
    described = pushed._spec.element_builds
    pushed.compiled()
    assert pushed._spec.element_builds == 2 * described

def test_a_result_keeps_the_model_it_was_computed_with():
    """Growing the model after a run leaves the run's compiled model, its
    accessors and its drawing as they were."""
    from lagmb import _drawing

    m = pendulum()
    r = mb.simulate(m, 0.2, n_out=3)
    tip = m.add_body("tip", 0.5, 0.01, position=(1.5, 0.0))
    m.add_revolute("elbow", "rod", tip, at=(1.0, 0.0))
    assert r._core.n_coordinates == 3 and m.compiled().n_coordinates == 6
    assert r.q.shape == (3, 3)
    assert np.isfinite(r.reaction("pin")).all()
    scene = _drawing.Scene(r)
    assert scene.bodies == ["rod"] and scene.joints == ["pin"]
    assert scene.summary() == "1 body, 1 joint"


def test_copies_are_edited_independently():
    m = pendulum()
    twin = m.copy()
    assert copy.copy(m).elements == m.elements
    twin.add_torque("push", "rod", 2.0)
    assert not m.compiled().has("push") and twin.compiled().has("push")
    assert [kw["name"] for _, kw in m.elements] == ["rod", "pin"]
    assert [kw["name"] for _, kw in twin.elements] == ["rod", "pin", "push"]
    assert twin.bodies[0].model is twin and m.bodies[0].model is m
    free = mb.simulate(m, 0.5, n_out=2).q[-1]
    pushed = mb.simulate(twin, 0.5, n_out=2).q[-1]
    assert pushed[2] > free[2] + 0.1  # the torque of 2 N m turns the copy further up
    # the original compiles to the same model as before the copy was edited
    assert m.compiled().n_coordinates == twin.compiled().n_coordinates == 3


def test_handles_belong_to_their_copy():
    m = pendulum()
    twin = m.copy()
    with pytest.raises(mb.ModelError, match="handle of another model"):
        twin.add_torque("push", m.bodies[0], 1.0)
    twin.add_torque("push", twin.bodies[0], 1.0)


def test_a_refused_element_leaves_the_model_as_it_was():
    m = pendulum()
    weld = m.add_weld("glue", m.ground, m.add_body("block", 1.0, 0.1, position=(3.0, 0.0)))
    before = m.compiled()
    with pytest.raises(mb.ModelError, match="revolute or translational"):
        m.add_joint_friction("drag", weld, mu=0.1)
    assert "drag" not in [kw["name"] for _, kw in m.elements]
    assert m.compiled() is before  # nothing changed, nothing to recompile
    m.add_joint_friction("drag", "pin", viscous=0.1)  # the name is still free
    r = mb.simulate(m, 0.1, n_out=2)
    assert np.isfinite(r.q).all()


def test_the_core_spec_checks_each_element_against_those_before():
    spec = _core.ModelSpec()
    spec.add("body", "rod", {"mass": 1.0, "inertia": 0.1})
    with pytest.raises(mb.ModelError, match="duplicate name 'rod'"):
        spec.add("body", "rod", {"mass": 1.0, "inertia": 0.1})
    with pytest.raises(mb.ModelError, match="body index 5 does not exist"):
        spec.add("revolute", "pin", {"body_i": -1, "body_j": 5, "at": (0.0, 0.0)})
    spec.add("revolute", "pin", {"body_i": -1, "body_j": 0, "at": (0.0, 0.0)})
    assert len(spec) == 2
    twin = copy.copy(spec)
    twin.add("torque", "push", {"body": 0, "torque": _core.constant(1.0)})
    assert (len(spec), len(twin)) == (2, 3)
    assert not spec.compile().has("push") and twin.compile().has("push")


def test_a_run_does_not_change_the_compiled_model():
    m = pendulum()
    core = m.compiled()
    q0, v0 = core.initial_state()
    mb.simulate(m, 0.3, n_out=2)
    q1, v1 = core.initial_state()
    np.testing.assert_array_equal(q0, q1)
    np.testing.assert_array_equal(v0, v1)
    assert m.compiled() is core


def test_none_means_the_default():
    m = pendulum()
    m.add_force("push", "rod", (1.0, 0.0), point=None, local=None)
    m.add_body("free", 1.0, 0.1, position=None, velocity=None)
    assert dict(m.elements)["add_force"]["local"] is False
    assert m.compiled().initial_state()[0][3:5].tolist() == [0.0, 0.0]


def _self_referencing(n_out=2):
    """A model whose torque callable refers to the model itself."""
    m = pendulum()
    m.add_torque("tau", "rod", lambda t, m=m: 0.1 * len(m.bodies))
    return m


def test_copies_and_compiled_models_are_collected_with_their_callables():
    import gc
    import weakref

    m = _self_referencing()
    twin = m.copy()
    mb.simulate(twin, 0.05, n_out=2)
    refs = [weakref.ref(m), weakref.ref(twin)]
    del m, twin
    gc.collect()
    assert [r() for r in refs] == [None, None]


def test_a_compiled_model_outliving_its_model_keeps_its_callables():
    """The collector may take the model and its spec; a compiled model still
    held elsewhere keeps working callables."""
    import gc

    m = _self_referencing()
    r = mb.simulate(m, 0.05, n_out=2)
    core = r._core
    del m, r
    gc.collect()
    again = _core.simulate(core, {"t_end": 0.05, "n_out": 2}, None)
    assert np.isfinite(again["q"]).all()


def test_the_description_is_the_one_copy_of_the_model():
    """mb.Model keeps the core's description and nothing beside it:
    elements() reads the spec back as the user gave it (bodies by name,
    points as tuples, the same mb.Input and callable, built-in functions
    equal to the ones given, a number where a function goes as a constant)."""
    m = pendulum()
    push = mb.Input(0.0)

    def wind(t):
        return 0.1 * t

    m.add_force("shove", "rod", (1.5, push), point=(1.0, 0.0))
    m.add_torque("gust", "rod", wind)
    m.add_rotational_spring_damper("coil", m.ground, "rod", stiffness=2.0, torque=mb.Linear(0.5, 0.25))
    assert not {"_elements", "_bodies"} & set(vars(m))
    given = dict((kw["name"], kw) for _, kw in m.elements)
    assert given["rod"]["position"] == (0.5, 0.0) and given["pin"]["body_i"] == "ground"
    force = given["shove"]["force"]
    assert force[1] is push and force[0] == mb.Constant(1.5)
    assert given["gust"]["torque"] is wind
    assert given["coil"]["torque"] == mb.Linear(0.5, 0.25)
    # the core keeps a linear function as one (its text reads back exactly)
    assert _core.linear(0.5, 0.25).text == "linear 0.5 0.25"
    # replaying the description rebuilds the same model
    again = mb.Model(gravity=m.gravity)
    for method, kwargs in m.elements:
        getattr(again, method)(**kwargs)
    assert again.elements == m.elements
    np.testing.assert_array_equal(mb.simulate(again, 0.2, n_out=3).q, mb.simulate(m, 0.2, n_out=3).q)
