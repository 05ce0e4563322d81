// SPDX-License-Identifier: MIT
// onnxruntime custom-op glue for HalfMatMul: inputs A [..., K] float32 and B [N, K] float16,
// output [..., N] float32; no attributes (K and N are B's dims). Shapes that do not fit give a
// status naming the node, never a crash.
#include "kernels/quant/half_matmul_op.h"

#include <string>
#include <vector>

#include "kernels/quant/half_matmul.h"

namespace silk {

namespace {

using Kernel = OpKernelBase;

OrtStatus* ReadShape(const Kernel& k, const OrtTensorView in[2], HalfMatMulShape* s) {
  if (in[1].dims.size() != 2) return k.Fail("B has shape " + DimsText(in[1].dims) + ", expected [N, K]");
  s->n = in[1].dims[0], s->k = in[1].dims[1];
  if (in[0].dims.empty() || in[0].dims.back() != s->k)
    return k.Fail("A has shape " + DimsText(in[0].dims) + ", expected [..., K] with K = " + std::to_string(s->k) +
                  " (B's second dim)");
  s->m = ElementCount(in[0].dims) / s->k;
  const char* why = nullptr;
  if (!HalfShapeSupported(*s, &why)) return k.Fail(std::string(why) + " (B has shape " + DimsText(in[1].dims) + ")");
  return nullptr;
}

OrtStatus* ORT_API_CALL Compute(void* kernel, OrtKernelContext* ctx) {
  const Kernel& k = *static_cast<const Kernel*>(kernel);
  OrtTensorView in[2];
  for (size_t i = 0; i < 2; ++i) SILK_ORT_TRY(ReadInput(k.api, ctx, i, &in[i]));
  HalfMatMulShape s;
  SILK_ORT_TRY(ReadShape(k, in, &s));
  std::vector<int64_t> out_dims = in[0].dims;
  out_dims.back() = s.n;
  float* y = nullptr;
  SILK_ORT_TRY(FloatOutput(k.api, ctx, 0, out_dims, &y));
  OrtPool pool{k.api, ctx};
  HalfMatMul(s, static_cast<const float*>(in[0].data), static_cast<const uint16_t*>(in[1].data), y, OrtPoolFor, &pool);
  return nullptr;
}

OrtStatus* ORT_API_CALL CreateKernel(const OrtCustomOp* op, const OrtApi* api, const OrtKernelInfo* info,
                                     void** kernel) {
  *kernel = NewKernel<Kernel>(op, api, info).release();
  return nullptr;
}

ONNXTensorElementDataType ORT_API_CALL InputType(const OrtCustomOp*, size_t i) {
  return i == 1 ? ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16 : ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
}

}  // namespace

void InitHalfMatMulOp(HalfMatMulOp* op, const OrtApi* api) {
  FillOpTable(op, api, kHalfMatMulOp, 2, 1);
  op->GetInputType = InputType;
  op->GetOutputType = [](const OrtCustomOp*, size_t) { return ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT; };
  SetKernel<Kernel>(op, CreateKernel, Compute);
}

}  // namespace silk
