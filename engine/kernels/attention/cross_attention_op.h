// SPDX-License-Identifier: MIT
// The ai.silk CrossAttention operator for onnxruntime (docs/model_contract.md): a decoder
// layer's attention over the point cloud's cross K/V in one node, in place of MatMul (transposed
// key), Mul, Softmax and MatMul. One op name, two kernels: float32 or float16 key/value rows
// (onnxruntime picks by the node's input type). Registered with the domain by kernels/silk_ops.
#pragma once
#include "kernels/attention/cached_attention.h"
#include "kernels/ort/ort_op_glue.h"

namespace silk {

constexpr const char* kCrossAttentionOp = "CrossAttention";

struct CrossAttentionOp : SilkCustomOp {
  CacheElement element = CacheElement::kFloat32;  // of key and value: kFloat32 or kFloat16
};
void InitCrossAttentionOp(CrossAttentionOp* op, const OrtApi* api, CacheElement element);

}  // namespace silk
