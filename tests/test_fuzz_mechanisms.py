"""Fuzzed inputs: random small mechanisms with hostile parameters and options.

Hypothesis draws cases (tests/fuzz_mechanisms.py: chains and closed loops of
1-5 bodies and particles, random joints, drivers, forces, stops, contacts,
parameters from wide and hostile ranges, then what a user runs:
degrees_of_freedom, assemble, solve_accelerations, simulate with random
options, equilibrium, result accessors, a Simulator advanced in chunks with
its inputs set and its state saved and restored). Each case runs in a worker
subprocess, so a crash or a hang fails that case instead of pytest.

The property: every call either returns numbers that are all finite (and a
successful run or equilibrium keeps max |Phi| <= 1e-4 (1 + max |q|)), or
raises one of lagmb's own exceptions (mb.ModelError and subclasses,
mb.SimulationError and subclasses, mb.SceneError). Anything else (another
exception type, a non-finite output, a silently violated constraint, a crash,
a hang past the timeout) is a finding.

The cases are not shrunk by hypothesis: all of them run, the findings are
grouped by kind (exception type, where it was raised and its message with the
numbers blanked; crash or hang and the call; non-finite output and which
array), and the shortest case of each kind is cut down op by op to a short
reproducer script, printed in the failure message (``python3
tests/fuzz_mechanisms.py --replay FILE.py`` reruns one the same way).

- test_fuzz_mechanisms_default: part of the default suite, deterministic
  (derandomize=True), 400 cases in about 10 s.
- test_fuzz_mechanisms_long: @pytest.mark.fuzz, 600 cases (LAGMB_FUZZ_EXAMPLES,
  LAGMB_FUZZ_SEED); run with ``python3 -m pytest -m fuzz -p no:warnings
  tests/test_fuzz_mechanisms.py`` or ``make test-fuzz``; the default suite
  deselects it (pyproject.toml addopts), and it skips itself unless ``-m``
  names ``fuzz``.
  LAGMB_FUZZ_REPORT=path.json writes the findings as JSON.
"""

import json
import os
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fuzz_mechanisms as fm  # noqa: E402

DEFAULT_EXAMPLES = 400
# s per call: the slowest healthy call takes ~3 s alone (rtol 1e-10, BDF order 1), and CI
# machines are shared; a real hang never ends, so the bound can be generous
DEFAULT_TIMEOUT = 30.0
LONG_TIMEOUT = 30.0


def _generate(n, derandomize, rng_seed=None):
    """n cases drawn by hypothesis (plain data). The deterministic draw runs in
    a fresh interpreter: in this one, what hypothesis draws depends on the
    modules other tests imported before (it mines their constants)."""
    if not derandomize:
        return fm.generate(n, derandomize=False, rng_seed=rng_seed)
    out = subprocess.run([sys.executable, fm.__file__, "--generate", str(n)], capture_output=True,
                         text=True, timeout=600, check=True)
    return json.loads(out.stdout)


def _check(cases, timeout, minimize_budget):
    outcomes = fm.run_cases(cases, timeout, n_workers=2)
    findings = fm.Findings()
    for case, (problems, statuses) in zip(cases, outcomes):
        findings.add(case, problems, statuses)
    if findings:
        findings.minimize_all(timeout, minimize_budget)
    path = os.environ.get("LAGMB_FUZZ_REPORT")
    if path:
        with open(path, "w") as f:
            json.dump({"cases": len(cases), "findings": findings.to_json()}, f, indent=1)
    assert not findings, (f"{len(cases)} fuzzed cases: every call must return finite numbers or raise "
                          f"mb.ModelError / mb.SimulationError / mb.SceneError.\n" + findings.report())


def test_fuzz_mechanisms_default():
    """400 random mechanisms (deterministic), in the default suite."""
    _check(_generate(DEFAULT_EXAMPLES, derandomize=True), DEFAULT_TIMEOUT, minimize_budget=8.0)


@pytest.mark.fuzz
def test_fuzz_mechanisms_long(request):
    """600 random mechanisms (LAGMB_FUZZ_EXAMPLES), selected with -m fuzz."""
    if "fuzz" not in (request.config.getoption("markexpr", "") or ""):
        pytest.skip("long fuzz run: select it with -m fuzz")
    n = int(os.environ.get("LAGMB_FUZZ_EXAMPLES", "600"))
    rng_seed = int(os.environ.get("LAGMB_FUZZ_SEED", "20240611"))
    _check(_generate(n, derandomize=False, rng_seed=rng_seed), LONG_TIMEOUT,
           minimize_budget=float(os.environ.get("LAGMB_FUZZ_MINIMIZE_S", "240")))
