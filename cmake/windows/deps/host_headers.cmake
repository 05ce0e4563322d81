# SPDX-License-Identifier: MIT
# Header-only libraries for the Windows cross-build, taken from the build machine's Debian -dev
# packages. Only the named headers are exposed (a staging folder of links), never /usr/include
# itself, which would shadow MinGW's C library headers with glibc's.
set(SILK_HOST_INCLUDE "${CMAKE_BINARY_DIR}/host-include")
function(silk_host_header_target target)  # silk_host_header_target(<target> <header or folder>...)
  if(TARGET ${target})
    return()
  endif()
  foreach(item ${ARGN})
    if(NOT EXISTS /usr/include/${item})
      message(FATAL_ERROR "/usr/include/${item} not found (install the Debian -dev package: scripts/setup_windows.sh)")
    endif()
    get_filename_component(parent "${SILK_HOST_INCLUDE}/${item}" DIRECTORY)
    file(MAKE_DIRECTORY "${parent}")
    file(CREATE_LINK /usr/include/${item} "${SILK_HOST_INCLUDE}/${item}" SYMBOLIC)
  endforeach()
  add_library(${target} INTERFACE IMPORTED GLOBAL)
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${SILK_HOST_INCLUDE}")
endfunction()
