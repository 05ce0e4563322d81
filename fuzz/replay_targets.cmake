# SPDX-License-Identifier: MIT
# Corpus replay: each fuzz/*_fuzzer.cpp also builds as <name>_replay with replay_main.cpp
# (any compiler, no libFuzzer), registered as a ctest test over fuzz/corpus/<name>/ and the
# shared bad corpus. Included from tests/CMakeLists.txt so it runs in every test build.
file(GLOB silk_fuzz_srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/fuzz/*_fuzzer.cpp)
foreach(src ${silk_fuzz_srcs})
  get_filename_component(name ${src} NAME_WE)
  if(name MATCHES "^(model_config|onnx_external_data)_fuzzer$" AND NOT SILK_HAVE_ONNXRUNTIME)
    continue()  # the runtime layer (model.json, ONNX files) is only built with onnxruntime
  endif()
  add_executable(${name}_replay ${src} ${PROJECT_SOURCE_DIR}/fuzz/replay_main.cpp)
  target_link_libraries(${name}_replay PRIVATE silk_static)
  target_include_directories(${name}_replay PRIVATE ${PROJECT_SOURCE_DIR}/fuzz)
  if(name STREQUAL "batch_list_fuzzer")  # silkgen's list parser: pure string work, its one source file
    target_sources(${name}_replay PRIVATE ${PROJECT_SOURCE_DIR}/apps/silkgen/batch_list.cpp)
    target_include_directories(${name}_replay PRIVATE ${PROJECT_SOURCE_DIR}/apps/silkgen)
  endif()
  set(replay_dirs)
  if(EXISTS ${PROJECT_SOURCE_DIR}/fuzz/corpus/${name})
    list(APPEND replay_dirs ${PROJECT_SOURCE_DIR}/fuzz/corpus/${name})
  endif()
  if(EXISTS ${SILK_SHARED_DIR_ABS}/corpus/bad)
    list(APPEND replay_dirs ${SILK_SHARED_DIR_ABS}/corpus/bad)
  endif()
  add_test(NAME ${name}_replay COMMAND ${name}_replay ${replay_dirs})
  set_tests_properties(${name}_replay PROPERTIES TIMEOUT 120)
endforeach()
