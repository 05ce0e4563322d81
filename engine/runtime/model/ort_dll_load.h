// SPDX-License-Identifier: MIT
// Builds with SILK_ORT_RUNTIME_LOAD (Windows, and the Linux pip wheel): libsilk is not linked
// against onnxruntime but loads it itself, by full path, when the first model is loaded. So a
// missing or unusable library is an ordinary Silk error naming the file and the reason (not a
// loader failure before main), tokenizer-only use needs no onnxruntime, and no search path
// (Windows' System32\onnxruntime.dll, PATH, LD_LIBRARY_PATH) is ever consulted.
//   Windows (ort_dll_load.cpp): <folder of libsilk.dll>\onnxruntime.dll.
//   Linux (ort_so_load.cpp): an onnxruntime already in the process (the Python package silk_mesh
//   loads the onnxruntime package's library by the full path importlib gives), else
//   <folder of libsilk.so>/SILK_ORT_RELATIVE_PATH (the wheel: the onnxruntime package beside it).
#pragma once
#ifdef SILK_ORT_RUNTIME_LOAD
#include "core/status.h"

namespace silk {

// Loads onnxruntime and initialises its C++ API (built with ORT_API_MANUAL_INIT). Once it has
// succeeded, later calls return Ok at once; after a failure the next call tries again (a library
// installed or replaced since is found). A release older than the headers' C API version is
// refused naming its version, before it is asked for that API (nothing printed by it).
Status LoadOnnxRuntimeLibrary();

}  // namespace silk
#endif  // SILK_ORT_RUNTIME_LOAD
