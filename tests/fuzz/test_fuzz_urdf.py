"""Fuzzed URDF files: random robots with hostile mutations (issue 39).

tests/fuzz/fuzz_urdf.py draws robots (chains and trees of revolute, continuous,
prismatic, fixed, planar and floating joints with limits, damping and
mimics) and mutates them: loops, self-parents, long mimic chains and
cycles, numbers in odd forms, encodings, lower > upper and equal limits,
huge and tiny values, duplicate and colliding names, long tokens, missing
elements, hostile load options. Each case runs in the worker of
tests/fuzz/fuzz_mechanisms.py (a subprocess: a crash or a hang fails the case,
not pytest): the file is written, loaded by mb.load_urdf and run for
0.01 s.

The property: every case loads and runs with finite outputs and its
constraints held, or lagmb refuses it with its own exception naming the
file or the argument; a robot without mutations (or with only those lagmb
must read: numbers in odd but valid forms, names it renames, a long
comment, a readable encoding) must load and run; a case with a mutation
lagmb must refuse must not load. Anything else is a finding, reported
grouped by kind with a reproducer script (``python3
tests/fuzz/fuzz_mechanisms.py --replay FILE.py`` reruns one).

- test_fuzz_urdf_default: 150 cases, seeded, about 5 s on 2 cores, in the
  default suite.
- test_fuzz_urdf_long: @pytest.mark.fuzz, 1,000 cases (LAGMB_FUZZ_URDF_EXAMPLES,
  LAGMB_FUZZ_SEED); run with ``python3 -m pytest -m fuzz tests/fuzz/test_fuzz_urdf.py``.
  LAGMB_FUZZ_REPORT=path.json writes the findings as JSON (path-urdf.json).
"""

import collections
import json
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fuzz_mechanisms as fm  # noqa: E402
import fuzz_urdf as fu  # noqa: E402

DEFAULT_EXAMPLES = 150
DEFAULT_SEED = 39
TIMEOUT = 60.0  # s per op: a 1,500-joint mimic chain loads and runs in a few s; a hang never ends


def _check(cases, minimize_budget):
    outcomes = fm.run_cases([ops for ops, _ in cases], TIMEOUT, n_workers=2)
    findings = fm.Findings()
    for (ops, _), (problems, statuses) in zip(cases, outcomes):
        findings.add(ops, problems, statuses)
    if findings:
        findings.minimize_all(TIMEOUT, minimize_budget)
    path = os.environ.get("LAGMB_FUZZ_REPORT")
    if path:
        root, ext = os.path.splitext(path)
        with open(f"{root}-urdf{ext or '.json'}", "w") as f:
            json.dump({"cases": len(cases), "findings": findings.to_json()}, f, indent=1)
    assert not findings, (f"{len(cases)} fuzzed URDF cases: each must load and run, or be refused by a lagmb "
                          "exception naming the file or the argument (and as the mutation requires).\n" +
                          findings.report())
    return outcomes


def test_fuzz_urdf_default():
    """150 seeded cases: no finding; every mutation is drawn, and both
    outcomes occur (robots that load and run, files that are refused)."""
    cases = fu.cases(DEFAULT_EXAMPLES, DEFAULT_SEED)
    assert set(fu.MUTATIONS) <= {m for _, mutations in cases for m in mutations}
    outcomes = _check(cases, minimize_budget=5.0)
    loads = collections.Counter(statuses.get("1", "skipped").split(" ")[0] for _, statuses in outcomes)
    runs = collections.Counter(statuses.get("2", "skipped").split(" ")[0] for _, statuses in outcomes)
    assert loads["ok"] >= 30 and loads["refused"] >= 50 and runs["ok"] >= 30, (loads, runs)


def test_the_fuzzer_finds_a_file_loaded_that_must_be_refused_and_a_foreign_exception():
    """The oracle itself: a clean robot whose load is marked "must be
    refused", and a load that raises KeyError, are each a finding."""
    import random

    links, joints = fu.robot(random.Random(1))
    text = fu.render(links, joints, random.Random(1))
    info = {"numbers": "plain", "declared": "UTF-8", "codec": "utf-8", "long": None}
    loaded = fu._ops(text, info, {}, verdict="refuse")
    foreign = fu._ops(text, info, {}, verdict="either")
    foreign[1]["code"] = "model = {}['j1']\n"
    outcomes = fm.run_cases([loaded, foreign], TIMEOUT, n_workers=1)
    assert [p["key"].split(" @ ")[0] for p in outcomes[0][0]] == ["AssertionError"]
    assert "loaded a file or arguments lagmb must refuse" in outcomes[0][0][0]["detail"]
    assert [p["key"].split(" @ ")[0] for p in outcomes[1][0]] == ["KeyError"]


@pytest.mark.fuzz
def test_fuzz_urdf_long(request):
    """1,000 cases (LAGMB_FUZZ_URDF_EXAMPLES; seed LAGMB_FUZZ_SEED), selected with -m fuzz."""
    if "fuzz" not in (request.config.getoption("markexpr", "") or ""):
        pytest.skip("long fuzz run: select it with -m fuzz")
    n = int(os.environ.get("LAGMB_FUZZ_URDF_EXAMPLES", "1000"))
    seed = int(os.environ.get("LAGMB_FUZZ_SEED", "20240611"))
    _check(fu.cases(n, seed), minimize_budget=float(os.environ.get("LAGMB_FUZZ_MINIMIZE_S", "120")))
