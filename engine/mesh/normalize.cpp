// SPDX-License-Identifier: MIT
// Bounding-box normalisation (token_format.md §2.1), written operation by operation as the spec gives it.
#include "mesh/normalize.h"

#include <cmath>

namespace silk {

StatusOr<NormalizeTransform> ComputeNormalization(const IoMesh& mesh, double bound) {
  if (mesh.positions.empty()) return InvalidArgument("mesh has no vertices");
  std::array<double, 3> lo = mesh.positions[0], hi = mesh.positions[0];
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(p[a]))
        return InvalidArgument("vertex " + std::to_string(i) + " has a non-finite coordinate");
      if (p[a] < lo[a]) lo[a] = p[a];
      if (p[a] > hi[a]) hi[a] = p[a];
    }
  }
  NormalizeTransform t;
  double extent = 0.0;
  for (int a = 0; a < 3; ++a) {
    t.center[a] = (hi[a] + lo[a]) / 2.0;
    const double e = hi[a] - lo[a];
    if (e > extent) extent = e;
  }
  if (!(extent > 0.0) || !std::isfinite(extent))
    return InvalidArgument("mesh has zero or infinite extent (all vertices coincide?)");
  const double two_bound = 2.0 * bound;
  t.scale = two_bound / extent;
  return t;
}

IoMesh ApplyNormalization(const IoMesh& mesh, const NormalizeTransform& t) {
  IoMesh out = mesh;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const double d = mesh.positions[i][a] - t.center[a];
      out.positions[i][a] = d * t.scale;
    }
  }
  return out;
}

std::array<double, 3> UndoNormalization(const std::array<double, 3>& p, const NormalizeTransform& t) {
  return {p[0] / t.scale + t.center[0], p[1] / t.scale + t.center[1], p[2] / t.scale + t.center[2]};
}

StatusOr<IoMesh> NormalizeMesh(const IoMesh& mesh, double bound) {
  SILK_ASSIGN_OR_RETURN(NormalizeTransform t, ComputeNormalization(mesh, bound));
  return ApplyNormalization(mesh, t);
}

}  // namespace silk
