// SPDX-License-Identifier: MIT
// Surface sampling by cumulative face areas (binary search per sample) and SplitMix64 draws.
#include "mesh/surface_sampling.h"

#include <algorithm>
#include <cmath>

#include "core/splitmix64.h"

namespace silk {

namespace {

using V3 = std::array<double, 3>;
V3 Sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 Cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double Norm(const V3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

}  // namespace

StatusOr<std::vector<OrientedPoint>> SampleSurface(const IoMesh& mesh, int32_t count, uint64_t seed,
                                                   const CancelCheck& cancel) {
  if (count <= 0) return InvalidArgument("surface sampling: sample count must be positive");
  std::vector<double> cumulative;
  std::vector<int32_t> face_of;
  cumulative.reserve(mesh.triangles.size());
  double total = 0;
  const int64_t nv = static_cast<int64_t>(mesh.positions.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= nv || t[1] >= nv || t[2] >= nv)
      return InvalidArgument("surface sampling: triangle " + std::to_string(f) + " has an index out of range");
    const double area = 0.5 * Norm(Cross(Sub(mesh.positions[t[1]], mesh.positions[t[0]]),
                                         Sub(mesh.positions[t[2]], mesh.positions[t[0]])));
    if (!(area > 0) || !std::isfinite(area)) continue;
    total += area;
    cumulative.push_back(total);
    face_of.push_back(static_cast<int32_t>(f));
  }
  if (cumulative.empty()) return InvalidArgument("surface sampling: the mesh has no face with positive area");
  SplitMix64 rng(seed);
  std::vector<OrientedPoint> out;
  out.reserve(static_cast<size_t>(count));
  for (int32_t i = 0; i < count; ++i) {
    if (i % kCancelPollInterval == 0 && CancelRequested(cancel)) return CancelledStatus("surface sampling");
    const double u = rng.Uniform() * total;
    size_t k = static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
    k = std::min(k, cumulative.size() - 1);
    const auto& t = mesh.triangles[face_of[k]];
    const V3& a = mesh.positions[t[0]];
    const V3& b = mesh.positions[t[1]];
    const V3& c = mesh.positions[t[2]];
    const double r1 = std::sqrt(rng.Uniform()), r2 = rng.Uniform();
    const double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2;
    OrientedPoint p;
    for (int d = 0; d < 3; ++d) p.position[d] = wa * a[d] + wb * b[d] + wc * c[d];
    V3 n = Cross(Sub(b, a), Sub(c, a));
    const double len = Norm(n);
    for (int d = 0; d < 3; ++d) p.normal[d] = n[d] / len;
    out.push_back(p);
  }
  return out;
}

std::vector<OrientedPoint> SubsamplePoints(const std::vector<OrientedPoint>& points, int32_t count, uint64_t seed) {
  if (count <= 0 || points.size() <= static_cast<size_t>(count)) return points;
  std::vector<int64_t> idx(points.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int64_t>(i);
  SplitMix64 rng(seed);
  std::vector<OrientedPoint> out;
  out.reserve(static_cast<size_t>(count));
  for (int32_t i = 0; i < count; ++i) {
    const uint64_t left = idx.size() - static_cast<size_t>(i);
    const size_t j = static_cast<size_t>(i) + static_cast<size_t>(rng.Next() % left);
    std::swap(idx[static_cast<size_t>(i)], idx[j]);
    out.push_back(points[static_cast<size_t>(idx[static_cast<size_t>(i)])]);
  }
  return out;
}

}  // namespace silk
