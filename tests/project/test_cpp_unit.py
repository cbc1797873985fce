"""The core's C++ unit tests (cpp/tests, one program per file, registered
with ctest; CMakeLists.txt, LAGMB_TESTS) run with the suite, so that `make
test` runs them: built in the CMake tree pip built this lagmb in
(test_cpp_library.setup_build_tree: its library is up to date, so only the
tests compile), or, without one, in build/ctest, configured here once
without Python as docs/install.md says to run them alone.
"""

import os
import pathlib
import re
import shutil

import pytest

from project.test_cpp_library import JOBS, ROOT, _run, setup_build_tree


@pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("ctest") is None, reason="needs cmake and ctest")
def test_the_cpp_unit_tests_pass():
    tree = setup_build_tree()
    if tree is None:
        tree = os.path.join(ROOT, "build", "ctest")
        if not os.path.exists(os.path.join(tree, "CMakeCache.txt")):
            _run(["cmake", "-S", ROOT, "-B", tree, "-DLAGMB_PYTHON=OFF"])
    _run(["cmake", "--build", tree, "--target", "lagmb_unit_tests", "-j", JOBS])
    out = _run(["ctest", "--output-on-failure"], cwd=tree)  # (fails with each failed check's line)

    # every program of cpp/tests ran and passed
    programs = sorted(p.stem for p in (pathlib.Path(ROOT) / "cpp" / "tests").glob("test_*.cpp"))
    passed = sorted(re.findall(r"Test +#\d+: (\S+) \.+ +Passed", out))
    assert programs and passed == programs, out
