// SPDX-License-Identifier: MIT
// The ai.silk HalfMatMul operator for onnxruntime (docs/model_contract.md, "Logits head"): A
// float32 [..., K] times the transpose of B float16 [N, K], float32 out, computed by
// kernels/quant/half_matmul. Registered with the domain by kernels/silk_ops.
#pragma once
#include "kernels/ort/ort_op_glue.h"

namespace silk {

constexpr const char* kHalfMatMulOp = "HalfMatMul";

struct HalfMatMulOp : SilkCustomOp {};
void InitHalfMatMulOp(HalfMatMulOp* op, const OrtApi* api);

}  // namespace silk
