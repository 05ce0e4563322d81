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

inline int64_t RowPast(const AttentionShape& s, int64_t r) { return s.row_past ? s.row_past[r] : s.past; }
inline int64_t RowChunk(const AttentionShape& s, int64_t r) { return s.row_chunk ? s.row_chunk[r] : s.chunk; }

// Row `pos` of kv head `h` of batch row `r`'s [kv_heads, capacity] block of rows.
const void* CacheRow(const void* block, const AttentionShape& s, CacheElement e, int64_t r, int64_t h, int64_t pos) {
  return static_cast<const unsigned char*>(block) +
         static_cast<size_t>((r * s.kv_heads + h) * s.capacity + pos) * CacheRowBytes(e, s.head_dim);
}

// Each row's new keys and values into its rows [past, past + chunk) of the two blocks.
void WriteNewRows(const AttentionShape& s, CacheElement e, const AttentionBuffers& b, const AttentionRows& rows) {
  for (int64_t r = 0; r < s.batch; ++r)
    for (int64_t t = 0, past = RowPast(s, r); t < RowChunk(s, r); ++t)
      for (int64_t h = 0; h < s.kv_heads; ++h) {
        const int64_t src = ((r * s.chunk + t) * s.kv_heads + h) * s.head_dim;
        rows.store(b.k + src, const_cast<void*>(CacheRow(b.key_cache, s, e, r, h, past + t)), s.head_dim);
        rows.store(b.v + src, const_cast<void*>(CacheRow(b.value_cache, s, e, r, h, past + t)), s.head_dim);
      }
}

// One batch row, new position and query head: index = (row * chunk + position) * heads + head.
void AttendOne(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const AttentionShape& s = *job.shape;
  const AttentionBuffers& b = *job.buffers;
  const AttentionRows& rows = *job.rows;
  const int64_t h = static_cast<int64_t>(index) % s.heads, rt = static_cast<int64_t>(index) / s.heads;
  const int64_t r = rt / s.chunk, t = rt % s.chunk, D = s.head_dim;
  float* out = b.out + rt * s.heads * D + h * D;
  std::fill(out, out + D, 0.0f);
  if (t >= RowChunk(s, r)) return;  // padding of a row with fewer new positions
  const int64_t kvh = h / (s.heads / s.kv_heads), length = RowPast(s, r) + t + 1;
  const float* q = b.q + rt * s.heads * D + h * D;
  std::vector<float> scores(static_cast<size_t>(length));
  rows.dots(q, CacheRow(b.key_cache, s, job.element, r, kvh, 0), length, D, s.scale, scores.data());
  const float top = *std::max_element(scores.begin(), scores.end());
  const float sum = rows.exp_shifted(scores.data(), length, top);
  rows.weighted_sum(scores.data(), CacheRow(b.value_cache, s, job.element, r, kvh, 0), length, D, 1.0f / sum, out);
}

}  // namespace

bool CachedAttentionVectorized() { return AttentionRowsFor(CacheElement::kFloat32, 64, RowKernels::kBest).vectorized; }

void CachedAttention(const AttentionShape& s, CacheElement element, const AttentionBuffers& b,
                     ParallelForFn parallel_for, void* parallel_context, RowKernels kernels) {
  const AttentionRows rows = AttentionRowsFor(element, s.head_dim, kernels);
  WriteNewRows(s, element, b, rows);
  Job job{&s, element, &b, &rows};
  RunTasks(parallel_for, parallel_context, AttendOne, &job, static_cast<size_t>(s.batch * s.chunk * s.heads));
}

}  // namespace silk
