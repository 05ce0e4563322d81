# SPDX-License-Identifier: MIT
# silkgen end-to-end checks with the committed tiny model (tests/tools/silkgen_checks.py):
# goldens (ids; meshes separately, they follow the decoder's face recovery) + determinism, the
# Python onnxruntime reference loop (skipped without it), bad
# inputs, output formats. Then the C API from Python (examples/generate_ctypes.py).
if(Python3_FOUND AND TARGET silkgen)
  foreach(mode golden golden_mesh reference bad formats orient)
    add_test(NAME silkgen_${mode}
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/silkgen_checks.py ${mode}
                     $<TARGET_FILE:silkgen> ${PROJECT_SOURCE_DIR})
  endforeach()
  set_tests_properties(silkgen_reference PROPERTIES SKIP_RETURN_CODE 77)
  if(SILK_SANITIZE)  # python cannot load an ASan-instrumented libsilk: scripts/face_step_check.py is left out
    set_tests_properties(silkgen_reference PROPERTIES ENVIRONMENT "SILK_PYTHON_WITHOUT_LIBSILK=1")
  endif()
  # Scan-like clouds without normals (binary PLY, XYZ): estimated normals, --save-points, and an
  # output mesh_check.py accepts (tests/tools/silkgen_points_checks.py; needs numpy).
  add_test(NAME silkgen_points_estimated
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/silkgen_points_checks.py
                   $<TARGET_FILE:silkgen> ${PROJECT_SOURCE_DIR} ${SILK_SHARED_DIR_ABS})
  # model.json v3 on copies of the tiny model made at test time (tests/tools/silkgen_v3_checks.py).
  foreach(mode defaults errors raw)
    add_test(NAME silkgen_v3_${mode}
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/silkgen_v3_checks.py ${mode}
                     $<TARGET_FILE:silkgen> ${PROJECT_SOURCE_DIR})
  endforeach()
  if(NOT SILK_SANITIZE)  # python cannot load an ASan-instrumented libsilk
    # The official architecture end to end: fixture imported at test time, libsilk's greedy ids
    # without the grammar mask = the official loop's (tests/tools/official_fixture_check.py;
    # skipped without its deps).
    add_test(NAME official_fixture_greedy
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/official_fixture_check.py
                     $<TARGET_FILE:generate_unconstrained> ${PROJECT_SOURCE_DIR} ${SILK_SHARED_DIR_ABS})
    set_tests_properties(official_fixture_greedy PROPERTIES SKIP_RETURN_CODE 77 LABELS slow
                         ENVIRONMENT "SILK_LIBRARY=$<TARGET_FILE:silk>")
    if(CMAKE_SYSTEM_NAME STREQUAL "Linux")  # ELF symbol versions: the 1.0 ABI still served
      add_test(NAME capi_abi_1_0
               COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/capi_abi_check.py $<TARGET_FILE:silk>
                       ${PROJECT_SOURCE_DIR}/tests/models/tiny)
    endif()
    add_test(NAME capi_generate_ctypes
             COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/examples/generate_ctypes.py
                     --library $<TARGET_FILE:silk> --model ${PROJECT_SOURCE_DIR}/tests/models/tiny
                     --input ${PROJECT_SOURCE_DIR}/samples/torus_knot.obj --max-tokens 200 --check)
  endif()
endif()
