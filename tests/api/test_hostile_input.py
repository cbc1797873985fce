"""Hostile and careless input (issue 14): no crash, no hang, no foreign
exception, no silently ignored equation.

Every case below was found by a fuzzer or by hand against an earlier
version. Where a crash was possible (SIGFPE, a segfault, an abort) the case
runs in a subprocess, so a crash fails its test instead of killing pytest.
"""

import math
import os
import signal
import subprocess
import sys
import textwrap
import threading
import warnings
import weakref

import numpy as np
import pytest

import lagmb as mb
from lagmb import _core
from builders import pendulum
import paths  # noqa: E402  (tests/paths.py)

G = 9.81


def in_subprocess(code, timeout=120):
    """Runs `code` in a fresh interpreter; returns its stdout. A crash or a
    failed assertion there fails here, with what it printed."""
    proc = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          timeout=timeout)
    assert proc.returncode == 0, (
        f"exit status {proc.returncode} (signal {-proc.returncode} if negative)\n"
        f"stdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
    return proc.stdout


def chain(n):
    m = mb.Model(gravity=(0.0, -G))
    previous = m.ground
    for k in range(n):
        b = m.add_body(f"link{k}", 1.0, 1.0 / 12.0, position=(k + 0.5, 0.0))
        m.add_revolute(f"joint{k}", previous, b, at=(float(k), 0.0))
        previous = b
    return m


# --- an empty model -------------------------------------------------------------


def test_an_empty_model_is_refused_by_name_not_by_a_crash():
    """degrees_of_freedom, assemble, solve_accelerations and simulate on a
    model without bodies used to die of SIGFPE (or overflow a heap buffer in
    the sparsity build): each is a ModelError saying the model has no bodies."""
    out = in_subprocess("""
        import lagmb as mb
        calls = {
            "degrees_of_freedom": lambda: mb.Model().degrees_of_freedom(),
            "assemble": lambda: mb.Model().assemble(),
            "solve_accelerations": lambda: mb.solve_accelerations(mb.Model(), [], []),
            "simulate": lambda: mb.simulate(mb.Model(), t_end=1.0),
            "equilibrium": lambda: mb.equilibrium(mb.Model()),
            "rank": lambda: mb.Model().rank(),
        }
        for name, call in calls.items():
            try:
                call()
            except mb.ModelError as e:
                assert "no bodies" in str(e), (name, str(e))
                print(name, "ok")
            else:
                raise AssertionError(name + " did not raise")
    """)
    assert out.count("ok") == 6


# --- the compiled module checks its arguments -----------------------------------------


def test_core_accessors_check_the_length_of_every_output_array():
    """lagmb._core is importable: reaction, energy, residual and friction at
    output times that do not match the rows of q, v or lam (an empty t
    among them) used to read past the end. Each is a ModelError naming the
    array."""
    out = in_subprocess("""
        import numpy as np
        import lagmb as mb
        from lagmb import _core
        m = mb.Model(gravity=(0.0, -9.81))
        rod = m.add_body("rod", 1.0, 1/12, position=(0.5, 0.0))
        m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
        m.add_joint_friction("rub", "pin", mu=0.1, pin_radius=0.01)
        r = mb.simulate(m, t_end=0.1, n_out=5)
        core = m.compiled()
        short = r.t[:2]
        cases = {
            "reaction": lambda t: core.reaction("pin", t, r.q, r.lam),
            "energy": lambda t: core.energy(t, r.q, r.v),
            "residual": lambda t: core.residual(t, r.q),
            "velocity_residual": lambda t: core.velocity_residual(t, r.q, r.v),
            "friction": lambda t: core.friction("rub", r.q[:len(t)], r.v, r.lam),
        }
        for name, call in cases.items():
            for t in (short, r.t[:0]):
                try:
                    call(t)
                except mb.ModelError as e:
                    assert "row" in str(e), (name, str(e))
                else:
                    raise AssertionError(name + " accepted mismatched arrays")
            print(name, "ok")
        for row in (-1, 2, 10**6):
            try:
                core.constraint_name_of_row(row)
            except mb.ModelError as e:
                assert str(row) in str(e)
        print("rows ok")
    """)
    assert out.count("ok") == 6


def test_a_result_cannot_be_made_inconsistent():
    """r.t = r.t[:0] used to let r.reaction read past the end of t. The
    arrays of a Result are read-only, and so are its attributes."""
    r = mb.simulate(pendulum(), t_end=0.1, n_out=5)
    for name in ("t", "q", "v", "a", "lam"):
        with pytest.raises(AttributeError):
            setattr(r, name, getattr(r, name)[:0])
        with pytest.raises(ValueError):
            getattr(r, name)[...] = 0.0
    assert r.reaction("pin").shape == (5, 3)


# --- runs that would never end -----------------------------------------------------


def test_a_step_bound_that_needs_too_many_steps_is_refused_up_front():
    """max_step = 1e-12 s over 1 s, or ali3p with step = 1e-9 s, used to run
    for as long as one waited. Both need more than max_steps (default
    500,000) steps, so both are refused before the run, naming the bound."""
    with pytest.raises(mb.ModelError, match=r"max_step = 1e-12 .* max_steps = 500000"):
        mb.simulate(pendulum(), t_end=1.0, max_step=1e-12)
    with pytest.raises(mb.ModelError, match=r"step = 1e-09 .* max_steps = 500000"):
        mb.simulate(pendulum(), t_end=1.0, formulation="ali3p", step=1e-9)
    # the bound holds for step counts the step size does not predict too
    with pytest.raises(mb.SimulationError, match="max_steps = 20") as failure:
        mb.simulate(pendulum(), t_end=1.0, rtol=1e-10, max_steps=20, formulation="ggl")
    assert failure.value.result is None or len(failure.value.result.t) < 101


def interrupt_after(seconds):
    """Sends SIGINT to this process after `seconds` (as Ctrl-C does). Python
    turns SIGINT into KeyboardInterrupt only if it was not ignored when the
    interpreter started (a shell's background job ignores it): install that
    handler here, so the test does not depend on how pytest was launched."""
    if signal.getsignal(signal.SIGINT) in (signal.SIG_IGN, signal.SIG_DFL):
        signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(seconds, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_stops_a_long_run_and_keeps_the_outputs():
    """SIGINT half a second into a run that would take minutes (a 200-link
    chain over 100 s at rtol 1e-10; 0.07 s of it computed by then on a busy
    2-core machine) raises KeyboardInterrupt itself, carrying the outputs
    computed so far as .result: they end before 10 s of the 100 asked (the
    core looks for the interrupt every 20 ms of wall time; the test counts
    how far the run got, not the seconds it took, which a loaded machine
    stretches)."""
    m = chain(200)
    timer = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt) as stop:
        mb.simulate(m, t_end=100.0, rtol=1e-10, n_out=100001)
    timer.cancel()
    partial = stop.value.result
    assert partial is not None and 1 <= len(partial.t) and partial.t[-1] < 10.0
    assert np.all(np.isfinite(partial.q)) and np.all(np.isfinite(partial.lam))
    assert partial.a.shape == partial.q.shape


def test_ctrl_c_stops_a_kinematic_analysis():
    """The kinematic analysis of a driven 100-link chain with a million outputs
    stops at Ctrl-C too: its outputs end before 100 s of the 1,000 asked
    (0.5 s of them on a busy 2-core machine)."""
    m = chain(100)
    for k in range(100):
        m.drive_joint(f"motor{k}", f"joint{k}", mb.Linear(0.1))
    timer = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt) as stop:
        mb.simulate(m, t_end=1000.0, n_out=1_000_000)
    timer.cancel()
    partial = stop.value.result
    assert partial is not None and partial.t[-1] < 100.0


@pytest.mark.parametrize("exception", [KeyboardInterrupt, SystemExit])
def test_an_interrupt_raised_in_a_user_function_comes_through_unchanged(exception):
    """KeyboardInterrupt or SystemExit raised inside a torque callable used
    to become SimulationError, so `except KeyboardInterrupt` never saw it.
    It passes unchanged, with the outputs before it."""
    m = pendulum()

    def torque(t):
        if t > 0.3:
            raise exception()
        return 0.0

    m.add_torque("hand", "rod", torque)
    with pytest.raises(exception) as stop:
        mb.simulate(m, t_end=1.0, n_out=101)
    partial = stop.value.result
    assert partial is not None and 0.2 < partial.t[-1] <= 0.3
    assert not isinstance(stop.value, mb.SimulationError)


def test_an_interrupt_in_equilibrium_comes_through_unchanged():
    m = pendulum()
    m.add_rotational_spring_damper("spring", m.ground, "rod", stiffness=20.0)

    def torque(t):
        raise KeyboardInterrupt

    m.add_torque("hand", "rod", torque)
    with pytest.raises(KeyboardInterrupt):
        mb.equilibrium(m)


# --- undefined behaviour --------------------------------------------------------


def test_a_model_without_constraints_has_empty_multipliers():
    """A free body (no constraint rows) used to make solve_outputs index an
    empty vector (UndefinedBehaviorSanitizer). lam has zero columns and the
    body falls freely: y = -g t^2 / 2."""
    m = mb.Model(gravity=(0.0, -G))
    m.add_body("ball", 1.0, 0.1)
    for formulation in ("ggl", "index3", "index1", "projection"):
        r = mb.simulate(m, t_end=1.0, n_out=11, rtol=1e-10, atol=1e-12, formulation=formulation)
        assert r.lam.shape == (11, 0)
        assert np.abs(r.body("ball").position[:, 1] + 0.5 * G * r.t**2).max() < 1e-8


# --- exceptions of lagmb's own types -----------------------------------------------------


def raising_pendulum():
    m = pendulum()
    m.add_rotational_spring_damper("spring", m.ground, "rod", stiffness=20.0)

    def torque(t):
        raise ZeroDivisionError("the user's bug")

    m.add_torque("hand", "rod", torque)
    return m


def test_a_failing_user_function_is_a_lagmb_error_with_its_cause_chained():
    """A callable that raises used to escape mb.equilibrium, start =
    "equilibrium" and kinematic analyses as RuntimeError. Each is lagmb's
    own error now, naming the element, with the user's exception as cause."""
    with pytest.raises(mb.EquilibriumError, match="'hand'") as e:
        mb.equilibrium(raising_pendulum())
    assert isinstance(e.value.__cause__, ZeroDivisionError)
    with pytest.raises(mb.SimulationError, match="'hand'") as e:
        mb.simulate(raising_pendulum(), t_end=1.0, start="equilibrium")
    assert isinstance(e.value.__cause__, ZeroDivisionError)
    with pytest.raises(mb.SimulationError, match="'hand'") as e:
        mb.simulate(raising_pendulum(), t_end=1.0)
    assert isinstance(e.value.__cause__, ZeroDivisionError)

    driven = pendulum()

    def angle(t):
        if t > 0.5:
            raise ZeroDivisionError("the user's bug")
        return (t, 1.0, 0.0)

    driven.drive_joint("motor", "pin", angle)
    with pytest.raises(mb.SimulationError, match="'motor'") as e:
        mb.simulate(driven, t_end=1.0, analysis="kinematic")
    assert isinstance(e.value.__cause__, ZeroDivisionError)
    assert e.value.result is not None and e.value.result.t[-1] <= 0.5


@pytest.mark.parametrize("options, named", [
    (dict(n_out=float("nan")), "n_out"),
    (dict(n_out=2**40), "n_out"),
    (dict(n_out="100"), "n_out"),
    (dict(max_order=float("nan")), "max_order"),
    (dict(max_order=101), "max_order"),
    (dict(t0="abc"), "t0"),
    (dict(t_end=10**400), "t_end"),
    (dict(rtol=None), "rtol"),
    (dict(atol=[1e-8, "x", 1e-8]), "atol"),
    (dict(max_steps=0.5), "max_steps"),
    (dict(formulation=3), "formulation"),
    (dict(integrator=3), "integrator"),  # None: the formulation's first
    (dict(analysis=["auto"]), "analysis"),
    (dict(baumgarte=(1.0, "b"), formulation="index1"), "baumgarte"),
    (dict(t_out=[0.0, "half", 1.0]), "t_out"),
    (dict(progress=42), "progress"),
])
def test_bad_options_are_model_errors_naming_the_argument(options, named):
    """Bad option types used to surface as TypeError, OverflowError or
    pybind11's "incompatible function arguments"."""
    options = {"t_end": 1.0, **options}
    with pytest.raises(mb.ModelError, match=named):
        mb.simulate(pendulum(), **options)


def test_bad_arguments_elsewhere_are_model_errors():
    r = mb.simulate(pendulum(), t_end=0.1, n_out=3)
    with pytest.raises(mb.ModelError, match="local_point"):
        r.point("rod", (1.0, 2.0, 3.0))
    with pytest.raises(mb.ModelError, match="'ghost'"):
        r.body("ghost")
    other = pendulum()
    m = pendulum()
    with pytest.raises(mb.ModelError, match="another model"):
        m.add_revolute("pin2", other.bodies[0], m.ground, at=(0.0, 0.0))
    with pytest.raises(mb.ModelError, match="tol"):
        mb.equilibrium(pendulum(), tol=float("nan"))
    with pytest.raises(mb.ModelError, match="q and v"):
        mb.solve_accelerations(pendulum(), [0.5, 0.0], [0.0, 0.0, 0.0])
    with pytest.raises(mb.ModelError, match="t must be"):
        pendulum().assemble(t="now")


# --- no equation silently dropped ---------------------------------------------------


def test_conflicting_drivers_are_refused_naming_both():
    """A pendulum whose joint is driven at 1 rad/s and whose rod is driven at
    2 rad/s: the two equations agree at t = 0 (so one used to be dropped
    there, and the run followed the other alone with residual 0). They
    conflict at velocity level, and both are named."""
    def model():
        m = pendulum()
        m.drive_joint("d1", "pin", mb.Linear(1.0))
        m.drive_body("d2", "rod", "angle", mb.Linear(2.0))
        return m

    with pytest.raises(mb.AssemblyError, match=r"'d[12]'.*'d[12]'.*velocity") as e:
        mb.simulate(model(), t_end=1.0, analysis="dynamic")
    assert {name for name, _ in e.value.violated} == {"d1", "d2"}
    # the kinematic analysis (what "auto" picks at 0 DOF) stops at its first output
    with pytest.raises(mb.SimulationError, match=r"'d[12]'.*'d[12]'"):
        mb.simulate(model(), t_end=1.0)


def flat_parallelogram():
    """Cranks of 1 m at x = 0 and 2 and a 2 m coupler, all on the x axis:
    a parallelogram started in its singular (flat) position."""
    m = mb.Model(gravity=(0.0, -G))
    a = m.add_body("crankA", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    c = m.add_body("coupler", 2.0, 2.0 * 4.0 / 12.0, position=(2.0, 0.0))
    b = m.add_body("crankB", 1.0, 1.0 / 12.0, position=(2.5, 0.0))
    m.add_revolute("A", m.ground, a, at=(0.0, 0.0))
    m.add_revolute("B", a, c, at=(1.0, 0.0))
    m.add_revolute("C", c, b, at=(3.0, 0.0))
    m.add_revolute("D", b, m.ground, at=(2.0, 0.0))
    return m


def test_a_parallelogram_started_flat_is_not_taken_apart():
    """Started in its singular position, joint C used to be dropped as
    "redundant": the linkage opened by 0.84 m while r.residual said 9.5e-9.
    The rank drop is momentary, so no equation is dropped: one degree of
    freedom. GGL stops at t = 0 naming the joints and pointing to ali3p,
    which runs it with every joint closed; so does the default (formulation
    "auto": the explicit projection method here), whose accelerations come
    from the augmented system, defined at the flat position too: it ends
    where ali3p does (3.5e-6 m apart, ali3p's step error at 1e-3 s)."""
    assert flat_parallelogram().degrees_of_freedom() == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error", mb.RedundantConstraintWarning)
        with pytest.raises(mb.SimulationError, match=r"singular.*ali3p"):
            mb.simulate(flat_parallelogram(), t_end=1.0, formulation="ggl")
        r = mb.simulate(flat_parallelogram(), t_end=1.0, formulation="ali3p", step=1e-3)
        default = mb.simulate(flat_parallelogram(), t_end=1.0)
    assert r.residual.max() < 1e-9 and default.residual.max() < 1e-9
    assert r.redundant_rows == [] and default.redundant_rows == []
    assert np.abs(default.q[-1] - r.q[-1]).max() < 1e-5


def test_a_loop_that_cannot_close_is_an_assembly_error():
    """Two 1 m links whose closing revolute sits 100 m away used to run with
    joint p1 gapping by 98 m."""
    m = mb.Model(gravity=(0.0, -G))
    a = m.add_body("a", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    b = m.add_body("b", 1.0, 1.0 / 12.0, position=(1.5, 0.0))
    m.add_revolute("p0", m.ground, a, at=(0.0, 0.0))
    m.add_revolute("p1", a, b, at=(1.0, 0.0))
    m.add_revolute("p2", b, m.ground, local_i=(0.5, 0.0), local_j=(100.0, 0.0))
    with pytest.raises(mb.AssemblyError, match="'p2'"):
        mb.simulate(m, t_end=1.0)


def test_a_slider_driven_past_its_reach_from_the_toggle_is_refused():
    """A slider-crank (crank 0.1 m, rod 0.3 m) started at its outer toggle with
    the slider driven outward: no position exists beyond 0.4 m. It used to
    drop the rod-slider joint and push the slider past the rod's reach."""
    m = mb.Model(gravity=(0.0, -G))
    crank = m.add_body("crank", 1.0, 1.0 / 1200.0, position=(0.05, 0.0))
    rod = m.add_body("rod", 1.0, 0.0075, position=(0.25, 0.0))
    slider = m.add_body("slider", 1.0, 1e-4, position=(0.4, 0.0))
    m.add_revolute("O", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("B", crank, rod, at=(0.1, 0.0))
    m.add_revolute("C", rod, slider, at=(0.4, 0.0))
    m.add_translational("guide", m.ground, slider, at=(0.4, 0.0), axis=(1.0, 0.0))
    m.drive_joint("push", "guide", mb.Linear(0.1))
    for analysis in ("auto", "dynamic"):
        with pytest.raises(mb.SimulationError, match="'push'"):
            mb.simulate(m, t_end=1.0, analysis=analysis)


def test_dropped_equations_count_in_the_residual_and_are_watched():
    """With the elbow of a double pendulum given twice, two rows are dropped
    (and named in the warning); r.residual is the max over every row,
    dropped ones included, so it equals a full evaluation of Phi."""
    m = mb.Model(gravity=(0.0, -G))
    a = m.add_body("upper", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    b = m.add_body("lower", 1.0, 1.0 / 12.0, position=(1.5, 0.0))
    m.add_revolute("shoulder", m.ground, a, at=(0.0, 0.0))
    m.add_revolute("elbow", a, b, at=(1.0, 0.0))
    m.add_revolute("elbow_again", a, b, at=(1.0, 0.0))
    with pytest.warns(mb.RedundantConstraintWarning, match="elbow"):
        r = mb.simulate(m, t_end=1.0, n_out=11)
    assert len(r.redundant_rows) == 2
    core = m.compiled()
    full = [np.abs(core.constraint_values(q, t)[0]).max() for t, q in zip(r.t, r.q)]
    assert np.array_equal(r.residual, full)


# --- finite numbers or an error ---------------------------------------------------------


@pytest.mark.parametrize("formulation", ["ggl", "index3", "index1", "projection", "ali3p"])
def test_a_non_finite_force_at_one_output_stops_the_run_naming_it(formulation):
    """A torque returning NaN exactly at t = 0.5 (an output time the
    integrator never visits otherwise) used to leave NaN in r.a and r.lam of
    a successful run. The run raises SimulationError naming the torque, and
    keeps the outputs before t = 0.5, all finite."""
    m = pendulum()
    m.add_torque("glitch", "rod", lambda t: float("nan") if t == 0.5 else 0.0)
    options = dict(step=1e-3) if formulation == "ali3p" else {}
    with pytest.raises(mb.SimulationError, match="'glitch'") as e:
        mb.simulate(m, t_end=1.0, n_out=11, formulation=formulation, **options)
    partial = e.value.result
    assert partial.t[-1] == pytest.approx(0.4)
    for x in (partial.q, partial.v, partial.a, partial.lam):
        assert np.all(np.isfinite(x))


def test_a_non_finite_force_with_stops_stops_the_run_too():
    m = pendulum()
    m.add_stop("limit", "pin", lower=-1.2, restitution=0.5)
    m.add_torque("glitch", "rod", lambda t: float("nan") if t == 0.5 else 0.0)
    with pytest.raises(mb.SimulationError, match="'glitch'") as e:
        mb.simulate(m, t_end=1.0, n_out=11)
    assert np.all(np.isfinite(e.value.result.lam))


def test_an_overflowing_spring_names_its_kind_and_body():
    """A spring of stiffness 1e308 stretched by 10 m overflows to inf."""
    m = pendulum()
    m.add_spring_damper("huge", m.ground, (0.0, -10.0), "rod", (1.0, 0.0), stiffness=1e308, free_length=0.0)
    with pytest.raises((mb.SimulationError, mb.ModelError), match="spring|huge"):
        mb.simulate(m, t_end=0.1)


# --- the garbage collector sees callables ---------------------------------------------


def test_models_whose_callables_refer_to_them_are_collected():
    """A Python callable that refers to its own model forms a cycle through
    the C++ model; it used to be invisible to the collector (100 models of
    8 MB each took resident memory from 27 to 792 MB). All are collected."""
    import gc

    alive = []
    for _ in range(20):
        m = pendulum()
        m.payload = np.ones(100_000)
        m.add_torque("hand", "rod", lambda t, m=m: 0.0 * len(m.bodies))
        m.add_force("push", "rod", lambda t, m=m: (0.0, 0.0 * len(m.bodies)))
        mb.simulate(m, t_end=0.01, n_out=2)
        alive.append(weakref.ref(m))
        del m
    gc.collect()
    assert sum(r() is not None for r in alive) == 0


def test_the_core_spec_is_collected_with_its_time_functions():
    import gc

    spec = _core.ModelSpec()
    spec.add("body", "b", {"mass": 1.0, "inertia": 0.1})
    f = _core.python_function(lambda t: spec and 0.0, "torque 't'", False)
    spec.add("torque", "t", {"body": 0, "torque": f})
    spec.compile()
    ref = weakref.ref(spec)
    del spec, f
    gc.collect()
    assert ref() is None


# --- singular passages ------------------------------------------------------------------


@pytest.mark.slow
def test_the_failure_at_a_singular_passage_points_to_ali3p():
    """The A02 N-four-bar under GGL stops at its first singular position;
    the message names the joints and says that formulation "ali3p" runs
    through such positions. The default ("auto": the explicit projection
    method, whose accelerations come from the augmented system) runs through
    them: 10 s with the energy kept to 1e-8 (seen 5.6e-10) and the positions
    of ALI3-P at a 0.1 ms step to 1e-5 (seen 1.6e-6, ALI3-P's own error)."""
    scene = os.path.join(paths.EXAMPLES, "n_four_bar.toml")
    m = mb.load_scene(scene).model
    with pytest.raises(mb.SimulationError, match='formulation="ali3p"'):
        mb.simulate(m, t_end=10.0, rtol=1e-10, atol=1e-12, formulation="ggl")
    default = mb.simulate(m, t_end=10.0, rtol=1e-10, atol=1e-12)
    assert default.stats["method_choice"].startswith("auto: projection-erk")
    assert np.ptp(default.energy) < 1e-8 * np.abs(default.energy).max()
    fine = mb.simulate(m, t_end=10.0, formulation="ali3p", step=1e-4, t_out=default.t)
    assert np.abs(fine.q - default.q).max() < 1e-5


def driven_crank(rate):
    """The pendulum turned by a motor at `rate` rad/s: 0 degrees of freedom,
    a kinematic analysis."""
    m = pendulum()
    m.drive_joint("motor", "pin", mb.Linear(rate))
    return m


def test_a_driver_too_fast_to_follow_is_refused_not_followed_for_ever():
    """A motor at 9.2e18 rad/s (a fuzzed scene) made the kinematic analysis
    halve its sub-step below 1e-19 s and run for ever. A sub-step shorter
    than the time resolution fails at once, naming the drivers' rates; a fast
    but followable motor meets max_steps, with the outputs kept."""
    with pytest.raises(mb.SimulationError, match="drivers' rates"):
        mb.simulate(driven_crank(9223372036854775808.0), t_end=2.0)
    with pytest.raises(mb.SimulationError, match="max_steps = 1000") as failure:
        mb.simulate(driven_crank(1e5), t_end=2.0, n_out=201, max_steps=1000)
    partial = failure.value.result
    assert partial is not None and 1 <= len(partial.t) < 201
    assert np.all(np.isfinite(partial.q))


def test_the_core_takes_options_by_name_and_refuses_unknown_ones():
    """_core.simulate reads SimulationOptions' fields by name (one list in
    simulate.hpp); a misspelt name is refused, not ignored."""
    core = pendulum().compiled()
    raw = _core.simulate(core, dict(t_end=0.1, n_out=3, rtol=1e-8))
    assert raw["t"].shape == (3,) and raw["stats"]["method_choice"].startswith("auto: projection-erk")
    with pytest.raises(_core.ModelError, match="unknown option 'rtoll'"):
        _core.simulate(core, dict(t_end=0.1, rtoll=1e-8))


def test_an_equilibrium_whose_forces_overflow_is_refused():
    """A body of 1e308 kg under gravity (a fuzzed model): its weight
    overflows, and equilibrium returned a force residual of inf. It is an
    EquilibriumError naming the body's force instead."""
    m = mb.Model(gravity=(0.0, -9.81))
    m.add_body("b0", mass=1e308, inertia=1e-12, position=(0.45, -0.23))
    m.add_body("b4", mass=1.0, inertia=2e-4, position=(-0.65, -0.05), angle=1e308)
    with pytest.raises(mb.EquilibriumError, match="applied force on body 'b0' y is not finite"):
        mb.equilibrium(m, allow_unstable=True)


def test_ali3p_outputs_of_a_body_turned_1e308_rad_are_finite():
    """A free body at an angle of 1e308 rad (a fuzzed model): ALI3-P's
    outputs between steps took (6 s^2 - 6 s)/h q_prev + ... + (-6 s^2 + 6 s)/h q,
    each term overflowing to inf, the sum NaN; in differences they are the
    body's (zero) angular velocity."""
    m = mb.Model(gravity=(0.0, -9.81))
    m.add_body("b3", mass=1.0, inertia=0.08333, position=(0.7557, -0.3569), angle=1e308)
    r = mb.simulate(m, t_end=0.05, formulation="ali3p", step=0.001)
    assert np.all(np.isfinite(r.v)) and np.all(r.v[:, 2] == 0.0)
    assert r.v[-1, 1] == pytest.approx(-9.81 * 0.05, rel=1e-9)


# --- round 3 (issue 23): spatial models, the Simulator, names, tolerances ----------


def spatial_block(**body):
    m = mb.Model(dimension=3)
    m.add_body("b", 1.0, (0.1, 0.1, 0.1), **body)
    return m


@pytest.mark.parametrize("body, element", [
    (dict(angular_velocity=(1e308, 0.0, 0.0)), None),
    ({}, ("add_torque", dict(body="b", torque=(1e308, 0.0, 0.0)))),
    ({}, ("add_torque", dict(body="b", torque=(mb.Linear(1e308), 0.0, 0.0)))),
])
def test_an_overflowing_spatial_body_is_named_by_its_coordinates(body, element):
    """Messages named spatial coordinates from a planar table {x, y, angle}:
    z was called "angle" and e0..e3 read past the table (a UnicodeDecodeError
    of garbage bytes, or "St16_Sp_counted_base")."""
    out = in_subprocess(f"""
        import lagmb as mb
        from lagmb import Linear
        m = mb.Model(dimension=3)
        m.add_body("b", 1.0, (0.1, 0.1, 0.1), **{body!r})
        element = {element!r}
        if element:
            getattr(m, element[0])("push", **element[1])
        try:
            mb.simulate(m, 0.1)
        except (mb.ModelError, mb.SimulationError) as e:
            print(type(e).__name__, e)
    """)
    assert out.split()[0] in ("SimulationError", "AssemblyError") and "angle" not in out
    if "body 'b' " in out:  # a coordinate named: one of a spatial body's
        assert any(f"body 'b' {c} " in out for c in ("x", "y", "z", "e0", "e1", "e2", "e3"))


def test_tolerances_must_mean_something():
    with pytest.raises(mb.ModelError, match="rtol = 1e\\+10 must be below 1"):
        mb.simulate(pendulum(), 1.0, rtol=1e10)
    with pytest.raises(mb.ModelError, match="rtol = 1 must be below 1"):
        mb.Simulator(pendulum(), rtol=1.0)


def test_times_finer_than_double_precision_resolves_are_refused():
    """At t = 1e8 s consecutive doubles are 1.5e-8 s apart: an output every
    1e-9 s gave 985 outputs with 68 distinct, non-increasing times."""
    sim = mb.Simulator(pendulum(), t0=1e8, output_interval=1e-9)
    with pytest.raises(mb.ModelError, match="below the time resolution"):
        sim.advance(1e8 + 1e-6)
    sim = mb.Simulator(pendulum())
    for t in (5e-324, 1e-310):  # used to fail inside IDA and stop the simulator
        with pytest.raises(mb.ModelError, match="time resolution"):
            sim.advance(t)
        with pytest.raises(mb.ModelError, match="time resolution"):
            mb.simulate(pendulum(), t_end=t)
    sim.advance(0.01)  # still usable
    with pytest.raises(mb.ModelError, match="beyond the times a run can resolve"):
        sim.advance(1e300)  # used to fail at t = 0 with a first step of 2.2e286 s
    with pytest.raises(mb.ModelError, match="t_end = 1e\\+12 is beyond"):
        mb.simulate(pendulum(), t_end=1e12)


def test_outputs_of_a_simulator_always_increase():
    sim = mb.Simulator(pendulum(), output_interval=0.003)
    for k in range(1, 40):
        sim.advance(k * 0.001 + 1e-17 * k)
    t = sim.result().t
    assert np.all(np.diff(t) > 0)


def test_max_steps_bounds_the_steps_between_outputs_not_the_run():
    """The IFToMM pendulum to 2000 s at rtol 1e-11 takes about 1.5 million
    steps and was refused at t = 685 s by max_steps = 500,000 over the run.
    Now the bound is per output interval (as SUNDIALS' mxstep): a run with
    outputs spaced as usual goes on; one that cannot reach its next output
    within max_steps stops, naming the option."""
    ggl = dict(rtol=1e-10, max_steps=300, formulation="ggl")
    r = mb.simulate(pendulum(), t_end=2.0, n_out=201, **ggl)
    assert r.stats["steps"] > 300  # more steps in all than the bound
    with pytest.raises(mb.SimulationError, match="max_steps = 300 .*between outputs"):
        mb.simulate(pendulum(), t_end=2.0, n_out=2, **ggl)


def test_a_spline_driver_evaluated_outside_its_times_is_safe():
    """ASan found the spline reading its second derivatives out of range
    (a time that is not a number fell in no interval)."""
    f = mb.Spline([0.0, 0.02, 0.04, 0.06], [0.0, 0.1, 0.3, 0.2])
    for t in (-1.0, 0.0, 0.06, 1.0):
        assert all(math.isfinite(x) for x in f(t))
    assert math.isnan(f(float("nan"))[0])


def test_names_must_be_printable():
    """A NUL or other control character in a name wrote invalid XML into an
    FMU; a newline broke the scene and `lagmb fmu`."""
    for bad in ("k\x00", "a\nb", "tab\there", " padded", "padded "):
        with pytest.raises(mb.ModelError, match="name"):
            mb.Model().add_body(bad, 1.0, 1.0)
    m = mb.Model()
    body = m.add_body("b", 1.0, 1.0)
    with pytest.raises(mb.ModelError, match="input name"):
        m.add_torque("t", body, mb.Input(0.0, name="bad\x01"))
    mb.Model().add_body("Ünïcode ok", 1.0, 1.0)  # printable text is fine


def test_bool_parameters_take_bools_only():
    """bool() turned local="False" into True, and an array into numpy's
    "truth value ... is ambiguous"."""
    m = spatial_block()
    for bad in ("False", np.array([1, 0]), 1, "yes"):
        with pytest.raises(mb.ModelError, match="local must be True or False"):
            m.add_torque("t", "b", (1.0, 0.0, 0.0), local=bad)
    m.add_torque("t", "b", (1.0, 0.0, 0.0), local=np.bool_(False))


@pytest.mark.parametrize("returned, expected", [("abc", "got str 'abc'"), (None, "got NoneType None"),
                                                ([1.0, 2.0], "\\(x, y, z\\)")])
def test_a_force_function_returning_no_number_is_named(returned, expected):
    m = spatial_block()
    m.add_torque("t", "b", lambda t: returned)
    with pytest.raises(mb.SimulationError, match=f"torque 't': the function must return .*{expected}"):
        mb.simulate(m, 0.1)


@pytest.mark.parametrize("make, message", [
    (lambda m: m.add_body("c", 1.0, (1e308,) * 3, position=(2.0, 0.0, 0.0)), "inertia is too large"),
    (lambda m: m.add_distance("d", "ground", (0.0, 0.0, 1.0), "b", (0.0, 0.0, 0.0), length=1e308),
     "length 1e\\+308 is too large"),
])
def test_numbers_whose_squares_overflow_are_refused_when_added(make, message):
    """Inertia (1e308,)*3 gave "moments (-nan, ...)"; a distance of 1e308
    was "left out as redundant ... |Phi| = nan"."""
    with pytest.raises(mb.ModelError, match=message):
        make(spatial_block())


def test_an_input_that_overflows_the_state_is_named():
    """A torque input of 1e308 gave IDA's "EwtSet function failed"; then it
    was taken and the run named the body whose state overflowed. Now it is
    refused where it is set (beyond 1e150: issue 56), and a value within
    that the run still cannot take names the input where the run fails."""
    m = spatial_block()
    m.add_torque("t", "b", (mb.Input(0.0), 0.0, 0.0))
    sim = mb.Simulator(m)
    with pytest.raises(mb.ModelError, match=r"input 't' = 1e\+308 is beyond 1e\+150"):
        sim.set_input("t", 1e308)
    sim.set_input("t", 1e150)
    with pytest.raises(mb.SimulationError, match=r"where inputs were set \(t = 0 s: 't' = 1e\+150 \(t\.torque\.x\)\)"):
        sim.advance(0.1)


def test_one_simulator_called_from_two_threads_serializes_the_calls():
    """advance releases the GIL, and nothing serialized a Simulator: two
    threads advancing one 30-link chain crashed (SIGSEGV) or failed with
    "IDAGetDky failed (-26)". Now one call waits for the other."""
    out = in_subprocess("""
        import threading
        import lagmb as mb
        for dimension in (2, 3):
            m = mb.Model(gravity=(0.0, -9.81) if dimension == 2 else (0.0, 0.0, -9.81), dimension=dimension)
            previous = m.ground
            for k in range(30):
                if dimension == 2:
                    b = m.add_body(f"l{k}", 1.0, 1.0 / 12.0, position=(k + 0.5, 0.0))
                    m.add_revolute(f"j{k}", previous, b, at=(float(k), 0.0))
                else:
                    b = m.add_body(f"l{k}", 1.0, (1e-3, 1 / 12, 1 / 12), position=(k + 0.5, 0.0, 0.0))
                    m.add_revolute(f"j{k}", previous, b, at=(float(k), 0.0, 0.0), axis=(0.0, 1.0, 0.0))
                previous = b
            sim = mb.Simulator(m)
            errors = []
            def work():
                try:
                    for _ in range(40):
                        target = sim.t + 0.002
                        try:
                            sim.advance(target)
                        except mb.ModelError:
                            if target > sim.t:
                                raise
                            continue  # the other thread went past it first: fine
                        sim.q, sim.a, sim.result()
                except Exception as e:
                    errors.append(e)
            threads = [threading.Thread(target=work) for _ in range(2)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            assert not errors, errors
            r = sim.result()
            assert r.t[-1] >= 40 * 0.002 - 1e-9 and (r.t[1:] > r.t[:-1]).all()
            assert r.residual.max() < 1e-6
            print(dimension, "ok")
    """, timeout=300)
    assert out.split() == ["2", "ok", "3", "ok"]


def test_a_simulator_called_from_its_own_force_function_is_refused():
    m = spatial_block()
    holder = {}

    def torque(t):
        if "sim" in holder:  # (not while the simulator starts)
            holder["sim"].advance(1.0)  # from inside the run
        return 0.0

    m.add_torque("t", "b", (torque, 0.0, 0.0))
    holder["sim"] = mb.Simulator(m)
    with pytest.raises(mb.SimulationError) as failure:
        holder["sim"].advance(0.1)
    assert "called from inside the simulator's own run" in str(failure.value.__cause__)


def test_a_saved_state_does_not_load_into_a_model_at_the_same_address():
    """SimulatorState named its model by address: a new model allocated
    where a freed one was accepted its state (a pendulum's state in a free
    body)."""
    import gc

    for _ in range(30):
        m = pendulum()
        state = mb.Simulator(m).state()
        del m
        gc.collect()
        other = mb.Model()
        other.add_body("free", 1.0, 1.0)
        with pytest.raises(mb.ModelError, match="another model"):
            mb.Simulator(other).set_state(state)


def test_set_input_refuses_a_handle_of_another_model():
    def motor():
        m = mb.Model()
        body = m.add_body("b", 1.0, 1.0)
        return m, m.add_torque("t", body, mb.Input(0.0))

    (a, handle_a), (b, _) = motor(), motor()
    with pytest.raises(mb.ModelError, match="another model"):
        mb.Simulator(b).set_input(handle_a, 1.0)


def test_a_wrong_argument_type_is_said_at_the_call():
    for call in (lambda: mb.Simulator("model"), lambda: mb.simulate("model", 1.0),
                 lambda: mb.equilibrium(None)):
        with pytest.raises(mb.ModelError, match="model must be a lagmb.Model"):
            call()


def test_models_pickle_and_deep_copy_and_states_say_what_to_do():
    import copy
    import pickle

    m = pendulum()
    push = mb.Input(0.5)  # one input feeding two places stays one input
    m.add_torque("push", "rod", push)
    m.add_force("shove", "rod", (push, mb.Harmonic(1.0, 3.0)))
    for other in (pickle.loads(pickle.dumps(m)), copy.deepcopy(m)):
        assert other is not m and [name for name, _ in other.elements] == [name for name, _ in m.elements]
        assert [d["name"] for d in other.compiled().inputs] == ["push"]
        a, b = mb.simulate(m, 0.5), mb.simulate(other, 0.5)
        assert np.array_equal(a.q, b.q)  # the same model, to the last bit
    sim = mb.Simulator(m)
    state = sim.state()
    sim.set_state(copy.deepcopy(state))  # a copy in this process is the same state
    with pytest.raises(mb.ModelError, match="cannot be pickled.*pickle the Model"):
        pickle.dumps(state)


def four_bar(dimension, crank_angle, rocker_angle, ground=1.0, crank=0.5, rocker=1.0, coupler=1.2):
    """A crank (revolute at the origin) and a rocker (revolute at (ground,
    0)) whose tips a distance element `coupler` joins; built at the given
    angles, where the tips are generally not `coupler` apart."""
    m = mb.Model(dimension=dimension)
    a = crank * np.array([np.cos(crank_angle), np.sin(crank_angle), 0.0])
    o = np.array([ground, 0.0, 0.0])
    b = o + rocker * np.array([np.cos(rocker_angle), np.sin(rocker_angle), 0.0])
    if dimension == 3:
        m.add_body("crank", 1.0, (0.05, 0.05, 0.01), position=tuple(a / 2))
        m.add_body("rocker", 1.0, (0.05, 0.05, 0.01), position=tuple((o + b) / 2))
        m.add_revolute("pin_c", m.ground, "crank", at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
        m.add_revolute("pin_r", m.ground, "rocker", at=tuple(o), axis=(0.0, 0.0, 1.0))
        m.add_distance("coupler", "crank", tuple(a), "rocker", tuple(b), length=coupler)
    else:
        m.add_body("crank", 1.0, 0.01, position=tuple(a[:2] / 2), angle=crank_angle)
        m.add_body("rocker", 1.0, 0.01, position=tuple((o + b)[:2] / 2), angle=rocker_angle)
        m.add_revolute("pin_c", m.ground, "crank", at=(0.0, 0.0))
        m.add_revolute("pin_r", m.ground, "rocker", at=tuple(o[:2]))
        m.add_distance("coupler", "crank", tuple(a[:2]), "rocker", tuple(b[:2]), length=coupler)
    return m


@pytest.mark.parametrize("dimension", [2, 3])
@pytest.mark.filterwarnings("ignore::lagmb.AssemblyWarning")  # moving the links far is what is asked here
def test_a_four_bar_that_can_close_assembles_from_any_start(dimension):
    """A Grashof crank-rocker (ground 1, crank 0.5, rocker 1, coupler 1.2 m)
    closes at every crank angle. Started with its links on one line, Newton
    stalled where the linear model cannot close the loop (and in space
    stretched the Euler parameters, then blamed "rocker (Euler parameters)",
    |Phi| 0.17); started at (60, 350) degrees a full step overshot to the
    collinear position. Now every start on a 30 degree grid assembles, to the
    coupler's length and unit Euler parameters."""
    starts = [(c, r) for c in range(0, 360, 30) for r in range(0, 360, 30)] + [(60, 350), (180, 180)]
    for crank_angle, rocker_angle in starts:
        m = four_bar(dimension, np.radians(crank_angle), np.radians(rocker_angle))
        q = m.assemble()[0]
        r = mb.simulate(m, 1e-3, n_out=2, analysis="dynamic")
        assert r.residual.max() < 1e-9, (crank_angle, rocker_angle)
        if dimension == 3:
            assert np.allclose([np.linalg.norm(q[3:7]), np.linalg.norm(q[10:14])], 1.0, atol=1e-12)


def test_a_four_bar_that_cannot_close_blames_its_coupler_not_euler_parameters():
    m = four_bar(3, 0.3, 2.0, ground=3.0, crank=0.5, rocker=0.5)  # 0.5 + 1.2 + 0.5 < 3
    with pytest.raises(mb.AssemblyError) as failure:
        m.assemble()
    assert failure.value.violated[0][0] == "coupler"
    assert not any("Euler" in name for name, _ in failure.value.violated)


@pytest.mark.filterwarnings("ignore::lagmb.AssemblyWarning")  # the drive moves the bodies 0.5 m: asked for
def test_a_driven_chain_with_a_heavy_body_assembles():
    """Found by the spatial fuzzer: a cylindrical joint driven 0.5 m, a
    universal joint to a 1,000 kg body; with a mass of 1 it assembled, with
    1,000 the assembly refused it; the safeguards of solve_positions
    (unit Euler parameters at every trial, bounded turns) close it."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    a = m.add_body("a", 0.69, (0.02875, 0.01725, 0.02875), position=(1.383, 1.038, 1.006),
                   orientation=(0.6641, 0.6104, -0.3052, 0.3052))
    m.add_cylindrical("slide", m.ground, a, at=(0.9744, 1.242, 0.8018), axis=(2.0, -1.0, 1.0))
    b = m.add_body("b", 1000.0, (41.67, 66.67, 108.3), position=(2.144, 1.187, 1.21),
                   orientation=(0.3371, 0.0, -0.6657, 0.6657))
    m.add_universal("cross", a, b, at=(1.791, 0.8338, 1.21), axis_i=(0.0, 0.0, 1.0), axis_j=(1.0, 0.0, 0.0))
    m.drive_joint("d", "slide", -0.5)
    q = m.assemble()[0]
    r = mb.simulate(m, 1e-3, n_out=2, analysis="dynamic")
    assert r.residual.max() < 1e-9 and np.isfinite(q).all()


# --- round 4 (issue 39): pickled results, edits during a run, overflow inside --------


def crank_and_pendulum():
    """A crank driven at 2 rad/s with a pendulum on its tip and a spring."""
    m = mb.Model(gravity=(0.0, -G))
    crank = m.add_body("crank", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    m.add_revolute("pin", m.ground, crank, at=(0.0, 0.0))
    m.drive_joint("motor", "pin", mb.Linear(2.0))
    bob = m.add_body("bob", 0.5, 0.01, position=(1.0, -0.5), angle=-math.pi / 2)
    m.add_revolute("tip", crank, bob, at=(1.0, 0.0))
    m.add_spring_damper("spring", m.ground, (1.0, -1.5), bob, (1.0, -0.5), stiffness=20.0, damping=0.3)
    return m


def test_results_and_analyses_pickle_and_answer_as_the_originals_bit_for_bit():
    """Result, Equilibrium, Modes and LinearSystem held the compiled model
    (TypeError: cannot pickle 'lagmb._core.Model'). They travel as the model's
    description and their arrays; the compiled model is rebuilt, with the
    parameter values the run was given."""
    import pickle

    m = crank_and_pendulum()
    r = mb.simulate(m, 1.0, parameters={"bob.mass": 0.7}, sensitivities=["spring.stiffness"])
    r2 = pickle.loads(pickle.dumps(r))
    assert r2.model is not m and r2.model.parameters == m.parameters
    for ask in (lambda x: x.q, lambda x: x.lam, lambda x: x.body("bob").position, lambda x: x.point("bob", (0, 0.1)),
                lambda x: x.reaction("tip"), lambda x: x.effort("motor"), lambda x: x.energy,
                lambda x: x.joint("tip").angle, lambda x: x.residual,
                lambda x: x.sensitivity("spring.stiffness").reaction("tip")):
        assert np.array_equal(ask(r), ask(r2))  # the run's bob.mass 0.7, not the model's 0.5
    assert r2.stats == r.stats and len(r2) == len(r)

    hanging = pendulum()
    hanging.add_rotational_spring_damper("twist", hanging.ground, "rod", stiffness=30.0, damping=0.2)
    eq = mb.equilibrium(hanging)
    modes, lin = mb.modes(hanging, eq), mb.linearize(hanging, eq, outputs=["pin.reaction.y"])
    eq2, modes2, lin2 = pickle.loads(pickle.dumps((eq, modes, lin)))
    assert np.array_equal(eq2.q, eq.q) and np.array_equal(eq2.reaction("pin"), eq.reaction("pin"))
    assert np.array_equal(eq2.body("rod").position, eq.body("rod").position) and eq2.stable is True
    assert np.array_equal(modes2.shapes, modes.shapes) and np.array_equal(modes2.omega, modes.omega)
    assert modes2.kinds == modes.kinds and modes2.equilibrium.model is not hanging
    for key in ("A", "B", "C", "D"):
        assert np.array_equal(getattr(lin2, key), getattr(lin, key))
    assert np.array_equal(lin2.descriptor().A, lin.descriptor().A) and lin2.states == lin.states
    # the unpickled equilibrium is one of the unpickled model, where modes takes it
    assert np.array_equal(mb.modes(eq2.model, eq2).omega, modes.omega)


def test_a_run_in_a_process_pool_comes_back_as_a_result():
    """ProcessPoolExecutor().submit(mb.simulate, m, 1.0).result() failed
    pickling the Result back."""
    from concurrent.futures import ProcessPoolExecutor

    m = crank_and_pendulum()
    with ProcessPoolExecutor(max_workers=1) as pool:
        r = pool.submit(mb.simulate, m, 1.0).result(timeout=120)
    here = mb.simulate(m, 1.0)
    assert np.array_equal(r.q, here.q) and np.array_equal(r.effort("motor"), here.effort("motor"))


def test_a_model_edited_by_another_thread_during_a_run_keeps_the_run_and_its_result():
    """The finished run raised "no body or element named 'extra'" from the
    live model (its warnings read the model's bodies) and the run was lost.
    A run works from a snapshot taken at its start: the Result answers for
    what ran, warns that the model changed, and its .model is that snapshot
    (the live model's handles still name its elements)."""
    m = chain(30)
    edited = threading.Event()

    def nudge(t):  # a force the run evaluates: once under way, the model is edited from another thread
        if t > 0.05 and not edited.is_set():
            editor = threading.Thread(target=lambda: (m.add_body("extra", 1.0, 0.1, position=(0.0, 5.0)),
                                                      edited.set()))
            editor.start()
            editor.join()
        return (0.0, 0.0)

    m.add_force("nudge", "link29", nudge)
    with pytest.warns(UserWarning, match="the model was changed .* while it ran"):
        r = mb.simulate(m, 0.2)
    assert edited.is_set() and "extra" in [b.name for b in m.bodies]
    assert r.model is not m and "extra" not in [b.name for b in r.model.bodies]
    assert r.q.shape[1] == 90 and np.isfinite(r.body(m.bodies[3]).position).all()
    assert r.reaction("joint2").shape == (len(r), 3)
    with pytest.raises(mb.ModelError, match="no body or element named 'extra'"):
        r.body("extra")
    # the model now has the extra body, and a new run has it
    assert mb.simulate(m, 0.1).q.shape[1] == 93


def test_sensitivities_must_be_a_list_of_names():
    for bad in (5, [1.0], None.__class__):
        with pytest.raises(mb.ModelError, match="simulate: sensitivities must be a list of parameter names"):
            mb.simulate(pendulum(), 0.1, sensitivities=bad)


@pytest.mark.parametrize("build, element", [
    ("""m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
        rod = m.add_body("rod", 1.0, (0.1, 0.1, 0.1), position=(1e200, 0.0, 0.0))
        m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))""", "pin"),
    ("""m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
        a = m.add_body("a", 1.0, (0.1, 0.1, 0.1), position=(0.5, 0.0, 0.0))
        b = m.add_body("b", 1.0, (0.1, 0.1, 0.1), position=(0.5, 0.0, -1.0))
        ja = m.add_revolute("ja", m.ground, a, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
        jb = m.add_revolute("jb", m.ground, b, at=(0.0, 0.0, -1.0), axis=(0.0, 1.0, 0.0))
        m.add_joint_coupling("mimic", jb, ja, 1e300)""", "mimic"),
])
def test_a_model_that_overflows_inside_names_the_element_not_an_internal_function(build, element):
    """A centre 1e200 m from its joint, a mimic multiplier of 1e300: finite
    numbers whose products overflow stopped every analysis with
    "constraint_rank: q and t must be finite"."""
    out = in_subprocess(f"""
        import warnings
        import lagmb as mb
        warnings.simplefilter("ignore")
        {build}
        for call in (lambda: mb.simulate(m, 0.1), lambda: mb.equilibrium(m), m.degrees_of_freedom, m.assemble):
            try:
                call()
            except mb.AssemblyError as e:
                print(e)
    """)
    lines = out.strip().splitlines()
    assert len(lines) == 4, out
    for line in lines:
        assert line.startswith(f"the equations of '{element}' overflow double precision at t = 0"), line
        assert "constraint_rank" not in line
