// SPDX-License-Identifier: MIT
// Row sizes and the row-to-float32 reading of cache_row.h (tests and diagnostics read a cache
// through it; the kernels' fast paths read rows in attention_rows.cpp).
#include "kernels/attention/cache_row.h"

#include <cstring>

#include "kernels/cpu/float16.h"

namespace silk {

int64_t CacheRowElements(CacheElement element, int64_t head_dim) {
  return element == CacheElement::kInt8 ? head_dim + 4 : head_dim;
}

size_t CacheRowBytes(CacheElement element, int64_t head_dim) {
  const size_t element_bytes = element == CacheElement::kFloat32 ? 4 : element == CacheElement::kFloat16 ? 2 : 1;
  return static_cast<size_t>(CacheRowElements(element, head_dim)) * element_bytes;
}

void CacheRowToFloats(CacheElement element, const unsigned char* row, int64_t head_dim, float* out) {
  if (element == CacheElement::kFloat32) {
    std::memcpy(out, row, static_cast<size_t>(head_dim) * sizeof(float));
  } else if (element == CacheElement::kFloat16) {
    uint16_t half[1];
    for (int64_t i = 0; i < head_dim; ++i) {
      std::memcpy(half, row + 2 * i, 2);
      out[i] = HalfToFloat(half[0]);
    }
  } else {
    float scale;
    std::memcpy(&scale, row + head_dim, sizeof(float));
    for (int64_t i = 0; i < head_dim; ++i) out[i] = static_cast<float>(static_cast<int8_t>(row[i])) * scale;
  }
}

}  // namespace silk
