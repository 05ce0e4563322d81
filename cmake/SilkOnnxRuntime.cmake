# SPDX-License-Identifier: MIT
# Finds onnxruntime for engine/runtime and silkgen: an installed CMake package first
# (find_package(onnxruntime CONFIG)), else a plain include/ + lib/ tree at ONNXRUNTIME_ROOT
# (default: <source>/.deps/onnxruntime, filled by scripts/fetch_onnxruntime.sh).
# Result: SILK_HAVE_ONNXRUNTIME, target onnxruntime::onnxruntime, SILK_ORT_LIBRARY_FILES
# (the library file and its soname links, for installing next to libsilk).
set(ONNXRUNTIME_ROOT "${PROJECT_SOURCE_DIR}/.deps/onnxruntime" CACHE PATH
    "onnxruntime tree with include/ and lib/ (used when no onnxruntime CMake package is found)")
set(ONNXRUNTIME_DLL_DIR "${PROJECT_SOURCE_DIR}/.deps/onnxruntime-windows" CACHE PATH
    "Windows build: folder holding onnxruntime.dll (scripts/fetch_onnxruntime_windows.sh)")
set(SILK_HAVE_ONNXRUNTIME OFF)
set(SILK_ORT_LIBRARY_FILES)

if(WIN32)
  # Windows (MinGW cross-build, scripts/build_windows.sh): headers only, never linked. libsilk
  # loads onnxruntime.dll itself from its own folder (runtime/model/ort_dll_load.cpp), so a missing DLL
  # is a Silk error naming the file, and tokenizer-only use needs no onnxruntime.dll.
  find_path(SILK_ORT_INCLUDE_DIR onnxruntime_cxx_api.h
            PATHS "${ONNXRUNTIME_ROOT}/include" NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH)
  find_file(SILK_ORT_DLL onnxruntime.dll PATHS "${ONNXRUNTIME_DLL_DIR}" NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH)
  if(SILK_ORT_INCLUDE_DIR AND SILK_ORT_DLL)
    set(SILK_HAVE_ONNXRUNTIME ON)
    set(SILK_ORT_LIBRARY_FILES "${SILK_ORT_DLL}")
    add_library(onnxruntime::onnxruntime INTERFACE IMPORTED)
    set_target_properties(onnxruntime::onnxruntime PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${SILK_ORT_INCLUDE_DIR}"
      INTERFACE_COMPILE_DEFINITIONS "ORT_API_MANUAL_INIT;SILK_ORT_RUNTIME_LOAD"
      INTERFACE_COMPILE_OPTIONS "SHELL:-include ${PROJECT_SOURCE_DIR}/cmake/windows/onnxruntime_mingw_compat.h")
    message(STATUS "onnxruntime: ${SILK_ORT_DLL} (loaded at run time)")
  endif()
elseif(SILK_WHEEL)
  # The pip wheel (cmake/SilkWheel.cmake): headers only, never linked. libsilk loads the onnxruntime
  # package's library at run time (runtime/model/ort_so_load.cpp): one silk_mesh preloaded by full
  # path, else site-packages/onnxruntime/capi/libonnxruntime.so.<version> relative to itself
  # (silk_mesh/lib/). <version>: the one fetch_onnxruntime.sh fetched (its VERSION file).
  find_path(SILK_ORT_INCLUDE_DIR onnxruntime_cxx_api.h
            PATHS "${ONNXRUNTIME_ROOT}/include" "${ONNXRUNTIME_ROOT}/include/onnxruntime" NO_DEFAULT_PATH)
  if(EXISTS "${ONNXRUNTIME_ROOT}/VERSION")
    file(STRINGS "${ONNXRUNTIME_ROOT}/VERSION" SILK_ORT_VERSION LIMIT_COUNT 1)
  endif()
  if(SILK_ORT_INCLUDE_DIR AND SILK_ORT_VERSION)
    set(SILK_HAVE_ONNXRUNTIME ON)
    add_library(onnxruntime::onnxruntime INTERFACE IMPORTED)
    set_target_properties(onnxruntime::onnxruntime PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${SILK_ORT_INCLUDE_DIR}"
      INTERFACE_COMPILE_DEFINITIONS "ORT_API_MANUAL_INIT;SILK_ORT_RUNTIME_LOAD;SILK_ORT_SONAME=\"libonnxruntime.so.1\";SILK_ORT_RELATIVE_PATH=\"../../onnxruntime/capi/libonnxruntime.so.${SILK_ORT_VERSION}\""
      INTERFACE_LINK_LIBRARIES "${CMAKE_DL_LIBS}")
    message(STATUS "onnxruntime: headers ${SILK_ORT_INCLUDE_DIR}; the wheel loads the onnxruntime ${SILK_ORT_VERSION} package's library at run time")
  else()  # a wheel without generation would pass for a complete one
    message(FATAL_ERROR "SILK_WHEEL: no onnxruntime headers and VERSION in ${ONNXRUNTIME_ROOT} (run scripts/fetch_onnxruntime.sh)")
  endif()
else()  # linked like any shared library
find_package(onnxruntime CONFIG QUIET)
if(onnxruntime_FOUND AND TARGET onnxruntime::onnxruntime)
  set(SILK_HAVE_ONNXRUNTIME ON)
  get_target_property(_ort_loc onnxruntime::onnxruntime LOCATION)
  if(_ort_loc)
    file(GLOB SILK_ORT_LIBRARY_FILES "${_ort_loc}*")
  endif()
  message(STATUS "onnxruntime: CMake package (${onnxruntime_DIR})")
else()
  find_path(SILK_ORT_INCLUDE_DIR onnxruntime_cxx_api.h
            PATHS "${ONNXRUNTIME_ROOT}/include" "${ONNXRUNTIME_ROOT}/include/onnxruntime" NO_DEFAULT_PATH)
  find_library(SILK_ORT_LIBRARY NAMES onnxruntime PATHS "${ONNXRUNTIME_ROOT}/lib" NO_DEFAULT_PATH)
  if(SILK_ORT_INCLUDE_DIR AND SILK_ORT_LIBRARY)
    set(SILK_HAVE_ONNXRUNTIME ON)
    add_library(onnxruntime::onnxruntime SHARED IMPORTED)
    set_target_properties(onnxruntime::onnxruntime PROPERTIES
      IMPORTED_LOCATION "${SILK_ORT_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${SILK_ORT_INCLUDE_DIR}")
    get_filename_component(_ort_dir "${SILK_ORT_LIBRARY}" DIRECTORY)
    file(GLOB SILK_ORT_LIBRARY_FILES "${_ort_dir}/libonnxruntime.so*")
    message(STATUS "onnxruntime: ${SILK_ORT_LIBRARY}")
  endif()
endif()
endif()

if(NOT SILK_HAVE_ONNXRUNTIME)
  message(STATUS "onnxruntime not found (run scripts/fetch_onnxruntime.sh or set ONNXRUNTIME_ROOT): "
                 "engine/runtime, silkgen, silk_generator_run and the generation tests/benchmarks are not built")
endif()
