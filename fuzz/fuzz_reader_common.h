// SPDX-License-Identifier: MIT
// Shared body of the reader fuzzers: read the bytes as one format through the public
// ReadMeshFromMemory and check what a successful read promises (indices in range, finite).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "io/mesh_reader.h"

namespace silk::fuzz {

inline int FuzzReadMesh(const uint8_t* data, size_t size, MeshFormat fmt, const char* name) {
  ReadOptions opts;
  opts.max_vertices = 4'000'000;  // keep well inside libFuzzer's rss limit
  opts.max_triangles = 4'000'000;
  opts.max_file_bytes = 64u << 20;
  StatusOr<IoMesh> m = ReadMeshFromMemory(data, size, fmt, name, opts);
  if (!m.ok()) {
    if (m.status().message().empty()) __builtin_trap();  // every error must say something
    return 0;
  }
  if (m->triangles.empty()) __builtin_trap();  // "no faces" must be an error
  const int64_t n = static_cast<int64_t>(m->positions.size());
  for (const auto& t : m->triangles)
    for (int32_t v : t)
      if (v < 0 || v >= n) __builtin_trap();
  for (const auto& p : m->positions)
    for (double c : p)
      if (!std::isfinite(c)) __builtin_trap();
  return 0;
}

}  // namespace silk::fuzz
