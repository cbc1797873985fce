#!/bin/sh
# make clean-room: the wheel in a bare Debian, as a user with Python and pip only.
#
# 1. A Debian 12 root made with debootstrap (minbase, plus python3 and
#    python3-venv; no compiler, no SUNDIALS, SuiteSparse or BLAS), kept in
#    build/clean-room/base and copied afresh for every run.
# 2. In it, without network (a network namespace of its own), the wheel and
#    its test requirements installed from a folder (pip --no-index), then
#    scripts/clean_room_checks.py (the seed pendulum under every method, a
#    redundant joint, an equilibrium, what the process maps), `lagmb demo`
#    and the test suite, which must end with 0 failed.
# 3. Then a compiler and CMake installed with apt and Eigen's headers with
#    pip (cmeel-eigen; the C++ user's machine): examples/cpp built against
#    the wheel's CMake package (`lagmb --cmake-prefix`) and run, and by a
#    scikit-build-core project told nothing; an FMU made by `lagmb fmu`,
#    checked by FMPy's validation, simulated, and tests/formats/test_fmu.py.
#
# Needs root (debootstrap, chroot, mount) and the network for steps 1 and 3
# and the first download of the wheelhouse. Usage: scripts/clean-room.sh DIST
# (the folder holding the wheel; make clean-room builds it first).
set -eu
DIST=${1:-build/wheel/dist}
cd "$(dirname "$0")/.."
ROOM=build/clean-room
BASE=$ROOM/base
RUN=$ROOM/run
WHEELS=$ROOM/wheelhouse
wheel=$(ls "$DIST"/lagmb-*.whl)
[ "$(id -u)" = 0 ] || { echo "clean-room: needs root (debootstrap, chroot, mount)"; exit 2; }

if [ ! -e "$BASE/.complete" ]; then
  command -v debootstrap >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null
  rm -rf "$BASE"
  echo "clean-room: debootstrap bookworm into $BASE"
  debootstrap --variant=minbase --include=python3,python3-venv bookworm "$BASE" http://deb.debian.org/debian \
    >"$ROOM.debootstrap.log" 2>&1 || { tail -20 "$ROOM.debootstrap.log"; exit 1; }
  touch "$BASE/.complete"
fi
pyver=$(chroot "$BASE" python3 -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')
# the room's Python must be the wheel's
case "$wheel" in *cp$(echo "$pyver" | tr -d .)-*) ;; *)
  echo "clean-room: $wheel is not for the room's Python $pyver"; exit 2;; esac

# the wheels pip installs in the room (downloaded once, for the room's Python)
mkdir -p "$WHEELS"
requirements='numpy scipy pytest hypothesis fmpy>=0.3.32 cmeel-eigen scikit-build-core'
stamp="$WHEELS/.complete-$pyver-$(echo "$requirements" | md5sum | cut -c1-8)"
if [ ! -e "$stamp" ]; then
  python3 -m pip download -q --disable-pip-version-check --only-binary=:all: --python-version "$pyver" \
    --platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 --platform manylinux2014_x86_64 \
    --platform any -d "$WHEELS" $requirements 2>"$ROOM.download.log" || { cat "$ROOM.download.log"; exit 1; }
  touch "$stamp"
fi

cleanup() {
  for m in "$RUN/proc" "$RUN/dev"; do mountpoint -q "$m" && umount -R -l "$m"; done
  return 0
}
trap cleanup EXIT INT TERM
cleanup
rm -rf "$RUN"
cp -a "$BASE" "$RUN"
mkdir -p "$RUN/wheels" "$RUN/src"
cp "$wheel" "$WHEELS"/*.whl "$RUN/wheels/"
git ls-files -z -co --exclude-standard | xargs -0 cp --parents -t "$RUN/src"   # the repository, for its tests
mount -t proc proc "$RUN/proc"
mount --rbind /dev "$RUN/dev"

echo "clean-room: phase 1, Python and pip only, no network"
start=$(date +%s)
unshare --net env -i /usr/sbin/chroot "$RUN" /bin/sh -eu -c '
  cd /src
  export HOME=/root PATH=/venv/bin:/usr/bin:/bin LC_ALL=C.UTF-8 MPLBACKEND=Agg
  for tool in cc gcc g++ c++ cmake; do
    if command -v $tool >/dev/null; then echo "clean-room: $tool is installed"; exit 1; fi
  done
  python3 -m venv /venv
  pip install -q --no-index --find-links /wheels --disable-pip-version-check "$(ls /wheels/lagmb-*.whl)[test]"
  python scripts/clean_room_checks.py
  lagmb demo | tail -n 4; echo "ok      lagmb demo"
  python -m pytest -q -p no:cacheprovider tests 2>&1 | tail -n 15 | tee /tmp/suite.txt
  tail -n 1 /tmp/suite.txt | grep -q " passed" && ! tail -n 1 /tmp/suite.txt | grep -Eq "[0-9]+ (failed|error)"
'
echo "clean-room: phase 1 passed in $(($(date +%s) - start)) s"

echo "clean-room: phase 2, a C++ user's machine (g++ and cmake from apt, Eigen from pip's cmeel-eigen)"
cp /etc/resolv.conf "$RUN/etc/resolv.conf"
env -i /usr/sbin/chroot "$RUN" /bin/sh -eu -c '
  export PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq --no-install-recommends g++ cmake make >/dev/null
'
unshare --net env -i /usr/sbin/chroot "$RUN" /bin/sh -eu -c '
  cd /src
  export HOME=/root PATH=/venv/bin:/usr/bin:/bin LC_ALL=C.UTF-8
  pip install -q --no-index --find-links /wheels --disable-pip-version-check cmeel-eigen
  test ! -e /usr/include/eigen3
  prefix=$(lagmb --cmake-prefix)
  cmake -S examples/cpp -B /tmp/example -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build /tmp/example -j 2 >/dev/null
  /tmp/example/pendulum | tail -n 3
  ldd /tmp/example/pendulum | grep liblagmb
  echo "ok      examples/cpp built against $prefix and run"
  # a project built by scikit-build-core finds the package without being told where
  pip install -q --no-index --find-links /wheels --disable-pip-version-check scikit-build-core
  mkdir -p /tmp/downstream && cp examples/cpp/pendulum.cpp /tmp/downstream/
  cat >/tmp/downstream/pyproject.toml <<\EOF
[build-system]
requires = ["scikit-build-core"]
build-backend = "scikit_build_core.build"

[project]
name = "downstream"
version = "0.1"
EOF
  cat >/tmp/downstream/CMakeLists.txt <<\EOF
cmake_minimum_required(VERSION 3.18)
project(downstream LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 17)
find_package(lagmb CONFIG REQUIRED)
add_executable(downstream_pendulum pendulum.cpp)
target_link_libraries(downstream_pendulum PRIVATE lagmb::core)
set_target_properties(downstream_pendulum PROPERTIES INSTALL_RPATH_USE_LINK_PATH ON)
install(TARGETS downstream_pendulum DESTINATION ${SKBUILD_SCRIPTS_DIR})
EOF
  pip install -q --no-index --no-build-isolation --disable-pip-version-check /tmp/downstream
  downstream_pendulum | tail -n 1
  echo "ok      a scikit-build-core project found lagmb (no CMAKE_PREFIX_PATH given) and its program runs"
  pip install -q --no-index --find-links /wheels --disable-pip-version-check fmpy
  lagmb fmu examples/cart_pole.toml -o /tmp/cart_pole.fmu --quiet
  python - <<EOF
import zipfile
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu
names = zipfile.ZipFile("/tmp/cart_pole.fmu").namelist()
binaries = sorted(n.rsplit("/", 1)[-1] for n in names if n.startswith("binaries/"))
assert "liblagmb.so" in binaries, binaries
problems = validate_fmu("/tmp/cart_pole.fmu")
assert problems == [], problems
t_end = simulate_fmu("/tmp/cart_pole.fmu", stop_time=1.0)["time"][-1]
print(f"ok      FMU: binaries {binaries}, FMPy validation clean, simulated to t = {t_end:g} s")
EOF
  python -m pytest -q -p no:cacheprovider tests/formats/test_fmu.py 2>&1 | tail -n 1
'
echo "clean-room: passed"
