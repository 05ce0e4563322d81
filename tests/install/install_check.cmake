# SPDX-License-Identifier: MIT
# ctest install_consumer: installs the build into a scratch prefix, then checks that
#  * a tiny consumer project configures with find_package(silk), builds and runs;
#  * libonnxruntime sits next to libsilk and the installed binaries find it through their
#    $ORIGIN RPATH (LD_LIBRARY_PATH cleared);
#  * the installed silkgen generates with the tiny model;
#  * silkgen's and silktok's sources build against the installed headers and libsilk alone
#    (apps_consumer); that silkgen gives the golden ids, that silktok encodes a golden mesh to
#    the official ids and decodes, checks and round-trips it.
# Usage: cmake -DBUILD_DIR=.. -DSOURCE_DIR=.. -DSHARED_DIR=.. -DWORK_DIR=.. -DGENERATOR=.. -DHAVE_ORT=ON|OFF
#        -P install_check.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
set(ENV{LD_LIBRARY_PATH} "")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(LAST_OUTPUT "${out}${err}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(f include/silk/silk.h include/silk/silk.hpp bin/silktok lib/cmake/silk/silkConfig.cmake)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB libsilk "${prefix}/lib*/libsilk.so*")
if(NOT libsilk)
  message(FATAL_ERROR "libsilk.so not installed")
endif()
if(HAVE_ORT)
  file(GLOB ort "${prefix}/lib*/libonnxruntime.so*")
  list(LENGTH ort n_ort)
  if(n_ort LESS 2)
    message(FATAL_ERROR "libonnxruntime.so (+ soname link) not installed next to libsilk: ${ort}")
  endif()
  if(NOT EXISTS "${prefix}/bin/silkgen")
    message(FATAL_ERROR "silkgen not installed")
  endif()
  run("${prefix}/bin/silkgen" "${SOURCE_DIR}/samples/torus_knot.obj" -o "${WORK_DIR}/gen.glb"
      --model "${SOURCE_DIR}/tests/models/tiny" --max-tokens 100 --threads 1 -q)
  if(NOT EXISTS "${WORK_DIR}/gen.glb")
    message(FATAL_ERROR "installed silkgen wrote no output")
  endif()
endif()
run("${prefix}/bin/silktok" --version)

run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/install/consumer" -B "${WORK_DIR}/consumer" -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/consumer")
run("${WORK_DIR}/consumer/consumer" "${SOURCE_DIR}/tests/models/tiny")
message(STATUS "consumer: ${LAST_OUTPUT}")

# Both tools from their sources against the installed package alone (silkgen only when it can
# generate), then a smoke run of each.
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/install/apps_consumer" -B "${WORK_DIR}/apps" -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}" "-DSILK_APPS_DIR=${SOURCE_DIR}/apps")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/apps")
# silktok: encode a golden mesh (ids equal the official ones), decode, check and round-trip it.
if(NOT EXISTS "${SHARED_DIR}/spec/golden/cube.obj")
  message(FATAL_ERROR "no golden mesh at ${SHARED_DIR}/spec/golden/cube.obj (set SILK_SHARED_DIR)")
endif()
run("${WORK_DIR}/apps/silktok" encode "${SHARED_DIR}/spec/golden/cube.obj" -o "${WORK_DIR}/cube.tokens.txt")
file(READ "${WORK_DIR}/cube.tokens.txt" got)
file(READ "${SHARED_DIR}/spec/golden/cube.tokens.txt" want)
if(NOT got STREQUAL want)
  message(FATAL_ERROR "silktok built against the installed headers encodes cube.obj to other ids than the golden")
endif()
run("${WORK_DIR}/apps/silktok" check "${WORK_DIR}/cube.tokens.txt")
run("${WORK_DIR}/apps/silktok" decode "${WORK_DIR}/cube.tokens.txt" -o "${WORK_DIR}/cube.obj")
run("${WORK_DIR}/apps/silktok" roundtrip "${SHARED_DIR}/spec/golden/cube.obj")
message(STATUS "apps consumer: silktok built from the installed headers; cube ids equal the golden; ${LAST_OUTPUT}")
if(HAVE_ORT)
  set(args "${SOURCE_DIR}/samples/torus_knot.obj" --model "${SOURCE_DIR}/tests/models/tiny" --max-tokens 300
      --seed 7 --threads 1 -q --surface-tolerance 0 --candidates 1 --orient tokens --face-guidance off)  # the golden pins a plain run
  run("${WORK_DIR}/apps/silkgen" ${args} -o "${WORK_DIR}/apps.obj" --tokens "${WORK_DIR}/apps.tokens.txt")
  file(READ "${WORK_DIR}/apps.tokens.txt" got)
  file(READ "${SOURCE_DIR}/tests/models/golden/torus_knot_s7.tokens.txt" want)
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "silkgen built against the installed headers gives other ids than the golden")
  endif()
  message(STATUS "apps consumer: silkgen built from the installed headers; ids equal the golden")
endif()
