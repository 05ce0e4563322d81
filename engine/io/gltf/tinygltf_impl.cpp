// SPDX-License-Identifier: MIT
// The one translation unit that compiles tinygltf's implementation into libsilk, so the
// library (and the fuzzers, instrumented) use exactly this build. Images are never decoded:
// no stb_image, no external image files (gltf_reader installs a no-op image loader).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#pragma GCC diagnostic ignored "-Wunused-variable"
#endif
#include <tiny_gltf.h>
