# SPDX-License-Identifier: MIT
# Issue 35's reproductions (tests/tools/hostile_files_checks.py): silkgen --batch and silktok under
# hostile input: inputs, lists and reports never written, refused list lines, FIFOs and devices,
# unwritable reports, output names, shards, signals. The property test over generated argument
# combinations is tests/tools/file_roles_property.py.
if(Python3_FOUND AND TARGET silkgen AND TARGET silktok AND NOT WIN32)
  foreach(mode batch files signals)
    add_test(NAME hostile_files_${mode}
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/hostile_files_checks.py ${mode}
                     $<TARGET_FILE:silkgen> $<TARGET_FILE:silktok> ${PROJECT_SOURCE_DIR})
    set_tests_properties(hostile_files_${mode} PROPERTIES TIMEOUT 300)
  endforeach()
  add_test(NAME file_roles_property
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/file_roles_property.py
                   $<TARGET_FILE:silkgen> $<TARGET_FILE:silktok> ${PROJECT_SOURCE_DIR})
  set_tests_properties(file_roles_property PROPERTIES TIMEOUT 300)
endif()
