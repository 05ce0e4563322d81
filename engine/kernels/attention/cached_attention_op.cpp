// SPDX-License-Identifier: MIT
// onnxruntime custom-op glue for CachedAttention (kernels/ort/ort_op_glue.h: the plain C API,
// so the same code serves libsilk's onnxruntime and Python's). Bad shapes give a status naming
// the node, never a crash.
#include "kernels/attention/cached_attention_op.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "kernels/attention/cached_attention.h"

namespace silk {

namespace {

struct Kernel : OpKernelBase {
  CacheElement element = CacheElement::kFloat16;
  int64_t heads = 0, kv_heads = 0;
  float scale = 0.0f;  // 0: GroupQueryAttention's default, 1 / sqrt(head_dim)
};

using Tensor = OrtTensorView;

// Inputs q, k, v, past_key, past_value, seqlens_k, total_sequence_length, checked against each
// other; fills the shape (capacity = past's) and returns nullptr, or a status naming the input.
OrtStatus* ReadInputs(const Kernel& k, OrtKernelContext* ctx, Tensor in[7], AttentionShape* s) {
  for (size_t i = 0; i < 7; ++i) SILK_ORT_TRY(ReadInput(k.api, ctx, i, &in[i]));
  const std::vector<int64_t>& q = in[0].dims;
  if (q.size() != 3 || q[0] != 1 || q[2] % k.heads != 0)
    return k.Fail("query has shape " + DimsText(q) + ", expected [1, T, heads * head_dim] with batch 1");
  s->heads = k.heads, s->kv_heads = k.kv_heads, s->head_dim = q[2] / k.heads, s->chunk = q[1];
  s->scale = k.scale != 0.0f ? k.scale : 1.0f / std::sqrt(static_cast<float>(s->head_dim));
  const std::vector<int64_t> kv = {1, s->chunk, s->kv_heads * s->head_dim};
  if (in[1].dims != kv || in[2].dims != kv)
    return k.Fail("key/value have shapes " + DimsText(in[1].dims) + ", " + DimsText(in[2].dims) + ", expected " +
                  DimsText(kv));
  const std::vector<int64_t>& past = in[3].dims;
  const int64_t row = CacheRowElements(k.element, s->head_dim);
  if (past.size() != 4 || past[0] != 1 || past[1] != s->kv_heads || past[3] != row || in[4].dims != past)
    return k.Fail("past_key/past_value have shapes " + DimsText(past) + ", " + DimsText(in[4].dims) + ", expected " +
                  (k.element == CacheElement::kInt8 ? "[1, kv_heads, capacity, head_dim + 4] = [1, "
                                                    : "[1, kv_heads, capacity, head_dim] = [1, ") +
                  std::to_string(s->kv_heads) + ", C, " + std::to_string(row) + "]");
  if (in[5].dims != std::vector<int64_t>{1} || in[6].dims.size() > 1 || (in[6].dims.size() == 1 && in[6].dims[0] != 1))
    return k.Fail("seqlens_k must have shape [1] and total_sequence_length one element");
  const int64_t total = static_cast<const int32_t*>(in[6].data)[0], seqlen = static_cast<const int32_t*>(in[5].data)[0];
  s->capacity = past[2];
  s->past = total - s->chunk;
  if (seqlen + 1 != total || s->chunk < 1 || s->past < 0 || s->past > s->capacity)
    return k.Fail("seqlens_k " + std::to_string(seqlen) + ", total_sequence_length " + std::to_string(total) + ", " +
                  std::to_string(s->chunk) + " new positions and a cache of " + std::to_string(s->capacity) +
                  " do not fit together");
  return nullptr;
}

// Outputs: attention [1, T, hidden] and the two present blocks, each the past block itself when
// the caller bound them to the same memory (in place), else a longer copy of it.
OrtStatus* MakeOutputs(const Kernel& k, OrtKernelContext* ctx, const Tensor in[7], AttentionShape* s,
                       AttentionBuffers* b) {
  SILK_ORT_TRY(FloatOutput(k.api, ctx, 0, {1, s->chunk, s->heads * s->head_dim}, &b->out));
  const int64_t present = std::max(s->capacity, s->past + s->chunk);
  const int64_t present_dims[4] = {1, s->kv_heads, present, CacheRowElements(k.element, s->head_dim)};
  void* blocks[2] = {nullptr, nullptr};
  for (int kv = 0; kv < 2; ++kv) {
    OrtValue* v = nullptr;
    SILK_ORT_TRY(k.api->KernelContext_GetOutput(ctx, 1 + kv, present_dims, 4, &v));
    SILK_ORT_TRY(k.api->GetTensorMutableData(v, &blocks[kv]));
    if (blocks[kv] == in[3 + kv].data) continue;  // in place
    const size_t row = CacheRowBytes(k.element, s->head_dim);
    for (int64_t h = 0; h < s->kv_heads; ++h)
      std::memcpy(static_cast<unsigned char*>(blocks[kv]) + h * present * row,
                  static_cast<const unsigned char*>(in[3 + kv].data) + h * s->capacity * row,
                  static_cast<size_t>(s->past) * row);
  }
  s->capacity = present;
  b->key_cache = blocks[0];
  b->value_cache = blocks[1];
  return nullptr;
}

OrtStatus* ORT_API_CALL Compute(void* kernel, OrtKernelContext* ctx) {
  const Kernel& k = *static_cast<const Kernel*>(kernel);
  Tensor in[7];
  AttentionShape s;
  SILK_ORT_TRY(ReadInputs(k, ctx, in, &s));
  AttentionBuffers b;
  b.q = static_cast<const float*>(in[0].data);
  b.k = static_cast<const float*>(in[1].data);
  b.v = static_cast<const float*>(in[2].data);
  SILK_ORT_TRY(MakeOutputs(k, ctx, in, &s, &b));
  OrtPool pool{k.api, ctx};
  CachedAttention(s, k.element, b, OrtPoolFor, &pool);
  return nullptr;
}

OrtStatus* ORT_API_CALL CreateKernel(const OrtCustomOp* op, const OrtApi* api, const OrtKernelInfo* info,
                                     void** kernel) {
  auto k = NewKernel<Kernel>(op, api, info);
  k->element = static_cast<const CachedAttentionOp*>(op)->element;
  SILK_ORT_TRY(api->KernelInfoGetAttribute_int64(info, "num_heads", &k->heads));
  SILK_ORT_TRY(api->KernelInfoGetAttribute_int64(info, "kv_num_heads", &k->kv_heads));
  if (OrtStatus* st = api->KernelInfoGetAttribute_float(info, "scale", &k->scale)) api->ReleaseStatus(st);  // optional
  if (k->heads < 1 || k->kv_heads < 1 || k->heads % k->kv_heads != 0 || k->heads > 4096)
    return k->Fail("num_heads " + std::to_string(k->heads) + " must be a positive multiple of kv_num_heads " +
                   std::to_string(k->kv_heads));
  *kernel = k.release();
  return nullptr;
}

ONNXTensorElementDataType CacheType(const OrtCustomOp* op) {
  return static_cast<const CachedAttentionOp*>(op)->element == CacheElement::kInt8
             ? ONNX_TENSOR_ELEMENT_DATA_TYPE_INT8
             : ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16;
}
ONNXTensorElementDataType ORT_API_CALL InputType(const OrtCustomOp* op, size_t i) {
  return i < 3 ? ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT : i < 5 ? CacheType(op) : ONNX_TENSOR_ELEMENT_DATA_TYPE_INT32;
}
ONNXTensorElementDataType ORT_API_CALL OutputType(const OrtCustomOp* op, size_t i) {
  return i == 0 ? ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT : CacheType(op);
}

}  // namespace

void InitCachedAttentionOp(CachedAttentionOp* op, const OrtApi* api, CacheElement element) {
  FillOpTable(op, api, kCachedAttentionOp, 7, 3);
  op->element = element;
  op->GetInputType = InputType;
  op->GetOutputType = OutputType;
  SetKernel<Kernel>(op, CreateKernel, Compute);
}

}  // namespace silk
