// SPDX-License-Identifier: MIT
// CachedAttention's input checks (attention_batch.h): shapes first, then each row's lengths.
#include "kernels/attention/attention_batch.h"

#include <algorithm>
#include <cmath>

#include "kernels/ort/ort_op_glue.h"

namespace silk {

namespace {

std::string Dims(const std::vector<int64_t>& d) { return DimsText(d); }

}  // namespace

std::string AttentionBatch::Resolve(const AttentionInputs& in) {
  const std::vector<int64_t>& q = in.query;
  if (q.size() != 3 || q[0] < 1 || q[1] < 1 || q[2] < 1 || q[2] % in.heads != 0)
    return "query has shape " + Dims(q) + ", expected [R, T, heads * head_dim] with R, T >= 1 and heads " +
           std::to_string(in.heads);
  AttentionShape& s = shape_;
  s = AttentionShape{};
  s.heads = in.heads, s.kv_heads = in.kv_heads, s.head_dim = q[2] / in.heads, s.chunk = q[1], s.batch = q[0];
  s.scale = in.scale != 0.0f ? in.scale : 1.0f / std::sqrt(static_cast<float>(s.head_dim));
  const std::vector<int64_t> kv = {s.batch, s.chunk, s.kv_heads * s.head_dim};
  if (in.key != kv || in.value != kv)
    return "key/value have shapes " + Dims(in.key) + ", " + Dims(in.value) + ", expected " + Dims(kv);
  const std::vector<int64_t>& past = in.past_key;
  const int64_t row = CacheRowElements(in.element, s.head_dim);
  if (past.size() != 4 || past[0] != s.batch || past[1] != s.kv_heads || past[3] != row || in.past_value != past)
    return "past_key/past_value have shapes " + Dims(past) + ", " + Dims(in.past_value) + ", expected " +
           (in.element == CacheElement::kInt8 ? "[R, kv_heads, capacity, head_dim + 4] = ["
                                              : "[R, kv_heads, capacity, head_dim] = [") +
           std::to_string(s.batch) + ", " + std::to_string(s.kv_heads) + ", C, " + std::to_string(row) +
           "] (one cache block per row of the batch)";
  s.capacity = past[2];
  return ResolveLengths(in);
}

// seqlens_k [R] (= past + new positions - 1 per row), total_sequence_length (the longest row's
// past + new positions) and, when given, new_positions [R] (1..T per row; absent: T for all).
std::string AttentionBatch::ResolveLengths(const AttentionInputs& in) {
  AttentionShape& s = shape_;
  const std::vector<int64_t> rows = {s.batch};
  if (in.seqlens_k != rows || in.total.size() > 1 || (in.total.size() == 1 && in.total[0] != 1))
    return "seqlens_k must have shape " + Dims(rows) + " (one per row) and total_sequence_length one element";
  if (in.has_new_positions && in.new_positions_shape != rows)
    return "new_positions has shape " + Dims(in.new_positions_shape) + ", expected " + Dims(rows) + " (one per row)";
  past_.assign(static_cast<size_t>(s.batch), 0);
  chunk_.assign(static_cast<size_t>(s.batch), s.chunk);
  int64_t longest = 0;
  for (int64_t r = 0; r < s.batch; ++r) {
    const int64_t seqlen = in.seqlens[r], fresh = in.has_new_positions ? in.new_positions[r] : s.chunk;
    const int64_t past = seqlen + 1 - fresh;
    if (fresh < 1 || fresh > s.chunk || past < 0 || past > s.capacity)
      return "row " + std::to_string(r) + ": seqlens_k " + std::to_string(seqlen) + ", " + std::to_string(fresh) +
             " new positions (of " + std::to_string(s.chunk) + ") and a cache of " + std::to_string(s.capacity) +
             " do not fit together";
    past_[static_cast<size_t>(r)] = past, chunk_[static_cast<size_t>(r)] = fresh;
    longest = std::max(longest, seqlen + 1);
  }
  if (longest != in.total_length)
    return "seqlens_k " +
           std::string(s.batch == 1 ? std::to_string(in.seqlens[0])
                                    : "(longest row " + std::to_string(longest - 1) + ")") +
           ", total_sequence_length " + std::to_string(in.total_length) + ", " + std::to_string(s.chunk) +
           " new positions and a cache of " + std::to_string(s.capacity) + " do not fit together";
  total_ = longest;
  s.row_past = past_.data(), s.row_chunk = chunk_.data();
  return "";
}

}  // namespace silk
