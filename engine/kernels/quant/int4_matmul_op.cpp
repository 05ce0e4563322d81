// SPDX-License-Identifier: MIT
// onnxruntime custom-op glue for Int4MatMul: inputs A [..., K] float32, B [N, K / block_size,
// block_size / 2] uint8 and scales [N * K / block_size] float32 (MatMulNBits' own tensors, so
// the rewrite moves no weights); attributes K, N, block_size (and bits, which must be 4).
// Shapes that do not fit give a status naming the node, never a crash.
#include "kernels/quant/int4_matmul_op.h"

#include <memory>
#include <string>
#include <vector>

#include "kernels/quant/int4_matmul.h"

namespace silk {

namespace {

struct Kernel : OpKernelBase {
  Int4MatMulShape shape;  // m set per call
};

OrtStatus* CheckInputs(const Kernel& k, const OrtTensorView in[3], int64_t* rows) {
  const Int4MatMulShape& s = k.shape;
  if (in[0].dims.empty() || in[0].dims.back() != s.k)
    return k.Fail("A has shape " + DimsText(in[0].dims) + ", expected [..., K] with K = " + std::to_string(s.k));
  const std::vector<int64_t> b = {s.n, s.k / s.block, s.block / 2};
  if (in[1].dims != b)
    return k.Fail("B has shape " + DimsText(in[1].dims) +
                  ", expected [N, K / block_size, block_size / 2] = " + DimsText(b));
  if (ElementCount(in[2].dims) != s.n * (s.k / s.block))
    return k.Fail("scales have shape " + DimsText(in[2].dims) +
                  ", expected N * K / block_size = " + std::to_string(s.n * (s.k / s.block)) + " values");
  *rows = ElementCount(in[0].dims) / s.k;
  return nullptr;
}

OrtStatus* ORT_API_CALL Compute(void* kernel, OrtKernelContext* ctx) {
  const Kernel& k = *static_cast<const Kernel*>(kernel);
  OrtTensorView in[3];
  for (size_t i = 0; i < 3; ++i) SILK_ORT_TRY(ReadInput(k.api, ctx, i, &in[i]));
  Int4MatMulShape s = k.shape;
  SILK_ORT_TRY(CheckInputs(k, in, &s.m));
  std::vector<int64_t> out_dims = in[0].dims;
  out_dims.back() = s.n;
  float* y = nullptr;
  SILK_ORT_TRY(FloatOutput(k.api, ctx, 0, out_dims, &y));
  OrtPool pool{k.api, ctx};
  Int4MatMul(s, static_cast<const float*>(in[0].data), static_cast<const uint8_t*>(in[1].data),
             static_cast<const float*>(in[2].data), y, OrtPoolFor, &pool);
  return nullptr;
}

OrtStatus* ORT_API_CALL CreateKernel(const OrtCustomOp* op, const OrtApi* api, const OrtKernelInfo* info,
                                     void** kernel) {
  auto k = NewKernel<Kernel>(op, api, info);
  int64_t bits = 4;
  SILK_ORT_TRY(api->KernelInfoGetAttribute_int64(info, "K", &k->shape.k));
  SILK_ORT_TRY(api->KernelInfoGetAttribute_int64(info, "N", &k->shape.n));
  SILK_ORT_TRY(api->KernelInfoGetAttribute_int64(info, "block_size", &k->shape.block));
  if (OrtStatus* st = api->KernelInfoGetAttribute_int64(info, "bits", &bits)) api->ReleaseStatus(st);  // optional
  const char* why = nullptr;
  if (bits != 4) return k->Fail("bits is " + std::to_string(bits) + "; only 4 is implemented");
  if (!Int4ShapeSupported(k->shape, &why))
    return k->Fail(std::string(why) + " (K " + std::to_string(k->shape.k) + ", N " + std::to_string(k->shape.n) +
                   ", block_size " + std::to_string(k->shape.block) + ")");
  *kernel = k.release();
  return nullptr;
}

ONNXTensorElementDataType ORT_API_CALL InputType(const OrtCustomOp*, size_t i) {
  return i == 1 ? ONNX_TENSOR_ELEMENT_DATA_TYPE_UINT8 : ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
}

}  // namespace

void InitInt4MatMulOp(Int4MatMulOp* op, const OrtApi* api) {
  FillOpTable(op, api, kInt4MatMulOp, 3, 1);
  op->GetInputType = InputType;
  op->GetOutputType = [](const OrtCustomOp*, size_t) { return ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT; };
  SetKernel<Kernel>(op, CreateKernel, Compute);
}

}  // namespace silk
