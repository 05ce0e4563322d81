// SPDX-License-Identifier: MIT
// libFuzzer target: arbitrary bytes through ReadXyz, the plain-text point-cloud reader (.xyz,
// .pts); a successful read promises at least one finite point, no faces, and either no normals
// or one finite, unit-length (within 10 %) normal per point.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/xyz/xyz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  silk::ReadOptions opts;
  opts.max_vertices = 4'000'000;
  opts.max_file_bytes = 64u << 20;
  auto pc = silk::ReadXyz(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.xyz", opts);
  if (!pc.ok()) {
    if (pc.status().message().empty()) __builtin_trap();
    return 0;
  }
  const auto& m = pc->mesh;
  if (m.positions.empty() || !m.triangles.empty()) __builtin_trap();
  if (!pc->normals.empty() && pc->normals.size() != m.positions.size()) __builtin_trap();
  for (const auto& p : m.positions)
    for (double c : p)
      if (!std::isfinite(c)) __builtin_trap();
  for (const auto& n : pc->normals) {
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(std::fabs(len - 1) <= 0.1)) __builtin_trap();
  }
  return 0;
}
