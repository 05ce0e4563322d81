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

#include "kernels/attention/attention_batch.h"
#include "kernels/attention/cached_attention.h"

namespace silk {

namespace {

struct Kernel : OpKernelBase {
  CacheElement element = CacheElement::kFloat16;
  int64_t heads = 0, kv_heads = 0;
  float scale = 0.0f;  // 0: GroupQueryAttention's default, 1 / sqrt(head_dim)
};

using Tensor = OrtTensorView;

constexpr size_t kInputs = 8;  // the eighth, new_positions (contract v4), is optional

// Inputs q, k, v, past_key, past_value, seqlens_k, total_sequence_length [, new_positions], checked
// against each other (attention_batch.h); fills the batch and returns nullptr, or a status naming
// the input.
OrtStatus* ReadInputs(const Kernel& k, OrtKernelContext* ctx, Tensor in[kInputs], AttentionBatch* batch) {
  size_t count = 0;
  SILK_ORT_TRY(k.api->KernelContext_GetInputCount(ctx, &count));
  for (size_t i = 0; i + 1 < kInputs; ++i) SILK_ORT_TRY(ReadInput(k.api, ctx, i, &in[i]));
  const OrtValue* fresh = nullptr;  // an optional input left out: absent or null
  if (count >= kInputs) SILK_ORT_TRY(k.api->KernelContext_GetInput(ctx, kInputs - 1, &fresh));
  if (fresh) SILK_ORT_TRY(DescribeValue(k.api, const_cast<OrtValue*>(fresh), &in[kInputs - 1]));
  AttentionInputs a;
  a.heads = k.heads, a.kv_heads = k.kv_heads, a.scale = k.scale, a.element = k.element;
  a.query = in[0].dims, a.key = in[1].dims, a.value = in[2].dims, a.past_key = in[3].dims, a.past_value = in[4].dims;
  a.seqlens_k = in[5].dims, a.total = in[6].dims;
  a.seqlens = static_cast<const int32_t*>(in[5].data);
  a.total_length = ElementCount(in[6].dims) == 1 ? static_cast<const int32_t*>(in[6].data)[0] : 0;
  a.has_new_positions = fresh != nullptr;
  if (a.has_new_positions)
    a.new_positions_shape = in[7].dims, a.new_positions = static_cast<const int32_t*>(in[7].data);
  const std::string problem = batch->Resolve(a);
  return problem.empty() ? nullptr : k.Fail(problem);
}

// Outputs: attention [R, T, hidden] and the two present blocks, each the past block itself when
// the caller bound them to the same memory (in place), else a longer copy of it (each row's past).
OrtStatus* MakeOutputs(const Kernel& k, OrtKernelContext* ctx, const Tensor in[kInputs], AttentionBatch* batch,
                       AttentionBuffers* b) {
  AttentionShape* s = batch->mutable_shape();
  SILK_ORT_TRY(FloatOutput(k.api, ctx, 0, {s->batch, s->chunk, s->heads * s->head_dim}, &b->out));
  const int64_t present = std::max(s->capacity, batch->total());
  const int64_t present_dims[4] = {s->batch, s->kv_heads, present, CacheRowElements(k.element, s->head_dim)};
  void* blocks[2] = {nullptr, nullptr};
  for (int kv = 0; kv < 2; ++kv) {
    OrtValue* v = nullptr;
    SILK_ORT_TRY(k.api->KernelContext_GetOutput(ctx, 1 + kv, present_dims, 4, &v));
    SILK_ORT_TRY(k.api->GetTensorMutableData(v, &blocks[kv]));
    if (blocks[kv] == in[3 + kv].data) continue;  // in place
    const size_t row = CacheRowBytes(k.element, s->head_dim);
    for (int64_t r = 0; r < s->batch; ++r)
      for (int64_t h = 0, block = r * s->kv_heads; h < s->kv_heads; ++h)
        std::memcpy(static_cast<unsigned char*>(blocks[kv]) + (block + h) * present * row,
                    static_cast<const unsigned char*>(in[3 + kv].data) + (block + h) * s->capacity * row,
                    static_cast<size_t>(batch->past(r)) * row);
  }
  s->capacity = present;
  b->key_cache = blocks[0];
  b->value_cache = blocks[1];
  return nullptr;
}

OrtStatus* ORT_API_CALL Compute(void* kernel, OrtKernelContext* ctx) {
  const Kernel& k = *static_cast<const Kernel*>(kernel);
  Tensor in[kInputs];
  AttentionBatch batch;
  SILK_ORT_TRY(ReadInputs(k, ctx, in, &batch));
  AttentionBuffers b;
  b.q = static_cast<const float*>(in[0].data);
  b.k = static_cast<const float*>(in[1].data);
  b.v = static_cast<const float*>(in[2].data);
  SILK_ORT_TRY(MakeOutputs(k, ctx, in, &batch, &b));
  OrtPool pool{k.api, ctx};
  CachedAttention(batch.shape(), k.element, b, OrtPoolFor, &pool);
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
  FillOpTable(op, api, kCachedAttentionOp, kInputs, 3);
  op->element = element;
  op->GetInputCharacteristic = [](const OrtCustomOp*, size_t i) {
    return i + 1 == kInputs ? INPUT_OUTPUT_OPTIONAL : INPUT_OUTPUT_REQUIRED;
  };
  op->GetInputType = InputType;
  op->GetOutputType = OutputType;
  SetKernel<Kernel>(op, CreateKernel, Compute);
}

}  // namespace silk
