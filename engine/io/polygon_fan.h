// SPDX-License-Identifier: MIT
// Fan triangulation of a polygon given as vertex indices: (v0, vi, vi+1) for i = 1..n-2.
// Documented reader behaviour for faces with more than 3 corners (OBJ, OFF, PLY, STL loops).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/io_mesh.h"
#include "io/read_error.h"
#include "io/read_options.h"

namespace silk {

inline void AppendFan(const int32_t* corners, size_t n, IoMesh* mesh) {
  for (size_t i = 1; i + 1 < n; ++i) mesh->triangles.push_back({corners[0], corners[i], corners[i + 1]});
  if (n > 3) ++mesh->polygons_triangulated;
}

// AppendFan after the triangle-limit check the OBJ, OFF, PLY and STL readers share
// ("<name>: more than <max_triangles> triangles"). `corners` holds at least 3 indices.
inline Status AppendFanWithinLimit(const std::vector<int32_t>& corners, const std::string& name,
                                   const ReadOptions& opts, IoMesh* mesh) {
  if (mesh->triangles.size() + corners.size() - 2 > opts.max_triangles)
    return LimitErrorIn(name, "more than " + std::to_string(opts.max_triangles) + " triangles");
  AppendFan(corners.data(), corners.size(), mesh);
  return Status::Ok();
}

}  // namespace silk
