// SPDX-License-Identifier: MIT
// libFuzzer target: arbitrary bytes through ReadPlyPointCloud, silkgen's point-cloud input path
// (faces optional, normals read when present); a successful read promises finite positions and
// normals, one normal per point or none, and face indices in range.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/ply/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  silk::ReadOptions opts;
  opts.max_vertices = 4'000'000;
  opts.max_triangles = 4'000'000;
  opts.max_file_bytes = 64u << 20;
  auto pc = silk::ReadPlyPointCloud(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply", opts);
  if (!pc.ok()) {
    if (pc.status().message().empty()) __builtin_trap();
    return 0;
  }
  const auto& m = pc->mesh;
  if (!pc->normals.empty() && pc->normals.size() != m.positions.size()) __builtin_trap();
  for (const auto& p : m.positions)
    for (double c : p)
      if (!std::isfinite(c)) __builtin_trap();
  for (const auto& n : pc->normals)
    for (double c : n)
      if (!std::isfinite(c)) __builtin_trap();
  const int64_t count = static_cast<int64_t>(m.positions.size());
  for (const auto& t : m.triangles)
    for (int32_t v : t)
      if (v < 0 || v >= count) __builtin_trap();
  return 0;
}
