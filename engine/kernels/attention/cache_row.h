// SPDX-License-Identifier: MIT
// The one layout of a cached key/value row (one position of one kv head), shared by the ai.silk
// attention kernels and by the runtime's KV cache (runtime/kv_cache.h), so that the bytes the
// cache allocates and the bytes the kernels read can never disagree.
#pragma once
#include <cstddef>
#include <cstdint>

namespace silk {

enum class CacheElement { kFloat32, kFloat16, kInt8 };
// Bytes of one cached row (one position of one kv head): head_dim floats or float16s, or for
// kInt8 head_dim int8 values followed by the row's float32 scale (value i = int8[i] * scale;
// the 4 bytes are the float's own, as memcpy writes them: little-endian on every target).
size_t CacheRowBytes(CacheElement element, int64_t head_dim);
// Elements of the cache tensor's last dimension: head_dim, or head_dim + 4 for kInt8.
int64_t CacheRowElements(CacheElement element, int64_t head_dim);
// The row's head_dim values as float32: float16 widened exactly, int8 dequantized (value x scale).
void CacheRowToFloats(CacheElement element, const unsigned char* row, int64_t head_dim, float* out);

}  // namespace silk
