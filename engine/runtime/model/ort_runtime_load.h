// SPDX-License-Identifier: MIT
// What loading onnxruntime at run time (ort_dll_load.h) shares on Windows and Linux: once, and the API check.
#pragma once
#ifdef SILK_ORT_RUNTIME_LOAD
#include <onnxruntime_c_api.h>

#include <string>

#include "core/status.h"

namespace silk {

// Loads the library the platform's way (ort_dll_load.cpp: LoadLibraryExW; ort_so_load.cpp:
// dlopen) and ends with InitOrtApi; a library it opened and could not use is closed again. Only
// LoadOnnxRuntimeLibrary calls it (until it succeeds).
Status LoadOnnxRuntimeForPlatform();

// Reads base's version (a release 1.M older than ORT_API_VERSION is Unsupported without being
// asked: it would print its own complaint to stderr), asks base for ORT_API_VERSION and
// initialises the C++ API with it; a null base or a refusal is Unsupported, naming library_name
// and its version.
Status InitOrtApi(const OrtApiBase* base, const std::string& library_name);

}  // namespace silk
#endif  // SILK_ORT_RUNTIME_LOAD
