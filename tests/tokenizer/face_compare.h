// SPDX-License-Identifier: MIT
// Test helper: compares decoded faces with the processed mesh of the goldens by grid
// coordinates, the way spec/golden-dev/README.md defines it (same corners, same cyclic order).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tokenizer/cleanup/quantize.h"
#include "tokenizer/tokenizer.h"

namespace silk::testing {

using CoordFace = std::array<QVec, 3>;

struct FaceComparison {
  int64_t target = 0;       // representable faces (processed minus unencodable)
  int64_t recovered = 0;    // target faces decoded with the same winding
  int64_t reversed = 0;     // target faces decoded with the opposite winding
  int64_t missing = 0;      // target faces not decoded at all
  int64_t extra_hole = 0;   // decoded non-target faces whose 3 edges are boundary edges of the target
  int64_t extra_other = 0;  // other decoded non-target faces
};

std::vector<int32_t> ReadIds(const std::string& path);
// 9 integers per line.
std::vector<CoordFace> ReadCoordFaces(const std::string& path);
std::vector<CoordFace> FacesAsCoords(const TokenizerDecodedMesh& mesh);
FaceComparison CompareFaces(const std::vector<CoordFace>& decoded, const std::vector<CoordFace>& target);
// Invariants: no edge (by vertex index) with > 2 faces, no directed edge used twice,
// no degenerate face. Returns "" or a description of the first violation.
std::string CheckManifoldOriented(const TokenizerDecodedMesh& mesh);

}  // namespace silk::testing
