// RawMesh: what every reader produces. Plain arrays, nothing welded or cleaned, so that
// non-manifold and duplicate faces survive to the tokenizer (spec §2.3-§2.4 need them as-is).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace silk {

struct RawMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<int32_t, 3>> triangles;  // 0-based indices into positions
};

}  // namespace silk
