// SPDX-License-Identifier: MIT
// Smooth per-vertex normals (area-weighted sum of incident face normals) for viewers: the
// GLB output carries them so generated parts shade smoothly.
#pragma once
#include <array>
#include <vector>

#include "io/io_mesh.h"

namespace silk {

// One unit normal per position; (0, 0, 1) for a vertex without faces of positive area.
std::vector<std::array<double, 3>> SmoothVertexNormals(const IoMesh& mesh);

}  // namespace silk
