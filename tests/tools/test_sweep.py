"""Parameter studies (mb.sweep): every case as a run alone would give it, on
any executor (in process, threads, processes, a Dask LocalCluster), failed
cases recorded, interrupted studies resumed from their store, designs
reproducible, bad input refused before any case runs."""

import errno
import os
import re
import signal
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import lagmb as mb
import paths  # (tests/paths.py)

xr = pytest.importorskip("xarray")
EXAMPLES = Path(paths.EXAMPLES)
GRID = {"rod.mass": [1.0, 2.5], "crank.inertia": [0.001, 0.002], "slider.mass": [0.5, 0.8]}


def slider_x_end(r):
    """The slider's position at the end (a module-level function: picklable)."""
    return float(r.body("slider").position[-1, 0])


def scene():
    return mb.load_scene(EXAMPLES / "slider_crank.toml")


def run_grid(executor=None, **kw):
    return mb.sweep(scene(), GRID, t_end=0.2, outputs={"x_end": slider_x_end, "peak": mb.sweep.peak_reaction("C"),
                                                        "torque": mb.sweep.peak_effort("motor")},
                    histories=[0.0, 0.1, 0.2], executor=executor, progress=False, **kw)


def test_a_grid_gives_case_by_case_what_each_run_gives_alone():
    ds = run_grid()
    assert ds.sizes["case"] == 8 and list(ds["status"].values) == ["ok"] * 8
    # the last name varies fastest, as itertools.product
    assert list(ds["slider.mass"].values[:2]) == [0.5, 0.8] and list(ds["rod.mass"].values[[0, 4]]) == [1.0, 2.5]
    s = scene()
    for i in range(8):
        params = {name: float(ds[name].values[i]) for name in GRID}
        alone = s.run(t_end=0.2, t_out=[0.0, 0.1, 0.2], parameters=params)
        assert ds["x_end"].values[i] == alone.body("slider").position[-1, 0]  # bit for bit
        assert ds["torque"].values[i] == np.abs(alone.effort("motor")).max()
        np.testing.assert_array_equal(ds["q"].values[i], alone.q)
        assert ds["steps"].values[i] == alone.stats["steps"]
    grid = mb.sweep.as_grid(ds)
    assert grid["peak"].dims == ("rod.mass", "crank.inertia", "slider.mass")
    assert grid["peak"].sel({"rod.mass": 2.5, "crank.inertia": 0.001, "slider.mass": 0.8}) == ds["peak"].values[5]
    assert ds.attrs["computed_cases"] == 8
    # what the plots and tables label with: each varied parameter's unit, each built-in output's
    assert ds["rod.mass"].attrs["units"] == "kg" and ds["crank.inertia"].attrs["units"] == "kg m^2"
    assert ds["peak"].attrs["units"] == "N" and ds["torque"].attrs["units"] == "N m"  # the motor turns the crank
    assert "units" not in ds["x_end"].attrs  # a function of the user's: no unit known


def test_threads_processes_and_a_dask_cluster_give_the_in_process_numbers():
    reference = run_grid()
    with ThreadPoolExecutor(2) as ex:
        threads = run_grid(ex)
    with ProcessPoolExecutor(2) as ex:
        processes = run_grid(ex, batch_size=3)
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        dask = run_grid(client)
    for ds in (threads, processes, dask):
        for name in ("x_end", "peak", "torque", "q", "steps"):
            np.testing.assert_array_equal(ds[name].values, reference[name].values)
        assert list(ds["case"].values) == list(range(8))


def four_bar_with_a_coupler_link():
    """Crank A(0, 0)-B(0, 1), rocker D(4, 0)-C(4, 3), the coupler a massless
    link B-C (its length a parameter, "coupler.length")."""
    m = mb.Model(gravity=(0.0, -9.81))
    crank = m.add_body("crank", 1.0, 1 / 12, position=(0.0, 0.5), angle=np.pi / 2, angular_velocity=2.0)
    rocker = m.add_body("rocker", 3.0, 9 / 4, position=(4.0, 1.5), angle=np.pi / 2)
    m.add_revolute("A", m.ground, crank, at=(0.0, 0.0))
    m.add_revolute("D", m.ground, rocker, at=(4.0, 0.0))
    m.add_distance("coupler", crank, (0.0, 1.0), rocker, (4.0, 3.0), length=float(np.hypot(4.0, 2.0)))
    return m


def test_a_failing_case_is_recorded_and_the_others_complete():
    model = four_bar_with_a_coupler_link()
    cases = [{"coupler.length": 4.5}, {"coupler.length": 20.0}, {"rtol": 1e-16}, {"max_steps": 1, "n_out": 2},
             {"crank.mass": 2.0}]
    ds = mb.sweep(model, cases, t_end=0.5, outputs={"rocker": mb.sweep.final("rocker.angle")}, progress=False)
    status = list(ds["status"].values)
    assert status[0] == "ok" and status[4] == "ok"
    assert status[1].startswith("AssemblyError: ")  # a coupler too long to close the loop
    assert status[2].startswith("ModelError: ") and "rtol" in status[2]
    assert status[3].startswith("SimulationError: ") and "max_steps" in status[3]
    assert np.isnan(ds["rocker"].values[1:4]).all() and np.isfinite(ds["rocker"].values[[0, 4]]).all()
    assert np.isnan(ds["coupler.length"].values[4]) and ds["coupler.length"].values[1] == 20.0
    assert ds["steps"].values[1] == -1 and ds["steps"].values[0] > 0
    # a coupler 0.03 m longer than the drawing: the case ran, and says what assembly did
    assert ds["warnings"].values[0].startswith("AssemblyWarning: assembly moved 2 bodies")
    assert ds["warnings"].values[4] == ""


# the output, in a module of its own that the interrupted sweep and the one
# that resumes it both import: the same function (a store knows its code);
# the sweep run in a subprocess slows it down
OUTPUTS_MODULE = """
import os, time

def x_end(r):
    time.sleep(float(os.environ.get("SLOW_OUTPUT", "0")))
    return float(r.q[-1, 6])
"""

SLOW_SWEEP = """
import sys
import lagmb as mb
from sweep_outputs import x_end

if __name__ == "__main__":
    mb.sweep(mb.load_scene(sys.argv[1]), {"rod.mass": [1.0 + 0.1 * k for k in range(12)]}, t_end=0.05,
             outputs={"x_end": x_end}, store=sys.argv[2], batch_size=2, progress=False)
"""


def batches_in(store):
    return sorted(p.name for p in store.iterdir() if p.name.startswith("batch_"))


def start_slow_sweep(tmp_path, store, batches=2):
    """A sweep of 12 cases in batches of 2 (0.15 s a case) in a subprocess
    writing store, once it has written `batches` batches."""
    (tmp_path / "sweep_outputs.py").write_text(OUTPUTS_MODULE)
    script = tmp_path / "slow_sweep.py"
    script.write_text(SLOW_SWEEP)
    env = dict(os.environ, SLOW_OUTPUT="0.15", PYTHONPATH=os.pathsep.join([str(tmp_path)] + sys.path))
    proc = subprocess.Popen([sys.executable, str(script), str(EXAMPLES / "slider_crank.toml"), str(store)], env=env)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not (store.is_dir() and len(batches_in(store)) >= batches):
        time.sleep(0.05)
    return proc


def resume(tmp_path, store, **kw):
    """The slow sweep's, in this process and at full speed."""
    sys.path.insert(0, str(tmp_path))
    try:
        from sweep_outputs import x_end
    finally:
        sys.path.remove(str(tmp_path))
    return mb.sweep(scene(), {"rod.mass": [1.0 + 0.1 * k for k in range(12)]}, t_end=0.05,
                    outputs={"x_end": x_end}, store=store, batch_size=2, progress=False, **kw)


def test_an_interrupted_sweep_resumes_from_its_store_computing_only_what_is_missing(tmp_path):
    store = tmp_path / "study.zarr"
    proc = start_slow_sweep(tmp_path, store)
    proc.send_signal(signal.SIGKILL)  # its lock goes with it
    proc.wait()
    finished = batches_in(store)
    assert 2 <= len(finished) < 6, finished
    before = mb.sweep.open_store(store)
    ds = resume(tmp_path, store)
    assert ds.attrs["computed_cases"] == 12 - 2 * len(finished)
    assert list(ds["case"].values) == list(range(12)) and list(ds["status"].values) == ["ok"] * 12
    # the cases finished before the kill were kept, not computed again
    np.testing.assert_array_equal(ds["x_end"].sel(case=before["case"].values).values, before["x_end"].values)
    again = resume(tmp_path, store)
    assert again.attrs["computed_cases"] == 0
    with pytest.raises(mb.ModelError, match="holds another sweep"):
        mb.sweep(scene(), {"rod.mass": [9.0]}, t_end=0.05, outputs={"x_end": slider_x_end}, store=store, progress=False)


def test_designs_are_reproducible_from_their_seed():
    bounds = {"rod.mass": (1.0, 3.0), "slider.mass": (0.2, 1.0)}
    for make in (mb.sweep.latin_hypercube, mb.sweep.sobol):
        a, b, c = make(bounds, 8, seed=7), make(bounds, 8, seed=7), make(bounds, 8, seed=8)
        assert a.cases == b.cases and a.cases != c.cases and len(a) == 8
        values = np.array([[case["rod.mass"], case["slider.mass"]] for case in a.cases])
        assert (values[:, 0] >= 1.0).all() and (values[:, 0] <= 3.0).all()
    lhs = np.array([case["rod.mass"] for case in mb.sweep.latin_hypercube(bounds, 8, seed=1).cases])
    assert sorted(np.floor((lhs - 1.0) / 0.25).astype(int)) == list(range(8))  # one per stratum
    mc = mb.sweep.monte_carlo({"rod.mass": (1.0, 3.0)}, 5, seed=3)
    assert mc.cases == mb.sweep.monte_carlo({"rod.mass": (1.0, 3.0)}, 5, seed=3).cases
    ds = mb.sweep(scene(), mc, t_end=0.05, outputs={"x_end": slider_x_end}, progress=False)
    np.testing.assert_array_equal(ds["rod.mass"].values, [case["rod.mass"] for case in mc.cases])


def test_bad_input_is_refused_before_any_case_runs():
    s = scene()
    with pytest.raises(mb.ModelError, match=r"no parameter 'rod\.length'; the model's parameters are crank\.mass"):
        mb.sweep(s, [{"rod.mass": 1.0}, {"rod.length": 0.3}], t_end=0.1, progress=False)
    with pytest.raises(mb.ModelError, match=r"case 1: rod\.mass = -2\.0: .*mass"):
        mb.sweep(s, {"rod.mass": [1.0, -2.0]}, t_end=0.1, progress=False)
    with pytest.raises(mb.ModelError, match="must be a number"):
        mb.sweep(s, [{"rod.mass": "heavy"}], t_end=0.1, progress=False)
    with pytest.raises(mb.ModelError, match="the grid is empty"):
        mb.sweep(s, {}, t_end=0.1, progress=False)
    with pytest.raises(mb.ModelError, match="axis 'rod.mass' has no values"):
        mb.sweep(s, {"rod.mass": []}, t_end=0.1, progress=False)
    with pytest.raises(mb.ModelError, match="the table is empty"):
        mb.sweep(s, [], t_end=0.1, progress=False)
    with pytest.raises(mb.ModelError, match="pickle"):
        with ProcessPoolExecutor(1) as ex:
            mb.sweep(s, {"rod.mass": [1.0]}, t_end=0.1, outputs={"x": lambda r: 0.0}, executor=ex, progress=False)


def test_run_settings_vary_like_parameters_method_included():
    ds = mb.sweep(scene(), [{"method": "ggl"}, {"method": "projection-erk", "rtol": 1e-10}], t_end=0.1,
                  analysis="dynamic", outputs={"x_end": slider_x_end}, progress=False)
    assert list(ds["method"].values) == ["ggl", "projection-erk"] and np.isnan(ds["rtol"].values[0])
    alone = scene().run(t_end=0.1, method="projection-erk", rtol=1e-10, analysis="dynamic")
    assert ds["x_end"].values[1] == alone.body("slider").position[-1, 0]
    assert ds["x_end"].values[0] == pytest.approx(ds["x_end"].values[1], abs=1e-6)


def test_a_thread_sweep_keeps_each_case_s_warnings_and_leaves_the_warnings_module_alone():
    import warnings

    model = four_bar_with_a_coupler_link()
    cases = [{"coupler.length": 4.5} if k % 2 else {"crank.mass": 1.0 + k} for k in range(8)]
    with ThreadPoolExecutor(2) as ex:
        ds = mb.sweep(model, cases, t_end=0.2, executor=ex, batch_size=1, progress=False)
    for k in range(8):
        assert ds["warnings"].values[k].startswith("AssemblyWarning") == bool(k % 2), (k, ds["warnings"].values[k])
    with pytest.warns(UserWarning, match="still shown"):
        warnings.warn("still shown")


# --- a store holds one study, whole, for one sweep at a time (issue 39) ------------

FOUR = {"rod.mass": [1.0, 2.0, 3.0, 4.0]}


def four_cases(store, outputs=None, **kw):
    """4 cases in batches of 2 (batch_000000, batch_000001) over 0.02 s."""
    return mb.sweep(scene(), FOUR, t_end=0.02, outputs=outputs or {"pin": mb.sweep.peak_reaction("B")},
                    store=store, batch_size=2, progress=False, **kw)


def user_output(name, column):
    """A function `name` of module "user_outputs" giving q[-1, column]: the
    same name and module, other code for another column (made by exec: no
    source, so the store knows it by its bytecode)."""
    namespace = {"__name__": "user_outputs"}
    exec(f"def {name}(r):\n    return float(r.q[-1, {column}])\n", namespace)
    return namespace[name]


def test_a_store_knows_what_each_output_computes_not_only_its_name(tmp_path):
    store = tmp_path / "study.zarr"
    first = four_cases(store)
    for other, there, here in [
            (mb.sweep.peak_reaction("C"), "peak_reaction('B')", "peak_reaction('C')"),
            (mb.sweep.final("der(slider.x)"), "peak_reaction('B')", "final('der(slider.x)')")]:
        with pytest.raises(mb.ModelError, match=rf"holds another sweep \(made with other outputs \(pin: "
                                                rf"{re.escape(there)} there, {re.escape(here)} here\)\)"):
            four_cases(store, {"pin": other})
    assert four_cases(store).attrs["computed_cases"] == 0  # the same outputs: nothing computed
    np.testing.assert_array_equal(four_cases(store)["pin"].values, first["pin"].values)
    # a function replaced under the same module and name
    mine = tmp_path / "mine.zarr"
    four_cases(mine, {"x": user_output("f", 6)})
    assert four_cases(mine, {"x": user_output("f", 6)}).attrs["computed_cases"] == 0
    with pytest.raises(mb.ModelError, match=r"other outputs \(x: user_outputs\.f \(\w+ \w+\) there, "
                                            r"user_outputs\.f \(\w+ \w+\) here\)"):
        four_cases(mine, {"x": user_output("f", 7)})


def test_a_sweep_writes_into_no_folder_but_a_store_of_its_own(tmp_path):
    project = tmp_path / "project"
    (project / "tmp_data").mkdir(parents=True)
    (project / "tmp_data" / "run.csv").write_text("kept")
    (project / "notes.txt").write_text("kept")
    with pytest.raises(mb.ModelError, match=rf"'{re.escape(str(project))}' is a folder that is not a study's store"):
        four_cases(project)
    assert sorted(p.name for p in project.iterdir()) == ["notes.txt", "tmp_data"]  # nothing removed, nothing added
    assert (project / "tmp_data" / "run.csv").read_text() == "kept"
    zarr = pytest.importorskip("zarr")
    foreign = tmp_path / "other.zarr"
    zarr.open_group(str(foreign), mode="w").create_array("temperature", shape=(3,), dtype="f8")[:] = [1.0, 2.0, 3.0]
    before = sorted(str(p.relative_to(foreign)) for p in foreign.rglob("*"))
    with pytest.raises(mb.ModelError, match="a Zarr store, but not a study's"):
        four_cases(foreign)
    with pytest.raises(mb.ModelError, match="a Zarr store, but not a study's"):
        mb.sweep.open_store(foreign)
    assert sorted(str(p.relative_to(foreign)) for p in foreign.rglob("*")) == before
    (tmp_path / "a_file").write_text("")
    with pytest.raises(mb.ModelError, match="is a file; a store is a folder"):
        four_cases(tmp_path / "a_file")
    empty = tmp_path / "empty"
    empty.mkdir()
    assert four_cases(empty).sizes["case"] == 4  # an empty folder becomes a store
    with pytest.raises(mb.ModelError, match=r"the store must be a folder's path \(a str or a pathlib\.Path\), got 7"):
        four_cases(7)


def damaged_copies(tmp_path):
    """{what was done: a copy of a finished 4-case store so damaged}, and
    the finished store's Dataset."""
    import shutil

    store = tmp_path / "study.zarr"
    whole = four_cases(store)

    def copy(label):
        target = tmp_path / label.replace(" ", "_")
        shutil.copytree(store, target)
        return target

    copies = {}
    target = copies["chunks missing"] = copy("chunks missing")  # a copy or a sync cut short
    for chunk in (target / "batch_000001").glob("*/c/*"):
        chunk.unlink()
    target = copies["emptied"] = copy("emptied")
    shutil.rmtree(target / "batch_000001")
    (target / "batch_000001").mkdir()
    target = copies["garbled"] = copy("garbled")
    chunk = target / "batch_000001" / "pin" / "c" / "0"
    data = bytearray(chunk.read_bytes())
    data[len(data) // 2] ^= 0xFF
    chunk.write_bytes(bytes(data))
    target = copies["moved"] = copy("moved")  # batch 0's cases under batch 1's name
    shutil.rmtree(target / "batch_000001")
    shutil.copytree(target / "batch_000000", target / "batch_000001")
    target = copies["beyond"] = copy("beyond")
    shutil.copytree(target / "batch_000000", target / "batch_000005")
    return copies, whole


def test_a_damaged_batch_is_named_left_out_by_open_store_and_computed_again_by_the_sweep(tmp_path):
    copies, whole = damaged_copies(tmp_path)
    why = {"chunks missing": r"its file case/c/0 is missing", "emptied": "it has no marker of its files",
           "garbled": "its file pin/c/0 differs from what was written",
           "moved": "it holds another sweep's cases, or another batch's"}
    for label, store in copies.items():
        if label == "beyond":
            continue
        named = rf"the store '{re.escape(str(store))}': batch_000001 \(cases 2\.\.3\): {why[label]}"
        with pytest.warns(UserWarning, match=named + r".*: left out"):
            ds = mb.sweep.open_store(store)
        assert list(ds["case"].values) == [0, 1], label  # never read back as "ok" with NaN
        with pytest.warns(UserWarning, match=named + r".*: computed again"):
            again = four_cases(store)
        assert again.attrs["computed_cases"] == 2, label
        np.testing.assert_array_equal(again["pin"].values, whole["pin"].values)
        assert list(again["status"].values) == ["ok"] * 4
    store = copies["beyond"]
    beyond = r"batch_000005 is no batch of its study \(4 cases in batches batch_000000\.\.batch_000001\): left out"
    with pytest.warns(UserWarning, match=beyond):
        assert mb.sweep.open_store(store).sizes["case"] == 4
    with pytest.warns(UserWarning, match=beyond):
        ds = four_cases(store)
    assert ds.sizes["case"] == 4 and ds.attrs["computed_cases"] == 0


def edit_description(store, **changes):
    import json

    meta = store / "zarr.json"
    held = json.loads(meta.read_text())
    held["attributes"]["lagmb_sweep"].update(changes)
    meta.write_text(json.dumps(held))


@pytest.mark.parametrize("damage, message", [
    (lambda store: (store / "zarr.json").write_text("{garbage"), r"cannot be read: its zarr\.json is damaged "
                                                                  r"\(JSONDecodeError"),
    (lambda store: (store / "zarr.json").unlink(), r"cannot be read: its zarr\.json is missing"),
    (lambda store: edit_description(store, batch_size=0),
     r"cannot be read: its description is damaged \(batch_size: 0\)"),
    (lambda store: edit_description(store, cases="4"), r"cannot be read: its description is damaged \(cases: '4'\)"),
    (lambda store: edit_description(store, format=1), r"was written by another version of lagmb \(store format 1"),
])
def test_a_store_whose_description_is_damaged_is_a_model_error_naming_it(tmp_path, damage, message):
    store = tmp_path / "study.zarr"
    four_cases(store)
    damage(store)
    named = rf"the store '{re.escape(str(store))}' "
    with pytest.raises(mb.ModelError, match=r"sweep\.open_store: " + named + message):
        mb.sweep.open_store(store)
    with pytest.raises(mb.ModelError, match=r"sweep: " + named + message):
        four_cases(store)


def test_a_store_is_used_by_one_sweep_at_a_time(tmp_path):
    store = tmp_path / "study.zarr"
    proc = start_slow_sweep(tmp_path, store, batches=1)
    try:
        assert proc.poll() is None, "the slow sweep ended too soon"
        with pytest.raises(mb.ModelError, match=rf"the store '{re.escape(str(store))}' is in use by another sweep "
                                                rf"\(pid {proc.pid}\)"):
            resume(tmp_path, store)
        assert proc.wait(timeout=120) == 0  # not disturbed: its batches were left alone
    finally:
        proc.kill()
    ds = resume(tmp_path, store)
    assert ds.attrs["computed_cases"] == 0 and list(ds["status"].values) == ["ok"] * 12
    # the lock file of a process that is gone is taken over
    (store / "lagmb_sweep.lock").write_text("999999999 elsewhere\n")
    assert resume(tmp_path, store).attrs["computed_cases"] == 0


@pytest.mark.skipif(not hasattr(os, "fork"), reason="forks a worker process")
def test_the_lock_of_a_process_that_died_is_taken_over_even_while_its_forked_workers_live(tmp_path):
    store = tmp_path / "study.zarr"
    four_cases(store)
    # the sweep's process locks the store, forks a worker (which inherits the
    # lock file's descriptor, as a process pool's fork does) and dies
    script = (f"import os, sys, time\nfrom lagmb.studies.store import Lock\nlock = Lock({str(store)!r}, 'sweep')\n"
              "worker = os.fork()\nif worker == 0:\n    time.sleep(60)\n    os._exit(0)\n"
              "print(worker, flush=True)\nos._exit(0)\n")
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    worker = int(proc.stdout.readline())
    try:
        assert proc.wait(timeout=60) == 0
        os.kill(worker, 0)  # the worker lives on
        assert four_cases(store).attrs["computed_cases"] == 0  # and the store is not "in use"
    finally:
        os.kill(worker, signal.SIGKILL)
        proc.stdout.close()


def test_two_sweeps_of_one_process_on_one_store_are_one_too_many(tmp_path):
    import threading

    store = tmp_path / "study.zarr"
    release = threading.Event()

    def held_until_released(r):
        release.wait(60)
        return 0.0

    first = ThreadPoolExecutor(1).submit(four_cases, store, {"held": held_until_released})
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not (store / "zarr.json").exists():
            time.sleep(0.01)
        with pytest.raises(mb.ModelError, match=rf"is in use by another sweep \(pid {os.getpid()}, this process\)"):
            four_cases(store, {"held": held_until_released})
    finally:
        release.set()
    assert first.result().sizes["case"] == 4


def test_a_store_on_a_file_system_without_locks_is_used_with_a_warning(tmp_path, monkeypatch):
    fcntl = pytest.importorskip("fcntl")

    def no_locks(*args):
        raise OSError(errno.ENOLCK, "No locks available")

    monkeypatch.setattr(fcntl, "lockf", no_locks)
    with pytest.warns(UserWarning, match=r"cannot be locked \(No locks available\): run no other sweep on it"):
        assert four_cases(tmp_path / "study.zarr").sizes["case"] == 4


def test_a_batch_written_twice_is_not_an_error(tmp_path):
    from lagmb import studies
    from lagmb.studies.store import Store

    store = tmp_path / "study.zarr"
    ds = four_cases(store)
    held = studies.check_store(store)
    writer = Store(store, held, "sweep")
    try:
        part = ds.isel(case=[0, 1])
        writer.write(0, 0, 2, part)  # already there and whole
    finally:
        writer.close()
    assert four_cases(store).attrs["computed_cases"] == 0


def t_end_or_die(r):
    """The run's end time; a worker process dies past LAGMB_TEST_DIE_PAST (s)."""
    past = os.environ.get("LAGMB_TEST_DIE_PAST")
    if past and r.t[-1] > float(past):
        os._exit(1)
    return float(r.t[-1])


def test_a_worker_process_that_dies_is_a_lagmb_error_and_the_finished_batches_stay(tmp_path, monkeypatch):
    store = tmp_path / "study.zarr"
    cases = [{"t_end": 0.01 * (k + 1)} for k in range(6)]
    monkeypatch.setenv("LAGMB_TEST_DIE_PAST", "0.045")  # the worker dies in the third batch
    with ProcessPoolExecutor(1) as ex:
        with pytest.raises(mb.SimulationError, match=r"sweep: a worker process died .* with 2 of 6 cases "
                                                     r"unfinished .*the 4 finished cases are in the store"):
            mb.sweep(scene(), cases, outputs={"t": t_end_or_die}, executor=ex, store=store, batch_size=2,
                     progress=False)
    assert batches_in(store) == ["batch_000000", "batch_000001"]
    monkeypatch.delenv("LAGMB_TEST_DIE_PAST")
    ds = mb.sweep(scene(), cases, outputs={"t": t_end_or_die}, store=store, batch_size=2, progress=False)
    assert ds.attrs["computed_cases"] == 2
    np.testing.assert_allclose(ds["t"].values, [0.01 * (k + 1) for k in range(6)])


def test_what_cannot_run_or_cannot_fit_is_refused_before_any_case_runs():
    s = scene()
    with pytest.raises(mb.ModelError, match=r"case 0: the run setting 'atol' must be one number or name a case, "
                                            r"got \[1e-06, .*give it as atol=\.\.\."):
        mb.sweep(s, [{"atol": [1e-6] * 6}], t_end=0.02, progress=False)
    with pytest.raises(mb.ModelError, match=r"case 1: 'rod\.mass' is too large for a float: an integer of about 400"):
        mb.sweep(s, [{"rod.mass": 1.0}, {"rod.mass": 10**400}], t_end=0.02, progress=False)
    with pytest.raises(mb.ModelError, match=r"case 0: 't_end' is too large for a float"):
        mb.sweep(s, [{"t_end": 10**400}], progress=False)
    with pytest.raises(mb.ModelError, match=r"100,000,000 cases: at most 10,000,000 in one sweep"):
        mb.sweep(s, {"rod.mass": np.linspace(1, 2, 10**4), "slider.mass": np.linspace(1, 2, 10**4)}, t_end=0.02,
                 progress=False)
    # 10,000 cases, each holding its 6 coordinates at a million times: about 1 TB
    with pytest.raises(mb.ModelError, match=r"10,000 cases would take about [\d,.]+ GB of memory \(this machine "):
        mb.sweep(s, {"rod.mass": np.linspace(1, 2, 10**4)}, t_end=0.02, histories=np.linspace(0, 0.02, 10**6),
                 progress=False)
    with pytest.raises(mb.ModelError, match=r"sweep\.monte_carlo: n = 1000000000000 cases: at most 10,000,000"):
        mb.sweep.monte_carlo({"rod.mass": (1.0, 2.0)}, 10**12, seed=1)
    with pytest.raises(mb.ModelError, match=r"sweep\.sobol: n = 1099511627776 cases: at most 10,000,000"):
        mb.sweep.sobol({"rod.mass": (1.0, 2.0)}, 2**40, seed=1)
    for make in (mb.sweep.latin_hypercube, mb.sweep.sobol, mb.sweep.monte_carlo):
        with pytest.raises(mb.ModelError, match=r"seed must be an integer >= 0 \(or None\), got 'seed'"):
            make({"rod.mass": (1.0, 2.0)}, 4, seed="seed")
    with pytest.raises(mb.ModelError, match=r"'rod\.mass' needs \(low, high\), got \(1, 1000"):
        mb.sweep.latin_hypercube({"rod.mass": (1, 10**400)}, 4, seed=1)


def test_a_data_frame_s_missing_value_keeps_the_model_s_value_as_a_list_of_dicts_does():
    pandas = pytest.importorskip("pandas")
    cases = [{"rod.mass": 2.0}, {"slider.mass": 0.8, "method": "ggl"}, {"rod.mass": 1.5, "slider.mass": 0.6}]
    table = pandas.DataFrame(cases)  # NaN (None in the text column) where a case gives no value
    assert table.isna().to_numpy().sum() == 4
    listed = mb.sweep(scene(), cases, t_end=0.02, outputs={"x_end": slider_x_end}, progress=False)
    framed = mb.sweep(scene(), table, t_end=0.02, outputs={"x_end": slider_x_end}, progress=False)
    assert list(framed["status"].values) == ["ok"] * 3
    np.testing.assert_array_equal(framed["x_end"].values, listed["x_end"].values)


def test_a_grid_written_as_text_is_linspace_or_the_list_in_the_order_given():
    """mb.sweep.grid_from_text reads NAME=SPEC as lagmb sweep --vary does:
    A:B:N is numpy.linspace(A, B, N), V1,V2,... the list, names in the order
    given, whole-number settings as ints; the grid is mb.sweep's."""
    from lagmb import studies

    assert studies.grid_from_text is mb.sweep.grid_from_text
    grid = studies.grid_from_text(["rod.mass=0.5:2:4", " slider.mass = 0.2, 0.4", "n_out=11,21"])
    assert grid == {"rod.mass": [0.5, 1.0, 1.5, 2.0], "slider.mass": [0.2, 0.4], "n_out": [11, 21]}
    assert list(grid) == ["rod.mass", "slider.mass", "n_out"] and all(type(n) is int for n in grid["n_out"])
    assert grid["rod.mass"] == list(np.linspace(0.5, 2.0, 4))
    assert studies.grid_from_text("crank.angle.start=-1:1:3") == {"crank.angle.start": [-1.0, 0.0, 1.0]}
    ds = mb.sweep(scene(), studies.grid_from_text(["rod.mass=1,2"]), t_end=0.05, progress=False)
    assert list(ds["rod.mass"].values) == [1.0, 2.0] and list(ds["status"].values) == ["ok", "ok"]


@pytest.mark.parametrize("specs, message", [
    (["rod.mass=1:2"], "'rod.mass=1:2': A:B:N has three parts (N values from A to B), got 2"),
    (["rod.mass=1:2:1.5"], "'rod.mass=1:2:1.5': N = 1.5 must be a whole number of values, at least 2 (one value: "
                           "rod.mass=V)"),
    (["rod.mass=1:1:3"], "'rod.mass=1:1:3': A:B:N runs from A to B: give A and B apart"),
    (["rod.mass=1,heavy"], "'rod.mass=1,heavy': 'heavy' is not a decimal number; SPEC is A:B:N"),
    (["rod.mass=1_0"], "'rod.mass=1_0': '1_0' is not a decimal number"),
    (["rod.mass=1,,2"], "'rod.mass=1,,2': an empty value"),
    (["rod.mass=inf,1"], "'rod.mass=inf,1': inf must be a finite number"),
    (["rod.mass=1,2,1"], "'rod.mass=1,2,1': 1 is listed twice"),
    (["n_out=10,20.5"], "'n_out=10,20.5': n_out takes whole numbers"),
    (["rod.mass"], "'rod.mass': must be NAME=SPEC"),
    (["rod.mass=1,2", "rod.mass=3"], "'rod.mass=3': rod.mass is varied twice (sweep.grid_from_text: 'rod.mass=1,2')"),
    (["a=1:2:10000", "b=1:2:10000"], ": 100,000,000 cases (10000 x 10000): at most 10,000,000 in one study"),
    ([], ": give at least one 'NAME=SPEC'"),
])
def test_a_grid_text_that_is_no_spec_is_a_model_error_naming_it(specs, message):
    with pytest.raises(mb.ModelError) as e:
        mb.sweep.grid_from_text(specs)
    assert str(e.value).startswith("sweep.grid_from_text") and message in str(e.value)
    with pytest.raises(mb.ModelError) as e:  # as the command line's option names it
        mb.sweep.grid_from_text(specs, who="--vary")
    assert "sweep.grid_from_text" not in str(e.value)
