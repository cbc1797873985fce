"""Effects a scene does not call for cost nothing (docs/design.md, section 2.3).

The assembly kernels add, per kind group and call, the number of elements
they evaluated into a counter (r.stats["element_evaluations"]). A 100-link
pendulum chain under gravity, and the same chain with every other kind of
element written in the scene file but disabled (``enabled = false``: read
and checked, not added), must take exactly the same steps and evaluate
exactly the same elements: counts are deterministic, so equality is exact.
Outputs that are not asked for (energy, reactions, residuals, friction) are
not computed: checked by counting the calls into the core.
"""

import numpy as np
import pytest

import lagmb as mb
from lagmb import _core
import builders  # noqa: E402  (tests/builders.py)

N_LINKS = 100


def chain_scene(n, disabled_kinds=False):
    """TOML of an n-link chain of uniform rods (L = 1 m, m = 1 kg) pinned
    end to end, released horizontal under gravity; with disabled_kinds,
    one element of every other kind (joints, drivers, forces, joint
    friction, contact, stops), each with enabled = false."""
    out = ["[model]", "gravity = [0.0, -9.81]", ""]
    for k in range(n):
        out += ["[[bodies]]", f'name = "rod{k}"', "mass = 1.0", f"inertia = {1 / 12!r}",
                f"position = [{k + 0.5!r}, 0.0]", ""]
    prev = "ground"
    for k in range(n):
        out += ["[[joints]]", 'type = "revolute"', f'name = "pin{k}"', f'body_i = "{prev}"',
                f'body_j = "rod{k}"', f"at = [{float(k)!r}, 0.0]", ""]
        prev = f"rod{k}"
    if disabled_kinds:
        off = "enabled = false"
        out += [
            "[[joints]]", 'type = "translational"', 'name = "x_slide"', 'body_i = "ground"',
            'body_j = "rod0"', "at = [0.5, 0.0]", "axis = [1.0, 0.0]", off, "",
            "[[joints]]", 'type = "weld"', 'name = "x_weld"', 'body_i = "rod0"', 'body_j = "rod1"', off, "",
            "[[joints]]", 'type = "distance"', 'name = "x_link"', 'body_i = "rod0"', "point_i = [0.5, 0.0]",
            'body_j = "rod2"', "point_j = [2.5, 0.0]", off, "",
            "[[joints]]", 'type = "pin_in_slot"', 'name = "x_slot"', 'body_i = "rod1"', 'body_j = "rod2"',
            "at = [2.0, 0.0]", "axis = [1.0, 0.0]", off, "",
            "[[joints]]", 'type = "gear"', 'name = "x_gear"', 'body_i = "rod3"', 'body_j = "rod4"',
            "ratio = -2.0", off, "",
            "[[joints]]", 'type = "rack_pinion"', 'name = "x_rack"', 'pinion = "rod5"', 'rack = "rod6"',
            "radius = 0.1", "axis = [1.0, 0.0]", off, "",
            "[[drivers]]", 'type = "joint"', 'name = "x_motor"', 'joint = "pin0"', "function = 0.0", off, "",
            "[[drivers]]", 'type = "body"', 'name = "x_lift"', 'body = "rod7"', 'coordinate = "y"',
            "function = 0.0", off, "",
            "[[forces]]", 'type = "spring_damper"', 'name = "x_spring"', 'body_i = "ground"',
            "point_i = [0.0, 1.0]", 'body_j = "rod0"', "point_j = [0.5, 0.0]", "stiffness = 10.0", off, "",
            "[[forces]]", 'type = "rotational_spring_damper"', 'name = "x_torsion"', 'body_i = "rod0"',
            'body_j = "rod1"', "stiffness = 1.0", "damping = 0.1", off, "",
            "[[forces]]", 'type = "force"', 'name = "x_push"', 'body = "rod3"', "force = [1.0, 0.0]", off, "",
            "[[forces]]", 'type = "torque"', 'name = "x_twist"', 'body = "rod4"', "torque = 1.0", off, "",
            "[[forces]]", 'type = "joint_friction"', 'name = "x_friction"', 'joint = "pin0"', "mu = 0.2",
            "pin_radius = 0.01", "viscous = 0.1", off, "",
            "[[forces]]", 'type = "contact"', 'name = "x_contact"', 'circle_body = "rod9"',
            "center = [9.5, 0.0]", "radius = 0.1", 'line_body = "ground"', "point = [0.0, -20.0]",
            "direction = [1.0, 0.0]", "stiffness = 1e6", "restitution = 0.8", off, "",
            "[[stops]]", 'name = "x_limit"', 'joint = "pin1"', "lower = -1.0", "upper = 1.0",
            "restitution = 0.5", off, "",
        ]
    return "\n".join(out) + "\n"


def run(path, **kw):
    scene = mb.load_scene(path)
    return scene.model, mb.simulate(scene.model, t_end=0.05, rtol=1e-6, atol=1e-8, n_out=2, **kw)


@pytest.mark.parametrize("formulation", ["ggl", "projection"])
def test_disabled_kinds_cost_nothing(tmp_path, formulation):
    """Same steps, residual and Jacobian evaluations, factorizations and
    element evaluations per step, to the count, and bit-identical motion."""
    plain, full = tmp_path / "chain.toml", tmp_path / "chain_all_kinds.toml"
    plain.write_text(chain_scene(N_LINKS))
    full.write_text(chain_scene(N_LINKS, disabled_kinds=True))
    m1, r1 = run(plain, formulation=formulation)
    m2, r2 = run(full, formulation=formulation)
    assert m1.elements == m2.elements  # the disabled ones were checked, not added
    keys = ["steps", "residual_evals", "jacobian_evals", "lu_factorizations", "newton_iterations",
            "augmented_factorizations", "projections", "element_evaluations", "root_evals", "events"]
    assert r1.stats["steps"] > 5 and r1.stats["element_evaluations"] > 0
    assert {k: r1.stats[k] for k in keys} == {k: r2.stats[k] for k in keys}
    per_step = r1.stats["element_evaluations"] / r1.stats["steps"]
    assert per_step == r2.stats["element_evaluations"] / r2.stats["steps"]
    assert np.array_equal(r1.q, r2.q) and np.array_equal(r1.lam, r2.lam)


def test_a_disabled_element_is_still_checked(tmp_path):
    """enabled = false does not switch the scene checks off: a bad key or a
    missing body in a disabled table is still an error naming it."""
    text = chain_scene(2) + '[[forces]]\ntype = "torque"\nname = "t"\nbody = "nobody"\ntorque = 1.0\nenabled = false\n'
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(mb.ModelError, match="nobody"):
        mb.load_scene(path)
    path.write_text(chain_scene(2) + '[[forces]]\ntype = "torque"\nname = "t"\nbody = "rod0"\n'
                    'torque = 1.0\nenabled = "no"\n')
    with pytest.raises(mb.ModelError, match="enabled"):
        mb.load_scene(path)


def test_the_counter_counts_each_kind_present():
    """One more element of a kind already present adds its evaluations: a
    12-link chain with a zero-stiffness torsion spring (a force kind the
    chain did not have) takes the same steps but evaluates more elements;
    the counter is what the test above relies on to see a cost."""
    def chain(extra):
        m = mb.Model(gravity=(0.0, -9.81))
        prev = m.ground
        for k in range(12):
            rod = m.add_body(f"rod{k}", mass=1.0, inertia=1 / 12, position=(k + 0.5, 0.0))
            m.add_revolute(f"pin{k}", prev, rod, at=(float(k), 0.0))
            prev = rod
        if extra:
            m.add_rotational_spring_damper("idle", "rod0", "rod1")
        return m

    r1 = mb.simulate(chain(False), t_end=0.05, n_out=2)
    r2 = mb.simulate(chain(True), t_end=0.05, n_out=2)
    assert r1.stats["steps"] == r2.stats["steps"]
    assert r2.stats["element_evaluations"] > r1.stats["element_evaluations"]


@pytest.fixture
def core_calls(monkeypatch):
    """Counts calls of the core's output functions (energy, reactions,
    residuals, friction) made through lagmb._core.Model."""
    calls = {}
    for name in ("energy", "reaction", "residual", "velocity_residual", "friction"):
        original = getattr(_core.Model, name)

        def counted(self, *a, _name=name, _original=original, **kw):
            calls[_name] = calls.get(_name, 0) + 1
            return _original(self, *a, **kw)

        monkeypatch.setattr(_core.Model, name, counted)
    return calls


def test_outputs_are_computed_only_when_asked(core_calls):
    """simulate and the arrays of a result compute no energy, reaction,
    residual or friction; each is computed once when asked (energy and
    residuals are cached: asking twice does not recompute)."""
    m = builders.pendulum()
    m.add_joint_friction("pin_friction", "pin", mu=0.2, pin_radius=0.01)
    r = mb.simulate(m, t_end=0.2, n_out=11)
    r.q, r.v, r.a, r.lam, r.body("rod").position, r.point("rod", (0.5, 0.0))
    assert core_calls == {}
    r.energy
    r.energy
    assert core_calls == {"energy": 1}
    r.residual
    r.residual
    r.reaction("pin", frame="joint")
    r.friction_power("pin_friction")
    assert core_calls == {"energy": 1, "residual": 1, "reaction": 1, "friction": 1}


def test_an_element_using_a_disabled_one_is_told_so(tmp_path):
    """A stop on a disabled joint: the error says the joint is disabled (not
    'defined later'), names where, and asks to disable its users too."""
    text = chain_scene(2) + ('[[joints]]\ntype = "revolute"\nname = "extra"\nbody_i = "rod0"\n'
                             'body_j = "rod1"\nat = [1.0, 0.0]\nenabled = false\n\n'
                             '[[stops]]\nname = "limit"\njoint = "extra"\nlower = -1.0\n')
    path = tmp_path / "uses_disabled.toml"
    path.write_text(text)
    with pytest.raises(mb.ModelError, match=r"joint 'extra' is disabled .*enabled = false.*disable"):
        mb.load_scene(path)


def spatial_chain(shapes=False, far_contact=False):
    """A 6-link spatial pendulum chain (revolutes about y) under gravity;
    with shapes, a collision box on every link and a ground plane that no
    contact pairs; with far_contact, a sphere on the last link paired with a
    plane 100 m below."""
    m = mb.Model(gravity=(0.0, 0.0, -9.81), dimension=3)
    prev = m.ground
    for k in range(6):
        rod = m.add_body(f"rod{k}", mass=1.0, inertia=(1e-3, 1 / 12, 1 / 12), position=(k + 0.5, 0.0, 0.0))
        m.add_revolute(f"pin{k}", prev, rod, at=(float(k), 0.0, 0.0), axis=(0.0, 1.0, 0.0))
        if shapes:
            m.add_shape(rod, "box", (1.0, 0.1, 0.1), (k + 0.5, 0.0, 0.0), role="collision")
        prev = rod
    if shapes:
        m.add_shape(m.ground, "plane", (), (0.0, 0.0, -10.0), role="collision")
    if far_contact:
        ball = m.add_shape(prev, "sphere", (0.1,), (5.5, 0.0, 0.0), role="collision")
        floor = m.add_shape(m.ground, "plane", (), (0.0, 0.0, -100.0), role="collision")
        m.add_contact("far", ball, floor, stiffness=1e6, restitution=0.5, friction=0.5)
    return m


def test_shapes_no_contact_pairs_cost_nothing_and_far_contacts_cost_their_gaps():
    """Collision shapes that no contact pairs are pictures: the chain with a
    box on every link and a ground plane takes the same steps and evaluates
    the same elements, bit for bit. A contact whose shapes stay 100 m apart
    adds its event functions (one gap read from the bounding spheres) and
    its force evaluations, zero: under one method (GGL: "auto" takes it for
    a model with contacts), the same steps and the same motion."""
    keys = ["steps", "residual_evals", "jacobian_evals", "lu_factorizations", "newton_iterations",
            "element_evaluations"]
    plain = mb.simulate(spatial_chain(), 0.5, rtol=1e-7, atol=1e-9, n_out=3)
    shaped = mb.simulate(spatial_chain(shapes=True), 0.5, rtol=1e-7, atol=1e-9, n_out=3)
    assert {k: plain.stats[k] for k in keys} == {k: shaped.stats[k] for k in keys}
    assert np.array_equal(plain.q, shaped.q)
    plain = mb.simulate(spatial_chain(), 0.5, rtol=1e-7, atol=1e-9, n_out=3, method="ggl")
    far = mb.simulate(spatial_chain(far_contact=True), 0.5, rtol=1e-7, atol=1e-9, n_out=3, method="ggl")
    assert far.stats["steps"] == plain.stats["steps"] and far.stats["events"] == 0
    assert np.array_equal(plain.q, far.q) and far.stats["root_evals"] > 0
