// SPDX-License-Identifier: MIT
// The shared half of ort_dll_load.h: ort_dll_load.cpp and ort_so_load.cpp keep only their own loading.
#ifdef SILK_ORT_RUNTIME_LOAD
#include "runtime/model/ort_runtime_load.h"

#include <onnxruntime_cxx_api.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

#include "runtime/model/ort_dll_load.h"

namespace silk {

namespace {
// The minor version of an onnxruntime "1.M.P" version string (release 1.M serves C API versions
// 1..M), or -1 when it does not read so.
int OrtMinorVersion(const char* version) {
  if (!version || std::strncmp(version, "1.", 2) != 0) return -1;
  char* end = nullptr;
  const long minor = std::strtol(version + 2, &end, 10);
  return end != version + 2 && minor >= 0 && minor < 1000 ? static_cast<int>(minor) : -1;
}
}  // namespace

Status InitOrtApi(const OrtApiBase* base, const std::string& library_name) {
  // An older release answers GetApi(newer) with a line of its own on stderr: its version is read
  // first, and such a library is refused in our message alone, without asking it.
  const char* version = base ? base->GetVersionString() : nullptr;
  const int minor = OrtMinorVersion(version);
  if (minor >= 0 && minor < ORT_API_VERSION)
    return Unsupported(library_name + ": onnxruntime " + version + " is too old: Silk needs 1." +
                       std::to_string(ORT_API_VERSION) + " or newer (C API version " + std::to_string(ORT_API_VERSION) +
                       ")");
  const OrtApi* api = base ? base->GetApi(ORT_API_VERSION) : nullptr;
  if (!api)
    return Unsupported(library_name + ": onnxruntime " + (base ? base->GetVersionString() : "?") +
                       " does not offer C API version " + std::to_string(ORT_API_VERSION));
  Ort::InitApi(api);
  return Status::Ok();
}

Status LoadOnnxRuntimeLibrary() {
  // Success is kept for the process; a failure is not, so installing or fixing onnxruntime and
  // loading a model again works without a restart.
  static std::mutex mu;
  static bool loaded = false;
  std::lock_guard<std::mutex> lock(mu);
  if (loaded) return Status::Ok();
  Status s = LoadOnnxRuntimeForPlatform();
  loaded = s.ok();
  return s;
}

}  // namespace silk
#endif  // SILK_ORT_RUNTIME_LOAD
