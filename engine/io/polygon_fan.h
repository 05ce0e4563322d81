// Fan triangulation of a polygon given as vertex indices: (v0, vi, vi+1) for i = 1..n-2.
// Documented reader behaviour for faces with more than 3 corners (OBJ, OFF, PLY, STL loops).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "io/io_mesh.h"

namespace silk {

inline void AppendFan(const int32_t* corners, size_t n, IoMesh* mesh) {
  for (size_t i = 1; i + 1 < n; ++i)
    mesh->triangles.push_back({corners[0], corners[i], corners[i + 1]});
  if (n > 3) ++mesh->polygons_triangulated;
}

}  // namespace silk
