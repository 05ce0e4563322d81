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
};

// The vertex limit the readers enforce: max_vertices, capped at INT32_MAX.
inline uint64_t VertexLimit(const ReadOptions& opts) {
  return std::min<uint64_t>(opts.max_vertices, INT32_MAX);
}

}  // namespace silk
