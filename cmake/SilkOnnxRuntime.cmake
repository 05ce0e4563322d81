# Finds onnxruntime for engine/runtime and silkgen: an installed CMake package first
# (find_package(onnxruntime CONFIG)), else a plain include/ + lib/ tree at ONNXRUNTIME_ROOT
# (default: <source>/.deps/onnxruntime, filled by scripts/fetch_onnxruntime.sh).
# Result: SILK_HAVE_ONNXRUNTIME, target onnxruntime::onnxruntime, SILK_ORT_LIBRARY_FILES
# (the library file and its soname links, for installing next to libsilk).
set(ONNXRUNTIME_ROOT "${PROJECT_SOURCE_DIR}/.deps/onnxruntime" CACHE PATH
    "onnxruntime tree with include/ and lib/ (used when no onnxruntime CMake package is found)")
set(SILK_HAVE_ONNXRUNTIME OFF)
set(SILK_ORT_LIBRARY_FILES)

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

if(NOT SILK_HAVE_ONNXRUNTIME)
  message(STATUS "onnxruntime not found (run scripts/fetch_onnxruntime.sh or set ONNXRUNTIME_ROOT): "
                 "engine/runtime, silkgen, silk_generator_run and the generation tests/benchmarks are not built")
endif()
