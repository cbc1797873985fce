"""Fuzzed inputs: random small mechanisms with hostile parameters and options.

Hypothesis draws cases (tests/fuzz/fuzz_mechanisms.py) in three families:

- planar (``cases``): chains and closed loops of 1-5 bodies and particles,
  random joints, drivers, forces, stops, contacts, parameters from wide and
  hostile ranges;
- spatial (``spatial_cases``): Model(dimension=3), chains and loops of 1-4
  bodies in random orientations (quaternions, rotation matrices, inertia
  tensors), spherical, revolute, cylindrical, translational, universal,
  planar, weld and distance joints, drivers whose values start far from the
  joints' initial coordinates (3.0, -1.7, a Linear from 2, ...), bushings,
  spring-dampers, forces and torques; in a Simulator, driver inputs jump by
  pi or more;
- two threads (``threaded_cases``): a Simulator (of a spatial model, or a
  planar one) that two Python threads advance at once, sim.advance(sim.t +
  dt) n times each (sometimes also setting inputs, or with a third thread
  reading the state);

then what a user runs: degrees_of_freedom, assemble, solve_accelerations,
simulate with random options, equilibrium, result accessors, a Simulator
advanced in chunks with its inputs set and its state saved and restored.
Each case runs in a worker subprocess, so a crash or a hang fails that case
instead of pytest (a worker that ran threads is replaced after the case, and
its death on the way out is that case's crash).

The property: every call either returns numbers that are all finite (and a
successful run or equilibrium keeps max |Phi| <= 1e-4 (1 + max |q|), its
output times in order, and, in space, every driver at what it commands: a
revolute's angle about its axis equal to f modulo 2 pi, a slide or a body's
coordinate equal to f), or raises one of lagmb's own exceptions
(mb.ModelError and subclasses, mb.SimulationError and subclasses,
mb.SceneError) - except that assembling a well-posed open chain of driven
joints (no hostile values) must succeed. Anything else (another exception
type, a non-finite output, a silently violated constraint or driver, a
crash, a hang past the timeout) is a finding. Two threads on one Simulator must be serialized: no crash, no
foreign exception, and together they advance it by at least n dt.

The cases are not shrunk by hypothesis: all of them run, the findings are
grouped by kind (exception type, where it was raised and its message with the
numbers blanked; crash or hang and the call; non-finite output and which
array; which check a result failed), and the shortest case of each kind is
cut down op by op to a short reproducer script, printed in the failure
message (``python3 tests/fuzz/fuzz_mechanisms.py --replay FILE.py`` reruns one the
same way).

- test_fuzz_mechanisms_default: part of the default suite, deterministic
  (derandomize=True), 400 planar cases in about 10 s.
- test_fuzz_spatial_mechanisms_default: 200 spatial cases, about 8 s.
- test_fuzz_two_threads_default: 12 threaded cases, about 10 s (a fresh worker per case).
- test_a_driven_spatial_revolute_holds_its_angle,
  test_two_threads_advancing_one_simulator_are_serialized: the two spatial
  properties on fixed cases, and test_the_driver_check_sees_an_angle_off_by_pi
  on the check itself.
- test_fuzz_*_long: @pytest.mark.fuzz, 600 planar, 600 spatial and 60
  threaded cases (LAGMB_FUZZ_EXAMPLES, LAGMB_FUZZ_SPATIAL_EXAMPLES,
  LAGMB_FUZZ_THREAD_EXAMPLES; LAGMB_FUZZ_SEED); run with ``python3 -m pytest
  -m fuzz -p no:warnings tests/fuzz/test_fuzz_mechanisms.py`` or ``make
  test-fuzz``; the default suite deselects them (pyproject.toml addopts), and
  they skip themselves unless ``-m`` names ``fuzz``.
  LAGMB_FUZZ_REPORT=path.json writes the findings as JSON (path-spatial.json,
  path-threads.json for the other families).
"""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fuzz_mechanisms as fm  # noqa: E402
import worker  # noqa: E402  (the fuzzers' worker: its checks)

DEFAULT_EXAMPLES = 400
DEFAULT_SPATIAL_EXAMPLES = 200
DEFAULT_THREAD_EXAMPLES = 12
# s per call: the slowest healthy call takes ~3 s alone (rtol 1e-10, BDF order 1), and CI
# machines are shared; a real hang never ends, so the bound can be generous
DEFAULT_TIMEOUT = 30.0
LONG_TIMEOUT = 30.0


def _generate(n, derandomize, rng_seed=None, family="planar"):
    """n cases drawn by hypothesis (plain data). The deterministic draw runs in
    a fresh interpreter: in this one, what hypothesis draws depends on the
    modules other tests imported before (it mines their constants)."""
    if not derandomize:
        return fm.generate(n, derandomize=False, rng_seed=rng_seed, family=family)
    out = subprocess.run([sys.executable, fm.__file__, "--generate", str(n), family], capture_output=True,
                         text=True, timeout=600, check=True)
    return json.loads(out.stdout)


def _check(cases, timeout, minimize_budget, family="planar"):
    outcomes = fm.run_cases(cases, timeout, n_workers=2)
    findings = fm.Findings()
    for case, (problems, statuses) in zip(cases, outcomes):
        findings.add(case, problems, statuses)
    if findings:
        findings.minimize_all(timeout, minimize_budget)
    path = os.environ.get("LAGMB_FUZZ_REPORT")
    if path:
        if family != "planar":
            root, ext = os.path.splitext(path)
            path = f"{root}-{family}{ext or '.json'}"
        with open(path, "w") as f:
            json.dump({"cases": len(cases), "findings": findings.to_json()}, f, indent=1)
    assert not findings, (f"{len(cases)} fuzzed {family} cases: every call must return finite numbers or raise "
                          f"mb.ModelError / mb.SimulationError / mb.SceneError.\n" + findings.report())


def _long(request):
    if "fuzz" not in (request.config.getoption("markexpr", "") or ""):
        pytest.skip("long fuzz run: select it with -m fuzz")
    return int(os.environ.get("LAGMB_FUZZ_SEED", "20240611")), float(os.environ.get("LAGMB_FUZZ_MINIMIZE_S", "240"))


def test_fuzz_mechanisms_default():
    """400 random planar mechanisms (deterministic), in the default suite."""
    _check(_generate(DEFAULT_EXAMPLES, derandomize=True), DEFAULT_TIMEOUT, minimize_budget=8.0)


def test_fuzz_spatial_mechanisms_default():
    """200 random spatial mechanisms (deterministic), in the default suite."""
    _check(_generate(DEFAULT_SPATIAL_EXAMPLES, derandomize=True, family="spatial"), DEFAULT_TIMEOUT,
           minimize_budget=8.0, family="spatial")


def test_fuzz_two_threads_default():
    """12 Simulators, each advanced by two threads at once (deterministic
    cases; the interleaving is not), in the default suite."""
    _check(_generate(DEFAULT_THREAD_EXAMPLES, derandomize=True, family="threads"), DEFAULT_TIMEOUT,
           minimize_budget=8.0, family="threads")


@pytest.mark.fuzz
def test_fuzz_mechanisms_long(request):
    """600 random planar mechanisms (LAGMB_FUZZ_EXAMPLES), selected with -m fuzz."""
    rng_seed, budget = _long(request)
    n = int(os.environ.get("LAGMB_FUZZ_EXAMPLES", "600"))
    _check(_generate(n, derandomize=False, rng_seed=rng_seed), LONG_TIMEOUT, minimize_budget=budget)


@pytest.mark.fuzz
def test_fuzz_spatial_mechanisms_long(request):
    """600 random spatial mechanisms (LAGMB_FUZZ_SPATIAL_EXAMPLES), selected with -m fuzz."""
    rng_seed, budget = _long(request)
    n = int(os.environ.get("LAGMB_FUZZ_SPATIAL_EXAMPLES", "600"))
    _check(_generate(n, derandomize=False, rng_seed=rng_seed, family="spatial"), LONG_TIMEOUT,
           minimize_budget=budget, family="spatial")


@pytest.mark.fuzz
def test_fuzz_two_threads_long(request):
    """60 Simulators advanced by two threads at once (LAGMB_FUZZ_THREAD_EXAMPLES), selected with -m fuzz."""
    rng_seed, budget = _long(request)
    n = int(os.environ.get("LAGMB_FUZZ_THREAD_EXAMPLES", "60"))
    _check(_generate(n, derandomize=False, rng_seed=rng_seed, family="threads"), LONG_TIMEOUT,
           minimize_budget=budget, family="threads")


# --- the spatial properties on fixed cases ----------------------------------

# An arm on a revolute with a tilted axis, driven, and a bob hanging from its
# tip on a spherical joint (so that the model has a free motion, and a static
# equilibrium). The hinge's angle is 0 as built.
DRIVEN_ARM = """
m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
arm = m.add_body('arm', 1.0, (0.01, 0.1, 0.1), position=(0.5, 0.0, 0.0))
bob = m.add_body('bob', 0.5, (0.001, 0.001, 0.001), position=(1.0, 0.0, -0.3))
m.add_revolute('hinge', m.ground, arm, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 1.0))
m.add_spherical('ball', arm, bob, at=(1.0, 0.0, 0.0))
m.drive_joint('motor', 'hinge', {f})
"""
RUNS = """
r = mb.simulate(m, t_end=0.1)
r = mb.simulate(m, t_end=0.1, formulation='ali3p', step=1e-3)
eq = mb.equilibrium(m)
r = mb.simulate(m, t_end=0.1, start='equilibrium')
sim = mb.Simulator(m)
sim.advance(0.02)
rs = sim.result()
"""
# an input far from 0, then jumps of pi, -2 pi - 4.7 and 7
INPUT_JUMPS = """
sim = mb.Simulator(m)
sim.advance(0.02)
sim.set_input('motor', 3.0 + np.pi)
sim.advance(0.04)
sim.set_input('motor', -1.7 - 2 * np.pi)
sim.advance(0.06)
sim.set_input('motor', 5.3)
sim.advance(0.08)
rs = sim.result()
"""
COMMANDS = ["mb.Constant(3.0)", "-1.7", "mb.Linear(1.0, start=2.0)", "mb.Harmonic(0.5, 3.0, offset=3.0)",
            "mb.Spline([0.0, 0.05, 0.1], [2.5, -2.0, 4.0])", "np.pi", "mb.Input(-3.0)"]


def _run_scripts(scripts):
    """Each script's ops, checked as in the fuzz run: {script: problems}."""
    cases = [fm.script_ops(fm.HEADER + s) for s in scripts]
    return {s: problems for s, (problems, _) in zip(scripts, fm.run_cases(cases, DEFAULT_TIMEOUT, n_workers=2))}


def test_a_driven_spatial_revolute_holds_its_angle():
    """A revolute driven to values far from its initial angle of 0 (3.0,
    -1.7, a Linear from 2, a Harmonic about 3, a Spline from 2.5, pi, an
    Input of -3 and then jumps of pi and more) is at f modulo 2 pi at every
    output: of simulate (inverse dynamics, ali3p, from equilibrium), of
    equilibrium, and of a Simulator."""
    scripts = [DRIVEN_ARM.format(f=f) + RUNS for f in COMMANDS] + \
        [DRIVEN_ARM.format(f="mb.Input(3.0)") + INPUT_JUMPS]
    found = {s: p for s, p in _run_scripts(scripts).items() if p}
    assert not found, "\n\n".join(f"{s}\n-> " + "\n-> ".join(f"{p['key']}: {p['detail']}" for p in problems)
                                  for s, problems in found.items())


def test_two_threads_advancing_one_simulator_are_serialized():
    """Two threads each advancing one Simulator 300 times by 1 ms, twice (the
    second thread also making the driver's input jump by pi every 10th time,
    and a third reading the state meanwhile, or not), in 4 workers: no crash,
    no exception but a refused call that the other thread overtook, at least
    300 ms advanced each time, and the result in time order with the driver
    at its inputs."""
    setup = DRIVEN_ARM.format(f="mb.Input(3.0)") + "sim = mb.Simulator(m)\n"
    cases = []
    for jumps, reader in [((), False), ((("motor", float(np.pi)),), True)] * 2:
        ops = fm.script_ops(fm.HEADER + setup)
        ops.append({"code": fm.THREAD_HELPERS, "kind": "def", "check": None})
        ops += [fm.two_threads_op(300, 1e-3, jumps, reader)] * 2
        ops += fm.script_ops("rs = sim.result()\n")
        cases.append(ops)
    for ops, (problems, _) in zip(cases, fm.run_cases(cases, DEFAULT_TIMEOUT, n_workers=2)):
        assert not problems, fm.reproducer(ops) + "\n-> " + "\n-> ".join(f"{p['key']}: {p['detail']}"
                                                                         for p in problems)


def test_the_driver_check_sees_an_angle_off_by_pi():
    """The check itself, on states made by hand: the driven arm (f = 3.0)
    turned by 3.0 about its hinge from where it was built passes, and so does
    3.0 - 2 pi; turned by 3.0 - pi it fails as 'revolute driver off by pi',
    by 3.1 as 'revolute driver off'."""
    import lagmb as mb

    ns = {"mb": mb, "np": np}
    exec(DRIVEN_ARM.format(f="3.0"), ns)
    model = ns["m"]
    core = model.compiled()
    q0 = np.asarray(core.initial_state()[0], dtype=float)
    axis = np.array([0.0, 1.0, 1.0]) / np.sqrt(2.0)  # the hinge's, through the origin

    def turned(angle):
        """(1, n): the arm and the bob turned together by angle about the hinge."""
        turn = np.array([np.cos(angle / 2), *(np.sin(angle / 2) * axis)])
        R = worker.rotations(turn[None])[0]
        q = q0.copy()
        for body in ("arm", "bob"):
            first, _ = core.body_coordinates(body)
            w, v = q[first + 3], q[first + 4:first + 7]
            q[first + 3:first + 7] = [turn[0] * w - turn[1:] @ v, *(turn[0] * v + w * turn[1:] + np.cross(turn[1:], v))]
            q[first:first + 3] = R @ q[first:first + 3]
        return q[None]

    def check(Q):
        return [tag for tag, _ in worker.driver_problems(np, model, core, np.array([0.0]), Q, None)]

    assert check(turned(3.0)) == []
    assert check(turned(3.0 - 2 * np.pi)) == []
    assert check(turned(3.0 - np.pi)) == ["revolute driver off by pi"]
    assert check(turned(3.1)) == ["revolute driver off"]
