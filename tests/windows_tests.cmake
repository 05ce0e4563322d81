# SPDX-License-Identifier: MIT
# Windows cross-build (scripts/build_windows.sh): the GoogleTest executables of the layers whose
# tests need no POSIX API, run under Wine by scripts/test_windows.sh (not by ctest: the build
# machine cannot run them). Test files that use POSIX-only calls are listed with the reason.
set(SILK_WINDOWS_TEST_LAYERS io mesh tokenizer decoder capi)
if(SILK_HAVE_ONNXRUNTIME)
  list(APPEND SILK_WINDOWS_TEST_LAYERS kernels runtime)
endif()
set(SILK_WINDOWS_POSIX_ONLY_TESTS
  io/mesh_reader_test.cpp   # setrlimit (sys/resource.h)
  io/writers_test.cpp       # POSIX permissions (sys/stat.h chmod) for unwritable folders
  capi/tokens_api_test.cpp  # passes std::filesystem::path::c_str() (wchar_t on Windows) as char*
)
file(GLOB SILK_TEST_SUPPORT CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/support/*.cpp)
foreach(layer ${SILK_WINDOWS_TEST_LAYERS})
  file(GLOB_RECURSE srcs CONFIGURE_DEPENDS RELATIVE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/${layer}/*.cpp)
  list(REMOVE_ITEM srcs ${SILK_WINDOWS_POSIX_ONLY_TESTS})
  if(srcs)
    add_executable(test_${layer} ${srcs} ${SILK_TEST_SUPPORT})
    target_link_libraries(test_${layer} PRIVATE silk_static GTest::gtest GTest::gtest_main)
    target_include_directories(test_${layer} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
    # Paths as Wine sees them (Z: is the build machine's /).
    target_compile_definitions(test_${layer} PRIVATE
      SILK_SHARED_DIR="Z:${SILK_SHARED_DIR_ABS}" SILK_SOURCE_DIR="Z:${PROJECT_SOURCE_DIR}"
      _USE_MATH_DEFINES)  # M_PI under MinGW in strict C++17
  endif()
endforeach()
