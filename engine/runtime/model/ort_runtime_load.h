// SPDX-License-Identifier: MIT
// What loading onnxruntime at run time (ort_dll_load.h) shares on Windows and Linux: once, and the API check.
#pragma once
#ifdef SILK_ORT_RUNTIME_LOAD
#include <onnxruntime_c_api.h>

#include <string>

#include "core/status.h"

namespace silk {

// Loads the library the platform's way (ort_dll_load.cpp: LoadLibraryExW; ort_so_load.cpp:
// dlopen) and ends with InitOrtApi. Only LoadOnnxRuntimeLibrary calls it, once.
Status LoadOnnxRuntimeForPlatform();

// Asks base for ORT_API_VERSION and initialises the C++ API with it; an older library (or a null
// base) is Unsupported, naming library_name and its version.
Status InitOrtApi(const OrtApiBase* base, const std::string& library_name);

}  // namespace silk
#endif  // SILK_ORT_RUNTIME_LOAD
