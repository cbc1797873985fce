"""Result.save: a run written as `lagmb run -o` writes it, by the suffix.

- .npz: t, q, v, a, lam, energy, residual, the coordinate names, and
  reaction_NAME / effort_NAME for every joint and driver unless listed;
- .csv: a header, then t, the coordinates and the listed reactions, efforts
  and energy per output time, floats as repr (read back bit for bit);
- the same bytes as the command line's file for the same run;
- a kinematic analysis has no multipliers: none written by default;
- another suffix is refused as the command line refuses it.
"""

import csv
import os
import subprocess
import sys
import zipfile

import numpy as np
import pytest

import lagmb as mb
from builders import pendulum

from paths import EXAMPLES  # noqa: E402


def slider_crank_run():
    return mb.load_scene(os.path.join(EXAMPLES, "slider_crank.toml")).run(t_end=0.1, n_out=11)


def test_npz_holds_the_run_and_every_joint_and_driver_by_default(tmp_path):
    r = slider_crank_run()
    path = tmp_path / "deep" / "run.npz"  # missing folders are made
    r.save(path)
    with np.load(path) as d:
        assert sorted(d.files) == sorted(["t", "q", "v", "a", "lam", "energy", "residual", "coordinates",
                                          "reaction_O", "reaction_B", "reaction_C", "reaction_guide",
                                          "effort_motor"])
        assert list(d["coordinates"]) == r.model.coordinate_names
        for name in ("t", "q", "v", "a", "lam", "energy", "residual"):
            assert np.array_equal(d[name], getattr(r, name))
        assert np.array_equal(d["reaction_C"], r.reaction("C")) and np.array_equal(d["effort_motor"],
                                                                                    r.effort("motor"))
    r.save(tmp_path / "some.npz", reactions=["B"], efforts=[], frame="joint")
    with np.load(tmp_path / "some.npz") as d:
        assert {f for f in d.files if f.startswith(("reaction_", "effort_"))} == {"reaction_B"}
        assert np.array_equal(d["reaction_B"], r.reaction("B", frame="joint"))


def test_csv_holds_the_coordinates_and_what_is_listed_exactly(tmp_path):
    r = slider_crank_run()
    r.save(tmp_path / "plain.csv")
    rows = list(csv.reader(open(tmp_path / "plain.csv", newline="")))
    assert rows[0] == ["t"] + r.model.coordinate_names and len(rows) == 1 + len(r.t)
    r.save(tmp_path / "x.csv", reactions=["C"], efforts=["motor"], frame="joint", energy=True)
    rows = list(csv.reader(open(tmp_path / "x.csv", newline="")))
    assert rows[0][-5:] == ["C.f1", "C.f2", "C.torque", "motor.effort", "energy"]
    data = np.array(rows[1:], dtype=float)
    assert np.array_equal(data[:, 0], r.t) and np.array_equal(data[:, 1:1 + r.q.shape[1]], r.q)
    assert np.array_equal(data[:, -5:-2], r.reaction("C", frame="joint"))
    assert np.array_equal(data[:, -2], r.effort("motor")) and np.array_equal(data[:, -1], r.energy)


def test_the_files_are_the_command_line_s_byte_for_byte(tmp_path):
    scene = os.path.join(EXAMPLES, "four_bar.toml")  # [output] reactions = ["A", "D"], energy = true
    for suffix in (".csv", ".npz"):
        cli = tmp_path / f"cli{suffix}"
        p = subprocess.run([sys.executable, "-m", "lagmb", "run", scene, "-o", str(cli), "--t-end", "0.05",
                            "--n-out", "6", "-q"], capture_output=True, text=True, timeout=300)
        assert p.returncode == 0, p.stderr
        r = mb.load_scene(scene).run(t_end=0.05, n_out=6)
        mine = tmp_path / f"api{suffix}"
        r.save(mine, reactions=["A", "D"], energy=True)
        if suffix == ".csv":
            assert mine.read_bytes() == cli.read_bytes()
        else:  # a zip: its members' bytes (the zip's own dates differ)
            with zipfile.ZipFile(cli) as a, zipfile.ZipFile(mine) as b:
                assert [(i.filename, a.read(i)) for i in a.infolist()] == [(i.filename, b.read(i))
                                                                           for i in b.infolist()]


def test_a_kinematic_analysis_writes_no_multipliers(tmp_path):
    model = mb.Model(gravity=(0.0, -9.81))
    rod = model.add_body("rod", mass=0.0, inertia=0.0, position=(0.5, 0.0))
    pin = model.add_revolute("pin", model.ground, rod, at=(0.0, 0.0))
    model.drive_joint("motor", pin, mb.Linear(rate=1.0))
    r = mb.simulate(model, t_end=0.2, n_out=3, analysis="kinematic")
    r.save(tmp_path / "k.npz")
    with np.load(tmp_path / "k.npz") as d:
        assert "lam" not in d.files and not [f for f in d.files if f.startswith(("reaction_", "effort_"))]
    with pytest.raises(mb.KinematicOnlyError):
        r.save(tmp_path / "k.csv", reactions=["pin"])


@pytest.mark.parametrize("name", ["run.txt", "run", "run.npz.gz"])
def test_another_suffix_is_refused(tmp_path, name):
    r = mb.simulate(pendulum(), t_end=0.1, n_out=3)
    with pytest.raises(mb.ModelError, match=r"the results file must end in \.npz or \.csv"):
        r.save(tmp_path / name)
    assert not os.listdir(tmp_path)
