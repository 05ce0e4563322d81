// The ai.silk CachedAttention operator for onnxruntime (docs/model_contract.md, "KV precision"):
// GroupQueryAttention's inputs, outputs and in-place cache, with a float16 or int8 (+ row scale)
// cache read at memory speed. libsilk adds it to every session it makes; RegisterCustomOps lets Python's onnxruntime
// run the same graphs (SessionOptions.register_custom_ops_library(<libsilk>)).
#pragma once
#include <onnxruntime_c_api.h>

namespace silk {

constexpr const char* kSilkOpDomain = "ai.silk";
constexpr const char* kCachedAttentionOp = "CachedAttention";

// Adds the ai.silk domain to `options`, for the onnxruntime whose API is `api`. Returns nullptr
// or an onnxruntime status naming the problem (the caller releases it).
OrtStatus* AddSilkOps(OrtSessionOptions* options, const OrtApi* api);

}  // namespace silk

#if defined(_WIN32)
#define SILK_ORT_OPS_EXPORT __declspec(dllexport)
#else
#define SILK_ORT_OPS_EXPORT __attribute__((visibility("default")))
#endif

// onnxruntime's custom-op library entry (the name it looks up in a library it is given).
extern "C" SILK_ORT_OPS_EXPORT OrtStatus* ORT_API_CALL RegisterCustomOps(OrtSessionOptions* options,
                                                                          const OrtApiBase* api_base);
