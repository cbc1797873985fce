"""lagmb is a C++ library too: install it with CMake (no Python), build the
examples in examples/cpp against the installed package with
find_package(lagmb) in a clean build directory, run them, and check the pin
force at release of the seed pendulum and of the same rod on a spherical
joint in a spatial model: m g / 4 upward on the rod (closed form, see
test_pendulum.py), also for the spatial rod run with its mass as a run-time
parameter; and the cart-pole controller of examples/cpp/cart_pole.cpp
(lagmb::Simulator, an input force set every 10 ms) holding the pole upright.

The default test installs the archive that the set-up already compiled (the
CMake tree pip built this lagmb in, pyproject.toml's build/{wheel_tag}; its
install component "cpp") after bringing it up to date; the slow one
configures and builds the library on its own, as docs/cpp.md does.
"""

import glob
import os
import re
import shutil
import subprocess
import sysconfig

import pytest

from paths import ROOT  # noqa: E402
JOBS = str(os.cpu_count() or 2)
needs_cmake = pytest.mark.skipif(shutil.which("cmake") is None, reason="needs cmake")


def _run(cmd, cwd=None):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    assert p.returncode == 0, f"{' '.join(cmd)} failed:\n{p.stdout}\n{p.stderr}"
    return p.stdout


def setup_build_tree():
    """The CMake tree pip built this interpreter's lagmb._core in (scikit-build's
    SKBUILD in its cache; build/asan, the sanitizer build, is not one), the
    latest if several, or None."""
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    trees = []
    for cache in glob.glob(os.path.join(ROOT, "build", "*", "CMakeCache.txt")):
        tree, core = os.path.dirname(cache), os.path.join(os.path.dirname(cache), "_core" + suffix)
        with open(cache) as f:
            if os.path.exists(core) and "SKBUILD:" in f.read():
                trees.append((os.path.getmtime(core), tree))
    return max(trees)[1] if trees else None


def build_and_install(prefix, lib_build):
    """The library on its own: configure without Python, build, install."""
    _run(["cmake", "-S", ROOT, "-B", str(lib_build), "-DLAGMB_PYTHON=OFF", f"-DCMAKE_INSTALL_PREFIX={prefix}"])
    _run(["cmake", "--build", str(lib_build), "-j", JOBS])
    _run(["cmake", "--install", str(lib_build)])


@needs_cmake
def test_installed_cpp_library_runs_the_seed_pendulum(tmp_path):
    prefix = tmp_path / "prefix"
    tree = setup_build_tree()
    if tree is None:  # (no set-up tree for this interpreter: build it here)
        build_and_install(prefix, tmp_path / "lib")
    else:
        _run(["cmake", "--build", tree, "--target", "lagmb_core", "-j", JOBS])  # (up to date: nothing to do)
        _run(["cmake", "--install", tree, "--component", "cpp", "--prefix", str(prefix)])
    check_examples(prefix, tmp_path / "example")


@needs_cmake
@pytest.mark.slow
def test_library_built_on_its_own_runs_the_examples(tmp_path):
    build_and_install(tmp_path / "prefix", tmp_path / "lib")
    check_examples(tmp_path / "prefix", tmp_path / "example")


def check_examples(prefix, ex_build):
    assert (prefix / "include" / "lagmb" / "lagmb.hpp").exists()

    _run(["cmake", "-S", os.path.join(ROOT, "examples", "cpp"), "-B", str(ex_build),
          f"-DCMAKE_PREFIX_PATH={prefix}"])
    _run(["cmake", "--build", str(ex_build), "-j", JOBS])
    out = _run([str(ex_build / "pendulum")])

    first = out.splitlines()[0]
    fx, fy = map(float, re.search(r"\(([-+\d.e]+), ([-+\d.e]+)\) N", first).groups())
    mg = 1.0 * 9.81
    assert abs(fx) < 1e-9 * mg
    assert abs(fy - mg / 4) < 1e-9 * mg
    assert re.search(r"\d+ steps", out)

    # the same rod in space: force (x, y, z) on it at release, m g / 4 up
    out = _run([str(ex_build / "spatial_pendulum")])
    first = out.splitlines()[0]
    force = [float(x) for x in re.search(r"force on rod = \(([^)]*)\)", first).group(1).split(",")]
    assert abs(force[0]) < 1e-9 * mg and abs(force[1]) < 1e-9 * mg
    assert abs(force[2] - mg / 4) < 1e-9 * mg
    # the run with a parameter: a rod of 2 kg with the same moment of
    # inertia I about its centre: at release the pin carries m g I / (I + m r^2)
    heavy = [float(x) for x in re.search(r"rod.mass = 2 kg: force on rod at release = \(([^)]*)\)", out)
             .group(1).split(",")]
    m2, inertia, r = 2.0, 1.0 / 12.0, 0.5
    assert abs(heavy[2] - m2 * 9.81 * inertia / (inertia + m2 * r * r)) < 1e-6  # (printed to 6 decimals)
    last = out.splitlines()[-3]
    p = [float(x) for x in re.search(r"p = \(([^)]*)\)", last).group(1).split(",")]
    assert abs(sum(x * x for x in p) - 1.0) < 1e-5  # (printed to 6 digits)
    assert p[1] == 0.0 and p[3] == 0.0  # it turns about y only

    # the controller loop in C++: the pole, started 0.1 rad off, is righted
    out = _run([str(ex_build / "cart_pole")])
    numbers = re.search(r"t = ([\d.]+) s: largest tilt = ([\d.e-]+) rad, after 1 s = ([\d.e-]+) rad", out)
    t, largest, after = map(float, numbers.groups())
    assert t == 10.0 and largest <= 0.1 + 1e-9 and after < 0.05
    changes, restarts = map(int, re.search(r"(\d+) input changes, (\d+) restarts", out).groups())
    assert changes >= 990 and restarts == changes
