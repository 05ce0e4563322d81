// SPDX-License-Identifier: MIT
// CrossAttention: per head, the queries that read one source (the candidates of one mesh) together:
// one pass of dot products over the head's key rows, the softmaxes, one weighted pass over its value
// rows (the float32 or float16 rows of CachedAttention, widened once for all those queries).
#include "kernels/attention/cross_attention.h"

#include <algorithm>
#include <vector>
#include <utility>

#include "kernels/attention/attention_rows.h"
#include "kernels/ort/ort_op_glue.h"

namespace silk {

namespace {

// The queries that read one source, in chunks: a task is one head of one source and up to
// kQueriesPerTask of its queries (rows x positions), which widen each key and value row once.
constexpr int64_t kQueriesPerTask = 8;

struct Task {
  int64_t source, head;
  size_t first, count;  // into Job::queries
};

struct Job {
  const CrossAttentionShape* shape;
  const float* q;
  const unsigned char *key, *value;  // [sources, heads, rows] rows of row_bytes
  size_t row_bytes;
  float* out;
  const AttentionRows* rows;
  std::vector<int64_t> queries;  // row * positions + position, grouped by source
  std::vector<Task> tasks;
};

// Each query: dot products with the head's key rows, the softmax, the weighted sum of its value
// rows (the same primitives, in the same order, as one query alone).
void AttendGroup(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const CrossAttentionShape& s = *job.shape;
  const Task& task = job.tasks[index];
  const int64_t D = s.head_dim, M = s.rows, n = static_cast<int64_t>(task.count);
  const float* q[kQueriesPerTask];
  float *out[kQueriesPerTask], *scores[kQueriesPerTask], factor[kQueriesPerTask];
  std::vector<float> buffer(static_cast<size_t>(n * M));
  for (int64_t i = 0; i < n; ++i) {
    const int64_t query = job.queries[task.first + static_cast<size_t>(i)];
    const int64_t b = query / s.positions, t = query % s.positions;
    const int64_t at = ((b * s.heads + task.head) * s.positions + t) * D;
    q[i] = job.q + at, out[i] = job.out + at, scores[i] = buffer.data() + i * M;
  }
  const size_t block = static_cast<size_t>((task.source * s.heads + task.head) * M) * job.row_bytes;
  job.rows->DotsOfMany(q, n, job.key + block, M, D, s.scale, scores);
  for (int64_t i = 0; i < n; ++i) {
    const float top = *std::max_element(scores[i], scores[i] + M);
    factor[i] = 1.0f / job.rows->exp_shifted(scores[i], M, top);
    std::fill(out[i], out[i] + D, 0.0f);
  }
  job.rows->WeightedSumsOfMany(scores, n, job.value + block, M, D, factor, out);
}

// Queries grouped by source (rows in order within one), and per head the chunks of each group.
void PlanTasks(const CrossAttentionShape& s, Job* job) {
  std::vector<int64_t> by_source(static_cast<size_t>(s.batch));
  for (int64_t b = 0; b < s.batch; ++b) by_source[static_cast<size_t>(b)] = b;
  const auto source = [&s](int64_t b) { return s.source ? int64_t{s.source[b]} : b; };
  std::stable_sort(by_source.begin(), by_source.end(), [&](int64_t a, int64_t b) { return source(a) < source(b); });
  std::vector<std::pair<int64_t, size_t>> groups;  // source, first query
  for (int64_t b : by_source) {
    if (groups.empty() || groups.back().first != source(b)) groups.emplace_back(source(b), job->queries.size());
    for (int64_t t = 0; t < s.positions; ++t) job->queries.push_back(b * s.positions + t);
  }
  for (int64_t h = 0; h < s.heads; ++h)
    for (size_t g = 0; g < groups.size(); ++g) {
      const size_t end = g + 1 < groups.size() ? groups[g + 1].second : job->queries.size();
      for (size_t first = groups[g].second; first < end; first += kQueriesPerTask)
        job->tasks.push_back(
            {groups[g].first, h, first, std::min<size_t>(static_cast<size_t>(kQueriesPerTask), end - first)});
    }
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
          &rows,
          {},
          {}};
  PlanTasks(s, &job);
  RunTasks(parallel_for, parallel_context, AttendGroup, &job, job.tasks.size());
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
