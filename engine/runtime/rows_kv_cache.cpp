// SPDX-License-Identifier: MIT
// The rows cache's growth (doubling, copying each slot's filled rows per head) and slot moves,
// with the same limit checks as KvCache so a huge shape fails with a message.
#include "runtime/rows_kv_cache.h"

#include <algorithm>
#include <cstring>
#include <new>
#include <string>

namespace silk {

Status RowsKvCache::Reserve(int32_t slots, int64_t max_capacity, const KvShape& shape, int64_t first) {
  if (slots <= 0 || max_capacity <= 0 || shape.layers <= 0 || shape.heads <= 0 || shape.head_dim <= 0)
    return InvalidArgument("rows kv cache: empty shape");
  if (slots > 1024 || shape.position_values() > (int64_t{1} << 26) || max_capacity > (int64_t{1} << 24))
    return LimitExceeded("rows kv cache: implausible shape");
  const int64_t most = int64_t{slots} * max_capacity * shape.position_bytes();
  if (most > (int64_t{1} << 38))
    return LimitExceeded("rows kv cache: " + std::to_string(slots) + " rows of " + std::to_string(max_capacity) +
                         " positions would take " + std::to_string(most >> 20) + " MiB");
  shape_ = shape;
  max_capacity_ = max_capacity;
  length_.assign(static_cast<size_t>(slots), 0);
  capacity_ = 0;
  data_.reset();
  allocated_ = 0;
  return Ensure(std::min(std::max<int64_t>(first, 1), max_capacity));
}

Status RowsKvCache::Allocate(int64_t capacity, std::unique_ptr<unsigned char[]>* data) {
  const int64_t bytes = slots() * capacity * shape_.position_bytes();
  data->reset(new (std::nothrow) unsigned char[static_cast<size_t>(bytes)]);
  if (!*data) return LimitExceeded("rows kv cache: cannot allocate " + std::to_string(bytes >> 20) + " MiB");
  return Status::Ok();
}

Status RowsKvCache::Ensure(int64_t positions) {
  if (positions <= capacity_) return Status::Ok();
  if (positions > max_capacity_)
    return LimitExceeded("rows kv cache: " + std::to_string(positions) + " positions exceed the limit of " +
                         std::to_string(max_capacity_));
  int64_t grown = std::max<int64_t>(capacity_, 1);
  while (grown < positions) grown *= 2;
  grown = std::min(grown, max_capacity_);
  std::unique_ptr<unsigned char[]> next;
  SILK_RETURN_IF_ERROR(Allocate(grown, &next));
  const int64_t row = shape_.row_bytes(), H = shape_.heads;
  const int64_t old_slot = H * capacity_ * row, new_slot = H * grown * row;
  for (int64_t lk = 0; lk < shape_.layers * 2; ++lk)
    for (int32_t s = 0; s < slots(); ++s) {
      const int64_t filled = length(s) * row;
      if (filled == 0) continue;
      for (int64_t h = 0; h < H; ++h) {
        const unsigned char* from = data_.get() + (lk * slots() + s) * old_slot + h * capacity_ * row;
        std::memcpy(next.get() + (lk * slots() + s) * new_slot + h * grown * row, from, static_cast<size_t>(filled));
      }
    }
  data_ = std::move(next);
  capacity_ = grown;
  allocated_ = slots() * grown * shape_.position_bytes();
  return Status::Ok();
}

void RowsKvCache::Move(int32_t from, int32_t to) {
  if (from == to) return;
  const int64_t row = shape_.row_bytes(), filled = length(from) * row;
  for (int64_t l = 0; l < shape_.layers; ++l)
    for (int kv = 0; kv < 2; ++kv)
      for (int64_t h = 0; h < shape_.heads; ++h) {
        auto* dst = static_cast<unsigned char*>(slot_block(l, kv, to)) + h * capacity_ * row;
        const auto* src = static_cast<const unsigned char*>(slot_block(l, kv, from)) + h * capacity_ * row;
        std::memcpy(dst, src, static_cast<size_t>(filled));
      }
  length_[static_cast<size_t>(to)] = length(from);
  Clear(from);
}

void RowsKvCache::CopyTimeMajor(int32_t slot, float* out) const {
  const int64_t H = shape_.heads, D = shape_.head_dim, row = shape_.row_bytes();
  for (int64_t t = 0; t < length(slot); ++t)
    for (int64_t l = 0; l < shape_.layers; ++l)
      for (int kv = 0; kv < 2; ++kv)
        for (int64_t h = 0; h < H; ++h, out += D) {
          const auto* base = static_cast<const unsigned char*>(slot_block(l, kv, slot));
          CacheRowToFloats(shape_.element(), base + (h * capacity_ + t) * row, D, out);
        }
}

}  // namespace silk
