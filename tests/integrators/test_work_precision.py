"""Work-precision studies: mb.work_precision, WorkPrecision and `lagmb accuracy`.

The study runs each method at each tolerance (atol = 1e-2 rtol) against a
tight reference run and reports one row per method x tolerance with the
columns promised in the docstring of lagmb.accuracy.  Here: the seed
pendulum (uniform rod, L = 1 m, m = 1 kg, released horizontal) over 2 s
(one full swing and back), methods ggl, projection-bdf and projection-adams,
rtol 1e-4 .. 1e-8.
"""

import json
import re
import math
from pathlib import Path

import numpy as np
import pytest

import lagmb as mb
import lagmb.accuracy
from builders import lagmb_command, pendulum
import paths  # noqa: E402  (tests/paths.py)

EXAMPLES = Path(paths.EXAMPLES)

METHODS = ["ggl", "projection-bdf", "projection-adams"]
TOLERANCES = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
T_END = 2.0

# The columns the module docstring of lagmb.accuracy promises, with their types.
TEXT = ["method", "formulation", "integrator", "reference", "status", "message"]
REAL = ["rtol", "atol", "error", "error_final", "cpu_time", "wall_time", "drift_position",
        "drift_velocity", "energy_error"]
COUNT = ["steps", "residual_evals", "jacobian_evals", "lu_factorizations",
         "augmented_factorizations", "error_test_failures", "convergence_failures"]
PROMISED = ["method", "formulation", "integrator", "rtol", "atol", "reference", "status", "message", "error",
            "error_final", "cpu_time", "wall_time", "steps", "residual_evals", "jacobian_evals",
            "lu_factorizations", "augmented_factorizations", "error_test_failures",
            "convergence_failures", "drift_position", "drift_velocity", "energy_error"]


@pytest.fixture(scope="module")
def wp():
    """The study (15 runs plus the reference, about 0.1 s)."""
    return mb.work_precision(pendulum(), T_END, methods=METHODS, tolerances=TOLERANCES)


def test_promised_columns_are_documented_and_exported():
    """Every promised column is named in the module docstring, and
    mb.WorkPrecision.columns is exactly the promised list, in that order."""
    doc = lagmb.accuracy.__doc__
    for c in PROMISED:
        assert c in doc, c
    assert list(mb.WorkPrecision.columns) == PROMISED
    assert sorted(TEXT + REAL + COUNT) == sorted(PROMISED)


def test_rows_have_every_column_with_the_right_type(wp):
    """One row per method x tolerance (methods in the order given, rtol from
    loose to tight), each with exactly the promised columns: text columns are
    str, counts are int (not bool) and >= 0 (steps >= 1), real columns are
    finite floats >= 0 (cpu_time > 0 is not required: a run can take less
    than the clock's resolution).  atol = 1e-2 rtol; formulation and
    integrator are those of mb.METHODS; status "ok" with an empty message."""
    assert len(wp.rows) == len(METHODS) * len(TOLERANCES)
    assert wp.methods == METHODS
    for i, row in enumerate(wp.rows):
        method = METHODS[i // len(TOLERANCES)]
        rtol = TOLERANCES[i % len(TOLERANCES)]
        assert set(row) == set(PROMISED), sorted(row)
        for c in TEXT:
            assert isinstance(row[c], str), (c, row[c])
        for c in COUNT:
            assert isinstance(row[c], int) and not isinstance(row[c], bool), (c, row[c])
            assert row[c] >= 0, (c, row[c])
        for c in REAL:
            assert isinstance(row[c], float), (c, row[c])
            assert math.isfinite(row[c]) and row[c] >= 0.0, (c, row[c])
        assert row["steps"] >= 1
        assert row["status"] == "ok" and row["message"] == ""
        assert row["method"] == method
        assert row["rtol"] == pytest.approx(rtol, rel=1e-15)
        assert row["atol"] == pytest.approx(1e-2 * rtol, rel=1e-15)
        assert row["formulation"] == mb.METHODS[method]["formulation"]
        assert row["integrator"] == mb.METHODS[method]["integrator"]
        assert row["error_final"] <= row["error"]


def test_error_column_is_the_distance_to_the_reference(wp):
    """error is max over outputs of max |q - q_ref| and drift_position is
    max |Phi| of that run: rerunning one row's method (ggl at rtol 1e-6) with
    the same outputs and tolerances reproduces both (runs are deterministic:
    to 1e-15).  The reference is projection-bdf at rtol 1e-10 (1e-2 x the
    tightest tolerance); it is good enough to measure the table's errors: its
    own distance to a GGL run at rtol 1e-12, atol 1e-14 is at most 1/4 of the
    smallest error in the table (measured 3.7e-9 against 8.1e-8)."""
    row = next(r for r in wp.rows if r["method"] == "ggl" and r["rtol"] == 1e-6)
    assert row["reference"] == "projection-bdf rtol 1e-10"
    ref = wp.reference_for("ggl")
    r = mb.simulate(pendulum(), t_out=ref.t, rtol=1e-6, atol=1e-8, **mb.METHODS["ggl"])
    assert abs(np.abs(r.q - ref.q).max() - row["error"]) <= 1e-15
    assert abs(np.abs(r.q[-1] - ref.q[-1]).max() - row["error_final"]) <= 1e-15
    assert abs(r.residual.max() - row["drift_position"]) <= 1e-15
    assert wp.reference_info["projection-bdf rtol 1e-10"]["rtol"] == pytest.approx(1e-10)
    assert wp.reference_for("projection-adams") is wp.reference["ggl rtol 1e-10"]
    tight = mb.simulate(pendulum(), t_out=ref.t, rtol=1e-12, atol=1e-14)
    smallest = min(r["error"] for r in wp.rows)
    assert np.abs(tight.q - ref.q).max() <= 0.25 * smallest


def test_error_falls_along_each_method_line(wp):
    """Along each method's line the error is monotone as rtol falls: each
    error at most 1.0x the previous one (measured at most 0.43x: ggl 0.43,
    projection-bdf 0.32, projection-adams 0.21), and from rtol 1e-4 to 1e-8
    it falls at least 1000x (measured: ggl 8.5e3, projection-bdf 4.4e3,
    projection-adams 1.1e5).  Measured errors at rtol 1e-4 / 1e-8: ggl
    6.9e-4 / 8.1e-8, projection-bdf 5.5e-3 / 1.3e-6, projection-adams
    5.4e-2 / 5.0e-7."""
    for m in METHODS:
        errors = [r["error"] for r in wp.method_rows(m)]
        assert len(errors) == len(TOLERANCES)
        for a, b in zip(errors, errors[1:]):
            assert b <= 1.0 * a, (m, errors)
        assert errors[-1] * 1000.0 <= errors[0], (m, errors)


def test_cheapest(wp):
    """cheapest(e) gives, for each method, the least CPU time among its runs
    with error <= e.  For e = the largest of the methods' best errors every
    method has such a run, and the answer is that minimum (computed here from
    the rows); for e = 1e-30 no run qualifies and every method gets None."""
    e = max(min(r["error"] for r in wp.method_rows(m)) for m in METHODS)
    best = wp.cheapest(e)
    assert set(best) == set(METHODS)
    for m in METHODS:
        expected = min(r["cpu_time"] for r in wp.method_rows(m) if r["error"] <= e)
        assert isinstance(best[m], float)
        assert best[m] == expected
    assert wp.cheapest(1e-30) == {m: None for m in METHODS}


def test_summary_names_the_references_and_the_cheapest_run_per_error(wp):
    """summary(): the error's definition with its units; one line per
    reference run naming the methods measured against it (every method
    once); for each error asked for, the run of least CPU time among all
    methods and tolerances that reaches it (checked against the rows), or
    that none did; by default one line per decade of the errors reached."""
    text = wp.summary([1e-4, 1e-30])
    assert "largest |q - q_ref| over every coordinate and output time (m for positions" in text
    named = [line for line in text.splitlines() if line.startswith("reference for ")]
    methods = [m for line in named for m in line[len("reference for "):].split(":")[0].split(", ")]
    assert sorted(methods) == sorted(wp.methods)
    for line in named:
        key = line.split(": ", 1)[1].split(" at rtol ")
        assert key[0] in ("ggl", "projection-bdf")  # the two families' reference methods
    ok = [r for r in wp.rows if r["status"] == "ok" and r["error"] <= 1e-4]
    best = min(ok, key=lambda r: r["cpu_time"])
    assert wp.cheapest_run(1e-4) is best
    assert (f"error <= 1e-04: cheapest {best['method']} at rtol {best['rtol']:.0e} "
            f"({best['cpu_time']:.2g} s CPU, error {best['error']:.1e})") in text
    assert "error <= 1e-30: no run reached it" in text
    decades = [line for line in wp.summary().splitlines() if line.startswith("error <= ")]
    reached = [r["error"] for r in wp.rows if r["status"] == "ok"]
    assert len(decades) == int(np.floor(np.log10(max(reached))) - np.ceil(np.log10(min(reached)))) + 1


def test_table_lists_every_run(wp):
    """table() is a header, a rule and one line per row, each naming its
    method and rtol."""
    lines = wp.table().splitlines()
    assert len(lines) == 2 + len(wp.rows)
    assert "method" in lines[0] and "error" in lines[0]
    assert "Newton" in lines[0] and "KKT" in lines[0]  # the two kinds of factorization apart
    for line, row in zip(lines[2:], wp.rows):
        assert line.startswith(row["method"])
        assert f"{row['rtol']:.0e}" in line
        if row["status"] == "ok":  # as the run's stats count them
            assert f" {row['lu_factorizations']:>6d} {row['augmented_factorizations']:>6d} " in line


def test_plot_writes_png(wp, tmp_path):
    """plot(path) writes a PNG (error against CPU time and drift along the
    middle-tolerance runs: one drift curve per method, at rtol 1e-6)."""
    pytest.importorskip("matplotlib")
    path = tmp_path / "wp.png"
    wp.plot(str(path), title="seed pendulum")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert path.stat().st_size > 10_000
    assert wp.middle_tolerance == 1e-6
    assert set(wp.drifts) == set(METHODS)


def test_save_round_trips_through_json(wp, tmp_path):
    """save(path) writes JSON that json.load reads back with the same rows
    (equal values: floats survive JSON's repr exactly), the promised columns,
    t_end and the reference's description."""
    path = tmp_path / "wp.json"
    wp.save(str(path))
    with open(path) as f:
        data = json.load(f)
    assert data["columns"] == PROMISED
    assert data["rows"] == wp.rows
    assert data["t_end"] == T_END
    assert data["reference"] == wp.reference_info


def test_unknown_method_raises_model_error():
    """An unknown method name raises mb.ModelError naming it and listing the
    known ones, before anything runs."""
    with pytest.raises(mb.ModelError) as exc:
        mb.work_precision(pendulum(), 0.1, methods=["ggl", "runge-kutta"], tolerances=[1e-4])
    assert "runge-kutta" in str(exc.value)
    for m in mb.METHODS:
        assert m in str(exc.value)


def test_command_line_accuracy(tmp_path):
    """`lagmb accuracy examples/seed_pendulum.toml --tolerances 1e-4 1e-6
    -o x.json --plot x.png` (all six methods, the scene's 2 s; about 2 s of
    wall time) exits 0 and writes both files: the JSON has 12 rows with the
    promised columns, all "ok"; the PNG starts with the PNG signature."""
    pytest.importorskip("matplotlib")
    out, png = tmp_path / "x.json", tmp_path / "x.png"
    proc = lagmb_command("accuracy", EXAMPLES / "seed_pendulum.toml", "--tolerances", "1e-4", "1e-6", "-o", out,
                         "--plot", png, timeout=120)
    assert proc.returncode == 0, proc.stderr
    with open(out) as f:
        data = json.load(f)
    assert len(data["rows"]) == len(mb.METHODS) * 2
    assert [r["method"] for r in data["rows"][::2]] == list(mb.METHODS)
    for row in data["rows"]:
        assert set(row) == set(PROMISED)
        assert row["status"] == "ok"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "reference for ggl, index3, index1" in proc.stdout
    assert re.search(r"error <= 1e-0\d: cheapest [a-z0-9-]+ at rtol 1e-0[46] \(", proc.stdout)
