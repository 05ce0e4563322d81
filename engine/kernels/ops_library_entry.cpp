// SPDX-License-Identifier: MIT
// onnxruntime's custom-op library entry, built into libsilk_ops alone (never into libsilk, which
// exports only silk_*): SessionOptions.register_custom_ops_library("libsilk_ops.so") in Python's
// onnxruntime looks this name up and gets the ai.silk domain of kernels/silk_ops.h.
#include <onnxruntime_c_api.h>

#include "kernels/silk_ops.h"

#if defined(_WIN32)
#define SILK_ORT_OPS_EXPORT __declspec(dllexport)
#else
#define SILK_ORT_OPS_EXPORT __attribute__((visibility("default")))
#endif

extern "C" SILK_ORT_OPS_EXPORT OrtStatus* ORT_API_CALL RegisterCustomOps(OrtSessionOptions* options,
                                                                         const OrtApiBase* api_base) {
  const OrtApi* api = api_base ? api_base->GetApi(ORT_API_VERSION) : nullptr;
  if (!api) return nullptr;  // an onnxruntime older than the headers: nothing can be reported through it
  return silk::AddSilkOps(options, api);
}
