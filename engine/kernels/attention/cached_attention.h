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
  int64_t chunk = 0;     // new positions this call (T); in a batch, the longest row's count
  int64_t past = 0;      // positions already in the cache before this call (every row, unless row_past)
  int64_t capacity = 0;  // positions each [kv_heads, capacity, row] cache block has room for
  float scale = 1.0f;    // score = scale * q.k
  // A batch of rows (decoder contract v4): sequences at their own depths, each with its own
  // [kv_heads, capacity] blocks, computed exactly as each row alone.
  int64_t batch = 1;
  const int64_t* row_past = nullptr;   // [batch]: row r's past (nullptr: `past` for every row)
  const int64_t* row_chunk = nullptr;  // [batch]: row r's new positions, 1..chunk (nullptr: `chunk`);
                                       // positions beyond them are padding: output zeros, nothing stored
};

struct AttentionBuffers {
  const float* q = nullptr;     // [batch, chunk, heads * head_dim]
  const float* k = nullptr;     // [batch, chunk, kv_heads * head_dim], the new positions' keys
  const float* v = nullptr;     // [batch, chunk, kv_heads * head_dim]
  void* key_cache = nullptr;    // [batch, kv_heads, capacity] rows of CacheRowBytes: [0, past) of
  void* value_cache = nullptr;  // each row are read, rows [past, past + its chunk) are written
  float* out = nullptr;         // [batch, chunk, heads * head_dim]
};

// For each row: writes its new keys and values into its cache rows [past, past + chunk), then for
// each new position i and head attends causally over rows [0, past + i]. The caller has checked
// the shape (each row's past + chunk <= capacity, heads % kv_heads == 0).
void CachedAttention(const AttentionShape& shape, CacheElement element, const AttentionBuffers& buffers,
                     ParallelForFn parallel_for, void* parallel_context, RowKernels kernels = RowKernels::kBest);

// Whether this CPU runs the vectorized rows (AVX2 + FMA + F16C); otherwise plain C++.
bool CachedAttentionVectorized();

}  // namespace silk
