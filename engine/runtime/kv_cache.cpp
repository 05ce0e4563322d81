// Cache allocation with an explicit limit check, so a huge model/cap combination fails with a
// message instead of std::bad_alloc.
#include "runtime/kv_cache.h"

#include <new>
#include <string>

namespace silk {

Status KvCache::Reserve(int64_t capacity, int64_t row_floats) {
  if (capacity <= 0 || row_floats <= 0) return InvalidArgument("kv cache: empty shape");
  const int64_t floats = capacity * row_floats;
  if (floats > (int64_t{1} << 34))
    return LimitExceeded("kv cache: " + std::to_string(floats * 4 >> 20) + " MiB is too large");
  capacity_ = capacity;
  row_floats_ = row_floats;
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

}  // namespace silk
