"""Parameter studies (mb.sweep): every case as a run alone would give it, on
any executor (in process, threads, processes, a Dask LocalCluster), failed
cases recorded, interrupted studies resumed from their store, designs
reproducible, bad input refused before any case runs."""

import os
import signal
import subprocess
import sys
import textwrap
import time
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import lagmb as mb

xr = pytest.importorskip("xarray")
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
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


SLOW_SWEEP = """
import sys, time
import lagmb as mb

def x_end(r):
    time.sleep(0.15)
    return float(r.q[-1, 6])

if __name__ == "__main__":
    scene = mb.load_scene(sys.argv[1])
    mb.sweep(scene, {{"rod.mass": [1.0 + 0.1 * k for k in range(12)]}}, t_end=0.05, outputs={{"x_end": x_end}},
             store=sys.argv[2], batch_size=2, progress=False)
"""


def x_end(r):  # the same output (by name) as the interrupted sweep's, without its sleep
    return float(r.q[-1, 6])


def test_an_interrupted_sweep_resumes_from_its_store_computing_only_what_is_missing(tmp_path):
    script = tmp_path / "slow_sweep.py"
    script.write_text(textwrap.dedent(SLOW_SWEEP.format()))
    store = tmp_path / "study.zarr"
    proc = subprocess.Popen([sys.executable, str(script), str(EXAMPLES / "slider_crank.toml"), str(store)])
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if store.is_dir() and sum(1 for p in store.iterdir() if p.name.startswith("batch_")) >= 2:
            break
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    finished = sorted(p.name for p in store.iterdir() if p.name.startswith("batch_"))
    assert 2 <= len(finished) < 6, finished
    before = mb.sweep.open_store(store)
    ds = mb.sweep(scene(), {"rod.mass": [1.0 + 0.1 * k for k in range(12)]}, t_end=0.05,
                  outputs={"x_end": x_end}, store=store, batch_size=2, progress=False)
    assert ds.attrs["computed_cases"] == 12 - 2 * len(finished)
    assert list(ds["case"].values) == list(range(12)) and list(ds["status"].values) == ["ok"] * 12
    # the cases finished before the kill were kept, not computed again
    np.testing.assert_array_equal(ds["x_end"].sel(case=before["case"].values).values, before["x_end"].values)
    again = mb.sweep(scene(), {"rod.mass": [1.0 + 0.1 * k for k in range(12)]}, t_end=0.05,
                     outputs={"x_end": x_end}, store=store, batch_size=2, progress=False)
    assert again.attrs["computed_cases"] == 0
    with pytest.raises(mb.ModelError, match="holds another sweep"):
        mb.sweep(scene(), {"rod.mass": [9.0]}, t_end=0.05, outputs={"x_end": x_end}, store=store, progress=False)


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
