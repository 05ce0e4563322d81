// The ai.silk operator domain (docs/model_contract.md): CachedAttention (float16 and int8 KV
// caches), CrossAttention (over the point cloud's K/V) and Int4MatMul (4-bit weights). libsilk adds it to every session it makes;
// RegisterCustomOps lets Python's onnxruntime run the same graphs
// (SessionOptions.register_custom_ops_library(<libsilk>)).
#pragma once
#include <onnxruntime_c_api.h>

namespace silk {

constexpr const char* kSilkOpDomain = "ai.silk";

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
