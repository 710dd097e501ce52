# Installs VIMLOP from BUILD_DIR into WORK_DIR/prefix, then configures, builds
# and runs Testing/Installation/OutsideProject against that installed tree.
# With PYTHON (and PYTHON_DESTINATION, the package's place under the prefix)
# the installed Python package is imported too and checked by PYTHON_TEST.
# Usage: cmake -DBUILD_DIR=... -DWORK_DIR=... -DSOURCE_DIR=...
#              [-DPYTHON=... -DPYTHON_DESTINATION=... -DPYTHON_TEST=...] -P RunOutsideProject.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" -G Ninja -DCMAKE_BUILD_TYPE=Release
  "-DCMAKE_PREFIX_PATH=${prefix}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/register-synthetic")
# Built with -mavx2 against the default library; it can run only on a CPU with AVX2.
if(EXISTS "${WORK_DIR}/build/register-synthetic-avx2")
  file(READ /proc/cpuinfo cpuinfo)
  if(cpuinfo MATCHES "[ \t]avx2[ \t\n]")
    run("${WORK_DIR}/build/register-synthetic-avx2")
  else()
    message("register-synthetic-avx2 built but not run: this CPU has no AVX2")
  endif()
else()
  message("register-synthetic-avx2 not built: the compiler has no -mavx2")
endif()
if(PYTHON)
  # The installed package, not the build tree's: only the prefix is on the path.
  set(package "${prefix}/${PYTHON_DESTINATION}")
  run(${CMAKE_COMMAND} -E env "PYTHONPATH=${package}" "${PYTHON}" -c
    "import sys, vimlop; print('vimlop from', vimlop.__file__); sys.exit(0 if vimlop.__file__.startswith(sys.argv[1]) else 1)"
    "${package}")
  run(${CMAKE_COMMAND} -E env "PYTHONPATH=${package}" "${PYTHON}" "${PYTHON_TEST}")
endif()
