// SPDX-License-Identifier: MIT
// CachedAttention: two passes over the cache per (position, head), keys then values, each row
// read once; float16 and int8 rows are widened in registers instead of in a float32 copy.
#include "kernels/attention/cached_attention.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "kernels/attention/attention_rows.h"

namespace silk {

namespace {

struct Job {
  const AttentionShape* shape;
  CacheElement element;
  const AttentionBuffers* buffers;
  const AttentionRows* rows;
};

// Row `pos` of kv head `h` of a [kv_heads, capacity] block of rows.
const void* CacheRow(const void* block, const AttentionShape& s, CacheElement e, int64_t h, int64_t pos) {
  return static_cast<const unsigned char*>(block) +
         static_cast<size_t>(h * s.capacity + pos) * CacheRowBytes(e, s.head_dim);
}

// The chunk's keys and values into rows [past, past + chunk) of the two blocks.
void WriteNewRows(const AttentionShape& s, CacheElement e, const AttentionBuffers& b, const AttentionRows& rows) {
  for (int64_t t = 0; t < s.chunk; ++t)
    for (int64_t h = 0; h < s.kv_heads; ++h) {
      const int64_t src = (t * s.kv_heads + h) * s.head_dim;
      void* kr = const_cast<void*>(CacheRow(b.key_cache, s, e, h, s.past + t));
      void* vr = const_cast<void*>(CacheRow(b.value_cache, s, e, h, s.past + t));
      rows.store(b.k + src, kr, s.head_dim);
      rows.store(b.v + src, vr, s.head_dim);
    }
}

// One new position (index / heads) and query head (index % heads).
void AttendOne(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const AttentionShape& s = *job.shape;
  const AttentionBuffers& b = *job.buffers;
  const AttentionRows& rows = *job.rows;
  const int64_t t = static_cast<int64_t>(index) / s.heads, h = static_cast<int64_t>(index) % s.heads;
  const int64_t kvh = h / (s.heads / s.kv_heads), length = s.past + t + 1, D = s.head_dim;
  const float* q = b.q + (t * s.heads + h) * D;
  std::vector<float> scores(static_cast<size_t>(length));
  const void* keys = CacheRow(b.key_cache, s, job.element, kvh, 0);
  rows.dots(q, keys, length, D, s.scale, scores.data());
  const float top = *std::max_element(scores.begin(), scores.end());
  const float sum = rows.exp_shifted(scores.data(), length, top);
  float* out = b.out + (t * s.heads + h) * D;
  std::fill(out, out + D, 0.0f);
  const void* values = CacheRow(b.value_cache, s, job.element, kvh, 0);
  rows.weighted_sum(scores.data(), values, length, D, 1.0f / sum, out);
}

}  // namespace

bool CachedAttentionVectorized() { return AttentionRowsFor(CacheElement::kFloat32, 64, RowKernels::kBest).vectorized; }

void CachedAttention(const AttentionShape& s, CacheElement element, const AttentionBuffers& b,
                     ParallelForFn parallel_for, void* parallel_context, RowKernels kernels) {
  const AttentionRows rows = AttentionRowsFor(element, s.head_dim, kernels);
  WriteNewRows(s, element, b, rows);
  Job job{&s, element, &b, &rows};
  RunTasks(parallel_for, parallel_context, AttendOne, &job, static_cast<size_t>(s.chunk * s.heads));
}

}  // namespace silk
