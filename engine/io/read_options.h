// SPDX-License-Identifier: MIT
// ReadOptions: resource limits every reader checks against header counts before it
// allocates, so a lying header fails fast instead of exhausting memory.
#pragma once
#include <algorithm>
#include <cstdint>

namespace silk {

struct ReadOptions {
  uint64_t max_vertices = 50'000'000;  // never above INT32_MAX (triangle indices are int32)
  uint64_t max_triangles = 50'000'000;
  uint64_t max_file_bytes = uint64_t{4} << 30;  // also caps the size after gzip inflation
  // gzip inflation bound (decompression bombs): a .gz input inflates to at most
  // max(max_inflated_bytes, max_inflation_ratio * its compressed size), and never past
  // max_file_bytes. A reader needs up to about 7 bytes of memory per input byte (an OBJ of
  // "v 0 0 0" lines), so a 64 MiB floor keeps a bomb under 512 MB while any .gz still reads
  // like an uncompressed file 32 times its size.
  uint64_t max_inflated_bytes = uint64_t{64} << 20;
  uint64_t max_inflation_ratio = 32;
};

// The vertex limit the readers enforce: max_vertices, capped at INT32_MAX.
inline uint64_t VertexLimit(const ReadOptions& opts) { return std::min<uint64_t>(opts.max_vertices, INT32_MAX); }

// The most bytes a gzip input of gz_bytes compressed bytes may inflate to (see ReadOptions).
inline uint64_t InflatedLimit(const ReadOptions& opts, uint64_t gz_bytes) {
  const uint64_t ratio = std::min<uint64_t>(opts.max_inflation_ratio, UINT64_MAX / std::max<uint64_t>(gz_bytes, 1));
  return std::min(opts.max_file_bytes, std::max(opts.max_inflated_bytes, ratio * gz_bytes));
}

}  // namespace silk
