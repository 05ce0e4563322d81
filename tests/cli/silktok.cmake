# SPDX-License-Identifier: MIT
# silktok end-to-end checks (tests/tools/cli_checks.py): bad inputs, goldens, round trips, decode.
if(Python3_FOUND AND TARGET silktok)
  foreach(mode bad golden roundtrip decode)
    add_test(NAME silktok_cli_${mode}
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/cli_checks.py ${mode}
                     $<TARGET_FILE:silktok> ${SILK_SHARED_DIR_ABS})
  endforeach()
  set_tests_properties(silktok_cli_golden silktok_cli_decode PROPERTIES LABELS slow)
  if(SILK_SANITIZE)  # the bad-input hang guard: ASan + UBSan run ~20x slower (2M-face file: 0.3 s -> 6 s)
    set_tests_properties(silktok_cli_bad PROPERTIES ENVIRONMENT "SILK_HANG_GUARD_S=120")
  endif()
endif()
