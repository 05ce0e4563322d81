// SPDX-License-Identifier: MIT
// Bounding-box normalisation (token_format.md §2.1), written operation by operation as the spec gives it.
#include "mesh/normalize.h"

#include <cmath>

#include "core/value_text.h"

namespace silk {

StatusOr<NormalizeTransform> ComputeNormalization(const IoMesh& mesh, double bound) {
  if (mesh.positions.empty()) return InvalidArgument("mesh has no vertices");
  std::array<double, 3> lo = mesh.positions[0], hi = mesh.positions[0];
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(p[a])) return InvalidArgument("vertex " + std::to_string(i) + " has a non-finite coordinate");
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
  // Extreme scales (1e-300, 1e300 and beyond) normalise fine down to what a double holds; past
  // that the centre or the scale would be infinite or denormal and every point garbage.
  if (!std::isnormal(t.scale) || !std::isnormal(extent) || !std::isfinite(t.center[0]) || !std::isfinite(t.center[1]) ||
      !std::isfinite(t.center[2]))
    return InvalidArgument("coordinates out of range: the extent " + ValueText(extent) +
                           " cannot be normalised (a double's range ends near 1e-308 and 1e308)");
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
