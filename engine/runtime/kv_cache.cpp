// Cache allocation with an explicit limit check, so a huge model/cap combination fails with a
// message instead of std::bad_alloc.
#include "runtime/kv_cache.h"

#include <cstring>
#include <new>
#include <string>

namespace silk {

Status KvCache::Reserve(int64_t capacity, const KvShape& shape) {
  if (capacity <= 0 || shape.layers <= 0 || shape.heads <= 0 || shape.head_dim <= 0)
    return InvalidArgument("kv cache: empty shape");
  if (shape.position_floats() > (int64_t{1} << 26) || capacity > (int64_t{1} << 24))
    return LimitExceeded("kv cache: implausible shape");
  const int64_t floats = capacity * shape.position_floats();
  if (floats > (int64_t{1} << 34))
    return LimitExceeded("kv cache: " + std::to_string(floats * 4 >> 20) + " MiB is too large");
  capacity_ = capacity;
  shape_ = shape;
  length_ = 0;
  if (allocated_ < floats) {
    data_.reset();
    allocated_ = 0;
    data_.reset(new (std::nothrow) float[static_cast<size_t>(floats)]);
    if (!data_)
      return LimitExceeded("kv cache: cannot allocate " + std::to_string(floats * 4 >> 20) + " MiB");
    allocated_ = floats;
  }
  return Status::Ok();
}

void KvCache::CopyTimeMajor(float* out) const {
  const int64_t H = shape_.heads, D = shape_.head_dim;
  for (int64_t t = 0; t < length_; ++t)
    for (int64_t l = 0; l < shape_.layers; ++l)
      for (int kv = 0; kv < 2; ++kv)
        for (int64_t h = 0; h < H; ++h, out += D)
          std::memcpy(out, block(l, kv) + (h * capacity_ + t) * D, static_cast<size_t>(D) * sizeof(float));
}

}  // namespace silk
