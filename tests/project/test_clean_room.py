"""The self-contained wheel in a bare Debian (docs/install.md, "A
self-contained wheel"): `make wheel` builds it (SUNDIALS and KLU inside
liblagmb.so; auditwheel grafts nothing), then scripts/clean-room.sh installs
it offline into a debootstrap root with Python and pip only and checks the
seed pendulum under every method, a redundant joint, an equilibrium, `lagmb
demo`, that every shared object the process maps is the wheel's, the
interpreter's or the C/C++ runtime's, and the test suite with 0 failed; then,
with a compiler installed there and Eigen from pip (cmeel-eigen),
examples/cpp built against the wheel's CMake package, a scikit-build-core
project that finds it unaided, and an FMU validated by FMPy. Slow (about 5 minutes with the
root cached, 8 without), and needs root and the network:
`pytest -m slow tests/project/test_clean_room.py` or `make clean-room`."""

import os
import shutil
import subprocess
import sys
import zipfile

import pytest

from paths import ROOT  # noqa: E402

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the clean room is a Debian root (Linux)"),
    pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0,
                       reason="debootstrap, chroot and mount need root"),
    pytest.mark.skipif(not shutil.which("apt-get"), reason="debootstrap comes from apt (Debian or Ubuntu)"),
]


def test_the_wheel_runs_in_a_bare_debian_and_grafts_nothing():
    built = subprocess.run(["scripts/wheel.sh", sys.executable], cwd=ROOT, capture_output=True, text=True)
    assert built.returncode == 0, built.stdout[-3000:] + built.stderr[-3000:]
    dist = os.path.join(ROOT, "build", "wheel", "dist")
    (wheel,) = [f for f in os.listdir(dist) if f.endswith(".whl")]
    assert "manylinux_" in wheel
    assert os.path.getsize(os.path.join(dist, wheel)) <= 10e6
    names = zipfile.ZipFile(os.path.join(dist, wheel)).namelist()
    assert not any(n.startswith("lagmb.libs/") for n in names)  # nothing grafted
    assert {"lagmb/lib/liblagmb.so", "lagmb/lib/cmake/lagmb/lagmbConfig.cmake", "lagmb/include/lagmb/lagmb.hpp",
            "lagmb/licenses/THIRD-PARTY.txt", "lagmb/licenses/KLU-License.txt"} <= set(names)

    room = subprocess.run(["scripts/clean-room.sh", dist], cwd=ROOT, capture_output=True, text=True)
    out = room.stdout + room.stderr
    assert room.returncode == 0 and "clean-room: passed" in out, out[-5000:]
    assert "from elsewhere: none" in out
    assert "a scikit-build-core project found lagmb" in out and "FMPy validation clean" in out
    suite = [line for line in out.splitlines() if " passed" in line and " in " in line][0]
    assert " failed" not in suite and " error" not in suite
