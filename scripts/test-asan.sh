#!/bin/sh
# make test-asan: the test suite (the default selection, as `make test`)
# against a lagmb._core built with AddressSanitizer and
# UndefinedBehaviorSanitizer. Usage: scripts/test-asan.sh PYTHON [pytest args]
#
# It leaves the normal build and the installed package alone: the sanitized
# module is built in build/asan (configured by CMake directly, only the _core
# and FMU runtime targets and the static lagmb_core they link) and staged in build/asan/pkg/lagmb
# next to symlinks to what python/lagmb holds (modules, subpackages, the
# viewer's page template) but a compiled module and the FMU runtime;
# PYTHONPATH puts that directory ahead of site-packages. Any sanitizer report
# fails the run: UB aborts (-fno-sanitize-recover), as do out-of-range
# std::vector/std::array indexing (-D_GLIBCXX_ASSERTIONS; UBSan sees v[i] of a
# vector that never allocated only as a null reference, and neither it nor
# ASan sees an index past size() but within capacity()).
set -eu
PYTHON=${1:-python3}
if [ $# -gt 0 ]; then shift; fi
BUILD=build/asan
PKG=$BUILD/pkg
JOBS=${JOBS:-2}
ROOT=$(pwd)

# the interpreter itself, not a wrapper (pyenv shims are shell scripts)
PY=$("$PYTHON" -c 'import sys; print(sys.executable)')
# what the build and the suite need; not the installed lagmb (`make setup`)
"$PY" -c 'import pybind11, pytest, numpy' ||
  { echo "test-asan: $PYTHON lacks pybind11, pytest or numpy: run make setup first" >&2; exit 1; }
SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"

t0=$(date +%s)
# no LTO (pybind11_add_module adds -flto otherwise): faster links, exact frames
cmake -S . -B $BUILD -DLAGMB_PYTHON=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$SAN -D_GLIBCXX_ASSERTIONS" \
  -DCMAKE_SHARED_LINKER_FLAGS="$SAN" -DCMAKE_MODULE_LINKER_FLAGS="$SAN" \
  -DCMAKE_EXE_LINKER_FLAGS="$SAN" -DCMAKE_INTERPROCEDURAL_OPTIMIZATION=OFF \
  -DPython_EXECUTABLE="$PY" -Dpybind11_DIR="$("$PY" -m pybind11 --cmakedir)" >/dev/null
cmake --build $BUILD --target _core lagmb_fmu -j "$JOBS"
t1=$(date +%s)

so=$(ls $BUILD/_core*.so)
rm -rf $PKG && mkdir -p $PKG/lagmb
for f in python/lagmb/*; do
  case "${f##*/}" in __pycache__|fmu_runtime|*.so) ;; *) ln -s "$ROOT/$f" $PKG/lagmb/ ;; esac
done
ln -s "$ROOT/$so" $PKG/lagmb/
mkdir -p $PKG/lagmb/fmu_runtime  # what `lagmb fmu` puts in an FMU (tests/formats/test_fmu.py)
for f in $BUILD/liblagmb_fmu.so cpp/fmu/fmi3.c cpp/fmu/lagmb_fmu.h; do ln -s "$ROOT/$f" $PKG/lagmb/fmu_runtime/; done

# Python is not instrumented, so the ASan runtime has to be loaded first,
# before the module (the UBSan runtime too: the module needs both). Tests that
# start processes inherit all of this: python -m lagmb and the examples load
# the sanitized module; tests/project/test_cpp_library.py runs cmake and the compiler
# under the preloaded runtime (harmless) and builds its own, unsanitized copy
# of the C++ library, as under make test.
CXX=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' $BUILD/CMakeCache.txt)
LD_PRELOAD="$("$CXX" -print-file-name=libasan.so) $("$CXX" -print-file-name=libubsan.so)"
# detect_leaks=0: CPython never frees much of what it allocates (interned
# objects, module state), so LeakSanitizer would drown the report in leaks that
# are not ours. exitcode=86: a sanitized process that dies is not mistaken for
# the exit 1 of a failed run (tests/tools/test_cli.py checks that exit code).
# handle_abort=1: an abort (a failed _GLIBCXX_ASSERTIONS check) prints the C++
# stack too, after the Python traceback from faulthandler.
ASAN_OPTIONS=detect_leaks=0:handle_abort=1:exitcode=86
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:exitcode=86
PYTHONPATH=$ROOT/$PKG${PYTHONPATH:+:$PYTHONPATH}
export LD_PRELOAD ASAN_OPTIONS UBSAN_OPTIONS PYTHONPATH

"$PY" -c 'import lagmb, lagmb._core as c; print("test-asan: lagmb._core from", c.__file__)'
"$PY" -c 'import sys, lagmb._core as c; sys.exit("/build/asan/pkg/" not in c.__file__)' ||
  { echo "test-asan: lagmb._core is not the sanitized module" >&2; exit 1; }

# -v: the name of each test is printed before it runs, so a report that kills
# pytest follows the name of its test. --capture=sys: reports written to fd 2
# reach the terminal (with fd capture they would die with the process).
rc=0
"$PY" -m pytest -v --capture=sys "$@" || rc=$?
t2=$(date +%s)
echo "test-asan: build $((t1 - t0)) s, suite $((t2 - t1)) s, pytest exit $rc"
exit $rc
