// SPDX-License-Identifier: MIT
// Self-attention of a chunk of new positions over a cache that holds every earlier position:
// the computation of the decoder's ai.silk CachedAttention op (docs/model_contract.md), kept
// apart from onnxruntime so it can be tested against a plain reference and timed on its own.
// onnxruntime 1.22's GroupQueryAttention reads a float16 cache at a fraction of the memory
// bandwidth (it widens the whole prefix to float32 first); this reads each cached row once.
// An int8 cache holds each row as head_dim int8 values and the row's float32 scale.
#pragma once
#include <cstddef>
#include <cstdint>

#include "kernels/attention/cache_row.h"
#include "kernels/cpu/cpu_kernels.h"

namespace silk {

struct AttentionShape {
  int64_t heads = 0;     // query heads
  int64_t kv_heads = 0;  // key/value heads (heads is a multiple of it)
  int64_t head_dim = 0;
  int64_t chunk = 0;     // new positions this call (T)
  int64_t past = 0;      // positions already in the cache before this call
  int64_t capacity = 0;  // positions each [kv_heads, capacity, row] cache block has room for
  float scale = 1.0f;    // score = scale * q.k
};

struct AttentionBuffers {
  const float* q = nullptr;     // [chunk, heads * head_dim]
  const float* k = nullptr;     // [chunk, kv_heads * head_dim], the new positions' keys
  const float* v = nullptr;     // [chunk, kv_heads * head_dim]
  void* key_cache = nullptr;    // [kv_heads, capacity] rows of CacheRowBytes: [0, past) are read,
  void* value_cache = nullptr;  // rows [past, past + chunk) are written
  float* out = nullptr;         // [chunk, heads * head_dim]
};

// Writes the chunk's keys and values into the cache rows [past, past + chunk), then for each new
// position i and head attends causally over rows [0, past + i]. The caller has checked the shape
// (past + chunk <= capacity, heads % kv_heads == 0).
void CachedAttention(const AttentionShape& shape, CacheElement element, const AttentionBuffers& buffers,
                     ParallelForFn parallel_for, void* parallel_context, RowKernels kernels = RowKernels::kBest);

// Whether this CPU runs the vectorized rows (AVX2 + FMA + F16C); otherwise plain C++.
bool CachedAttentionVectorized();

}  // namespace silk
