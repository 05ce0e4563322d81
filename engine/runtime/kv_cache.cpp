// SPDX-License-Identifier: MIT
// Cache allocation with an explicit limit check, so a huge model/cap combination fails with a
// message instead of std::bad_alloc.
#include "runtime/kv_cache.h"

#include <new>
#include <string>

#include "runtime/model/ort_support.h"

namespace silk {

Status KvCache::Reserve(int64_t capacity, const KvShape& shape) {
  if (capacity <= 0 || shape.layers <= 0 || shape.heads <= 0 || shape.head_dim <= 0)
    return InvalidArgument("kv cache: empty shape");
  if (shape.position_values() > (int64_t{1} << 26) || capacity > (int64_t{1} << 24))
    return LimitExceeded("kv cache: implausible shape");
  const int64_t bytes = capacity * shape.position_bytes();
  if (bytes > (int64_t{1} << 36))
    return LimitExceeded("kv cache: " + std::to_string(bytes >> 20) + " MiB is too large");
  capacity_ = capacity;
  shape_ = shape;
  length_ = 0;
  if (allocated_ < bytes) {
    data_.reset();
    allocated_ = 0;
    data_.reset(new (std::nothrow) unsigned char[static_cast<size_t>(bytes)]);
    if (!data_) return LimitExceeded("kv cache: cannot allocate " + std::to_string(bytes >> 20) + " MiB");
    allocated_ = bytes;
  }
  return Status::Ok();
}

void KvCache::CopyTimeMajor(float* out) const {
  const int64_t H = shape_.heads, D = shape_.head_dim, row = shape_.row_bytes();
  for (int64_t t = 0; t < length_; ++t)
    for (int64_t l = 0; l < shape_.layers; ++l)
      for (int kv = 0; kv < 2; ++kv)
        for (int64_t h = 0; h < H; ++h, out += D) {
          const auto* base = static_cast<const unsigned char*>(block(l, kv));
          CacheRowToFloats(shape_.element(), base + (h * capacity_ + t) * row, D, out);
        }
}

}  // namespace silk
