// SPDX-License-Identifier: MIT
// Normal estimation (mesh/nearest_points, plane_fit, normal_orientation, normal_estimation) on clouds
// whose true normals are known exactly: a sphere (radial, outward), a plane (+-z, one sign), a
// cube's faces (the face normals, outward, away from the edges); the k-d tree against brute
// force; the Jacobi eigen-decomposition against its definition; determinism and refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/splitmix64.h"
#include "mesh/distinct_points.h"
#include "mesh/normal_estimation.h"
#include "mesh/plane_fit.h"
#include "mesh/nearest_points.h"

namespace silk {
namespace {

double Dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

TEST(PointKnn, MatchesBruteForceWithTiesAndDuplicates) {
  SplitMix64 rng(5);
  std::vector<Point3> pts;
  for (int i = 0; i < 600; ++i)  // on a coarse lattice: many equal distances and some repeated points
    pts.push_back({std::floor(rng.Uniform() * 8), std::floor(rng.Uniform() * 8), std::floor(rng.Uniform() * 3)});
  const KnnGraph g = NearestNeighbors(pts, 12);
  ASSERT_EQ(g.k, 12);
  for (size_t i = 0; i < pts.size(); ++i) {
    std::vector<std::pair<double, int32_t>> all;
    for (size_t j = 0; j < pts.size(); ++j)
      if (j != i) {
        const Point3 d{pts[j][0] - pts[i][0], pts[j][1] - pts[i][1], pts[j][2] - pts[i][2]};
        all.push_back({Dot(d, d), static_cast<int32_t>(j)});
      }
    std::sort(all.begin(), all.end());
    for (int s = 0; s < g.k; ++s) ASSERT_EQ(g.Of(i)[s], all[s].second) << "point " << i << " rank " << s;
  }
  EXPECT_EQ(NearestNeighbors(std::vector<Point3>(3, Point3{1, 1, 1}), 8).k, 2);  // min(k, n - 1)
}

TEST(PlaneFit, JacobiEigenpairsSatisfyTheirDefinition) {
  SplitMix64 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    Matrix3 m{};
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c) m[r][c] = m[c][r] = (rng.Uniform() - 0.5) * std::pow(10.0, trial % 7 - 3);
    const SymmetricEigen3 e = EigenSymmetric3(m);
    const double scale = std::max({std::fabs(e.eigenvalues[0]), std::fabs(e.eigenvalues[2]), 1e-300});
    EXPECT_LE(e.eigenvalues[0], e.eigenvalues[1]);
    EXPECT_LE(e.eigenvalues[1], e.eigenvalues[2]);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(Dot(e.eigenvectors[i], e.eigenvectors[i]), 1, 1e-12);
      for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(Dot(e.eigenvectors[i], e.eigenvectors[j]), 0, 1e-10);
      for (int r = 0; r < 3; ++r)  // (M v)_r = lambda v_r
        EXPECT_NEAR(Dot(m[r], e.eigenvectors[i]), e.eigenvalues[i] * e.eigenvectors[i][r], 1e-10 * scale);
    }
  }
}

// n points spread evenly over a sphere (Fibonacci lattice).
std::vector<Point3> Sphere(int n, const Point3& c, double r) {
  std::vector<Point3> pts;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2.0 * i + 1) / n, rho = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
    pts.push_back({c[0] + r * rho * std::cos(phi), c[1] + r * rho * std::sin(phi), c[2] + r * z});
  }
  return pts;
}

TEST(NormalEstimation, SphereNormalsAreRadialAndOutward) {
  const Point3 c{1, -2, 3};
  for (int k : {8, 16, 24}) {
    const auto pts = Sphere(3000, c, 2.5);
    auto n = EstimateNormals(pts, NormalEstimationParams{k});
    ASSERT_TRUE(n.ok()) << n.status().ToString();
    double worst = 1;
    for (size_t i = 0; i < pts.size(); ++i) {
      const Point3 radial{(pts[i][0] - c[0]) / 2.5, (pts[i][1] - c[1]) / 2.5, (pts[i][2] - c[2]) / 2.5};
      EXPECT_NEAR(Dot((*n)[i], (*n)[i]), 1, 1e-12);
      worst = std::min(worst, Dot((*n)[i], radial));
    }
    EXPECT_GT(worst, 0.99) << "k " << k;  // radial, and every one outward
  }
}

TEST(NormalEstimation, PlaneNormalsAreOneSignOfZ) {
  SplitMix64 rng(3);
  std::vector<Point3> pts;
  for (int i = 0; i < 1600; ++i) pts.push_back({rng.Uniform() * 10 - 5, rng.Uniform() * 4, 0.5});
  auto n = EstimateNormals(pts);
  ASSERT_TRUE(n.ok());
  const double sign = (*n)[0][2] > 0 ? 1 : -1;
  for (const Point3& v : *n) EXPECT_GT(sign * v[2], 0.999999);
}

TEST(NormalEstimation, CubeFacesGetTheirOutwardNormals) {
  std::vector<Point3> pts, truth;
  const int g = 30;  // g x g points per face of the cube [-1, 1]^3
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0})
      for (int u = 0; u < g; ++u)
        for (int v = 0; v < g; ++v) {
          Point3 p, t{0, 0, 0};
          p[axis] = side, t[axis] = side;
          p[(axis + 1) % 3] = -1 + 2 * (u + 0.5) / g, p[(axis + 2) % 3] = -1 + 2 * (v + 0.5) / g;
          pts.push_back(p), truth.push_back(t);
        }
  auto n = EstimateNormals(pts);
  ASSERT_TRUE(n.ok());
  int interior = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    int axis = 0;
    while (truth[i][axis] == 0) ++axis;
    const double edge = std::min(1 - std::fabs(pts[i][(axis + 1) % 3]), 1 - std::fabs(pts[i][(axis + 2) % 3]));
    EXPECT_GT(Dot((*n)[i], truth[i]), 0) << "point " << i << " faces inward";  // all outward, edges too
    if (edge > 4.0 / g) {  // away from the edges (neighbourhoods within one face): the exact face normal
      EXPECT_GT(Dot((*n)[i], truth[i]), 0.999999) << "point " << i;
      ++interior;
    }
  }
  EXPECT_GT(interior, 6 * 400);
}

TEST(NormalEstimation, DeterministicAndRefusesWhatItCannotFit) {
  SplitMix64 rng(9);
  std::vector<Point3> pts;
  for (int i = 0; i < 2000; ++i) {
    const double a = rng.Uniform() * 6.283185307179586, b = rng.Uniform() * 6.283185307179586;
    pts.push_back({(2 + 0.7 * std::cos(b)) * std::cos(a), (2 + 0.7 * std::cos(b)) * std::sin(a), 0.7 * std::sin(b)});
  }
  auto a = EstimateNormals(pts), b = EstimateNormals(pts);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(*a, *b);  // bit for bit
  auto two = EstimateNormals({{0, 0, 0}, {1, 0, 0}});
  ASSERT_FALSE(two.ok());
  EXPECT_NE(two.status().message().find("at least 3"), std::string::npos) << two.status().ToString();
  auto nan = EstimateNormals({{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}});
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.status().message().find("point 2"), std::string::npos);
  EXPECT_FALSE(EstimateNormals(pts, NormalEstimationParams{2}).ok());
  // Collinear and coincident neighbourhoods still give unit normals (some direction), never NaN.
  auto line = EstimateNormals({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, 0}});
  ASSERT_TRUE(line.ok());
  for (const Point3& v : *line) EXPECT_NEAR(Dot(v, v), 1, 1e-12);
}

std::vector<Point3> TorusCloud(int n, uint64_t seed) {
  SplitMix64 rng(seed);
  std::vector<Point3> pts;
  for (int i = 0; i < n; ++i) {
    const double a = rng.Uniform() * 6.283185307179586, b = rng.Uniform() * 6.283185307179586;
    pts.push_back({(2 + 0.7 * std::cos(b)) * std::cos(a), (2 + 0.7 * std::cos(b)) * std::sin(a), 0.7 * std::sin(b)});
  }
  return pts;
}

// Issue 35 item 7: duplicates are merged before the neighbour search. Every copy of a point gets
// the normal the point has in the cloud without copies (before: a copy's neighbours were its own
// copies, an empty plane, and n identical points took O(n^2): 100,000 took minutes).
TEST(NormalEstimation, DuplicatePointsAreMergedAndEachCopyGetsItsPositionsNormal) {
  const std::vector<Point3> distinct = TorusCloud(1500, 21);
  std::vector<Point3> copies;
  for (int c = 0; c < 40; ++c)  // 40 copies of each, interleaved (copy c of point i at c * 1500 + i)
    copies.insert(copies.end(), distinct.begin(), distinct.end());
  auto want = EstimateNormals(distinct), got = EstimateNormals(copies);
  ASSERT_TRUE(want.ok() && got.ok()) << got.status().ToString();
  ASSERT_EQ(got->size(), copies.size());
  for (size_t i = 0; i < copies.size(); ++i) ASSERT_EQ((*got)[i], (*want)[i % distinct.size()]) << i;
  auto merged = MergeDuplicatePoints(copies);
  EXPECT_TRUE(merged.merged());
  EXPECT_EQ(merged.points, distinct);
  EXPECT_FALSE(MergeDuplicatePoints(distinct).merged());  // nothing copied when there is nothing to merge
}

TEST(NormalEstimation, IdenticalPointsAreRefusedNamingTheCount) {
  const std::vector<Point3> same(100000, Point3{0.25, -1, 3});
  auto r = EstimateNormals(same);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("the 100000 points lie at 1 distinct position(s), at least 3 are needed"),
            std::string::npos)
      << r.status().ToString();
  std::vector<Point3> two = same;
  two.push_back({1, 1, 1});
  EXPECT_FALSE(EstimateNormals(two).ok());
}

TEST(NormalEstimation, APointLimitIsEnforcedWithAMessageNamingIt) {
  const std::vector<Point3> pts = TorusCloud(1001, 3);
  NormalEstimationParams p;
  p.max_points = 1000;
  auto r = EstimateNormals(pts, p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("cannot estimate normals for 1001 points: the limit is 1000"), std::string::npos)
      << r.status().ToString();
  EXPECT_EQ(NormalEstimationParams{}.max_points, kMaxNormalEstimationPoints);
  p.max_points = 1001;
  EXPECT_TRUE(EstimateNormals(pts, p).ok());
}

// Issue 35 item 12: a cloud at 1e-100 or 1e100 (and near the ends of a double's range) has the
// normals of the same cloud at unit scale, bit for bit (before: axis-aligned normals).
TEST(NormalEstimation, ExtremeScalesGiveTheNormalsOfTheUnitScaleCloud) {
  const std::vector<Point3> pts = TorusCloud(3000, 17);
  auto want = EstimateNormals(pts);
  ASSERT_TRUE(want.ok());
  for (int e : {-1000, -332, -40, 40, 332, 1000}) {  // 2^-332 ~ 1e-100, 2^332 ~ 1e100
    std::vector<Point3> scaled = pts;
    for (Point3& p : scaled)
      for (double& x : p) x = std::ldexp(x, e);
    auto got = EstimateNormals(scaled);
    ASSERT_TRUE(got.ok()) << e << ": " << got.status().ToString();
    EXPECT_EQ(*got, *want) << "scale 2^" << e;
  }
}

TEST(NormalEstimation, CancelIsPolled) {
  const std::vector<Point3> pts = TorusCloud(200000, 5);
  int polls = 0;
  auto r = EstimateNormals(pts, {}, [&] { return ++polls >= 3; });
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kCancelled) << r.status().ToString();
  EXPECT_EQ(polls, 3);
}

}  // namespace
}  // namespace silk
