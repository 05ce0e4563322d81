// SPDX-License-Identifier: MIT
// Chamfer distance: the grid nearest-neighbour index against brute force on random sets (some
// clustered, some queries far outside), the symmetric mean, empty/degenerate meshes, and the
// cancel polled in chunks while scoring (issue 20).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/splitmix64.h"
#include "mesh/chamfer_distance.h"

namespace silk {
namespace {

double BruteNearest(const std::vector<Point3>& set, const Point3& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const Point3& p : set)
    best = std::min(
        best, std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2])));
  return best;
}

std::vector<Point3> RandomPoints(SplitMix64* rng, int n, double scale, bool flat) {
  std::vector<Point3> v;
  for (int i = 0; i < n; ++i)
    v.push_back({scale * (2 * rng->Uniform() - 1), scale * (2 * rng->Uniform() - 1),
                 flat ? 0.25 : scale * (2 * rng->Uniform() - 1)});
  return v;
}

TEST(ChamferDistance, NearestMatchesBruteForce) {
  SplitMix64 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 1 + static_cast<int>(rng.Uniform() * 800);
    const auto set = RandomPoints(&rng, n, 1.0, trial % 3 == 0);  // some sets on a plane
    NearestPointIndex index(set);
    const auto queries = RandomPoints(&rng, 300, trial % 2 ? 3.0 : 1.0, false);  // many outside the box
    for (const Point3& q : queries) ASSERT_DOUBLE_EQ(index.Distance(q), BruteNearest(set, q)) << "trial " << trial;
  }
}

TEST(ChamferDistance, NearestIndexIsTheBruteForceArgminWithTheLowestIndexOnTies) {
  SplitMix64 rng(5);
  for (int trial = 0; trial < 8; ++trial) {
    auto set = RandomPoints(&rng, 1 + static_cast<int>(rng.Uniform() * 500), 1.0, trial % 2 == 0);
    const size_t unique = set.size();
    for (size_t i = 0; i < unique; i += 7) set.push_back(set[i]);  // exact duplicates: ties
    NearestPointIndex index(set);
    for (const Point3& q : RandomPoints(&rng, 200, 2.0, false)) {
      const NearestPointIndex::Hit hit = index.Nearest(q);
      int32_t want = -1;
      double best = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < set.size(); ++i) {
        const Point3& p = set[i];
        const double d =
            std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
        if (d < best) best = d, want = static_cast<int32_t>(i);
      }
      ASSERT_EQ(hit.index, want) << "trial " << trial;
      ASSERT_DOUBLE_EQ(hit.distance, best);
    }
  }
  const NearestPointIndex none(std::vector<Point3>{});
  EXPECT_EQ(none.Nearest({0, 0, 0}).index, -1);
  EXPECT_TRUE(std::isinf(none.Nearest({0, 0, 0}).distance));
}

TEST(ChamferDistance, SymmetricMeanMatchesBruteForce) {
  SplitMix64 rng(11);
  const auto a = RandomPoints(&rng, 400, 1.0, false), b = RandomPoints(&rng, 250, 0.7, true);
  double ab = 0, ba = 0;
  for (const Point3& p : a) ab += BruteNearest(b, p);
  for (const Point3& p : b) ba += BruteNearest(a, p);
  const ChamferDistance d = PointSetChamfer(a, b);
  EXPECT_NEAR(d.a_to_b, ab / a.size(), 1e-12);
  EXPECT_NEAR(d.b_to_a, ba / b.size(), 1e-12);
  EXPECT_NEAR(d.value(), 0.5 * (ab / a.size() + ba / b.size()), 1e-12);
  EXPECT_EQ(PointSetChamfer(a, a).value(), 0.0);
}

TEST(ChamferDistance, MeshSamplesAgainstPoints) {
  IoMesh square;  // unit square in z = 0
  square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  std::vector<Point3> above;  // the same square lifted by 0.5: every distance >= 0.5
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) above.push_back({i / 20.0, j / 20.0, 0.5});
  const ChamferDistance d = MeshToPointsChamfer(square, above, 2000, 3);
  EXPECT_GE(d.a_to_b, 0.5);
  EXPECT_LT(d.a_to_b, 0.5 + 0.03);  // grid spacing 0.05: at most ~0.035 sideways
  EXPECT_NEAR(d.b_to_a, 0.5, 0.01);
  EXPECT_EQ(MeshToPointsChamfer(square, above, 2000, 3).value(), d.value());  // seeded
}

TEST(ChamferDistance, NoFaceOrNoPointIsInfinite) {
  IoMesh flat;  // one zero-area face
  flat.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  flat.triangles = {{0, 1, 2}};
  const std::vector<Point3> pts = {{0, 0, 0}};
  EXPECT_TRUE(std::isinf(MeshToPointsChamfer(flat, pts, 100, 0).value()));
  EXPECT_TRUE(std::isinf(MeshToPointsChamfer(IoMesh{}, pts, 100, 0).value()));
  EXPECT_TRUE(std::isinf(NearestPointIndex({}).Distance({0, 0, 0})));
}

// Scoring against a million encoder points takes seconds: the cancellable form polls every
// kChamferPollInterval queries, stops at the first poll that asks, and otherwise gives the
// identical value.
TEST(ChamferDistance, CancelIsPolledInChunksAndLeavesTheValue) {
  SplitMix64 rng(9);
  const std::vector<Point3> a = RandomPoints(&rng, static_cast<int>(3 * kChamferPollInterval + 5), 1.0, false);
  const std::vector<Point3> b = RandomPoints(&rng, static_cast<int>(2 * kChamferPollInterval), 1.0, true);
  int polls = 0;
  const auto counted = PointSetChamfer(a, b, [&] { return ++polls < 0; });
  ASSERT_TRUE(counted.ok());
  EXPECT_EQ(counted->value(), PointSetChamfer(a, b).value());
  // b's index (1: one per 65,536 points of partitioning work), a's queries, between the
  // directions, a's index (2), b's queries.
  EXPECT_EQ(polls, 1 + 3 + 1 + 2 + 2);
  polls = 0;
  const auto stopped = PointSetChamfer(a, b, [&] { return ++polls >= 2; });
  EXPECT_EQ(stopped.status().code(), StatusCode::kCancelled);
  EXPECT_EQ(polls, 2);
}

}  // namespace
}  // namespace silk
