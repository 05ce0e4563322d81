// KvCache: one pre-allocated self-attention cache for a whole generation, one head-major block
// [H, capacity, D] per layer and K/V (docs/model_contract.md). decoder.onnx reads the prefix of
// each block in place and writes a chunk's new rows at P, so a step copies nothing.
#pragma once
#include <cstdint>
#include <memory>

#include "core/status.h"

namespace silk {

struct KvShape {
  int64_t layers = 0, heads = 0, head_dim = 0;
  int64_t position_floats() const { return layers * 2 * heads * head_dim; }  // K+V of one position
};

class KvCache {
 public:
  // Room for `capacity` positions (reuses the buffer when it is already big enough).
  Status Reserve(int64_t capacity, const KvShape& shape);
  void Clear() { length_ = 0; }

  int64_t capacity() const { return capacity_; }
  const KvShape& shape() const { return shape_; }
  int64_t length() const { return length_; }  // positions filled
  // The block of layer `layer`, keys (kv 0) or values (kv 1): [H, capacity, D].
  float* block(int64_t layer, int kv) { return data_.get() + (layer * 2 + kv) * block_floats(); }
  const float* block(int64_t layer, int kv) const { return data_.get() + (layer * 2 + kv) * block_floats(); }
  int64_t block_floats() const { return shape_.heads * capacity_ * shape_.head_dim; }
  void Extend(int64_t n) { length_ += n; }
  // Forgets positions from n on (rewinding a generation; the rows are simply overwritten).
  void Truncate(int64_t n) {
    if (n >= 0 && n < length_) length_ = n;
  }
  // Copies positions [0, length) out as time-major [length, L, 2, H, D] (tests, diagnostics).
  void CopyTimeMajor(float* out) const;
  int64_t bytes() const { return allocated_ * static_cast<int64_t>(sizeof(float)); }

 private:
  // Left uninitialised: pages are only touched (and counted in RSS) as positions fill.
  std::unique_ptr<float[]> data_;
  int64_t allocated_ = 0;
  int64_t capacity_ = 0, length_ = 0;
  KvShape shape_;
};

}  // namespace silk
