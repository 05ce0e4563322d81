// SPDX-License-Identifier: MIT
// Output-mesh consistency check shared by the OBJ and PLY writers.
#include "io/mesh_validation.h"

#include <cmath>
#include <string>

namespace silk {

Status ValidateOutputMesh(const IoMesh& mesh) {
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (double c : mesh.positions[i])
      if (!std::isfinite(c)) return InvalidArgument("vertex " + std::to_string(i) + " has a non-finite coordinate");
  const int64_t n = static_cast<int64_t>(mesh.positions.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int32_t v : mesh.triangles[f])
      if (v < 0 || v >= n)
        return InvalidArgument("triangle " + std::to_string(f) + ": index " + std::to_string(v) + " out of range (" +
                               std::to_string(n) + " vertices)");
  return Status::Ok();
}

}  // namespace silk
