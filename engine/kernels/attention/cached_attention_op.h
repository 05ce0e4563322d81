// SPDX-License-Identifier: MIT
// The ai.silk CachedAttention operator for onnxruntime (docs/model_contract.md, "KV precision"):
// GroupQueryAttention's inputs, outputs and in-place cache, with a float16 or int8 (+ row scale)
// cache read at memory speed. Registered with the rest of the domain by kernels/silk_ops.
#pragma once
#include "kernels/attention/cached_attention.h"
#include "kernels/ort/ort_op_glue.h"

namespace silk {

constexpr const char* kCachedAttentionOp = "CachedAttention";

// One table per cache element type, all named CachedAttention: onnxruntime picks the one whose
// input types match the node's (past_*/present_* float16 or int8).
struct CachedAttentionOp : SilkCustomOp {
  CacheElement element = CacheElement::kFloat16;
};
void InitCachedAttentionOp(CachedAttentionOp* op, const OrtApi* api, CacheElement element);

}  // namespace silk
