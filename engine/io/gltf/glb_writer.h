// SPDX-License-Identifier: MIT
// Binary glTF (GLB) output of generated meshes: one node + mesh per part ("part_000", ...),
// each with POSITION, smooth NORMAL and optionally a per-part COLOR_0, 32-bit indices.
// Written by hand (JSON chunk + BIN chunk); atomically.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"

namespace silk {

struct GlbPart {
  std::string name;
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 3>> normals;  // empty, or one per position
  std::vector<std::array<uint32_t, 3>> triangles;
  std::optional<std::array<float, 3>> color;  // linear RGB in [0, 1], written as COLOR_0
};

StatusOr<std::string> FormatGlb(const std::vector<GlbPart>& parts, const std::string& generator = "silk");
Status WriteGlbFile(const std::string& path, const std::vector<GlbPart>& parts, const std::string& generator = "silk");

}  // namespace silk
