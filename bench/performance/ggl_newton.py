"""What one Newton iteration of GGL costs on a long chain, and where it goes.

The chain of bench/performance/chain.py, 1 s at rtol 1e-6 (atol 1e-8), the default
method (GGL, IDA BDF). For each N:

- wall time per Newton iteration and per link (fastest of --repeat runs;
  IDA's nonlinear iterations from r.stats["newton_iterations"]);
- the split of the instructions inside lagmb::simulate (valgrind callgrind,
  inclusive counts, on a copy of the module built without stripping; see
  bench/performance/effects.py) between the residual (GglFormulation::residual), the
  Newton matrix's assembly (GglFormulation::newton_matrix), its
  factorization (klu_factor, klu_refactor, klu_rcond), the solves
  (klu_solve) and the rest (IDA's own algorithm and vector operations,
  outputs), each also as instructions per link per Newton iteration.

Prints a table and writes bench/results/ggl_newton.json.

    python bench/performance/ggl_newton.py [--n 128 512] [--repeat 3] [--no-callgrind]
"""

import argparse
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

import lagmb as mb  # noqa: E402
from bench.common.chain import chain  # noqa: E402
from bench.common.paths import RESULTS, ROOT  # noqa: E402
from bench.performance.effects import unstripped_module  # noqa: E402

SETTINGS = {"t_end": 1.0, "rtol": 1e-6, "atol": 1e-8, "n_out": 2, "method": "ggl"}  # GGL asked for: auto picks the explicit method here
# (label, callgrind function names whose inclusive counts make the part)
PARTS = (
    ("residual", ("lagmb::GglFormulation::residual(",)),
    ("newton matrix", ("lagmb::GglFormulation::newton_matrix(",)),
    ("factorization", ("klu_factor", "klu_refactor", "klu_rcond")),
    ("solves", ("klu_solve",)),
)

RUNNER = """
import json, sys
sys.path.insert(0, sys.argv[1]); sys.path.insert(0, sys.argv[2])
import lagmb as mb
assert mb.__file__.startswith(sys.argv[1]), mb.__file__
from bench.common.chain import chain
m = chain(int(sys.argv[3])); m.compiled()
r = mb.simulate(m, **json.loads(sys.argv[4]))
print(json.dumps(r.stats))
"""


def wall(n, repeat):
    m = chain(n)
    m.compiled()
    best = None
    for _ in range(repeat):
        r = mb.simulate(m, **SETTINGS)
        if best is None or r.stats["wall_time"] < best["wall_time"]:
            best = dict(r.stats)
    return best


def callgrind_split(pkg, n, work):
    out = os.path.join(work, f"ggl_{n}.callgrind")
    cmd = ["valgrind", "--tool=callgrind", "--toggle-collect=lagmb::simulate(*",
           "--toggle-collect=std::_Function_handler<void (double), pybind11_init__core*_M_invoke*",
           f"--callgrind-out-file={out}", sys.executable, "-c", RUNNER, pkg, ROOT, str(n), json.dumps(SETTINGS)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"callgrind failed:\n{p.stderr[-2000:]}")
    stats = json.loads(p.stdout.strip().splitlines()[-1])
    total = int(re.search(r"^(?:summary|totals):\s*(\d+)", open(out).read(), re.M).group(1))
    report = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out],
                            capture_output=True, text=True, check=True).stdout
    inclusive = {}
    for line in report.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\([^)]*\)\s+\S*?:(.*?)\s*(\[.*\])?$", line)
        if m:
            inclusive.setdefault(m.group(2), int(m.group(1).replace(",", "")))
    parts = {}
    for label, names in PARTS:
        parts[label] = sum(v for k, v in inclusive.items() if any(k.startswith(nm) for nm in names))
    parts["IDA and the rest"] = total - sum(parts.values())
    return total, parts, stats


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, nargs="+", default=[128, 512])
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--no-callgrind", action="store_true")
    p.add_argument("--build-dir", default=os.path.join(tempfile.gettempdir(), "lagmb-effects-build"))
    p.add_argument("--out", default=os.path.join(RESULTS, "ggl_newton.json"))
    args = p.parse_args()
    use_callgrind = not args.no_callgrind and shutil.which("valgrind")
    pkg = unstripped_module(args.build_dir) if use_callgrind else None
    work = tempfile.mkdtemp(prefix="lagmb-ggl-")
    rows = []
    for n in args.n:
        s = wall(n, args.repeat)
        it = s["newton_iterations"]
        row = {"n": n, "steps": s["steps"], "newton_iterations": it, "lu_factorizations": s["lu_factorizations"],
               "wall_time": s["wall_time"], "us_per_link_per_iteration": 1e6 * s["wall_time"] / it / n}
        print(f"N = {n}: {s['steps']} steps, {it} Newton iterations, {s['lu_factorizations']} factorizations, "
              f"{s['wall_time']:.3f} s: {row['us_per_link_per_iteration']:.3f} us per link per iteration")
        if pkg:
            total, parts, cs = callgrind_split(pkg, n, work)
            assert cs["newton_iterations"] == it, (cs["newton_iterations"], it)
            row["instructions"] = total
            row["parts"] = {k: {"instructions": v, "fraction": v / total,
                                "instructions_per_link_per_iteration": v / n / it} for k, v in parts.items()}
            for k, v in row["parts"].items():
                print(f"    {k:18s} {100 * v['fraction']:5.1f} %   {v['instructions_per_link_per_iteration']:8.0f}"
                      " instructions / link / iteration")
        rows.append(row)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump({"machine": platform.platform(), "settings": SETTINGS, "results": rows}, f, indent=1)


if __name__ == "__main__":
    main()
