// SPDX-License-Identifier: MIT
// The ai.silk Int4MatMul operator for onnxruntime (docs/model_contract.md, "INT4 weights"):
// com.microsoft MatMulNBits' inputs and attributes for bits 4 without zero points, computed by
// kernels/quant/int4_matmul at memory speed. Registered with the domain by kernels/silk_ops.
#pragma once
#include "kernels/ort/ort_op_glue.h"

namespace silk {

constexpr const char* kInt4MatMulOp = "Int4MatMul";

struct Int4MatMulOp : SilkCustomOp {};
void InitInt4MatMulOp(Int4MatMulOp* op, const OrtApi* api);

}  // namespace silk
