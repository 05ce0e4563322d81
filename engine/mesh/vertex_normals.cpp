// SPDX-License-Identifier: MIT
// Cross products are already area-weighted (|a x b| = 2 * area), so they are summed as is.
#include "mesh/vertex_normals.h"

#include <cmath>

namespace silk {

std::vector<std::array<double, 3>> SmoothVertexNormals(const IoMesh& mesh) {
  std::vector<std::array<double, 3>> n(mesh.positions.size(), {0, 0, 0});
  for (const auto& t : mesh.triangles) {
    const auto& a = mesh.positions[t[0]];
    const auto& b = mesh.positions[t[1]];
    const auto& c = mesh.positions[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double f[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) n[t[k]][d] += f[d];
  }
  for (auto& v : n) {
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0 && std::isfinite(len))
      v = {v[0] / len, v[1] / len, v[2] / len};
    else
      v = {0, 0, 1};
  }
  return n;
}

}  // namespace silk
