// SPDX-License-Identifier: MIT
// C API: model folders by name (silk_models_dir, silk_model_default_dir, silk_model_find,
// silk_models_list), forwarding to io/files/model_folders.h and runtime/model/model_catalog.h.
#include <string>

#include "capi/capi_internal.h"
#include "io/files/model_folders.h"
#if defined(SILK_HAVE_RUNTIME)
#include "runtime/model/model_catalog.h"
#endif

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

namespace {

// A path into the caller's buffer by the size-query rule (bytes, the terminating NUL counted).
silk_status CopyPath(const char* function, const silk::StatusOr<std::string>& path, char* out, size_t capacity,
                     size_t* out_count) {
  if (!path.ok()) {
    if (out_count) *out_count = 0;
    return SetError(path.status().WithContext(std::string(function) + ": "));
  }
  const size_t needed = path->size() + 1;
  if (silk_status c; !silk::capi::BeginCopy(function, out, capacity, needed, out_count, &c)) return c;
  std::memcpy(out, path->c_str(), needed);
  return Ok();
}

}  // namespace

extern "C" {

silk_status silk_models_dir(const char* name, char* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    return CopyPath("silk_models_dir", name ? silk::UserModelDir(name) : silk::UserModelsDir(), out, capacity,
                    out_count);
  });
}

silk_status silk_model_default_dir(char* out, size_t capacity, size_t* out_count) {
  return Guard([&] { return CopyPath("silk_model_default_dir", silk::BundledModelDir(), out, capacity, out_count); });
}

silk_status silk_model_find(const char* name_or_dir, char* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    return CopyPath("silk_model_find", silk::ResolveModelDir(name_or_dir ? name_or_dir : ""), out, capacity, out_count);
  });
}

silk_status silk_models_list(silk_report** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_models_list: out is NULL");
    *out = nullptr;
#if defined(SILK_HAVE_RUNTIME)
    auto r = std::make_unique<silk_report>();
    r->json = silk::ModelCatalogJson();
    *out = r.release();
    return Ok();
#else
    return SetError(SILK_ERR_UNSUPPORTED,
                    "silk_models_list: this libsilk was built without onnxruntime (no generation)");
#endif
  });
}

}  // extern "C"
