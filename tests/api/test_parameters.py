"""Run-time parameters: the numbers given to a model's elements, changed
per run without rebuilding the model (docs/design.md, 2.2, "Run-time parameters").

A run with parameters={...} must be the run of a model built with those
values, bit for bit; the model itself keeps its values; one compiled model
runs on many threads at once, each with its own inputs and parameters.
"""

import threading

import numpy as np
import pytest

import lagmb as mb
import builders

G = 9.81


def pendulum(mass=1.0, length=1.0, stiffness=0.0, push=None, inertia=None):
    """A rod pinned at the origin, a spring to a point above, and a force
    input (``push``) at its tip; the inertia of a uniform rod unless given."""
    m = builders.pendulum(L=length, m=mass, g=G, inertia=inertia)
    m.add_spring_damper("spring", m.ground, (0.0, 1.0), "rod", (length, 0.0), stiffness=stiffness, free_length=1.0)
    if push is not None:
        m.add_force("tip", "rod", (0.0, push), point=(length, 0.0))
    return m


def same_run(a, b):
    """Every output of two results equal, bit for bit."""
    for x, y in ((a.t, b.t), (a.q, b.q), (a.v, b.v), (a.a, b.a), (a.lam, b.lam)):
        assert np.array_equal(x, y)


def test_parameters_are_named_as_the_fmu_names_them():
    p = pendulum(stiffness=20.0).parameters
    assert p["rod.mass"] == 1.0
    assert p["rod.inertia"] == pytest.approx(1 / 12)
    assert (p["rod.position.x"], p["rod.position.y"]) == (0.5, 0.0)
    # a body's initial angle: "rod.angle" is the coordinate (an FMU output)
    assert p["rod.angle.start"] == 0.0 and "rod.angle" not in p
    assert (p["pin.at.x"], p["pin.at.y"]) == (0.0, 0.0)
    assert p["spring.stiffness"] == 20.0 and p["spring.free_length"] == 1.0
    info = {d["name"]: d for d in pendulum().parameter_info}
    assert info["rod.mass"]["unit"] == "kg" and info["rod.mass"]["element"] == "rod"
    assert info["pin.at.y"]["key"] == "at" and info["pin.at.y"]["component"] == 1


def test_spatial_parameters_have_three_components():
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    b = m.add_body("b", mass=2.0, inertia=(0.1, 0.2, 0.3), position=(0.0, 0.0, -1.0))
    m.add_spherical("ball", m.ground, b, at=(0.0, 0.0, 0.0))
    p = m.parameters
    assert p["b.mass"] == 2.0
    assert [p[f"b.position.{c}"] for c in "xyz"] == [0.0, 0.0, -1.0]
    assert [p[f"ball.at.{c}"] for c in "xyz"] == [0.0, 0.0, 0.0]
    assert not any(name.startswith("b.inertia") or name.startswith("b.orientation") for name in p)


def test_a_run_with_parameters_is_the_run_of_a_model_built_with_them():
    """A heavier, longer rod on a stiffer spring: the run of the default
    model with parameters equals the run of a model built with the values."""
    changed = {"rod.mass": 2.5, "rod.inertia": 2.5 * 1.2**2 / 12, "rod.position.x": 0.6, "pin.at.x": 0.0,
               "spring.point_j.x": 1.2, "spring.stiffness": 40.0}
    r = mb.simulate(pendulum(stiffness=20.0), 1.0, rtol=1e-8, parameters=changed)
    built = mb.simulate(pendulum(mass=2.5, length=1.2, stiffness=40.0), 1.0, rtol=1e-8)
    same_run(r, built)
    assert np.array_equal(r.reaction("pin"), built.reaction("pin"))
    assert np.array_equal(r.energy, built.energy)
    # and it is another motion than the default one
    default = mb.simulate(pendulum(stiffness=20.0), 1.0, rtol=1e-8)
    assert np.abs(default.q - r.q).max() > 1e-2


def test_the_model_keeps_its_values():
    m = pendulum()
    before = mb.simulate(m, 0.5)
    mb.simulate(m, 0.5, parameters={"rod.mass": 3.0})
    assert m.parameters["rod.mass"] == 1.0
    same_run(mb.simulate(m, 0.5), before)
    # an empty dict is no change
    same_run(mb.simulate(m, 0.5, parameters={}), before)


def test_bad_parameters_are_refused_by_name():
    m = pendulum()
    with pytest.raises(mb.ModelError, match=r"no parameter 'rod.mas'; the parameters are rod.mass, rod.inertia"):
        mb.simulate(m, 1.0, parameters={"rod.mas": 2.0})
    with pytest.raises(mb.ModelError, match=r"body 'rod': mass must be positive .* got -2"):
        mb.simulate(m, 1.0, parameters={"rod.mass": -2.0})
    with pytest.raises(mb.ModelError, match=r"parameter 'rod.mass' must be finite"):
        mb.simulate(m, 1.0, parameters={"rod.mass": float("nan")})
    with pytest.raises(mb.ModelError, match=r"parameter 'rod.mass' must be a number"):
        mb.Simulator(m, parameters={"rod.mass": "heavy"})
    with pytest.raises(mb.ModelError, match=r"parameters must be a dict"):
        mb.simulate(m, 1.0, parameters=[("rod.mass", 2.0)])
    # a negative free length: the builder's check
    with pytest.raises(mb.ModelError, match="spring damper 'spring'"):
        mb.simulate(m, 1.0, parameters={"spring.free_length": -1.0})


def test_a_simulator_runs_with_parameters():
    m = pendulum(push=mb.Input(0.0, name="push"))
    sim = mb.Simulator(m, rtol=1e-8, parameters={"rod.mass": 2.0, "spring.stiffness": 5.0})
    sim.set_input("push", 3.0)
    sim.advance(0.5)
    ref = mb.Simulator(pendulum(mass=2.0, inertia=1 / 12, stiffness=5.0, push=mb.Input(0.0, name="push")), rtol=1e-8)
    ref.set_input("push", 3.0)
    ref.advance(0.5)
    same_run(sim.result(), ref.result())
    assert np.array_equal(sim.result().reaction("pin"), ref.result().reaction("pin"))


def in_threads(work, n=8):
    """work(k) for k = 0..n-1, each on its own thread, all at once."""
    threads = [threading.Thread(target=work, args=(k,)) for k in range(n)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()


def drive(sim, k):
    """Thread k's run: its own input history, 20 advances of 0.05 s."""
    for step in range(20):
        sim.set_input("push", np.sin(0.3 * step + k) * (1.0 + k))
        sim.advance(0.05 * (step + 1))
    return sim.result()


def test_eight_threads_run_one_compiled_model_with_their_own_inputs_and_parameters():
    """One compiled model, 8 threads at once, each with its own input
    history and rod mass: every run equals the same run done alone, and the
    run of a model built with that mass."""
    model = pendulum(stiffness=10.0, push=mb.Input(0.0, name="push"))
    masses = [1.0 + 0.25 * k for k in range(8)]
    results = [None] * 8
    barrier = threading.Barrier(8)

    def work(k):
        sim = mb.Simulator(model, rtol=1e-9, parameters={"rod.mass": masses[k]})
        barrier.wait()  # all advance at once
        results[k] = drive(sim, k)

    in_threads(work)
    for k in range(8):
        alone = drive(mb.Simulator(model, rtol=1e-9, parameters={"rod.mass": masses[k]}), k)
        same_run(results[k], alone)
        built = drive(mb.Simulator(pendulum(mass=masses[k], inertia=1 / 12, stiffness=10.0,
                                            push=mb.Input(0.0, name="push")), rtol=1e-9), k)
        same_run(results[k], built)
        assert np.array_equal(results[k].input("push"), alone.input("push"))
    # the threads did run different motions, with their own inputs
    assert np.abs(results[0].q - results[7].q).max() > 1e-3
    assert results[7].input("push")[1] == pytest.approx(np.sin(7.0) * 8.0)


def test_eight_threads_run_simulate_with_their_own_parameters():
    model = pendulum(stiffness=10.0)
    stiffness = [5.0 * (k + 1) for k in range(8)]
    results = [None] * 8

    def work(k):
        results[k] = mb.simulate(model, 1.0, rtol=1e-9, parameters={"spring.stiffness": stiffness[k]})

    in_threads(work)
    for k in range(8):
        same_run(results[k], mb.simulate(pendulum(stiffness=stiffness[k]), 1.0, rtol=1e-9))
