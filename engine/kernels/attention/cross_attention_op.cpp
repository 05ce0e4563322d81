// SPDX-License-Identifier: MIT
// onnxruntime custom-op glue for CrossAttention: inputs query [R, H, T, D] float32, key and value
// [S, H, M, D] (float32 or float16: the op table's element), optionally source int32 [R] (which
// of the S each row reads; absent: S = R or 1), attribute scale; output [R, H, T, D] float32.
// Shapes that do not fit give a status naming the node, never a crash.
#include "kernels/attention/cross_attention_op.h"

#include <memory>
#include <string>
#include <vector>

#include "kernels/attention/cross_attention.h"

namespace silk {

namespace {

struct Kernel : OpKernelBase {
  CacheElement element = CacheElement::kFloat32;
  float scale = 1.0f;
};

constexpr size_t kInputs = 4;  // the fourth, source (contract v4), is optional

OrtStatus* ORT_API_CALL Compute(void* kernel, OrtKernelContext* ctx) {
  const Kernel& k = *static_cast<const Kernel*>(kernel);
  OrtTensorView in[kInputs];
  for (size_t i = 0; i + 1 < kInputs; ++i) SILK_ORT_TRY(ReadInput(k.api, ctx, i, &in[i]));
  size_t count = 0;
  const OrtValue* source = nullptr;  // an optional input left out: absent or null
  SILK_ORT_TRY(k.api->KernelContext_GetInputCount(ctx, &count));
  if (count >= kInputs) SILK_ORT_TRY(k.api->KernelContext_GetInput(ctx, kInputs - 1, &source));
  if (source) SILK_ORT_TRY(DescribeValue(k.api, const_cast<OrtValue*>(source), &in[kInputs - 1]));
  const CrossAttentionInputs inputs{in[0].dims, in[1].dims,        in[2].dims,
                                    in[3].dims, source != nullptr, static_cast<const int32_t*>(in[3].data)};
  CrossAttentionShape s;
  std::vector<int32_t> sources;
  const std::string problem = ResolveCrossAttention(inputs, k.scale, &s, &sources);
  if (!problem.empty()) return k.Fail(problem);
  float* y = nullptr;
  SILK_ORT_TRY(FloatOutput(k.api, ctx, 0, in[0].dims, &y));
  OrtPool pool{k.api, ctx};
  CrossAttention(s, k.element, static_cast<const float*>(in[0].data), in[1].data, in[2].data, y, OrtPoolFor, &pool);
  return nullptr;
}

OrtStatus* ORT_API_CALL CreateKernel(const OrtCustomOp* op, const OrtApi* api, const OrtKernelInfo* info,
                                     void** kernel) {
  auto k = NewKernel<Kernel>(op, api, info);
  k->element = static_cast<const CrossAttentionOp*>(op)->element;
  SILK_ORT_TRY(api->KernelInfoGetAttribute_float(info, "scale", &k->scale));
  if (!(k->scale == k->scale) || k->scale == 0.0f) return k->Fail("scale must be a non-zero number");
  *kernel = k.release();
  return nullptr;
}

ONNXTensorElementDataType ORT_API_CALL InputType(const OrtCustomOp* op, size_t i) {
  if (i + 1 == kInputs) return ONNX_TENSOR_ELEMENT_DATA_TYPE_INT32;
  return i > 0 && static_cast<const CrossAttentionOp*>(op)->element == CacheElement::kFloat16
             ? ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16
             : ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
}

}  // namespace

void InitCrossAttentionOp(CrossAttentionOp* op, const OrtApi* api, CacheElement element) {
  FillOpTable(op, api, kCrossAttentionOp, kInputs, 1);
  op->element = element;
  op->GetInputCharacteristic = [](const OrtCustomOp*, size_t i) {
    return i + 1 == kInputs ? INPUT_OUTPUT_OPTIONAL : INPUT_OUTPUT_REQUIRED;
  };
  op->GetInputType = InputType;
  op->GetOutputType = [](const OrtCustomOp*, size_t) { return ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT; };
  SetKernel<Kernel>(op, CreateKernel, Compute);
}

}  // namespace silk
