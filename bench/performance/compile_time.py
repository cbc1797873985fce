"""Where the build's time goes: CPU seconds per translation unit.

Configures a fresh build of the Python module and the C++ library (the same
targets and flags as `pip install .`: Release, lagmb._core, liblagmb_fmu) in
a temporary folder, builds it with this script as the compiler launcher, and
records each compiler and linker call's user + system CPU time (wall time on
this shared machine says little; CPU time adds up to what a 2-core fresh
set-up waits for, divided by 2). Prints the table, writes
bench/results/compile_time.json.

    python bench/performance/compile_time.py [--jobs 2] [--label NAME] [-D CMAKE_OPTION=VALUE ...] [--keep DIR]
"""

import argparse
import datetime
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from bench.common.paths import RESULTS, ROOT  # noqa: E402

RECORD = os.path.join(RESULTS, "compile_time.json")


def launch(argv):
    """Compiler-launcher mode: run the compiler, append its CPU time to the log."""
    out = argv[argv.index("-o") + 1] if "-o" in argv else argv[-1]
    start = time.perf_counter()
    code = subprocess.call(argv)
    wall = time.perf_counter() - start
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(os.environ["LAGMB_COMPILE_LOG"], "a") as log:
        log.write(json.dumps({"output": out, "cpu": usage.ru_utime + usage.ru_stime,
                              "wall": wall}) + "\n")
    return code


def short(output):
    """The source or target a compiler output stands for."""
    for marker in ("/cpp/", "CMakeFiles/"):
        if marker in output:
            output = output.split(marker, 1)[1]
    return output.replace(".cpp.o", ".cpp").replace("lagmb_core.dir/", "").replace("_core.dir/", "")


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--launch":
        sys.exit(launch(sys.argv[2:]))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--label", default="current")
    ap.add_argument("-D", dest="defines", action="append", default=[])
    ap.add_argument("--keep", metavar="DIR", help="build in DIR and keep it (e.g. to run its module)")
    args = ap.parse_args()
    import pybind11

    build = args.keep or tempfile.mkdtemp(prefix="lagmb-compile-")
    log = os.path.join(build, "compile.log")
    env = dict(os.environ, LAGMB_COMPILE_LOG=log)
    launcher = f"{sys.executable};{os.path.abspath(__file__)};--launch"
    configure = ["cmake", "-S", ROOT, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 "-DLAGMB_PYTHON=ON", f"-Dpybind11_DIR={pybind11.get_cmake_dir()}",
                 f"-DCMAKE_CXX_COMPILER_LAUNCHER={launcher}",
                 f"-DCMAKE_CXX_LINKER_LAUNCHER={launcher}"] + [f"-D{d}" for d in args.defines]
    subprocess.run(configure, check=True, env=env, stdout=subprocess.DEVNULL)
    start = time.perf_counter()
    made = subprocess.run(["cmake", "--build", build, "-j", str(args.jobs)], env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if made.returncode:
        sys.exit(f"the build failed (kept in {build}):\n" + made.stdout[-5000:])
    wall = time.perf_counter() - start
    with open(log) as f:
        calls = [json.loads(line) for line in f]
    if not args.keep:
        shutil.rmtree(build, ignore_errors=True)
    calls.sort(key=lambda c: -c["cpu"])
    total = sum(c["cpu"] for c in calls)
    print(f"{len(calls)} compiler/linker calls, {total:.0f} CPU s, {wall:.0f} s wall with -j{args.jobs}")
    for c in calls[:25]:
        print(f"{c['cpu']:7.1f}  {short(c['output'])}")
    record = {"label": args.label, "date": datetime.date.today().isoformat(), "jobs": args.jobs,
              "defines": args.defines, "cpu_total_s": round(total, 1), "wall_s": round(wall, 1),
              "calls": [{"target": short(c["output"]), "cpu_s": round(c["cpu"], 2)} for c in calls]}
    runs = []
    if os.path.exists(RECORD):
        with open(RECORD) as f:
            runs = json.load(f)
    runs = [r for r in runs if r["label"] != args.label] + [record]
    with open(RECORD, "w") as f:
        json.dump(runs, f, indent=1)


if __name__ == "__main__":
    main()
