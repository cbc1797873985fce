#!/bin/sh
# Installs what lagmb needs and is missing: Eigen 3.4, SUNDIALS and SuiteSparse (apt, on
# Debian/Ubuntu), then the Python build tools, and the package with its
# test, plot, fmu, robots, mjcf, docs, sweep and view extras. Usage: scripts/setup.sh PYTHON
set -eu
PYTHON=${1:-python3}

need=""
if command -v dpkg >/dev/null 2>&1; then
  for pkg in libsundials-dev libeigen3-dev libsuitesparse-dev; do
    dpkg -s "$pkg" >/dev/null 2>&1 || need="$need $pkg"
  done
  if [ "$PYTHON" = .venv/bin/python ] && [ ! -x .venv/bin/python ]; then
    python3 -c 'import ensurepip' >/dev/null 2>&1 || need="$need python3-venv"
  fi
  command -v c++ >/dev/null 2>&1 || need="$need g++"
  command -v cmake >/dev/null 2>&1 || python3 -c 'import cmake' >/dev/null 2>&1 || need="$need cmake"
fi
if [ -n "$need" ]; then
  echo "setup: installing$need with apt"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need >/dev/null
elif ! command -v dpkg >/dev/null 2>&1; then
  echo "setup: not a Debian system; install SUNDIALS >= 6, Eigen 3.4 and SuiteSparse yourself (see README.md)"
fi
# the viewer's tests open its pages in a headless Chromium; without one they are skipped with the reason
if command -v dpkg >/dev/null 2>&1 && ! command -v chromium-headless-shell >/dev/null 2>&1 \
    && ! command -v chromium >/dev/null 2>&1; then
  echo "setup: installing chromium-headless-shell with apt (for tests/tools/test_viewer.py)"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO=sudo
  { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
      --no-install-recommends chromium-headless-shell >/dev/null; } \
    || echo "setup: chromium-headless-shell could not be installed; the browser tests will be skipped"
fi

if [ "$PYTHON" = .venv/bin/python ] && [ ! -x .venv/bin/python ]; then
  echo "setup: python3 is externally managed; creating .venv"
  python3 -m venv .venv
fi

"$PYTHON" -m pip install -q --disable-pip-version-check "scikit-build-core>=0.10" "pybind11>=2.12" numpy
# The compiler's progress ([12/40] Building CXX object ...) shows as it goes;
# pip's whole output is kept in build/setup-pip.log and its end shown if it fails.
mkdir -p build
log=build/setup-pip.log
echo "setup: building lagmb (pip install .[test,plot,fmu,robots,mjcf,docs,sweep,view]; log in $log)"
( "$PYTHON" -m pip install -v --disable-pip-version-check --no-build-isolation ".[test,plot,fmu,robots,mjcf,docs,sweep,view]" 2>&1
  echo $? > "$log.status" ) | tee "$log" | grep --line-buffered -E '^ *\[[0-9]+/[0-9]+\] |^\*\*\* |^Successfully installed' || true
status=$(cat "$log.status")
rm -f "$log.status"
if [ "$status" != 0 ]; then
  tail -n 60 "$log"
  echo "setup: pip install failed (exit $status); the whole output is in $log"
  exit "$status"
fi
