// SPDX-License-Identifier: MIT
// onnxruntime custom-op glue for CrossAttention: inputs query [B, H, T, D] float32, key and value
// [B, H, M, D] (float32 or float16: the op table's element), attribute scale; output [B, H, T, D]
// float32. Shapes that do not fit give a status naming the node, never a crash.
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

OrtStatus* CheckShapes(const Kernel& k, const OrtTensorView in[3], CrossAttentionShape* s) {
  const std::vector<int64_t>& q = in[0].dims;
  const std::vector<int64_t>& key = in[1].dims;
  if (q.size() != 4 || key.size() != 4 || in[2].dims != key || key[0] != q[0] || key[1] != q[1] || key[3] != q[3] ||
      key[2] < 1 || q[3] < 1)
    return k.Fail("query " + DimsText(q) + ", key " + DimsText(key) + " and value " + DimsText(in[2].dims) +
                  " do not fit: expected [B, H, T, D] and [B, H, M, D] with M >= 1");
  s->heads = q[0] * q[1], s->positions = q[2], s->rows = key[2], s->head_dim = q[3], s->scale = k.scale;
  return nullptr;
}

OrtStatus* ORT_API_CALL Compute(void* kernel, OrtKernelContext* ctx) {
  const Kernel& k = *static_cast<const Kernel*>(kernel);
  OrtTensorView in[3];
  for (size_t i = 0; i < 3; ++i) SILK_ORT_TRY(ReadInput(k.api, ctx, i, &in[i]));
  CrossAttentionShape s;
  SILK_ORT_TRY(CheckShapes(k, in, &s));
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
  return i > 0 && static_cast<const CrossAttentionOp*>(op)->element == CacheElement::kFloat16
             ? ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16
             : ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
}

}  // namespace

void InitCrossAttentionOp(CrossAttentionOp* op, const OrtApi* api, CacheElement element) {
  FillOpTable(op, api, kCrossAttentionOp, 3, 1);
  op->element = element;
  op->GetInputType = InputType;
  op->GetOutputType = [](const OrtCustomOp*, size_t) { return ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT; };
  SetKernel<Kernel>(op, CreateKernel, Compute);
}

}  // namespace silk
