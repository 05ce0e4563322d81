// SPDX-License-Identifier: MIT
// CrossAttention: per (head, position), one pass of dot products over the head's key rows, the
// softmax, one weighted pass over its value rows (the float32 or float16 rows of CachedAttention).
#include "kernels/attention/cross_attention.h"

#include <algorithm>
#include <vector>

#include "kernels/attention/attention_rows.h"
#include "kernels/ort/ort_op_glue.h"

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

// index = (head * batch + row) * positions + position: a head's keys and values are read for
// every row and position in turn, so rows sharing a source find them in cache.
void AttendOne(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const CrossAttentionShape& s = *job.shape;
  const int64_t t = static_cast<int64_t>(index) % s.positions, hb = static_cast<int64_t>(index) / s.positions;
  const int64_t h = hb / s.batch, b = hb % s.batch, src = s.source ? s.source[b] : b;
  const int64_t D = s.head_dim, M = s.rows, at = ((b * s.heads + h) * s.positions + t) * D;
  const size_t block = static_cast<size_t>((src * s.heads + h) * M) * job.row_bytes;
  std::vector<float> scores(static_cast<size_t>(M));
  job.rows->dots(job.q + at, job.key + block, M, D, s.scale, scores.data());
  const float top = *std::max_element(scores.begin(), scores.end());
  const float sum = job.rows->exp_shifted(scores.data(), M, top);
  float* out = job.out + at;
  std::fill(out, out + D, 0.0f);
  job.rows->weighted_sum(scores.data(), job.value + block, M, D, 1.0f / sum, out);
}

}  // namespace

void CrossAttention(const CrossAttentionShape& s, CacheElement element, const float* q, const void* key,
                    const void* value, float* out, ParallelForFn parallel_for, void* parallel_context,
                    RowKernels kernels) {
  if (s.heads <= 0 || s.positions <= 0 || s.batch <= 0) return;
  const AttentionRows rows = AttentionRowsFor(element, s.head_dim, kernels);
  Job job{&s,
          q,
          static_cast<const unsigned char*>(key),
          static_cast<const unsigned char*>(value),
          CacheRowBytes(element, s.head_dim),
          out,
          &rows};
  RunTasks(parallel_for, parallel_context, AttendOne, &job, static_cast<size_t>(s.heads * s.batch * s.positions));
}

std::string ResolveCrossAttention(const CrossAttentionInputs& in, float scale, CrossAttentionShape* s,
                                  std::vector<int32_t>* sources) {
  const std::vector<int64_t>&q = in.query, &key = in.key;
  if (q.size() != 4 || key.size() != 4 || in.value != key || key[1] != q[1] || key[3] != q[3] || key[2] < 1 ||
      q[3] < 1 || key[0] < 1 || (!in.has_source && key[0] != q[0] && key[0] != 1))
    return "query " + DimsText(q) + ", key " + DimsText(key) + " and value " + DimsText(in.value) +
           " do not fit: expected [R, H, T, D] and [S, H, M, D] with M >= 1 and S = R or 1 (or a source input)";
  *s = CrossAttentionShape{q[1], q[2], key[2], q[3], scale};
  s->batch = q[0];
  sources->assign(static_cast<size_t>(q[0]), 0);
  for (int64_t b = 0; b < q[0]; ++b) (*sources)[static_cast<size_t>(b)] = key[0] == 1 ? 0 : static_cast<int32_t>(b);
  if (in.has_source) {
    if (in.source_shape != std::vector<int64_t>{q[0]})
      return "source has shape " + DimsText(in.source_shape) + ", expected [" + std::to_string(q[0]) +
             "] (one per row)";
    for (int64_t b = 0; b < q[0]; ++b) {
      if (in.source[b] < 0 || in.source[b] >= key[0])
        return "source[" + std::to_string(b) + "] is " + std::to_string(in.source[b]) + ", not one of the " +
               std::to_string(key[0]) + " key/value sources";
      (*sources)[static_cast<size_t>(b)] = in.source[b];
    }
  }
  s->source = sources->data();
  return "";
}

}  // namespace silk
