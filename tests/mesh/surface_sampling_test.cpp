// SPDX-License-Identifier: MIT
// Surface sampling: points lie on the faces, normals are the faces' unit normals, draws are
// area-proportional and seeded; point-cloud subsets are seeded and without repeats.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "mesh/surface_sampling.h"

namespace silk {
namespace {

// Two triangles: a big one in z=0 (area 2), a small one in x=5 (area 0.5), plus a degenerate.
IoMesh TwoTriangles() {
  IoMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {5, 0, 0}, {5, 1, 0}, {5, 0, 1}, {7, 7, 7}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 6, 6}};
  return m;
}

TEST(SurfaceSampling, PointsOnFacesWithFaceNormals) {
  auto pts = SampleSurface(TwoTriangles(), 4000, 42);
  ASSERT_TRUE(pts.ok());
  ASSERT_EQ(pts->size(), 4000u);
  int on_big = 0;
  for (const OrientedPoint& p : *pts) {
    if (p.position[2] == 0 && p.position[0] < 4) {
      ++on_big;
      EXPECT_GE(p.position[0], 0);
      EXPECT_GE(p.position[1], 0);
      EXPECT_LE(p.position[0] + p.position[1], 2 + 1e-12);
      EXPECT_EQ(p.normal[2], 1.0);  // counter-clockwise in z=0: +z
    } else {
      EXPECT_DOUBLE_EQ(p.position[0], 5);
      EXPECT_EQ(p.normal[0], 1.0);
    }
  }
  EXPECT_NEAR(on_big / 4000.0, 2.0 / 2.5, 0.03);  // area-weighted
}

TEST(SurfaceSampling, SeededAndErrors) {
  auto a = SampleSurface(TwoTriangles(), 50, 7);
  auto b = SampleSurface(TwoTriangles(), 50, 7);
  auto c = SampleSurface(TwoTriangles(), 50, 8);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ((*a)[17].position, (*b)[17].position);
  EXPECT_NE((*a)[17].position, (*c)[17].position);
  IoMesh flat;
  flat.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  flat.triangles = {{0, 1, 2}};
  EXPECT_FALSE(SampleSurface(flat, 10, 0).ok());
  EXPECT_FALSE(SampleSurface(TwoTriangles(), 0, 0).ok());
  IoMesh bad = TwoTriangles();
  bad.triangles.push_back({0, 1, 99});
  EXPECT_FALSE(SampleSurface(bad, 10, 0).ok());
}

TEST(SurfaceSampling, SubsampleWithoutRepeats) {
  std::vector<OrientedPoint> pts;
  for (int i = 0; i < 100; ++i) pts.push_back({{double(i), 0, 0}, {0, 0, 1}});
  const auto sub = SubsamplePoints(pts, 30, 5);
  ASSERT_EQ(sub.size(), 30u);
  std::set<double> xs;
  for (const auto& p : sub) xs.insert(p.position[0]);
  EXPECT_EQ(xs.size(), 30u);
  EXPECT_EQ(SubsamplePoints(pts, 30, 5)[3].position, sub[3].position);
  EXPECT_EQ(SubsamplePoints(pts, 200, 5).size(), 100u);
}

// Long sampling runs can be stopped: the cancel check is polled once per kCancelPollInterval
// samples, and a stop request ends the run with kCancelled (no samples).
TEST(SurfaceSampling, PollsTheCancelCheckPeriodically) {
  int polls = 0;
  const CancelCheck third_poll_stops = [&] { return ++polls == 3; };
  auto pts = SampleSurface(TwoTriangles(), 1 << 20, 42, third_poll_stops);
  ASSERT_FALSE(pts.ok());
  EXPECT_EQ(pts.status().code(), StatusCode::kCancelled);
  EXPECT_NE(pts.status().message().find("surface sampling"), std::string::npos) << pts.status().ToString();
  EXPECT_EQ(polls, 3);
  // Never stopping: one poll per started block of samples, same samples as without a check.
  polls = 0;
  const CancelCheck never = [&] { return ++polls < 0; };
  auto all = SampleSurface(TwoTriangles(), 3 * static_cast<int32_t>(kCancelPollInterval) + 1, 7, never);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(polls, 4);
  auto plain = SampleSurface(TwoTriangles(), 3 * static_cast<int32_t>(kCancelPollInterval) + 1, 7);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ((*all)[12345].position, (*plain)[12345].position);
}

}  // namespace
}  // namespace silk
