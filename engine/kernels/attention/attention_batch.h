// SPDX-License-Identifier: MIT
// The rows of one CachedAttention call (decoder contract v4: R sequences, each at its own depth
// with its own count of new positions) from the op's input shapes and length values: one check of
// every input against the others, kept apart from onnxruntime so tests call it as the op does.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/attention/cached_attention.h"

namespace silk {

// What a CachedAttention node receives, as plain shapes and values.
struct AttentionInputs {
  int64_t heads = 0, kv_heads = 0;  // the node's num_heads, kv_num_heads
  float scale = 0.0f;               // the node's scale (0: 1 / sqrt(head_dim))
  CacheElement element = CacheElement::kFloat16;
  std::vector<int64_t> query, key, value, past_key, past_value, seqlens_k, total;  // shapes
  const int32_t* seqlens = nullptr;                                                // seqlens_k's values
  int32_t total_length = 0;                                                        // total_sequence_length
  bool has_new_positions = false;  // the optional eighth input (contract v4)
  std::vector<int64_t> new_positions_shape;
  const int32_t* new_positions = nullptr;
};

// The rows' lengths and the shape that points at them (not copyable: the shape points into it).
class AttentionBatch {
 public:
  AttentionBatch() = default;
  AttentionBatch(const AttentionBatch&) = delete;
  AttentionBatch& operator=(const AttentionBatch&) = delete;
  // Fills the batch from the inputs; "" when they fit together, else what does not fit (the op
  // prefixes the node's name).
  std::string Resolve(const AttentionInputs& in);
  const AttentionShape& shape() const { return shape_; }
  AttentionShape* mutable_shape() { return &shape_; }
  int64_t past(int64_t row) const { return past_[static_cast<size_t>(row)]; }
  // The longest row's past + new positions: total_sequence_length.
  int64_t total() const { return total_; }

 private:
  std::string ResolveLengths(const AttentionInputs& in);
  AttentionShape shape_;
  std::vector<int64_t> past_, chunk_;
  int64_t total_ = 0;
};

}  // namespace silk
