"""Without the optional extras the suite skips, it does not fail: the whole
default suite runs in a child interpreter where importing any module of an
extra (matplotlib and Pillow, trimesh, xarray, pandas, Dask, zarr, MuJoCo,
Pinocchio, example-robot-data, FMPy, Sphinx, tqdm) raises ImportError, as in
an environment that has only lagmb and its test requirements (numpy, SciPy,
pytest, hypothesis). Slow (the suite again, about 90 s): `pytest -m slow
tests/test_extras_absent.py`."""

import os
import subprocess
import sys
import textwrap

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXTRAS = ("matplotlib", "PIL", "trimesh", "xarray", "pandas", "dask", "distributed", "zarr", "mujoco",
          "pinocchio", "example_robot_data", "cmeel", "fmpy", "sphinx", "myst_parser", "sphinx_gallery",
          "furo", "tqdm", "exudyn")

BLOCKER = textwrap.dedent(f"""\
    # the optional extras are absent here: importing one of them fails
    import sys

    class _Absent:
        names = {EXTRAS!r}

        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in self.names:
                raise ModuleNotFoundError(f"No module named {{name!r}} (an optional extra, blocked)", name=name)
            return None

    sys.meta_path.insert(0, _Absent())

    # importlib.util.find_spec answers None for them, as for a module not installed
    import importlib.util

    _find_spec = importlib.util.find_spec

    def _find_spec_absent(name, package=None):
        if name.split(".")[0] in _Absent.names:
            return None
        return _find_spec(name, package)

    importlib.util.find_spec = _find_spec_absent
    """)


@pytest.mark.slow
def test_the_suite_skips_without_the_optional_extras(tmp_path):
    (tmp_path / "sitecustomize.py").write_text(BLOCKER)
    package = os.path.dirname(os.path.dirname(__import__("lagmb").__file__))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tmp_path), package]))
    check = subprocess.run([sys.executable, "-c", "import matplotlib"], env=env, capture_output=True, text=True)
    assert check.returncode != 0 and "optional extra, blocked" in check.stderr  # (the blocker is in place)
    p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-x",
                        "--deselect", "tests/test_extras_absent.py", "tests"],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
    tail = "\n".join(p.stdout.splitlines()[-30:])
    assert p.returncode == 0, tail
    assert " skipped" in tail and " failed" not in tail, tail
