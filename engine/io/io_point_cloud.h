// SPDX-License-Identifier: MIT
// IoPointCloud: what the point-cloud readers produce (a PLY without faces, an XYZ file): the
// points in an IoMesh without triangles and, when the file carries them, one normal per point.
#pragma once
#include <array>
#include <vector>

#include "io/io_mesh.h"

namespace silk {

struct IoPointCloud {
  IoMesh mesh;                                 // positions; triangles only for a PLY that has faces
  std::vector<std::array<double, 3>> normals;  // empty (the file has none) or one per position, as read
};

}  // namespace silk
