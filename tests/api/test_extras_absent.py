"""Without the optional extras the suite skips, it does not fail: the whole
default suite runs in a child interpreter where importing any module of an
extra (matplotlib and Pillow, trimesh, xarray, pandas, Dask, zarr, MuJoCo,
Pinocchio, example-robot-data, FMPy, Sphinx, tqdm) raises ImportError, as in
an environment that has only lagmb and its test requirements (numpy, SciPy,
pytest, hypothesis). Slow (the suite again, about 90 s): `pytest -m slow
tests/api/test_extras_absent.py`. And lagmb itself, asked for what an absent
extra gives (mb.sweep, lagmb.view, a plot), says which extra to install
(mb.MissingExtraError), not Python's bare ModuleNotFoundError."""

import os
import subprocess
import sys
import textwrap

import pytest

from paths import ROOT  # noqa: E402
import builders  # noqa: E402  (tests/builders.py)
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


def _absent(monkeypatch, *modules):
    """Importing each of `modules` fails from here on, as if not installed."""
    for module in modules:
        monkeypatch.setitem(sys.modules, module, None)


def _pendulum():
    return builders.pendulum()


def test_a_sweep_without_its_extra_says_to_install_it(monkeypatch, tmp_path):
    """Issue 56: mb.sweep without xarray raised a bare ModuleNotFoundError."""
    import lagmb as mb

    _absent(monkeypatch, "xarray")
    with pytest.raises(mb.MissingExtraError, match=r"^mb.sweep needs xarray, from lagmb's optional 'sweep' extra: "
                                                   r'pip install "lagmb\[sweep\]"$') as info:
        mb.sweep(_pendulum(), {"rod.mass": [1.0, 2.0]}, t_end=0.1, progress=False)
    error = info.value
    assert (error.name, error.extra) == ("xarray", "sweep")
    assert isinstance(error, ImportError) and isinstance(error, mb.ModelError)  # (either except catches it)
    _absent(monkeypatch, "zarr")
    (tmp_path / "study.zarr").mkdir()
    (tmp_path / "study.zarr" / "zarr.json").write_text("{}")
    with pytest.raises(mb.MissingExtraError, match=r"^sweep.open_store's store needs zarr, .*'sweep' extra"):
        mb.sweep.open_store(tmp_path / "study.zarr")


def test_a_view_and_a_plot_without_their_extras_say_to_install_them(monkeypatch, tmp_path):
    import lagmb as mb
    from lagmb import plotting, viewer

    r = mb.simulate(_pendulum(), 0.1, n_out=3)
    _absent(monkeypatch, "trimesh", "matplotlib")
    viewer.three_js.cache_clear()  # (three.js read from trimesh once per process)
    try:
        with pytest.raises(mb.MissingExtraError, match=r"^lagmb.view needs three.js, which it takes from the trimesh "
                                                       r"wheel, from lagmb's optional 'view' extra: "
                                                       r'pip install "lagmb\[view\]"$') as info:
            mb.view(r, tmp_path / "run.html")
        assert (info.value.name, info.value.extra) == ("trimesh", "view")
    finally:
        viewer.three_js.cache_clear()
    with pytest.raises(mb.MissingExtraError, match=r'^lagmb plotting needs matplotlib, .*pip install "lagmb\[plot\]"'):
        plotting.plot_result(r, tmp_path / "run.png")
    assert not (tmp_path / "run.html").exists() and not (tmp_path / "run.png").exists()


@pytest.mark.slow
def test_the_suite_skips_without_the_optional_extras(tmp_path):
    (tmp_path / "sitecustomize.py").write_text(BLOCKER)
    package = os.path.dirname(os.path.dirname(__import__("lagmb").__file__))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tmp_path), package]))
    check = subprocess.run([sys.executable, "-c", "import matplotlib"], env=env, capture_output=True, text=True)
    assert check.returncode != 0 and "optional extra, blocked" in check.stderr  # (the blocker is in place)
    p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-x",
                        "--deselect", "tests/api/test_extras_absent.py", "tests"],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
    tail = "\n".join(p.stdout.splitlines()[-30:])
    assert p.returncode == 0, tail
    assert " skipped" in tail and " failed" not in tail, tail
