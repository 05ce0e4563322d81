// Windows only: libsilk loads onnxruntime.dll itself, by full path from its own folder, so a
// missing or unusable DLL is an ordinary Silk error naming the file and the reason (not a loader
// failure before main), tokenizer-only use needs no onnxruntime.dll, and Windows' own, older
// System32\onnxruntime.dll is never picked up by the search order.
#pragma once
#ifdef _WIN32
#include "core/status.h"

namespace silk {

// Loads <folder of this module>\onnxruntime.dll once and initialises onnxruntime's C++ API
// (built with ORT_API_MANUAL_INIT); later calls return the first call's result.
Status LoadOnnxRuntimeLibrary();

}  // namespace silk
#endif  // _WIN32
