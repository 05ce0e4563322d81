// SPDX-License-Identifier: MIT
// The ai.silk operator domain (docs/model_contract.md): CachedAttention (float16 and int8 KV
// caches), CrossAttention (over the point cloud's K/V), Int4MatMul (4-bit weights) and HalfMatMul
// (float16 weights). The one registry of the kernels layer: libsilk adds the domain to every
// session it makes, and libsilk_ops (ops_library_entry.cpp) hands it to Python's onnxruntime.
#pragma once
#include <onnxruntime_c_api.h>

namespace silk {

constexpr const char* kSilkOpDomain = "ai.silk";

// Adds the ai.silk domain to `options`, for the onnxruntime whose API is `api`. Returns nullptr
// or an onnxruntime status naming the problem (the caller releases it).
OrtStatus* AddSilkOps(OrtSessionOptions* options, const OrtApi* api);

}  // namespace silk
