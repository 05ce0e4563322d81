# SPDX-License-Identifier: MIT
# The shared material folder (spec/, corpus/, tools/) the tests read: CMake's copy of the one rule
# (scripts/shared_dir.sh states it; export/silk_export/paths.py is Python's). Its result is the
# default of the cache variable SILK_SHARED_DIR, which the C++ tests get compiled in
# (tests/support/test_paths.cpp) and the script tests are given.
#   1. $SILK_SHARED_DIR when set; 2. else ../shared beside this checkout, when it holds spec/;
#   3. else ../shared beside the checkout this one was cloned from (git's remote.origin.url, a
#   local folder), when it holds spec/; 4. else a warning naming the places looked in (the
#   tests then stop with one message naming the folder).
function(silk_shared_dir out)
  if(DEFINED ENV{SILK_SHARED_DIR} AND NOT "$ENV{SILK_SHARED_DIR}" STREQUAL "")
    if(NOT IS_DIRECTORY "$ENV{SILK_SHARED_DIR}")
      message(WARNING "no shared material: SILK_SHARED_DIR=$ENV{SILK_SHARED_DIR} is not a folder")
    endif()
    set(${out} "$ENV{SILK_SHARED_DIR}" PARENT_SCOPE)
    return()
  endif()
  set(candidates "${PROJECT_SOURCE_DIR}/../shared")
  find_package(Git QUIET)
  if(GIT_FOUND)
    execute_process(COMMAND ${GIT_EXECUTABLE} -C ${PROJECT_SOURCE_DIR} config --get remote.origin.url
                    OUTPUT_VARIABLE origin OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
    if(rc EQUAL 0 AND NOT origin STREQUAL "")
      list(APPEND candidates "${origin}/../shared")
    endif()
  endif()
  foreach(candidate ${candidates})
    if(IS_DIRECTORY "${candidate}/spec")
      get_filename_component(found "${candidate}" ABSOLUTE)
      set(${out} "${found}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  string(REPLACE ";" " nor " looked "${candidates}")
  message(WARNING "no shared material (spec/, corpus/): SILK_SHARED_DIR is not set and neither ${looked} "
                  "holds spec/; set SILK_SHARED_DIR to the folder that does")
  set(${out} "${PROJECT_SOURCE_DIR}/../shared" PARENT_SCOPE)
endfunction()
