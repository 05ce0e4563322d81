// SPDX-License-Identifier: MIT
// Attention of new positions over a fixed set of rows (the point cloud's cross K/V, 261 per head
// for the release network): the computation of the decoder's ai.silk CrossAttention op
// (docs/model_contract.md). onnxruntime runs it as MatMul with a transposed key, Mul, Softmax and
// MatMul, its batched small products reading the keys at a third of memory speed; this reads each
// key and value row once per head for all the queries that share its source (the candidates of one
// mesh), up to 8 at a time. The rows are float32, or float16 in the silk form of the cache variants
// (half the bytes of each call's cross reads; docs/model_contract.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/attention/cached_attention.h"
#include "kernels/cpu/cpu_kernels.h"

namespace silk {

struct CrossAttentionShape {
  int64_t heads = 0;
  int64_t positions = 0;  // T: new positions (queries per head)
  int64_t rows = 0;       // M: key/value rows per head
  int64_t head_dim = 0;   // D
  float scale = 1.0f;     // score = scale * q.k
  // A batch of rows (decoder contract v4): q and out [batch, heads, positions, head_dim], key and
  // value [sources, heads, rows, head_dim]; row b reads source[b] (nullptr: source b), so the
  // candidates of one mesh share its cross K/V and different meshes each have their own.
  int64_t batch = 1;
  const int32_t* source = nullptr;
};

// out[b, h, t] = softmax_j(scale * q[b, h, t] . key[src, h, j]) . value[src, h, j] with src =
// source[b]: q and out float32, key and value rows of `element` (kFloat32 or kFloat16; arithmetic
// in float32), each row computed exactly as alone. The caller has checked the shapes and sources.
void CrossAttention(const CrossAttentionShape& shape, CacheElement element, const float* q, const void* key,
                    const void* value, float* out, ParallelForFn parallel_for, void* parallel_context,
                    RowKernels kernels = RowKernels::kBest);

// The op's inputs as plain shapes and values: query [R, H, T, D], key and value [S, H, M, D] and
// the optional source [R] (absent: S must be R, row b reading source b, or 1, shared by all).
struct CrossAttentionInputs {
  std::vector<int64_t> query, key, value, source_shape;
  bool has_source = false;
  const int32_t* source = nullptr;
};

// The shape for those inputs, its `source` pointing into *sources; "" when they fit together,
// else what does not (the op prefixes the node's name).
std::string ResolveCrossAttention(const CrossAttentionInputs& in, float scale, CrossAttentionShape* shape,
                                  std::vector<int32_t>* sources);

}  // namespace silk
