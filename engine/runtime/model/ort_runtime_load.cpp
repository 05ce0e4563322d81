// SPDX-License-Identifier: MIT
// The shared half of ort_dll_load.h: ort_dll_load.cpp and ort_so_load.cpp keep only their own loading.
#ifdef SILK_ORT_RUNTIME_LOAD
#include "runtime/model/ort_runtime_load.h"

#include <onnxruntime_cxx_api.h>

#include <mutex>
#include <string>

#include "runtime/model/ort_dll_load.h"

namespace silk {

Status InitOrtApi(const OrtApiBase* base, const std::string& library_name) {
  const OrtApi* api = base ? base->GetApi(ORT_API_VERSION) : nullptr;
  if (!api)
    return Unsupported(library_name + ": onnxruntime " + (base ? base->GetVersionString() : "?") +
                       " does not offer C API version " + std::to_string(ORT_API_VERSION));
  Ort::InitApi(api);
  return Status::Ok();
}

Status LoadOnnxRuntimeLibrary() {
  static std::once_flag once;
  static Status result = Status::Ok();
  std::call_once(once, [] { result = LoadOnnxRuntimeForPlatform(); });
  return result;
}

}  // namespace silk
#endif  // SILK_ORT_RUNTIME_LOAD
