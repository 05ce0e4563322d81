// SPDX-License-Identifier: MIT
// Face scores against the input's points (runtime/sampling/face_guide.h): the distance field of
// surface guidance at points on the face, the input normals nearest it.
#include "runtime/sampling/face_guide.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "runtime/sampling/surface_guide.h"

namespace silk {

namespace {

std::vector<Point3> GridPoints(const std::vector<float>& points) {
  std::vector<Point3> out;
  out.reserve(points.size() / 6);
  for (size_t i = 0; i + 6 <= points.size(); i += 6)
    out.push_back({(points[i] + 1.0) * 64 - 0.5, (points[i + 1] + 1.0) * 64 - 0.5, (points[i + 2] + 1.0) * 64 - 0.5});
  return out;
}

std::vector<Point3> UnitNormals(const std::vector<float>& points) {
  std::vector<Point3> out;
  out.reserve(points.size() / 6);
  for (size_t i = 0; i + 6 <= points.size(); i += 6) {
    const double x = points[i + 3], y = points[i + 4], z = points[i + 5];
    const double n = std::sqrt(x * x + y * y + z * z);
    out.push_back(n > 0 && std::isfinite(n) ? Point3{x / n, y / n, z / n} : Point3{0, 0, 0});
  }
  return out;
}

// floor(v / scale + 1/2) for scale 1..4 and v >= 0: the cell nearest v / scale.
int32_t NearestCell(int32_t v, int32_t scale) {
  const int32_t c = (2 * v + scale) / (2 * scale);
  return std::min(std::max(c, 0), SurfaceGuide::kBins - 1);
}

}  // namespace

const char* FaceGuidanceName(FaceGuidance g) {
  switch (g) {
    case FaceGuidance::kOff:
      return "off";
    case FaceGuidance::kHard:
      return "hard";
    case FaceGuidance::kSoft:
      return "soft";
  }
  return "unknown";
}

bool ParseFaceGuidanceName(const std::string& text, FaceGuidance* out) {
  for (FaceGuidance g : {FaceGuidance::kOff, FaceGuidance::kHard, FaceGuidance::kSoft})
    if (text == FaceGuidanceName(g)) {
      *out = g;
      return true;
    }
  return false;
}

// M_PI is POSIX, not C++17: MinGW's <cmath> has no M_PI without _USE_MATH_DEFINES.
constexpr double kPi = 3.14159265358979323846;  // the double M_PI names

FaceGuide::FaceGuide(std::shared_ptr<const SurfaceGuide> field, const std::vector<float>& points, double tolerance)
    : field_(std::move(field)),
      index_(GridPoints(points)),
      normals_(UnitNormals(points)),
      root_(3 * 127 * 127 + 1),
      tolerance_(tolerance),
      angle_scale_(1.0 / (1.0 - std::cos(kFaceAngleLimitDegrees * kPi / 180.0))),
      fold_cos_(std::cos(kFaceFoldLimitDegrees * kPi / 180.0)) {
  for (size_t i = 0; i < root_.size(); ++i) root_[i] = static_cast<float>(std::sqrt(static_cast<double>(i)));
}

int32_t FaceGuide::NearestPoint(const QVec& q) const {
  return index_.Nearest({double(q.x), double(q.y), double(q.z)}).index;
}

double FaceGuide::Distance(int32_t x, int32_t y, int32_t z, int32_t scale) const {
  const QVec c{NearestCell(x, scale), NearestCell(y, scale), NearestCell(z, scale)};
  const int32_t d2 = field_->CellDistance2(c);  // no input point at all: "far" (beyond the table)
  return d2 < static_cast<int32_t>(root_.size()) ? root_[static_cast<size_t>(d2)] : std::sqrt(static_cast<double>(d2));
}

double FaceGuide::EdgeInterior(const QVec& a, const QVec& b) const {
  double d = Distance(a.x + b.x, a.y + b.y, a.z + b.z, 2);
  d = std::max(d, Distance(3 * a.x + b.x, 3 * a.y + b.y, 3 * a.z + b.z, 4));
  d = std::max(d, Distance(a.x + 3 * b.x, a.y + 3 * b.y, a.z + 3 * b.z, 4));
  return d / tolerance_;
}

double FaceGuide::EdgeScore(const QVec& a, const QVec& b) const {
  const double ends = std::max(Distance(a.x, a.y, a.z, 1), Distance(b.x, b.y, b.z, 1)) / tolerance_;
  return std::max(ends, EdgeInterior(a, b));
}

double FaceGuide::FoldScore(const QVec& x, const QVec& y, const QVec& p, const QVec& q) const {
  const double ex = y.x - x.x, ey = y.y - x.y, ez = y.z - x.z, e2 = ex * ex + ey * ey + ez * ez;
  if (e2 == 0) return 0;
  // The parts of p - x and q - x perpendicular to the edge; the angle between them.
  auto perp = [&](const QVec& r, double* o) {
    const double rx = r.x - x.x, ry = r.y - x.y, rz = r.z - x.z, t = (rx * ex + ry * ey + rz * ez) / e2;
    o[0] = rx - t * ex, o[1] = ry - t * ey, o[2] = rz - t * ez;
    return o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
  };
  double a[3], b[3];
  const double la = perp(p, a), lb = perp(q, b);
  if (la == 0 || lb == 0) return 0;
  const double cos_t = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / std::sqrt(la * lb);
  if (cos_t <= fold_cos_) return (1 + cos_t) / (1 + fold_cos_);
  return 1 + kFaceFoldSpan * (cos_t - fold_cos_) / (1 - fold_cos_);
}

double FaceGuide::FaceDistance(const QVec& a, const QVec& b, const QVec& c) const {
  const double d = std::max(EdgeScore(a, b), std::max(EdgeScore(b, c), EdgeScore(c, a)));
  return std::max(d, Distance(a.x + b.x + c.x, a.y + b.y + c.y, a.z + b.z + c.z, 3) / tolerance_);
}

double FaceGuide::FaceScore(const QVec& a, const QVec& b, const QVec& c, int32_t n_a, int32_t n_b, int32_t n_c) const {
  const double d = FaceDistance(a, b, c);
  if (d > 1) return d;  // strays by distance: the normal cannot save it (and its query is skipped)
  // The face's normal against the input normals nearest its centroid and corners, up to sign.
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
  if (len == 0 || normals_.empty()) return d;  // zero area: the decoder drops it; no normal to judge
  const Point3 centroid{(a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0, (a.z + b.z + c.z) / 3.0};
  const int32_t near[4] = {index_.Nearest(centroid).index, n_a, n_b, n_c};
  double agree = 0;
  int32_t counted = 0;  // points with a normal (a zero normal says nothing)
  for (int32_t i : near) {
    if (i < 0) continue;
    const Point3& m = normals_[static_cast<size_t>(i)];
    if (m[0] == 0 && m[1] == 0 && m[2] == 0) continue;
    agree += std::fabs(nx * m[0] + ny * m[1] + nz * m[2]) / len;
    ++counted;
  }
  if (counted == 0) return d;
  const double a_term = (1.0 - agree / counted) * angle_scale_;
  return std::max(d, a_term);
}

}  // namespace silk
