"""`lagmb sweep SCENE --vary ... --output ...` and `lagmb sweep --plot STORE`
(issue 29, item 2), run in this process on examples/slider_crank.toml over
0.05 s.

- --vary NAME=A:B:N gives numpy.linspace(A, B, N), NAME=V1,V2,... the list;
  several --vary the grid of every combination, the last varying fastest,
  as mb.sweep's grid.
- The printed table holds, per case, the varied parameters, ok or failed
  and the outputs, each as mb.sweep gives it for the same cases (to the 6
  digits printed); outputs are named peak_reaction_B, peak_effort_motor,
  final_slider.x, energy_drift. A failed case (rtol 1e-16) is listed with
  its error and the command exits 0; more than 20 cases print the first
  and last rows and each output's range.
- -o STORE, then the same command again (on 2 processes): nothing is
  computed ("computed 0 of ...", ds.attrs["computed_cases"] == 0) and the
  table is the same; --scheduler (an in-process Dask cluster) prints the
  table of a run in this process.
- --plot STORE -o FIG.png writes a PNG with one subplot per output, the
  failed cases counted in the title; without -o, next to the store.
- Bad options exit 2 with one line naming the option and the value (an
  unknown parameter: lagmb's ModelError listing the parameters).
"""

import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import lagmb as mb
from lagmb import cli, plotting, studies
from builders import lagmb_main as lagmb
import paths  # noqa: E402  (tests/paths.py)

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")
SCENE = os.path.join(paths.EXAMPLES, "slider_crank.toml")
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
T_END = "0.05"
OUTPUTS = ["--output", "peak_reaction=B", "--output", "peak_effort=motor", "--output", "final=slider.x",
           "--output", "energy_drift"]
BUILT_IN = {"peak_reaction_B": mb.sweep.peak_reaction("B"), "peak_effort_motor": mb.sweep.peak_effort("motor"),
            "final_slider.x": mb.sweep.final("slider.x"), "energy_drift": mb.sweep.energy_drift()}


def table(out):
    """The table: (its head, [the row's fields, ...]) for the rows of cases."""
    lines = out.splitlines()
    k = next(i for i, line in enumerate(lines) if line.split()[:1] == ["case"])
    head = lines[k].split()
    rows = [line.split() for line in lines[k + 1:]
            if line.split()[:1] and line.split()[0].isdigit() and len(line.split()) == len(head)]
    return head, rows


def test_a_spec_gives_linspace_or_the_list_and_several_make_the_grid(capsys):
    grid, typed = cli.sweep._grid(["rod.mass=0.5:2:4", "slider.mass=0.2,0.4", "n_out=11,21"])
    assert grid == {"rod.mass": list(np.linspace(0.5, 2.0, 4)), "slider.mass": [0.2, 0.4], "n_out": [11, 21]}
    assert grid["rod.mass"] == [0.5, 1.0, 1.5, 2.0] and all(type(n) is int for n in grid["n_out"])
    assert typed["rod.mass"] == "rod.mass=0.5:2:4"
    assert cli.sweep._grid(["crank.angle.start=-1:1:3"])[0] == {"crank.angle.start": [-1.0, 0.0, 1.0]}

    code, out, err = lagmb(capsys, "sweep", SCENE, "--vary", "rod.mass=0.5:2:4", "--vary", "slider.mass=0.2,0.4",
                           "--t-end", T_END, "--output", "peak_effort=motor")
    assert code == 0, err
    assert out.splitlines()[0].endswith("8 cases (rod.mass 4 x slider.mass 2), t = 0 .. 0.05 s, in this process")
    head, rows = table(out)
    assert head == ["case", "rod.mass", "slider.mass", "status", "peak_effort_motor"]
    assert [r[0] for r in rows] == [str(i) for i in range(8)]
    # every combination, the last varying fastest
    assert [(float(r[1]), float(r[2])) for r in rows] == [(m, s) for m in (0.5, 1.0, 1.5, 2.0) for s in (0.2, 0.4)]
    assert "computed 8 of 8 cases" in out and "nothing written: -o STORE keeps the results" in out


def test_the_printed_outputs_are_mb_sweeps_for_the_same_cases(capsys):
    code, out, err = lagmb(capsys, "sweep", SCENE, "--vary", "rod.mass=1:3:3", "--vary", "crank.inertia=0.001,0.002",
                           "--t-end", T_END, *OUTPUTS)
    assert code == 0, err
    head, rows = table(out)
    assert head == ["case", "rod.mass", "crank.inertia", "status", "peak_reaction_B", "peak_effort_motor",
                    "final_slider.x", "energy_drift"]
    ds = mb.sweep(mb.load_scene(SCENE), {"rod.mass": [1.0, 2.0, 3.0], "crank.inertia": [0.001, 0.002]},
                  outputs=BUILT_IN, t_end=float(T_END), progress=False)
    assert len(rows) == ds.sizes["case"] == 6
    for i, row in enumerate(rows):
        assert row[3] == "ok" == ds["status"].values[i]
        assert row[1:3] == [f"{ds['rod.mass'].values[i]:.6g}", f"{ds['crank.inertia'].values[i]:.6g}"]
        assert row[4:] == [f"{ds[name].values[i]:.6g}" for name in BUILT_IN]


def test_failed_cases_are_listed_and_many_cases_summarised(capsys):
    # rtol 1e-16 is refused by the integrator: that case fails, the others run
    code, out, err = lagmb(capsys, "sweep", SCENE, "--vary", "rtol=1e-6,1e-16", "--vary", "rod.mass=1:2:11",
                           "--t-end", T_END, "--output", "peak_reaction=B", "--output", "peak_effort=motor")
    assert code == 0, err
    head, rows = table(out)
    assert len(rows) == 10  # 22 cases: the first and last 5
    assert [r[0] for r in rows] == ["0", "1", "2", "3", "4", "17", "18", "19", "20", "21"]
    assert [r[3] for r in rows] == ["ok"] * 5 + ["failed"] * 5 and rows[-1][4:] == ["-", "-"]
    assert "the first and last 5 of 22 cases; over the 11 ok cases:" in out
    ds = mb.sweep(mb.load_scene(SCENE), {"rod.mass": list(np.linspace(1.0, 2.0, 11))},
                  outputs={"peak_reaction_B": BUILT_IN["peak_reaction_B"]}, t_end=float(T_END), rtol=1e-6,
                  progress=False)
    peak = ds["peak_reaction_B"].values
    assert (f"peak_reaction_B    min {peak.min():.6g} (case {peak.argmin()}), max {peak.max():.6g} "
            f"(case {peak.argmax()})") in out
    assert "11 of 22 cases failed:" in out and "case 11: ModelError: " in out and "rtol" in out
    assert "and 6 more" in out


def test_a_store_run_again_computes_nothing(capsys, tmp_path, monkeypatch):
    store = tmp_path / "study.zarr"
    args = ["sweep", SCENE, "--vary", "rod.mass=1,2", "--vary", "slider.mass=0.5:1:3", "--t-end", T_END, *OUTPUTS,
            "-o", store, "--batch-size", "2"]
    code, first, err = lagmb(capsys, *args)
    assert code == 0, err
    assert "computed 6 of 6 cases" in first and f"results in {store}" in first
    ds = mb.sweep.open_store(store)
    assert ds.sizes["case"] == 6 and set(BUILT_IN) <= set(ds.data_vars)
    assert sorted(p.name for p in store.iterdir() if p.name.startswith("batch_")) == [
        "batch_000000", "batch_000001", "batch_000002"]

    calls = []
    real = mb.sweep

    def counted(*a, **kw):  # what the command's mb.sweep call returned
        result = real(*a, **kw)
        calls.append(result.attrs["computed_cases"])
        return result

    monkeypatch.setattr(studies, "sweep", counted)
    code, again, err = lagmb(capsys, *args, "--workers", "2")
    assert code == 0, err
    assert calls == [0]
    assert "computed 0 of 6 cases" in again and "the other 6 were in the store" in again
    assert table(again) == table(first)


def test_scheduler_runs_the_cases_on_a_dask_cluster(capsys):
    distributed = pytest.importorskip("distributed")
    args = ["sweep", SCENE, "--vary", "rod.mass=1,2,3", "--t-end", T_END, "--output", "peak_effort=motor"]
    code, alone, err = lagmb(capsys, *args)
    assert code == 0, err
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=":0",
                                  silence_logs=40) as cluster:
        code, out, err = lagmb(capsys, *args, "--scheduler", cluster.scheduler_address)
    assert code == 0, err
    assert f"on the Dask cluster at {cluster.scheduler_address}" in out.splitlines()[0]
    assert table(out) == table(alone)


def test_plot_draws_one_subplot_per_output(capsys, tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    store = tmp_path / "study.zarr"
    code, out, err = lagmb(capsys, "sweep", SCENE, "--vary", "rod.mass=1:2:3", "--vary", "rtol=1e-6,1e-16",
                           "--t-end", T_END, "--output", "peak_reaction=B", "--output", "peak_effort=motor",
                           "-o", store)
    assert code == 0, err
    figures = []
    real = plotting.plot_sweep

    def kept(*a, **kw):
        figures.append(real(*a, **kw))
        return figures[-1]

    monkeypatch.setattr(plotting, "plot_sweep", kept)
    png = tmp_path / "figures" / "study.png"
    code, out, err = lagmb(capsys, "sweep", "--plot", store, "-o", png)
    assert code == 0, err
    assert png.read_bytes()[:8] == PNG_MAGIC
    assert out.strip() == (f"{store}: 6 cases, 2 outputs (peak_reaction_B, peak_effort_motor) drawn in {png}")
    fig = figures[-1]
    # each axis with its unit, as the store recorded them (the motor drives an angle: N m)
    assert [ax.get_ylabel() for ax in fig.axes] == ["peak_reaction_B (N)", "peak_effort_motor (N m)"]
    assert fig.axes[-1].get_xlabel() == "rod.mass (kg)"
    assert fig.axes[0].get_legend().get_title().get_text() == "rtol"  # (a tolerance has no unit)
    assert "3 failed cases left out" in fig._suptitle.get_text()
    # a line per value of the second parameter with ok cases: rtol 1e-16's all failed
    assert [line.get_label() for line in fig.axes[0].lines] == ["1e-06"]
    assert list(fig.axes[0].lines[0].get_xdata()) == [1.0, 1.5, 2.0]
    # without -o: next to the store
    code, out, err = lagmb(capsys, "sweep", "--plot", store)
    assert code == 0, err
    assert (tmp_path / "study.png").read_bytes()[:8] == PNG_MAGIC


def test_a_fully_driven_scene_says_why_it_takes_no_steps(capsys):
    """The slider-crank is driven in its one degree of freedom: each output
    is a kinematic solve, and the table's "steps 0" comes with that reason."""
    code, out, err = lagmb(capsys, "sweep", SCENE, "--vary", "rod.mass=1,2", "--t-end", T_END)
    assert code == 0, err
    head, rows = table(out)
    assert head[-1] == "steps" and [row[-1] for row in rows] == ["0", "0"]
    assert "steps 0: every degree of freedom is driven, so each output is solved from the drivers" in out


def test_plot_sweep_draws_heat_maps_bands_and_designs(tmp_path):
    pytest.importorskip("matplotlib")
    scene = mb.load_scene(SCENE)
    outputs = {"peak_reaction_B": BUILT_IN["peak_reaction_B"], "peak_effort_motor": BUILT_IN["peak_effort_motor"]}
    many = mb.sweep(scene, {"B.at.y": np.linspace(0.06, 0.14, 9), "rod.mass": np.linspace(1.0, 4.0, 9)},
                    outputs=outputs, t_end=0.02, n_out=5, progress=False)
    fig = plotting.plot_sweep(many, tmp_path / "heat.png")
    assert len(fig.axes) == 4 and [ax.get_title() for ax in fig.axes[:2]] == list(outputs)  # and 2 colour bars
    three = mb.sweep(scene, {"rod.mass": [1.0, 2.0], "slider.mass": [0.5, 1.0], "B.at.y": [0.08, 0.1]},
                     outputs=outputs, t_end=0.02, n_out=5, progress=False)
    fig = plotting.plot_sweep(three, outputs=["peak_effort_motor"])
    assert len(fig.axes) == 1 and "mean and range over slider.mass, B.at.y" in fig._suptitle.get_text()
    design = mb.sweep(scene, mb.sweep.latin_hypercube({"rod.mass": (1.0, 3.0), "slider.mass": (0.5, 1.0)}, 6, seed=2),
                      outputs=outputs, t_end=0.02, n_out=5, progress=False)
    fig = plotting.plot_sweep(design)
    assert len(fig.axes) == 4 and "rod.mass, slider.mass varied" in fig._suptitle.get_text()
    with pytest.raises(ValueError, match="no output 'torque'; the study's outputs are peak_reaction_B"):
        plotting.plot_sweep(design, outputs=["torque"])


@pytest.mark.parametrize("options, message", [
    (["--vary", "rod.length=1,2"],
     "--vary rod.length=1,2: sweep: case 0: no parameter 'rod.length'; the model's parameters are crank.mass, "),
    (["--vary", "rod.mass=1,-2"], "--vary rod.mass=1,-2: sweep: case 1: rod.mass = -2.0: body 'rod': mass must be"),
    (["--vary", "rod.mass=1:2"], "--vary rod.mass=1:2: A:B:N has three parts"),
    (["--vary", "rod.mass=1:2:1.5"], "--vary rod.mass=1:2:1.5: N = 1.5 must be a whole number of values"),
    (["--vary", "rod.mass=1,heavy"], "--vary rod.mass=1,heavy: 'heavy' is not a decimal number"),
    (["--vary", "rod.mass=1,,2"], "--vary rod.mass=1,,2: an empty value"),
    (["--vary", "rod.mass=nan,1"], "--vary rod.mass=nan,1: nan must be a finite number"),
    # read as TOML writes numbers: float() takes '1_0' for 10 and the Arabic-Indic digit one for 1
    (["--vary", "rod.mass=1_0"], "--vary rod.mass=1_0: '1_0' is not a decimal number"),
    (["--vary", "rod.mass=1,\u0661"], "--vary rod.mass=1,\u0661: '\u0661' is not a decimal number"),
    (["--vary", "rod.mass=1:2:1_0"], "--vary rod.mass=1:2:1_0: '1_0' is not a decimal number"),
    (["--vary", "rod.mass=1:2:10000", "--vary", "slider.mass=1:2:10000"],
     "--vary: 100,000,000 cases (10000 x 10000): at most 10,000,000 in one study"),
    (["--vary", "rod.mass=1:2:100000000"], "--vary rod.mass=1:2:100000000: N = 100000000: at most 10,000,000 values"),
    (["--vary", "atol=1e-6,1e-8", "--vary", "rod.mass=1e400"], "--vary rod.mass=1e400: '1e400' is too large for a float"),
    (["--vary", "rod.mass"], "--vary rod.mass: must be NAME=SPEC"),
    (["--vary", "rod.mass=1,2", "--vary", "rod.mass=3"], "--vary rod.mass=3: rod.mass is varied twice"),
    ([], "give at least one --vary NAME=SPEC"),
    (["--vary", "rod.mass=1,2", "--output", "peak_force=B"],
     "--output peak_force=B: unknown kind 'peak_force'; the kinds are peak_reaction=JOINT, peak_effort=DRIVER, "
     "final=COORDINATE and energy_drift"),
    (["--vary", "rod.mass=1,2", "--output", "peak_reaction=D"],
     "has no joint or driver 'D'; its joints and drivers are O, B, C, guide, motor"),
    (["--vary", "rod.mass=1,2", "--output", "peak_effort=B"], "has no driver 'B'; its drivers are motor"),
    (["--vary", "rod.mass=1,2", "--output", "final=slider.angel"],
     "has no coordinate 'slider.angel'; its coordinates"),
    (["--vary", "rod.mass=1,2", "--output", "energy_drift=B"],
     "--output energy_drift=B: energy_drift takes no argument"),
    (["--vary", "rod.mass=1,2", "--output", "peak_effort"], "--output peak_effort: give peak_effort=NAME"),
    (["--vary", "rod.mass=1,2", "--workers", "0"], "--workers 0: must be at least 1"),
    (["--vary", "rod.mass=1,2", "--workers", "2", "--scheduler", "tcp://127.0.0.1:8786"],
     "--workers 2: the cluster at --scheduler tcp://127.0.0.1:8786 runs the cases on its own workers"),
    (["--vary", "rod.mass=1,2", "--batch-size", "0"], "--batch-size 0: must be at least 1"),
    (["--vary", "rod.mass=1,2", "--t-end", "-1"], "--t-end -1: must be finite and greater than 0"),
])
def test_bad_options_exit_2_naming_the_option(capsys, options, message):
    code, out, err = lagmb(capsys, "sweep", SCENE, "--t-end", T_END, *options)
    assert code == 2 and out == ""
    assert err.startswith("lagmb sweep: ") and message in err and len(err.splitlines()) == 1, err


def test_bad_stores_and_plots_exit_2(capsys, tmp_path):
    code, out, err = lagmb(capsys, "sweep", "--plot", tmp_path / "missing.zarr")
    assert code == 2 and err.startswith(f"lagmb sweep: --plot {tmp_path / 'missing.zarr'}: ") and "no store" in err
    store = tmp_path / "study.zarr"
    args = ["sweep", SCENE, "--vary", "rod.mass=1,2", "--t-end", T_END, "--output", "peak_effort=motor"]
    assert lagmb(capsys, *args, "-o", store)[0] == 0
    code, out, err = lagmb(capsys, *args[:3], "rod.mass=1,3", *args[4:], "-o", store)
    assert code == 2 and f"-o {store}: " in err and "holds another sweep" in err
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "a.txt").write_text("mine")
    code, out, err = lagmb(capsys, *args, "-o", tmp_path / "notes")
    assert code == 2 and "a folder that is not a study's store" in err
    assert sorted(os.listdir(tmp_path / "notes")) == ["a.txt"]  # left alone
    code, out, err = lagmb(capsys, "sweep", SCENE, "--plot", store)
    assert code == 2 and "give no scene with it" in err
    code, out, err = lagmb(capsys, "sweep", "--plot", store, "--vary", "rod.mass=1,2")
    assert code == 2 and err.startswith("lagmb sweep: --vary rod.mass=1,2: --plot") and "give no --vary" in err
    code, out, err = lagmb(capsys, "sweep", "--plot", store, "-o", tmp_path / "study.mp4")
    assert code == 2 and f"-o {tmp_path / 'study.mp4'}: must end in one of the formats" in err


def test_number_options_are_read_as_toml_writes_numbers(capsys):
    for option, value in [("--t-end", "0_05"), ("--workers", "1_0"), ("--batch-size", "2.5")]:
        code, out, err = lagmb(capsys, "sweep", SCENE, "--vary", "rod.mass=1,2", option, value)
        assert code == 2 and out == ""
        assert f"argument {option}: '{value}' is not a" in err, err


def test_o_takes_a_study_s_store_only_and_one_sweep_at_a_time(capsys, tmp_path):
    zarr = pytest.importorskip("zarr")
    args = ["sweep", SCENE, "--vary", "rod.mass=1,2", "--t-end", T_END, "--output", "peak_effort=motor"]
    foreign = tmp_path / "other.zarr"
    zarr.open_group(str(foreign), mode="w").attrs["owner"] = "another program"
    code, out, err = lagmb(capsys, *args, "-o", foreign)
    assert code == 2 and err.startswith(f"lagmb sweep: -o {foreign}: ") and "a Zarr store, but not a study's" in err
    assert sorted(p.name for p in foreign.iterdir()) == ["zarr.json"]  # left alone
    store = tmp_path / "study.zarr"
    assert lagmb(capsys, *args, "-o", store)[0] == 0
    # another process holds the store's lock, as a sweep writing it does
    holder = subprocess.Popen([sys.executable, "-c", "import sys; from lagmb.studies.store import Lock; "
                               f"lock = Lock({str(store)!r}, 'sweep'); print('held', flush=True); "
                               "sys.stdin.read()"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline() == "held\n"
        code, out, err = lagmb(capsys, *args, "-o", store)
    finally:
        holder.communicate("")
    assert code == 2 and err.startswith(f"lagmb sweep: -o {store}: sweep: the store '{store}' is in use by another "
                                        f"sweep (pid {holder.pid})")
    assert lagmb(capsys, *args, "-o", store)[0] == 0


def test_a_damaged_store_is_completed_and_the_warning_says_which_batch(capsys, tmp_path):
    store = tmp_path / "study.zarr"
    args = ["sweep", SCENE, "--vary", "rod.mass=1:2:6", "--t-end", T_END, "--output", "peak_effort=motor",
            "--batch-size", "2", "-o", store]
    code, first, err = lagmb(capsys, *args)
    assert code == 0, err
    shutil.rmtree(store / "batch_000001")  # as a copy cut short would leave it
    (store / "batch_000001").mkdir()
    code, again, err = lagmb(capsys, *args)
    assert code == 0
    assert err == (f"lagmb sweep: UserWarning: sweep: the store '{store}': batch_000001 (cases 2..3): it has no "
                   "marker of its files (it was not finished, or was copied in part): computed again\n")
    assert "computed 2 of 6 cases" in again and table(again) == table(first)


def test_a_urdf_file_is_swept_as_run_and_info_take_it(capsys, tmp_path):
    from builders import ARM_URDF

    path = tmp_path / "arm.urdf"
    path.write_text(ARM_URDF)
    code, out, err = lagmb(capsys, "sweep", path, "--vary", "upper.mass=1,2", "--t-end", "0.3", "--no-limits",
                           "--output", "final=upper.x")
    assert code == 0, err
    ds = mb.sweep(mb.load_urdf(path, limits=False), {"upper.mass": [1.0, 2.0]}, t_end=0.3,
                  outputs={"x": mb.sweep.final("upper.x")}, progress=False)
    head, rows = table(out)
    assert head == ["case", "upper.mass", "status", "final_upper.x"]
    assert [float(r[3]) for r in rows] == [float(f"{x:.6g}") for x in ds["x"].values]
    code, out, err = lagmb(capsys, "sweep", path, "--vary", "upper.mass=1,2")
    assert code == 2 and "no end time" in err


def test_ctrl_c_during_a_sweep_on_workers_prints_one_line(tmp_path):
    """SIGINT to the whole process group, as a terminal's Ctrl-C: the
    workers ignore it (they printed a traceback each) and are stopped;
    lagmb prints its one line and exits 130, the finished batches in the
    store. The 60 cases are computed long before their 60 batches are
    written: the Ctrl-C comes when the workers wait for tasks."""
    store = tmp_path / "study.zarr"
    proc = subprocess.Popen([sys.executable, "-m", "lagmb", "sweep", SCENE, "--vary", "rod.mass=1:3:60",
                             "--t-end", T_END, "--workers", "2", "--batch-size", "1", "-o", str(store)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not (store.is_dir() and sum(
                p.name.startswith("batch_") for p in store.iterdir()) >= 10):
            time.sleep(0.02)
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 130, err
    assert err == (f"lagmb sweep: interrupted; the finished cases are in {store}: the same command finishes the "
                   "study\n")


def test_a_worker_of_lagmb_sweep_ignores_ctrl_c():
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(1, initializer=cli.sweep._quiet_worker) as ex:
        assert ex.submit(signal.getsignal, signal.SIGINT).result() == signal.SIG_IGN
