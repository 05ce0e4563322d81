// SPDX-License-Identifier: MIT
// Attention of new positions over a fixed set of rows (the point cloud's cross K/V, 261 per head
// for the release network): the computation of the decoder's ai.silk CrossAttention op
// (docs/model_contract.md). onnxruntime runs it as MatMul with a transposed key, Mul, Softmax and
// MatMul, its batched small products reading the keys at a third of memory speed; this reads each
// key and value row once per position and head. The rows are float32, or float16 in the silk form
// of the cache variants (half the bytes of each call's cross reads; docs/model_contract.md).
#pragma once
#include <cstdint>

#include "kernels/attention/cached_attention.h"
#include "kernels/cpu/cpu_kernels.h"

namespace silk {

struct CrossAttentionShape {
  int64_t heads = 0;
  int64_t positions = 0;  // T: new positions (queries per head)
  int64_t rows = 0;       // M: key/value rows per head
  int64_t head_dim = 0;   // D
  float scale = 1.0f;     // score = scale * q.k
};

// out[0, h, t] = softmax_j(scale * q[0, h, t] . key[0, h, j]) . value[0, h, j], all
// [1, heads, positions or rows, head_dim]: q and out float32, key and value rows of `element`
// (kFloat32 or kFloat16; arithmetic in float32). The caller has checked the shapes.
void CrossAttention(const CrossAttentionShape& shape, CacheElement element, const float* q, const void* key,
                    const void* value, float* out, ParallelForFn parallel_for, void* parallel_context,
                    RowKernels kernels = RowKernels::kBest);

}  // namespace silk
