"""What a benchmark's JSON records of the run (which code, which build, on
what machine) and how it is written to bench/results/."""

import datetime
import hashlib
import json
import os
import platform
import subprocess
import time

from bench.common.paths import ROOT


def one_blas_thread():
    """BLAS/LAPACK (behind NumPy and SciPy) and OpenMP on one thread unless
    set otherwise: on a shared machine threaded OpenBLAS made dense calls up
    to 50 times slower. Call before NumPy is imported."""
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")


def git(*args):
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout.strip()


def changed(*paths):
    """The lines of `git status --porcelain` under `paths`: what of the code
    measured differs from the commit recorded."""
    return git("status", "--porcelain", "--", *paths).splitlines()


def stamp(benchmark, changes):
    """The head of a result: the benchmark, when, which commit (and its
    uncommitted `changes`), on what machine."""
    return {"benchmark": benchmark, "date": datetime.datetime.now().isoformat(timespec="minutes"),
            "commit": git("rev-parse", "--short", "HEAD"), "changes": changes,
            "machine": platform.platform(), "python": platform.python_version(), "cpus": os.cpu_count()}


def stamp_line(out, loads=None):
    """The stamp as one printed line: date, commit (+ changes), machine, CPUs
    (and the load average at the start and the end, `loads`)."""
    line = (f"{out['date']}, commit {out['commit']}{' + changes' if out['changes'] else ''}, {out['machine']}, "
            f"{out['cpus']} CPUs")
    return line if loads is None else line + f", load average {loads[0]:.2f} .. {loads[1]:.2f}"


def load_average():
    """The 1-minute load average (None where the system has none)."""
    return os.getloadavg()[0] if hasattr(os, "getloadavg") else None


def write_json(path, out, **dump_options):
    """`out` as indented JSON with a final newline; says where. No path
    (a --quick run without --out), nothing written."""
    if not path:
        return
    with open(path, "w", encoding="utf-8") as f:
        json.dump(out, f, indent=1, **dump_options)
        f.write("\n")
    print(f"written: {os.path.relpath(path, ROOT)}")


def run_versions(mb, **others):
    """{"lagmb": version, "lagmb_build": build_id, **others}: what a bench's
    JSON records of the code that ran."""
    return {"lagmb": mb.__version__, "lagmb_build": build_id(mb), **others}


def build_id(mb):
    """Which build ran: md5 (12 digits) and time of the compiled core, so that
    results from a rebuilt lagmb can be told apart."""
    core = getattr(mb, "_core", None)
    path = getattr(core, "__file__", None)
    if not path or not os.path.exists(path):
        return "core build unknown"
    with open(path, "rb") as f:
        digest = hashlib.md5(f.read()).hexdigest()[:12]
    built = time.strftime("%Y-%m-%d %H:%M", time.gmtime(os.path.getmtime(path)))
    return f"_core md5 {digest}, {built} UTC"
