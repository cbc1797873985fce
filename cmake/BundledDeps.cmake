# LAGMB_BUNDLED_DEPS: SUNDIALS and SuiteSparse's KLU built from pinned
# source archives inside the build tree, static and position-independent, to
# be linked into one shared liblagmb (their symbols hidden there): the wheel
# then needs nothing but the C and C++ runtimes (docs/install.md, "A
# self-contained wheel").
#
# The archives are Debian's source packages (the versions Debian 12 ships),
# checked against their SHA-256. They are looked for in LAGMB_DEPS_DIR first
# (default: build/deps-src in the source tree, or the environment variable of
# that name) and downloaded from deb.debian.org only if missing, so a build
# with the two files in place needs no network.
#
# Defines: LAGMB_SUNDIALS_LIBS (SUNDIALS' IDAS, CVODE, ARKODE, serial
# N_Vector: imported static targets) and LAGMB_SUITESPARSE_LIBS (one static
# library lagmb_klu: KLU with AMD, COLAMD, BTF and SuiteSparse_config, the
# real 32-bit-index routines), LAGMB_SUITESPARSE_INCLUDE_DIR, and
# LAGMB_BUNDLED_LICENSES (the licence files the package carries).

set(_lagmb_sundials_archive "sundials_6.4.1+dfsg1.orig.tar.xz")
set(_lagmb_sundials_sha256 "c61157f1d4be06c704bea40cb131eb63ba2dada161989071604d0a0959cdf04a")
set(_lagmb_sundials_url "https://deb.debian.org/debian/pool/main/s/sundials/${_lagmb_sundials_archive}")
set(_lagmb_suitesparse_archive "suitesparse_5.12.0+dfsg.orig.tar.xz")
set(_lagmb_suitesparse_sha256 "bb106c43049138c19675cd70322e72ff8e4fd8bdcab3a096307fd78488913faf")
set(_lagmb_suitesparse_url "https://deb.debian.org/debian/pool/main/s/suitesparse/${_lagmb_suitesparse_archive}")

set(_lagmb_deps_default "${CMAKE_CURRENT_SOURCE_DIR}/build/deps-src")
if(DEFINED ENV{LAGMB_DEPS_DIR})
  set(_lagmb_deps_default "$ENV{LAGMB_DEPS_DIR}")
endif()
set(LAGMB_DEPS_DIR "${_lagmb_deps_default}" CACHE PATH "Where the dependencies' source archives are (downloaded there if missing)")

# Fetches (if missing) and checks one archive; sets ${out} to its path.
function(_lagmb_archive name sha256 url out)
  set(path "${LAGMB_DEPS_DIR}/${name}")
  if(EXISTS "${path}")
    file(SHA256 "${path}" actual)
    if(NOT actual STREQUAL sha256)
      message(FATAL_ERROR "lagmb: ${path} has SHA-256 ${actual}, expected ${sha256}; remove it to download it again")
    endif()
  else()
    message(STATUS "lagmb: downloading ${url}")
    file(DOWNLOAD "${url}" "${path}" EXPECTED_HASH SHA256=${sha256} STATUS status TLS_VERIFY ON)
    list(GET status 0 code)
    if(NOT code EQUAL 0)
      file(REMOVE "${path}")
      list(GET status 1 why)
      message(FATAL_ERROR "lagmb: could not download ${url} (${why}). Without network, put ${name} "
                          "(SHA-256 ${sha256}) in ${LAGMB_DEPS_DIR} or point LAGMB_DEPS_DIR at it.")
    endif()
  endif()
  set(${out} "${path}" PARENT_SCOPE)
endfunction()

# Extracts an archive into dir once (a stamp marks a complete extraction).
function(_lagmb_extract archive dir)
  if(NOT EXISTS "${dir}/.extracted")
    file(REMOVE_RECURSE "${dir}")
    file(MAKE_DIRECTORY "${dir}")
    file(ARCHIVE_EXTRACT INPUT "${archive}" DESTINATION "${dir}")
    file(TOUCH "${dir}/.extracted")
  endif()
endfunction()

enable_language(C)
set(_lagmb_deps_build "${CMAKE_CURRENT_BINARY_DIR}/deps")

# --- SUNDIALS 6.4.1: configured, built and installed into the build tree now,
# at configure time, so that its CMake package is there for find_package
_lagmb_archive(${_lagmb_sundials_archive} ${_lagmb_sundials_sha256} ${_lagmb_sundials_url} _archive)
_lagmb_extract("${_archive}" "${_lagmb_deps_build}/src")
set(_sun_src "${_lagmb_deps_build}/src/sundials-6.4.1")
set(_sun_prefix "${_lagmb_deps_build}/sundials")
if(NOT EXISTS "${_sun_prefix}/.installed")
  message(STATUS "lagmb: building SUNDIALS 6.4.1 (IDAS, CVODE, ARKODE; static, PIC) into ${_sun_prefix}")
  include(ProcessorCount)
  ProcessorCount(_cores)
  if(_cores EQUAL 0)
    set(_cores 2)
  endif()
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${_sun_src} -B ${_lagmb_deps_build}/sundials-build -G ${CMAKE_GENERATOR}
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=${_sun_prefix} -DCMAKE_INSTALL_LIBDIR=lib
      -DCMAKE_C_COMPILER=${CMAKE_C_COMPILER} -DCMAKE_POSITION_INDEPENDENT_CODE=ON
      -DBUILD_STATIC_LIBS=ON -DBUILD_SHARED_LIBS=OFF
      -DBUILD_ARKODE=ON -DBUILD_CVODE=ON -DBUILD_IDAS=ON
      -DBUILD_CVODES=OFF -DBUILD_IDA=OFF -DBUILD_KINSOL=OFF
      -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_ENABLE_CXX=OFF -DEXAMPLES_INSTALL=OFF
      -DBUILD_FORTRAN_MODULE_INTERFACE=OFF -DENABLE_MPI=OFF -DENABLE_OPENMP=OFF -DENABLE_PTHREAD=OFF
      -DENABLE_KLU=OFF -DENABLE_LAPACK=OFF -DSUNDIALS_BUILD_WITH_MONITORING=OFF
    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  if(_rc EQUAL 0)
    execute_process(COMMAND ${CMAKE_COMMAND} --build ${_lagmb_deps_build}/sundials-build --parallel ${_cores}
                    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  endif()
  if(_rc EQUAL 0)
    execute_process(COMMAND ${CMAKE_COMMAND} --install ${_lagmb_deps_build}/sundials-build
                    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  endif()
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "lagmb: building SUNDIALS failed:\n${_out}")
  endif()
  file(TOUCH "${_sun_prefix}/.installed")
endif()
find_package(SUNDIALS 6.4.1 EXACT REQUIRED CONFIG PATHS ${_sun_prefix} NO_DEFAULT_PATH)
set(LAGMB_SUNDIALS_LIBS SUNDIALS::idas_static SUNDIALS::cvode_static SUNDIALS::arkode_static
    SUNDIALS::nvecserial_static)

# --- SuiteSparse 5.12.0: KLU and the orderings it calls, compiled here (the
# default build of each file is the real, 32-bit-index routines lagmb calls)
_lagmb_archive(${_lagmb_suitesparse_archive} ${_lagmb_suitesparse_sha256} ${_lagmb_suitesparse_url} _archive)
set(_ss "${_lagmb_deps_build}/src/SuiteSparse-5.12.0")
if(NOT EXISTS "${_ss}/.extracted")
  file(MAKE_DIRECTORY "${_ss}")
  # only the five packages' folders and the licence of the whole (the archive holds 40 MB)
  file(ARCHIVE_EXTRACT INPUT "${_archive}" DESTINATION "${_lagmb_deps_build}/src"
       PATTERNS SuiteSparse-5.12.0/SuiteSparse_config SuiteSparse-5.12.0/AMD SuiteSparse-5.12.0/COLAMD
                SuiteSparse-5.12.0/BTF SuiteSparse-5.12.0/KLU SuiteSparse-5.12.0/LICENSE.txt)
  file(TOUCH "${_ss}/.extracted")
endif()
file(GLOB _klu_sources ${_ss}/AMD/Source/amd_*.c ${_ss}/BTF/Source/btf_*.c ${_ss}/KLU/Source/klu*.c)
list(FILTER _klu_sources EXCLUDE REGEX "(amd_dump|klu_dump)\\.c$")
list(APPEND _klu_sources ${_ss}/COLAMD/Source/colamd.c ${_ss}/SuiteSparse_config/SuiteSparse_config.c)
add_library(lagmb_klu STATIC ${_klu_sources})
target_include_directories(lagmb_klu PUBLIC ${_ss}/SuiteSparse_config ${_ss}/AMD/Include ${_ss}/COLAMD/Include
                           ${_ss}/BTF/Include ${_ss}/KLU/Include)
target_compile_definitions(lagmb_klu PRIVATE NDEBUG)
set_target_properties(lagmb_klu PROPERTIES POSITION_INDEPENDENT_CODE ON C_VISIBILITY_PRESET hidden)
set(LAGMB_SUITESPARSE_LIBS lagmb_klu)
set(LAGMB_SUITESPARSE_INCLUDE_DIR ${_ss}/KLU/Include)

set(LAGMB_BUNDLED_LICENSES
  "${_sun_src}/LICENSE|SUNDIALS-LICENSE" "${_sun_src}/NOTICE|SUNDIALS-NOTICE"
  "${_ss}/LICENSE.txt|SuiteSparse-LICENSE.txt" "${_ss}/KLU/Doc/License.txt|KLU-License.txt"
  "${_ss}/AMD/Doc/License.txt|AMD-License.txt" "${_ss}/COLAMD/Doc/License.txt|COLAMD-License.txt"
  "${_ss}/BTF/Doc/License.txt|BTF-License.txt" "${_ss}/KLU/Doc/lesser.txt|LGPL-2.1.txt")
