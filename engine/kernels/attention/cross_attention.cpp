// SPDX-License-Identifier: MIT
// CrossAttention: per (head, position), one pass of dot products over the head's key rows, the
// softmax, one weighted pass over its value rows (the float32 or float16 rows of CachedAttention).
#include "kernels/attention/cross_attention.h"

#include <algorithm>
#include <vector>

#include "kernels/attention/attention_rows.h"

namespace silk {

namespace {

struct Job {
  const CrossAttentionShape* shape;
  const float* q;
  const unsigned char *key, *value;  // [heads, rows] rows of row_bytes
  size_t row_bytes;
  float* out;
  const AttentionRows* rows;
};

void AttendOne(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const CrossAttentionShape& s = *job.shape;
  const int64_t h = static_cast<int64_t>(index) / s.positions, t = static_cast<int64_t>(index) % s.positions;
  const int64_t D = s.head_dim, M = s.rows;
  const float* q = job.q + (h * s.positions + t) * D;
  std::vector<float> scores(static_cast<size_t>(M));
  job.rows->dots(q, job.key + h * M * job.row_bytes, M, D, s.scale, scores.data());
  const float top = *std::max_element(scores.begin(), scores.end());
  const float sum = job.rows->exp_shifted(scores.data(), M, top);
  float* out = job.out + (h * s.positions + t) * D;
  std::fill(out, out + D, 0.0f);
  job.rows->weighted_sum(scores.data(), job.value + h * M * job.row_bytes, M, D, 1.0f / sum, out);
}

}  // namespace

void CrossAttention(const CrossAttentionShape& s, CacheElement element, const float* q, const void* key,
                    const void* value, float* out, ParallelForFn parallel_for, void* parallel_context,
                    RowKernels kernels) {
  if (s.heads <= 0 || s.positions <= 0) return;
  const AttentionRows rows = AttentionRowsFor(element, s.head_dim, kernels);
  Job job{&s,
          q,
          static_cast<const unsigned char*>(key),
          static_cast<const unsigned char*>(value),
          CacheRowBytes(element, s.head_dim),
          out,
          &rows};
  RunTasks(parallel_for, parallel_context, AttendOne, &job, static_cast<size_t>(s.heads * s.positions));
}

}  // namespace silk
