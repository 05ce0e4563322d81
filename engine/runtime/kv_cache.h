// KvCache: one pre-allocated, time-major self-attention cache [capacity, L, 2, H, D] for a
// whole generation. Time-major means the prefix [0, P) is one contiguous block (passed to
// decoder.onnx as past_kv without copying) and a chunk's new_kv lands contiguously at P.
#pragma once
#include <cstdint>
#include <memory>

#include "core/status.h"

namespace silk {

class KvCache {
 public:
  // Allocates capacity * row_floats floats (reuses the buffer when it is already big enough).
  Status Reserve(int64_t capacity, int64_t row_floats);
  void Clear() { length_ = 0; }

  int64_t capacity() const { return capacity_; }
  int64_t row_floats() const { return row_floats_; }
  int64_t length() const { return length_; }        // positions filled
  float* row(int64_t t) { return data_.get() + t * row_floats_; }
  const float* data() const { return data_.get(); }
  void Extend(int64_t n) { length_ += n; }
  // Forgets positions from n on (rewinding a generation; the rows are simply overwritten).
  void Truncate(int64_t n) {
    if (n >= 0 && n < length_) length_ = n;
  }
  int64_t bytes() const { return allocated_ * static_cast<int64_t>(sizeof(float)); }

 private:
  // Left uninitialised: pages are only touched (and counted in RSS) as positions fill.
  std::unique_ptr<float[]> data_;
  int64_t allocated_ = 0;
  int64_t capacity_ = 0, row_floats_ = 0, length_ = 0;
};

}  // namespace silk
