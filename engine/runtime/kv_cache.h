// KvCache: one pre-allocated self-attention cache for a whole generation, one head-major block
// [H, capacity, D] per layer and K/V (docs/model_contract.md), of float32 or float16 elements as
// the decoder graph's past_*/present_* are (KV precision). decoder.onnx reads the prefix of each
// block in place and writes a chunk's new rows at P, so a step copies nothing.
#pragma once
#include <cstdint>
#include <memory>

#include "core/status.h"

namespace silk {

struct KvShape {
  int64_t layers = 0, heads = 0, head_dim = 0;
  int64_t elem_bytes = 4;  // 4: float32 cache, 2: float16 cache
  int64_t position_elems() const { return layers * 2 * heads * head_dim; }  // K+V of one position
  int64_t position_bytes() const { return position_elems() * elem_bytes; }
};

class KvCache {
 public:
  // Room for `capacity` positions (reuses the buffer when it is already big enough).
  Status Reserve(int64_t capacity, const KvShape& shape);
  void Clear() { length_ = 0; }

  int64_t capacity() const { return capacity_; }
  const KvShape& shape() const { return shape_; }
  int64_t length() const { return length_; }  // positions filled
  // The block of layer `layer`, keys (kv 0) or values (kv 1): [H, capacity, D] elements of
  // shape().elem_bytes each.
  void* block(int64_t layer, int kv) { return data_.get() + (layer * 2 + kv) * block_bytes(); }
  const void* block(int64_t layer, int kv) const { return data_.get() + (layer * 2 + kv) * block_bytes(); }
  int64_t block_elems() const { return shape_.heads * capacity_ * shape_.head_dim; }
  int64_t block_bytes() const { return block_elems() * shape_.elem_bytes; }
  void Extend(int64_t n) { length_ += n; }
  // Forgets positions from n on (rewinding a generation; the rows are simply overwritten).
  void Truncate(int64_t n) {
    if (n >= 0 && n < length_) length_ = n;
  }
  // Copies positions [0, length) out as time-major float32 [length, L, 2, H, D] (tests,
  // diagnostics; a float16 cache is widened exactly).
  void CopyTimeMajor(float* out) const;
  int64_t bytes() const { return allocated_; }

 private:
  // Left uninitialised: pages are only touched (and counted in RSS) as positions fill.
  std::unique_ptr<unsigned char[]> data_;
  int64_t allocated_ = 0;  // bytes
  int64_t capacity_ = 0, length_ = 0;
  KvShape shape_;
};

}  // namespace silk
