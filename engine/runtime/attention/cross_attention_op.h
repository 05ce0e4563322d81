// The ai.silk CrossAttention operator for onnxruntime (docs/model_contract.md): a decoder
// layer's attention over the point cloud's cross K/V in one node, in place of MatMul (transposed
// key), Mul, Softmax and MatMul. Registered with the domain by runtime/ops/silk_ops.
#pragma once
#include "runtime/ops/ort_op_glue.h"

namespace silk {

constexpr const char* kCrossAttentionOp = "CrossAttention";

struct CrossAttentionOp : SilkCustomOp {};
void InitCrossAttentionOp(CrossAttentionOp* op, const OrtApi* api);

}  // namespace silk
