# SPDX-License-Identifier: MIT
# Windows cross-build: tinygltf as a header (libsilk compiles its implementation itself).
include(${CMAKE_CURRENT_LIST_DIR}/host_headers.cmake)
silk_host_header_target(TinyGLTF::TinyGLTF tiny_gltf.h nlohmann)
# As engine/io/gltf/tinygltf_impl.cpp builds it: no image codecs. (On Linux Debian's
# libtinygltf.so supplies the default image callbacks the header refers to otherwise.)
set_property(TARGET TinyGLTF::TinyGLTF PROPERTY INTERFACE_COMPILE_DEFINITIONS
             TINYGLTF_NO_STB_IMAGE= TINYGLTF_NO_STB_IMAGE_WRITE= TINYGLTF_NO_EXTERNAL_IMAGE=)
