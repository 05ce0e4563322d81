// SPDX-License-Identifier: MIT
// IoMesh: the io layer's mesh (docs/mesh_types.md). What every reader produces and every writer
// takes; mesh/ and EncodeMesh work on it too. Plain arrays, nothing welded or cleaned, so that
// non-manifold and duplicate faces survive to the tokenizer (token_format.md §2.3-§2.4 need them as-is).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace silk {

struct IoMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<int32_t, 3>> triangles;  // 0-based indices into positions
  // Additive reader diagnostics (never affect positions/triangles).
  int64_t polygons_triangulated = 0;  // input faces with > 3 corners, fan-triangulated
  std::vector<std::string> warnings;  // e.g. ignored OBJ statements, skipped glTF primitives
};

}  // namespace silk
