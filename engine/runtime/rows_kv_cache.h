// SPDX-License-Identifier: MIT
// RowsKvCache: the self-attention cache of R sequences decoded together (decoder contract v4),
// one tensor per layer and K/V of R blocks [H, C, row] (docs/model_contract.md), each row's own
// block at its slot. C grows by doubling as the deepest row grows (each slot's filled rows copied),
// so memory follows depth: no R x max-length block up front. A row that ends leaves its slot; the
// last slot's row moves into it, so the rows of a call are always the slots 0..R'-1.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/status.h"
#include "runtime/kv_cache.h"

namespace silk {

class RowsKvCache {
 public:
  // `slots` rows of up to `max_capacity` positions each; starts with room for min(first, max).
  Status Reserve(int32_t slots, int64_t max_capacity, const KvShape& shape, int64_t first = 512);
  // Room for `positions` in every slot (doubling C up to max_capacity); LimitExceeded beyond it.
  Status Ensure(int64_t positions);

  int32_t slots() const { return static_cast<int32_t>(length_.size()); }
  int64_t capacity() const { return capacity_; }
  int64_t max_capacity() const { return max_capacity_; }
  const KvShape& shape() const { return shape_; }
  int64_t length(int32_t slot) const { return length_[static_cast<size_t>(slot)]; }
  void Extend(int32_t slot, int64_t n) { length_[static_cast<size_t>(slot)] += n; }
  void Clear(int32_t slot) { length_[static_cast<size_t>(slot)] = 0; }
  // Moves slot `from`'s filled rows and length into slot `to` (from is cleared).
  void Move(int32_t from, int32_t to);

  // Layer `layer`'s keys (kv 0) or values (kv 1): [slots, H, capacity] rows of row_bytes().
  void* block(int64_t layer, int kv) { return data_.get() + (layer * 2 + kv) * block_bytes(); }
  void* slot_block(int64_t layer, int kv, int32_t slot) {
    return static_cast<unsigned char*>(block(layer, kv)) + slot * slot_bytes();
  }
  const void* slot_block(int64_t layer, int kv, int32_t slot) const {
    return data_.get() + (layer * 2 + kv) * block_bytes() + slot * slot_bytes();
  }
  int64_t slot_bytes() const { return shape_.heads * capacity_ * shape_.row_bytes(); }
  int64_t block_bytes() const { return slots() * slot_bytes(); }
  int64_t bytes() const { return allocated_; }
  // Slot `slot`'s positions [0, length) as time-major float32 [length, L, 2, H, D] (tests).
  void CopyTimeMajor(int32_t slot, float* out) const;

 private:
  Status Allocate(int64_t capacity, std::unique_ptr<unsigned char[]>* data);
  std::unique_ptr<unsigned char[]> data_;  // uninitialised: pages are touched as rows fill
  int64_t allocated_ = 0, capacity_ = 0, max_capacity_ = 0;
  std::vector<int64_t> length_;
  KvShape shape_;
};

}  // namespace silk
