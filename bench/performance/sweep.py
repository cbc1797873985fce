"""Parameter studies (mb.sweep, issue 29): how many cases per second a sweep
runs in process, on 2 threads, on 2 processes and on a 2-worker Dask
cluster, what the scheduling costs, and what a study of a million cases
would take.

The cases: the slider-crank of examples/slider_crank.toml, its own
settings (a kinematic analysis: fully driven; rtol 1e-8, atol 1e-10),
t_end T_END with an output every 2.5 ms (the scene's 401 outputs in 1 s),
rod.mass over --cases values (1,000; linspace(1, 3)), two built-in outputs
per case (peak_effort("motor"), peak_reaction("C")). A run's cost is set by
its outputs (one Newton solve of the positions, velocities and
accelerations each), so t_end sets it: (0) measures the cost of one case in
process at t_end 0.25 .. 2 s, and T_END = 1 s is the one near 10 ms.

    (1) throughput: one sweep of the cases on each executor, cases per
        second (cases / wall time of mb.sweep, everything included: the
        cases checked, the tasks sent, the Dataset built) and the ratio to
        in process measured in the same round:
            in_process   executor=None
            threads      ThreadPoolExecutor(2)
            processes    ProcessPoolExecutor(2) (fork: the workers inherit
                         this process's imports)
            dask         a distributed.LocalCluster, 2 worker processes of 1
                         thread (the scheduler in this process)
        each with the default batch (cases / (4 x workers), at most 256),
        and the Dask cluster also at batch_size 1, 8 and 64. The pools are
        made once, the cluster anew in each round for its variants only
        (idle, its processes take about 0.1 core from the others' second
        worker), each warmed first (a sweep of WARM cases at batch 1,
        twice): their start-up (made + first sweep - second sweep) is
        reported apart, not in the throughput.
    (2) overhead: (workers x wall - the sum of the cases' own wall_time) /
        the sum of the cases' own wall_time, wall_time being the core's
        run alone (r.stats["wall_time"], without the GIL): the share of the
        workers' time spent elsewhere than in the runs, relative to the
        work. In process it is the Python around each run (the Result,
        with_parameters, the outputs) and the sweep's own set-up; the
        executors' excess over that is scheduling (and waiting for a core).
        From it, the ratio at equal run speed, workers x (1 + overhead in
        process) / (1 + overhead), same round: the speed-up if each
        worker's runs went as fast as in process's (on this machine a run
        is at times much slower while both cores are busy: (3) measures
        it, alternating one busy core with two).
    (3) threads: the same per-case work (the core's run alone, and a whole
        sweep case: studies.runs.run_case) looped on 1 thread, 2 threads and 2
        forked processes; the cost of each layer of a case in process (the
        core's run, _core.simulate with the conversion of its result,
        mb.simulate, the case with its outputs): what holds the GIL; the
        core's run alone with one core busy and with both, alternated.
        Also whether a thread sweep leaves the warnings module as it found
        it (each case records its warnings in warnings.catch_warnings,
        which is not thread-safe).
    (4) the store: one sweep of the cases into a Zarr store (store=, on the
        Dask cluster, default batch and batch 256) in a temporary
        directory: bytes per case, files per batch, the write of one batch
        in this process; the sweep's serial work in this process per case
        (the cases checked before any runs, the Dataset built after); and
        from these and (1)-(2) an estimate of a study of 1e6 such cases on
        100 machines of 2 cores (200 workers).

The variants of (1) are interleaved in each of --repeats rounds (the order
reversed every other round); min and median over rounds are reported. The
machine is shared (2 cores): the load average is recorded, and for each
sweep the CPU the whole machine used (/proc/stat) against what this
process and its workers used (psutil), the difference being other jobs'.

    python bench/performance/sweep.py [--repeats 3] [--cases 1000] [--quick] [--out FILE]

Prints markdown tables and writes bench/results/sweep.json (with the git
commit and date); --quick (200 cases, 2 rounds, Dask batch 1 and the
default only) writes nothing unless --out is given. BLAS on one thread (set
unless already set).
"""

import argparse
import concurrent.futures
import math
import multiprocessing
import os
import shutil
import sys
import tempfile
import threading
import time
import warnings

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.record import one_blas_thread  # noqa: E402

one_blas_thread()

import numpy as np  # noqa: E402

import lagmb as mb  # noqa: E402
from bench.common.paths import EXAMPLES, RESULTS  # noqa: E402
from bench.common.record import changed, load_average, stamp, stamp_line, write_json  # noqa: E402
from lagmb import _core, studies  # noqa: E402
from lagmb.studies import cases as study_cases, dataset as study_dataset, runs  # noqa: E402

SCENE = os.path.join(EXAMPLES, "slider_crank.toml")
T_END = 1.0
OUTPUT_INTERVAL = 0.0025  # s: the scene's 401 outputs in 1 s
CALIBRATION_T_END = [0.25, 0.5, 1.0, 2.0]
WORKERS = 2
WARM = 8  # cases of the warm-up sweeps, at batch 1
QUIET_WAIT = 10  # s: at most, before each round, for the other jobs to use under 0.3 cores
QUIET = 0.25  # cores: a sweep during which the other jobs used less is "quiet"
DASK_BATCHES = [1, 8, 64]
PAPER_CASES, PAPER_MACHINES, PAPER_CORES = 1_000_000, 100, 2
OUTPUTS = {"torque": studies.peak_effort("motor"), "peak_C": studies.peak_reaction("C")}


def n_out(t_end):
    return int(round(t_end / OUTPUT_INTERVAL)) + 1


def wait_for_quiet(limit, threshold=0.3, window=1.0):
    """Waits (at most limit s) until the machine's other jobs use under
    threshold cores over a window; returns (seconds waited, their cores)."""
    t0 = time.perf_counter()
    others = None
    while True:
        with Meter() as m:
            time.sleep(window)
        others = m.others_cores
        if others is None or others < threshold or time.perf_counter() - t0 >= limit:
            return time.perf_counter() - t0, others


class Meter:
    """Wall time, and the CPU (in cores) the whole machine (/proc/stat), this
    process with its workers (psutil) and the hypervisor (steal) took
    meanwhile."""

    def __init__(self):
        try:
            import psutil

            self.me = psutil.Process()
        except ImportError:
            self.me = None

    def ours(self):
        """CPU seconds of this process, of its live descendants and of its
        children that ended (reaped): (all, this process)."""
        if self.me is None:
            return float("nan"), float("nan")
        ended = os.times()
        total, mine = ended.children_user + ended.children_system, 0.0
        for p in [self.me] + self.me.children(recursive=True):
            try:
                t = p.cpu_times()
                total += t.user + t.system
                if p.pid == self.me.pid:
                    mine = t.user + t.system
            except Exception:  # noqa: BLE001 - a process gone meanwhile
                pass
        return total, mine

    @staticmethod
    def machine():
        try:
            with open("/proc/stat") as f:
                fields = [int(x) for x in f.readline().split()[1:]]
        except OSError:
            return None
        user, nice, system, idle, iowait, irq, softirq, steal = (fields + [0] * 8)[:8]
        busy = user + nice + system + irq + softirq
        hz = os.sysconf("SC_CLK_TCK")
        return busy / hz, steal / hz

    def __enter__(self):
        self.m0, self.o0, self.t0 = self.machine(), self.ours(), time.perf_counter()
        return self

    def __exit__(self, *exc):
        self.wall = time.perf_counter() - self.t0
        m1, o1 = self.machine(), self.ours()
        self.ours_cores = (o1[0] - self.o0[0]) / self.wall
        self.this_process_cores = (o1[1] - self.o0[1]) / self.wall
        if m1 and self.m0:
            self.machine_cores = (m1[0] - self.m0[0]) / self.wall
            self.steal_cores = (m1[1] - self.m0[1]) / self.wall
            self.others_cores = max(0.0, self.machine_cores - self.ours_cores)
        else:
            self.machine_cores = self.steal_cores = self.others_cores = None
        return False

    def record(self):
        r = lambda x: None if x is None else round(x, 3)  # noqa: E731
        return dict(wall=self.wall, machine_cores=r(self.machine_cores), ours_cores=r(self.ours_cores),
                    this_process_cores=r(self.this_process_cores), others_cores=r(self.others_cores),
                    steal_cores=r(self.steal_cores))


def summary(x):
    return dict(min=float(np.min(x)), median=float(np.median(x)), max=float(np.max(x)))


# --- (0) the cost of one case ----------------------------------------------------------


def calibrate(model, count):
    rows = []
    for t_end in CALIBRATION_T_END:
        settings = dict(t_end=t_end, rtol=1e-8, atol=1e-10, n_out=n_out(t_end))
        runs.run_case(model, {"rod.mass": 2.0}, settings, OUTPUTS, None)
        walls, cores = [], []
        for k in range(count):
            t0 = time.perf_counter()
            record = runs.run_case(model, {"rod.mass": 1.0 + 1e-3 * k}, settings, OUTPUTS, None)
            walls.append(time.perf_counter() - t0)
            cores.append(record["wall_time"])
            assert record["status"] == "ok", record["status"]
        rows.append(dict(t_end=t_end, n_out=settings["n_out"], case=summary(walls), core=summary(cores)))
    return rows


# --- (3) threads ------------------------------------------------------------------------


def captured_core_call(model, settings):
    """The arguments mb.simulate gives _core.simulate for one case (the
    binding called alone: the run without the GIL, then its result
    converted to numpy with it)."""
    held = {}
    original = _core.simulate

    def capture(*args):
        held["args"] = args
        return original(*args)

    _core.simulate = capture
    try:
        mb.simulate(model, parameters={"rod.mass": 1.5}, **settings)
    finally:
        _core.simulate = original
    return held["args"]


def layers(model, settings, count):
    """The cost of each layer of a case, in process (s): min and median."""
    core_args = captured_core_call(model, settings)
    run = dict(settings)
    t_end = run.pop("t_end")
    calls = {
        "core_call": lambda k: _core.simulate(*core_args),
        "mb_simulate": lambda k: mb.simulate(model, t_end, parameters={"rod.mass": 1.0 + 1e-3 * k}, **run),
        "case_without_outputs": lambda k: runs.run_case(model, {"rod.mass": 1.0 + 1e-3 * k}, settings, {}, None),
        "case": lambda k: runs.run_case(model, {"rod.mass": 1.0 + 1e-3 * k}, settings, OUTPUTS, None),
    }
    times = {name: [] for name in calls}
    core = []
    for k in range(count):
        for name, call in calls.items():
            t0 = time.perf_counter()
            out = call(k)
            times[name].append(time.perf_counter() - t0)
            if name == "core_call":
                core.append(out["stats"]["wall_time"])
    r = mb.simulate(model, t_end, **run)
    outputs = {}
    for name, f in OUTPUTS.items():
        ts = []
        for _ in range(count):
            t0 = time.perf_counter()
            f(r)
            ts.append(time.perf_counter() - t0)
        outputs[name] = summary(ts)
    out = {name: summary(t) for name, t in times.items()}
    out["core_wall_time"] = summary(core)
    out["outputs"] = outputs
    return out


def scaling_round(model, settings, count):
    """Cases per second of the same per-case work on 1 thread, 2 threads and
    2 forked processes, for the core's run alone ("core") and a whole sweep
    case ("case"); the mean time of the core's run (its wall_time) and the
    share of the threads' (processes') time inside it."""
    core_args = captured_core_call(model, settings)
    work = {
        "core": lambda k: _core.simulate(*core_args)["stats"]["wall_time"],
        "case": lambda k: runs.run_case(model, {"rod.mass": 1.0 + 1e-3 * k}, settings, OUTPUTS, None)["wall_time"],
    }
    fork = multiprocessing.get_context("fork")
    out = {}
    for layer, f in work.items():
        def loop(first, n, into):
            into.append(sum(f(first + k) for k in range(n)))

        def child(first, n, queue):
            queue.put(sum(f(first + k) for k in range(n)))

        row = {}
        for mode in ("1 thread", "2 threads", "2 processes"):
            inside = []
            meter = Meter().__enter__()
            t0 = time.perf_counter()
            if mode == "1 thread":
                loop(0, count, inside)
            elif mode == "2 threads":
                ts = [threading.Thread(target=loop, args=(i * count // 2, count // 2, inside)) for i in range(2)]
                [t.start() for t in ts]
                [t.join() for t in ts]
            else:
                queue = fork.SimpleQueue()
                ps = [fork.Process(target=child, args=(i * count // 2, count // 2, queue)) for i in range(2)]
                [p.start() for p in ps]
                inside = [queue.get() for _ in ps]
                [p.join() for p in ps]
            wall = time.perf_counter() - t0
            meter.__exit__(None, None, None)
            threads = 1 if mode == "1 thread" else 2
            row[mode] = dict(rate=count / wall, wall=wall, others_cores=meter.others_cores,
                             in_core=sum(inside) / (threads * wall), core_run=sum(inside) / count)
        out[layer] = row
    return out


def busy_cores_speed(model, settings, count, times):
    """The core's run alone (its wall_time, median of count runs) with one
    core busy (here) and with both (two forked processes at once),
    alternated: on this machine a run is at times slower when the other
    core is busy too."""
    core_args = captured_core_call(model, settings)
    fork = multiprocessing.get_context("fork")

    def work():
        return [_core.simulate(*core_args)["stats"]["wall_time"] for _ in range(count)]

    def child(queue):
        queue.put(work())

    rows = []
    for _ in range(times):
        one = float(np.median(work()))
        queue = fork.SimpleQueue()
        ps = [fork.Process(target=child, args=(queue,)) for _ in range(2)]
        [p.start() for p in ps]
        both = [queue.get() for _ in ps]
        [p.join() for p in ps]
        rows.append(dict(one_busy=one, two_busy=float(np.median(both[0] + both[1]))))
    return rows


def warnings_state():
    return (warnings._showwarnmsg_impl, warnings.showwarning)


# --- (1)-(2) the sweeps ---------------------------------------------------------------------


def run_sweep(scene, grid, executor, batch_size, workers):
    with Meter() as meter:
        ds = mb.sweep(scene, grid, outputs=OUTPUTS, t_end=T_END, n_out=n_out(T_END), executor=executor,
                      batch_size=batch_size, progress=False)
    status = ds["status"].values
    assert (status == "ok").all(), sorted(set(status))
    n = ds.sizes["case"]
    work = float(ds["wall_time"].values.sum())
    row = meter.record()
    row.update(cases=n, rate=n / meter.wall, work=work, mean_case_wall_time=work / n,
               overhead=(workers * meter.wall - work) / work)
    return row, ds


# --- the measurements, in the order they run ------------------------------------------------


def calibration(model, count):
    """(0): one case in process at each t_end, printed as measured."""
    print(f"(0) one case in process (studies.runs.run_case: mb.simulate and the two outputs), an output every "
          f"{OUTPUT_INTERVAL * 1e3:g} ms; min (median) of {count} cases\n")
    print("| t_end (s) | outputs | case (ms) | core's run alone, wall_time (ms) |")
    print("|---:|---:|---:|---:|")
    rows = calibrate(model, count)
    for row in rows:
        print(f"| {row['t_end']:g} | {row['n_out']} | {row['case']['min'] * 1e3:.2f} ({row['case']['median'] * 1e3:.2f}) "
              f"| {row['core']['min'] * 1e3:.2f} ({row['core']['median'] * 1e3:.2f}) |", flush=True)
    return rows


def probe_threads(out, model, settings, quick):
    """(3), before any pool or cluster: forking a process with threads running is unsafe."""
    probe_count = 60 if quick else 200
    out["layers"] = layers(model, settings, 20 if quick else 50)
    scaling = []
    for _ in range(2 if quick else 3):
        waited, quiet = wait_for_quiet(0 if quick else QUIET_WAIT / 2)
        scaling.append(scaling_round(model, settings, probe_count))
        scaling[-1]["waited"], scaling[-1]["others_cores_before"] = waited, quiet
    out["thread_scaling"] = dict(cases=probe_count, rounds=scaling)
    out["busy_cores_speed"] = busy_cores_speed(model, settings, 20 if quick else 40, 4 if quick else 8)


class Executors:
    """The pools, made once, and the Dask cluster, made anew for its
    variants only; the start-up of each: made, then a warm-up sweep twice."""

    def __init__(self, scene, warm):
        import distributed

        self.distributed, self.scene, self.warm = distributed, scene, warm
        self.startup, self.holder = {}, {}
        self.start("in_process", lambda: None, 1)
        self.processes = self.start("processes", lambda: concurrent.futures.ProcessPoolExecutor(WORKERS), WORKERS)
        self.threads = self.start("threads", lambda: concurrent.futures.ThreadPoolExecutor(WORKERS), WORKERS)

    def start(self, name, make, workers):
        t0 = time.perf_counter()
        executor = make()
        made = time.perf_counter() - t0
        first, _ = run_sweep(self.scene, self.warm, executor, 1, workers)
        second, _ = run_sweep(self.scene, self.warm, executor, 1, workers)
        self.startup[name] = dict(made=made, first_sweep=first["wall"], second_sweep=second["wall"],
                                  startup=made + first["wall"] - second["wall"])
        return executor

    def make_dask(self):
        holder = self.holder
        holder["cluster"] = self.distributed.LocalCluster(n_workers=WORKERS, threads_per_worker=1, processes=True,
                                                          dashboard_address=None, silence_logs=40)
        holder["client"] = self.distributed.Client(holder["cluster"])
        return holder["client"]

    def close_dask(self):
        if self.holder.get("client") is not None:
            self.holder.pop("client").close()
            self.holder.pop("cluster").close()

    def shutdown(self):
        self.close_dask()
        self.processes.shutdown()
        self.threads.shutdown()


def sweep_rounds(ex, scene, grid, n, repeats, dask_batches, quick, loads):
    """(1)-(2): every variant once a round, the order reversed every other
    round; the rows, the last Dataset of each variant, the thread sweeps
    that left the warnings module redirected and the Dask start-ups."""
    # the Dask cluster lives only while its variants run: idle, its five
    # processes (scheduler in this one, 2 nannies, 2 workers) took about 0.1
    # cores, which the other executors' second worker would miss
    dask_startups = []
    variants = {"in_process": (None, None, 1), "threads": (ex.threads, None, WORKERS),
                "processes": (ex.processes, None, WORKERS), "dask": ("dask", None, WORKERS)}
    for b in dask_batches:
        variants[f"dask, batch {b}"] = ("dask", b, WORKERS)
    rows = {name: [] for name in variants}
    loads["rounds"], loads["waits"] = [], []
    disturbed = 0
    before = warnings_state()
    last = {}
    for round_ in range(repeats):
        waited, quiet = wait_for_quiet(0 if quick else QUIET_WAIT)
        loads["waits"].append(dict(waited=waited, others_cores=quiet))
        order = list(variants) if round_ % 2 == 0 else list(reversed(variants))
        for name in order:
            executor, batch, workers = variants[name]
            if executor == "dask":
                if "client" not in ex.holder:
                    ex.start("dask", ex.make_dask, WORKERS)
                    dask_startups.append(ex.startup["dask"])
                executor = ex.holder["client"]
            elif "client" in ex.holder:
                ex.close_dask()
            row, ds = run_sweep(scene, grid, executor, batch, workers)
            row["batch_size"] = batch or max(1, min(256, math.ceil(n / (4 * workers))))
            row["tasks"] = math.ceil(n / row["batch_size"])
            # the work of this process (the client; for Dask also the scheduler) per task
            row["this_process_cpu_per_task"] = row["this_process_cores"] * row["wall"] / row["tasks"]
            row["round"] = round_
            row["workers"] = workers
            rows[name].append(row)
            last[name] = ds
            if name == "threads" and warnings_state() != before:
                disturbed += 1
                warnings._showwarnmsg_impl, warnings.showwarning = before
            print(f"round {round_}: {name}: {row['wall']:.2f} s, {row['rate']:.0f} cases/s, overhead "
                  f"{row['overhead']:.3f}, others' CPU {row['others_cores']} cores", flush=True)
        loads["rounds"].append(load_average())
    return rows, last, disturbed, dask_startups


def store_sweeps(scene, warm, grid, client, n, quick, reference):
    """(4): sweeps into a Zarr store in a temporary directory, and one batch
    written as the store writes it, in this process."""
    tmp = tempfile.mkdtemp(prefix="lagmb_sweep_bench_")
    stores = []
    try:
        t0 = time.perf_counter()  # the first store of this process imports zarr's codecs: apart
        mb.sweep(scene, warm, outputs=OUTPUTS, t_end=T_END, n_out=n_out(T_END), executor=client, batch_size=1,
                 store=os.path.join(tmp, "warm.zarr"), progress=False)
        mb.sweep.open_store(os.path.join(tmp, "warm.zarr"))
        store_warm = time.perf_counter() - t0
        for b in ([None] if quick else [None, 256]):
            path = os.path.join(tmp, f"study_{b}.zarr")
            with Meter() as meter:
                ds = mb.sweep(scene, grid, outputs=OUTPUTS, t_end=T_END, n_out=n_out(T_END), executor=client,
                              batch_size=b, store=path, progress=False)
            assert (ds["status"].values == "ok").all()
            size = files = blocks = 0
            for root, _, names in os.walk(path):
                for f in names:
                    st = os.stat(os.path.join(root, f))
                    size, files, blocks = size + st.st_size, files + 1, blocks + st.st_blocks * 512
            batches = sum(1 for x in os.listdir(path) if x.startswith("batch_"))
            t0 = time.perf_counter()
            mb.sweep.open_store(path)
            reopen = time.perf_counter() - t0
            stores.append(dict(batch_size=b or max(1, min(256, math.ceil(n / (4 * WORKERS)))), batches=batches,
                               wall=meter.wall, rate=n / meter.wall, bytes=size, disk_bytes=blocks, files=files,
                               bytes_per_case=size / n, disk_bytes_per_case=blocks / n,
                               files_per_batch=files / batches, open_store=reopen,
                               open_store_per_batch=reopen / batches))
        # one batch written as the store writes it, in this process
        writes = []
        for b in sorted({min(125, n), min(256, n)}):
            times = []
            for k in range(3):
                part = reference.isel(case=slice(0, b))
                part.attrs = dict(part.attrs)
                t0 = time.perf_counter()
                part.to_zarr(os.path.join(tmp, "writes.zarr"), group=f"tmp_{b}_{k}", mode="w", consolidated=False)
                os.rename(os.path.join(tmp, "writes.zarr", f"tmp_{b}_{k}"), os.path.join(tmp, "writes.zarr",
                                                                                    f"batch_{b}_{k}"))
                times.append(time.perf_counter() - t0)
            writes.append(dict(batch_size=b, write=summary(times)))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return dict(sweeps=stores, batch_writes=writes, first_store_of_the_process=store_warm)


def serial_work(model, grid, ref, n):
    """The sweep's serial work in this process, per case: the cases checked
    before any run, the Dataset built after the last."""
    cases = study_cases.cases_of(grid, "sweep")[0]
    t0 = time.perf_counter()
    checked = study_cases.checked_cases(model, cases, "sweep")
    check = (time.perf_counter() - t0) / n
    records = {i: {"status": "ok", "warnings": "", "steps": int(ref["steps"].values[i]),
                   "wall_time": float(ref["wall_time"].values[i]), "history": None,
                   "outputs": {k: np.asarray(ref[k].values[i]) for k in OUTPUTS}} for i in range(n)}
    t0 = time.perf_counter()
    study_dataset.dataset(checked, records, ["rod.mass"], OUTPUTS, [("rod.mass", list(grid["rod.mass"]))], None,
                          model.coordinate_names)
    dataset = (time.perf_counter() - t0) / n
    return dict(check_cases=check, build_dataset=dataset)


# --- summaries ----------------------------------------------------------------------------------


def throughput_table(rows, n):
    """(1)-(2) per variant: min and median over the rounds, the ratio to in
    process, the quiet sweeps, the ratio at equal run speed."""
    base = np.array([r["wall"] for r in rows["in_process"]])
    table = {}
    for name, rs in rows.items():
        wall = np.array([r["wall"] for r in rs])
        per_round = base / wall  # the ratio in each round
        table[name] = dict(
            batch_size=rs[0]["batch_size"], wall=summary(wall), rate=dict(best=n / wall.min(), median=n / np.median(wall)),
            ratio=dict(of_best=float(base.min() / wall.min()), of_medians=float(np.median(base) / np.median(wall)),
                       per_round=per_round.tolist()),
            overhead=summary([r["overhead"] for r in rs]),
            mean_case_wall_time=summary([r["mean_case_wall_time"] for r in rs]),
            others_cores=summary([r["others_cores"] for r in rs if r["others_cores"] is not None] or [float("nan")]),
            ours_cores=summary([r["ours_cores"] for r in rs]),
            cases_per_cpu_second=summary([r["cases"] / (r["ours_cores"] * r["wall"]) for r in rs]),
            this_process_cores=summary([r["this_process_cores"] for r in rs]),
            this_process_cpu_per_task=summary([r["this_process_cpu_per_task"] for r in rs]))
        # at equal run speed: the ratio if each worker's runs went as fast as in process's (same round)
        equal = [r["workers"] * (1 + b["overhead"]) / (1 + r["overhead"]) for r, b in zip(rs, rows["in_process"])]
        table[name]["ratio_at_equal_run_speed"] = summary(equal)
        quiet = [r["wall"] for r in rs if r["others_cores"] is not None and r["others_cores"] < QUIET]
        table[name]["quiet"] = dict(sweeps=len(quiet), rate=n / min(quiet) if quiet else None,
                                    ratio=float(base.min() / min(quiet)) if quiet else None)
    return table


def estimate_study(out, n):
    """The estimate: 1e6 cases on 100 machines x 2 cores, each machine as the Dask cluster here."""
    table = out["table"]
    base = np.array([r["wall"] for r in out["sweeps"]["in_process"]])
    workers = PAPER_MACHINES * PAPER_CORES
    tasks_batch = max(1, min(256, math.ceil(PAPER_CASES / (4 * workers))))
    tasks = math.ceil(PAPER_CASES / tasks_batch)
    writes_256 = next(w for w in out["store"]["batch_writes"] if w["batch_size"] == min(256, n))
    store_bytes = [s["bytes_per_case"] for s in out["store"]["sweeps"]]
    estimate = {}
    cs = out["client_serial_per_case"]
    store_default = out["store"]["sweeps"][-1]  # batch 256 in the full run
    for key in ("min", "median"):
        own = table["in_process"]["mean_case_wall_time"][key]  # the core's run alone, in process
        per_case = {
            # each worker with a core of its own: the run as in process, plus the Dask cluster's overhead
            "own_cores": own * (1 + table["dask"]["overhead"][key]),
            # this machine as it was: the 2-worker cluster's cases/s, per worker
            "as_measured": WORKERS * table["dask"]["wall"][key] / n,
        }
        check, build = PAPER_CASES * cs["check_cases"], PAPER_CASES * cs["build_dataset"]
        limit = tasks_batch / writes_256["write"][key]  # cases/s this process can write into a store
        rows_ = {}
        for basis, c in per_case.items():
            compute = math.ceil(tasks / workers) * tasks_batch * c
            rows_[basis] = dict(per_case_on_a_worker=c, compute=compute, total=check + compute + build,
                                total_with_store=check + max(compute, PAPER_CASES / limit)
                                + tasks * store_default["open_store_per_batch"])
        per_task = out["dask_cpu_per_task"][key]
        estimate[key] = dict(client_and_scheduler_cpu=tasks * per_task, per_task_cpu=per_task,
                             per_case_in_process=(base.min() if key == "min" else np.median(base)) / n,
                             core_run_in_process=own, ideal=PAPER_CASES * own / workers, check_cases=check,
                             build_dataset=build, store_write_limit_cases_per_s=limit,
                             open_store=tasks * store_default["open_store_per_batch"], **rows_)
    return dict(cases=PAPER_CASES, machines=PAPER_MACHINES, cores=PAPER_CORES, workers=workers,
                default_batch=tasks_batch, tasks=tasks, waves=math.ceil(tasks / workers),
                store_bytes_per_case=store_bytes, store_gb=[PAPER_CASES * b / 1e9 for b in store_bytes],
                **estimate)


# --- tables -------------------------------------------------------------------------------------


def print_throughput(out):
    n, repeats, table = out["cases"], out["repeats"], out["table"]
    print(f"\n(1)-(2) {n} cases of {T_END:g} s ({n_out(T_END)} outputs), min (median) of {repeats} rounds; "
          f"ratio: cases/s over in process in the same rounds; overhead: (workers x wall - sum of the cases' "
          f"wall_time) / sum of the cases' wall_time; quiet: the variant's sweeps during which the other jobs used "
          f"under {QUIET} cores, the best of them against in process's best; at equal run speed: workers x (1 + "
          f"overhead in process) / (1 + overhead), same round, best (median)\n")
    print("| executor | batch | wall (s) | cases/s | ratio to in process | quiet: sweeps, ratio | overhead "
          "| ratio at equal run speed | case's own run (ms) | our CPU (cores) | this process's CPU per task (ms) "
          "| others' CPU (cores) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, t in table.items():
        per_task = (f"{t['this_process_cpu_per_task']['min'] * 1e3:.1f} ({t['this_process_cpu_per_task']['median'] * 1e3:.1f})"
                    if name.startswith(("processes", "dask")) else "-")
        print(f"| {name} | {t['batch_size']} | {t['wall']['min']:.2f} ({t['wall']['median']:.2f}) "
              f"| {t['rate']['best']:.0f} ({t['rate']['median']:.0f}) "
              f"| {t['ratio']['of_best']:.2f} ({t['ratio']['of_medians']:.2f}) "
              f"| {t['quiet']['sweeps']}, {'-' if t['quiet']['ratio'] is None else format(t['quiet']['ratio'], '.2f')} "
              f"| {t['overhead']['min']:.3f} ({t['overhead']['median']:.3f}) "
              f"| {t['ratio_at_equal_run_speed']['max']:.2f} ({t['ratio_at_equal_run_speed']['median']:.2f}) "
              f"| {t['mean_case_wall_time']['min'] * 1e3:.2f} ({t['mean_case_wall_time']['median'] * 1e3:.2f}) "
              f"| {t['ours_cores']['min']:.2f} ({t['ours_cores']['median']:.2f}) "
              f"| {per_task} "
              f"| {t['others_cores']['min']:.2f} ({t['others_cores']['median']:.2f}) |")


def print_startup(startup):
    print(f"\nStart-up (s): made + first warm-up sweep ({WARM} cases, batch 1) - the second\n")
    print("| executor | made | first sweep | second sweep | start-up |")
    print("|---|---:|---:|---:|---:|")
    for name, st in startup.items():
        if "rounds" in st:  # made again in each round: min (median)
            print(f"| {name} ({st['rounds']} rounds) | " + " | ".join(
                f"{st[k]['min']:.3f} ({st[k]['median']:.3f})" for k in ("made", "first_sweep", "second_sweep", "startup"))
                + " |")
        else:
            print(f"| {name} | {st['made']:.3f} | {st['first_sweep']:.3f} | {st['second_sweep']:.3f} "
                  f"| {st['startup']:.3f} |")


def print_threads(out):
    L = out["layers"]
    probe_count, scaling = out["thread_scaling"]["cases"], out["thread_scaling"]["rounds"]
    print("\n(3) a case's layers in process (ms), min (median)\n")
    print("| core's run (wall_time) | _core.simulate | mb.simulate | case without outputs | case |")
    print("|---:|---:|---:|---:|---:|")
    print("| " + " | ".join(f"{L[k]['min'] * 1e3:.3f} ({L[k]['median'] * 1e3:.3f})" for k in
                            ("core_wall_time", "core_call", "mb_simulate", "case_without_outputs", "case")) + " |")
    print("\noutputs (ms): " + ", ".join(f"{k} {v['min'] * 1e3:.3f}" for k, v in L["outputs"].items()))
    print(f"\nthe same work looped, cases/s ({probe_count} cases; ratio to 1 thread; the mean core's run "
          f"(wall_time) and the share of the threads' or processes' time inside it; others: the other jobs' CPU "
          f"meanwhile, cores)\n")
    print("| work | round | 1 thread | 2 threads | 2 processes |")
    print("|---|---:|---:|---:|---:|")
    for i, rnd in enumerate(scaling):
        for layer in ("core", "case"):
            row = rnd[layer]
            one = row["1 thread"]["rate"]
            cells = []
            for mode in ("1 thread", "2 threads", "2 processes"):
                c = row[mode]
                cell = f"{c['rate']:.0f} ({c['rate'] / one:.2f}), run {c['core_run'] * 1e3:.2f} ms, {c['in_core']:.2f} in it"
                if c["others_cores"] is not None:
                    cell += f", others {c['others_cores']:.1f}"
                cells.append(cell)
            print(f"| {layer} | {i} | " + " | ".join(cells) + " |")
    speed = out["busy_cores_speed"]
    print("\nthe core's run alone (median, ms) with one core busy and with both, alternated: "
          + ", ".join(f"{r['one_busy'] * 1e3:.2f} / {r['two_busy'] * 1e3:.2f}" for r in speed)
          + f"; median ratio {np.median([r['two_busy'] / r['one_busy'] for r in speed]):.2f}")
    warned = out["threads_left_warnings_redirected"]
    print(f"\nthread sweeps that left warnings redirected into a case's list: {warned['disturbed']} of "
          f"{warned['sweeps']}")


def print_store(out):
    print("\n(4) the store\n")
    print("| batch | batches | sweep (s) | cases/s | bytes/case | on disk/case | files/batch | open_store (s) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for st in out["store"]["sweeps"]:
        print(f"| {st['batch_size']} | {st['batches']} | {st['wall']:.2f} | {st['rate']:.0f} "
              f"| {st['bytes_per_case']:.0f} | {st['disk_bytes_per_case']:.0f} | {st['files_per_batch']:.0f} "
              f"| {st['open_store']:.2f} |")
    print(f"\nthe first store of the process (imports; {WARM} cases): {out['store']['first_store_of_the_process']:.2f} s")
    print("\none batch written (ms): " + ", ".join(f"batch {w['batch_size']} {w['write']['min'] * 1e3:.1f} "
                                                  f"({w['write']['median'] * 1e3:.1f})"
                                                  for w in out["store"]["batch_writes"]))
    cs = out["client_serial_per_case"]
    print(f"this process's serial work per case: cases checked {cs['check_cases'] * 1e6:.1f} us, Dataset built "
          f"{cs['build_dataset'] * 1e6:.1f} us")


def print_estimate(e):
    workers = e["workers"]
    print(f"\n1e6 cases on {PAPER_MACHINES} machines x {PAPER_CORES} cores ({workers} workers), default batch "
          f"{e['default_batch']}, {e['tasks']} tasks in {e['waves']} waves; from the min (median) of (1)\n")
    print("| basis | per case on a worker (ms) | compute (s) | + cases checked + Dataset (s) "
          "| with a store instead of the Dataset (s) |")
    print("|---|---:|---:|---:|---:|")
    for basis, label in (("own_cores", "a core per worker: the core's run in process x (1 + Dask overhead)"),
                         ("as_measured", "this machine as measured: 2 / the cluster's cases/s")):
        b, m = e["min"][basis], e["median"][basis]
        print(f"| {label} | {b['per_case_on_a_worker'] * 1e3:.2f} ({m['per_case_on_a_worker'] * 1e3:.2f}) "
              f"| {b['compute']:.0f} ({m['compute']:.0f}) | {b['total']:.0f} ({m['total']:.0f}) "
              f"| {b['total_with_store']:.0f} ({m['total_with_store']:.0f}) |")
    b = e["min"]
    print(f"\nideal (the core's runs alone over {workers} workers): {b['ideal']:.0f} s; this process: cases checked "
          f"{b['check_cases']:.0f} s before the first task, Dataset {b['build_dataset']:.0f} s after the last; "
          f"it writes a store at up to {b['store_write_limit_cases_per_s']:.0f} cases/s and reads it back in "
          f"{b['open_store']:.0f} s; store {', '.join(f'{g:.2f}' for g in e['store_gb'])} GB; the client and the "
          f"scheduler (this process) {b['per_task_cpu'] * 1e3:.1f} ms CPU per task (batch 1 against the default): "
          f"{b['client_and_scheduler_cpu']:.0f} s for the {e['tasks']} tasks, beside the compute")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    p.add_argument("--repeats", type=int, default=None, help="rounds of (1) (default 3, --quick 2)")
    p.add_argument("--cases", type=int, default=None, help="cases per sweep (default 1000, --quick 200)")
    p.add_argument("--quick", action="store_true", help="200 cases, 2 rounds; writes nothing unless --out")
    p.add_argument("--out", default=None, help="the JSON written (default bench/results/sweep.json)")
    args = p.parse_args()
    repeats = args.repeats or (2 if args.quick else 3)
    n = args.cases or (200 if args.quick else 1000)
    dask_batches = [1] if args.quick else DASK_BATCHES
    started = time.perf_counter()
    loads = {"start": load_average()}

    import dask
    import distributed
    import xarray
    import zarr

    scene = mb.load_scene(SCENE)
    model = scene.model
    model.compiled()
    settings = dict(t_end=T_END, rtol=1e-8, atol=1e-10, n_out=n_out(T_END))
    assert {k: scene.settings[k] for k in ("rtol", "atol")} == {"rtol": 1e-8, "atol": 1e-10}, scene.settings
    grid = {"rod.mass": np.linspace(1.0, 3.0, n)}
    out = {**stamp("sweep", changed("cpp", "python/lagmb")),
           "numpy": np.__version__, "dask": dask.__version__, "distributed": distributed.__version__,
           "xarray": xarray.__version__, "zarr": zarr.__version__,
           "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS"), "repeats": repeats, "cases": n,
           "model": "examples/slider_crank.toml", "varied": "rod.mass = linspace(1, 3, cases)",
           "settings": settings, "outputs": {k: repr(v) for k, v in OUTPUTS.items()}, "workers": WORKERS}

    out["calibration"] = calibration(model, 10 if args.quick else 30)
    probe_threads(out, model, settings, args.quick)
    loads["after_probe"] = load_average()
    warm = {"rod.mass": np.linspace(1.0, 3.0, WARM)}
    ex = Executors(scene, warm)
    try:
        rows, last, disturbed, dask_startups = sweep_rounds(ex, scene, grid, n, repeats, dask_batches, args.quick,
                                                            loads)
        ex.startup["dask"] = dict({k: summary([x[k] for x in dask_startups]) for k in dask_startups[0]},
                                  rounds=len(dask_startups))
        out["startup"] = ex.startup
        client = ex.holder["client"] if "client" in ex.holder else ex.make_dask()
        # every executor gives the in-process numbers
        for name, ds in last.items():
            for key in OUTPUTS:
                np.testing.assert_array_equal(ds[key].values, last["in_process"][key].values)
        out["threads_left_warnings_redirected"] = dict(sweeps=repeats, disturbed=disturbed)
        out["store"] = store_sweeps(scene, warm, grid, client, n, args.quick, last["in_process"])
        out["client_serial_per_case"] = serial_work(model, grid, last["in_process"], n)
    finally:
        ex.shutdown()
    loads["end"] = load_average()

    out["sweeps"] = rows
    out["table"] = throughput_table(rows, n)
    # this process's CPU (the client and the Dask scheduler) per task: batch 1 against the default, same rounds
    cpu = lambda r: r["this_process_cores"] * r["wall"]  # noqa: E731
    slope = [(cpu(a) - cpu(b)) / (a["tasks"] - b["tasks"]) for a, b in zip(rows["dask, batch 1"], rows["dask"])]
    out["dask_cpu_per_task"] = summary(slope)
    out["estimate"] = estimate_study(out, n)
    out["load_average_1min"] = loads
    out["seconds"] = time.perf_counter() - started

    print_throughput(out)
    print_startup(out["startup"])
    print_threads(out)
    print_store(out)
    print_estimate(out["estimate"])
    print(f"\n{stamp_line(out, (loads['start'], loads['end']))} (rounds: "
          f"{', '.join(f'{x:.2f}' for x in loads['rounds'])}), {out['seconds']:.0f} s")
    write_json(args.out or (None if args.quick else os.path.join(RESULTS, "sweep.json")), out, default=float)


if __name__ == "__main__":
    sys.exit(main())
