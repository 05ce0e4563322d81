# SPDX-License-Identifier: MIT
# CMake toolchain: Windows x64 cross-build with Debian's MinGW-w64 (posix thread model, for
# std::thread/std::mutex), used by scripts/build_windows.sh. Header-only third-party libraries
# come from the build machine's Debian -dev packages through cmake/windows/deps/*Config.cmake.
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(SILK_MINGW_TRIPLE x86_64-w64-mingw32)
set(CMAKE_C_COMPILER ${SILK_MINGW_TRIPLE}-gcc-posix)
set(CMAKE_CXX_COMPILER ${SILK_MINGW_TRIPLE}-g++-posix)
set(CMAKE_RC_COMPILER ${SILK_MINGW_TRIPLE}-windres)
set(CMAKE_FIND_ROOT_PATH /usr/${SILK_MINGW_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_FIND_PACKAGE_PREFER_CONFIG ON)

# 64-bit off_t/stat sizes in the POSIX-style calls MinGW provides.
set(CMAKE_C_FLAGS_INIT "-D_FILE_OFFSET_BITS=64")
set(CMAKE_CXX_FLAGS_INIT "-D_FILE_OFFSET_BITS=64")
# libstdc++, libgcc and winpthread linked in statically: the zip then needs no MinGW runtime
# DLLs, and cannot pick up another program's (different, possibly win32-thread-model)
# libstdc++-6.dll / libwinpthread-1.dll from PATH.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "-static")

foreach(pkg TinyGLTF nlohmann_json CLI11 GTest)
  set(${pkg}_DIR "${CMAKE_CURRENT_LIST_DIR}/deps" CACHE PATH "")
endforeach()
# zlib: Debian's libz-mingw-w64-dev, the static archive (no zlib1.dll to ship).
set(ZLIB_INCLUDE_DIR /usr/${SILK_MINGW_TRIPLE}/include CACHE PATH "")
set(ZLIB_LIBRARY /usr/${SILK_MINGW_TRIPLE}/lib/libz.a CACHE FILEPATH "")
