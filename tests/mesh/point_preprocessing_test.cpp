// SPDX-License-Identifier: MIT
// Pre-processing (mesh/point_preprocessing): the official kind is seeded, rounds to float16,
// keeps face normals, draws n_points distinct samples that lie on the surface, and merges
// near-duplicate vertices; Silk's kind is unchanged from plain surface sampling; float16
// rounding and vertex merging on their own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "mesh/close_vertex_merge.h"
#include "mesh/float16_rounding.h"
#include "mesh/point_preprocessing.h"
#include "mesh/surface_sampling.h"

namespace silk {
namespace {

// An axis-aligned box [0,2]x[0,1]x[0,1] (12 outward triangles).
IoMesh Box() {
  IoMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {0, 1, 1}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                 {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return m;
}

TEST(Float16Rounding, KnownValuesTiesAndRange) {
  EXPECT_EQ(RoundToFloat16(1.0), 1.0);
  EXPECT_EQ(RoundToFloat16(0.1), 0.0999755859375);  // 0x2E66
  EXPECT_EQ(RoundToFloat16(0.95), 0.9501953125);    // 0x3B9A
  EXPECT_EQ(RoundToFloat16(-0.95), -0.9501953125);
  EXPECT_EQ(RoundToFloat16(1.0 + std::ldexp(1.0, -11)), 1.0);  // tie -> even mantissa
  EXPECT_EQ(RoundToFloat16(1.0 + 3 * std::ldexp(1.0, -11)), 1.0 + std::ldexp(1.0, -9));
  EXPECT_EQ(RoundToFloat16(65504.0), 65504.0);
  EXPECT_EQ(RoundToFloat16(65519.0), 65504.0);
  EXPECT_TRUE(std::isinf(RoundToFloat16(65520.0)));
  EXPECT_EQ(RoundToFloat16(std::ldexp(1.0, -24)), std::ldexp(1.0, -24));  // smallest subnormal
  EXPECT_EQ(RoundToFloat16(std::ldexp(1.0, -26)), 0.0);
  EXPECT_EQ(RoundToFloat16(3 * std::ldexp(1.0, -26)), std::ldexp(1.0, -24));
  EXPECT_EQ(RoundToFloat16(0.0), 0.0);
  EXPECT_TRUE(std::isnan(RoundToFloat16(std::numeric_limits<double>::quiet_NaN())));
  // Nearest, within half a step, idempotent, over a sweep of magnitudes.
  for (double x = 1e-7; x < 6e4; x *= 1.0137) {
    const double r = RoundToFloat16(x);
    EXPECT_EQ(RoundToFloat16(r), r);
    int e = 0;
    std::frexp(x, &e);
    const double step = std::ldexp(1.0, std::max(e - 1, -14) - 10);
    EXPECT_LE(std::fabs(r - x), step / 2) << x;
  }
}

TEST(CloseVertexMerge, MergesNearDuplicatesAndDropsDegenerateAndRepeatedFaces) {
  IoMesh m;
  // A unit square (two triangles) whose second triangle uses copies of two corners moved by
  // 1e-3, a sliver triangle inside the merge distance, a repeated face, an unreferenced vertex.
  m.positions = {{0, 0, 0},     {1, 0, 0},     {1, 1, 0},       {0, 1, 0},       {0.001, 0, 0},
                 {1, 1.001, 0}, {0.5, 0.5, 0}, {0.5, 0.505, 0}, {0.505, 0.5, 0}, {9, 9, 9}};
  m.triangles = {{0, 1, 2}, {4, 5, 3}, {6, 7, 8}, {2, 0, 1}};
  const double diag = ReferencedBoundingBoxDiagonal(m);
  EXPECT_NEAR(diag, std::sqrt(1.0 + 1.001 * 1.001), 1e-12);  // (9,9,9) is not referenced
  VertexMergeReport rep;
  IoMesh out = MergeCloseVertices(m, 0.01 * diag, &rep);
  EXPECT_EQ(rep.vertices_before, 10);
  EXPECT_EQ(rep.faces_before, 4);
  ASSERT_EQ(out.triangles.size(), 2u);  // the sliver collapsed, the repeat dropped
  EXPECT_EQ(out.positions.size(), 4u);  // 4 corners; the copies took their leaders' positions
  std::set<std::array<double, 3>> corners(out.positions.begin(), out.positions.end());
  EXPECT_EQ(corners, (std::set<std::array<double, 3>>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  // Below the distance nothing merges; a copy 0.02 away (> 1 % of the diagonal) stays apart.
  IoMesh far = MergeCloseVertices(m, 0.0, nullptr);
  EXPECT_EQ(far.triangles.size(), 3u);  // only the repeated face goes
  m.positions[4] = {0.02, 0, 0};
  IoMesh apart = MergeCloseVertices(m, 0.01 * ReferencedBoundingBoxDiagonal(m), nullptr);
  EXPECT_EQ(apart.positions.size(), 5u);
}

TEST(PointPreprocessing, OfficialIsSeededFloat16OnTheSurfaceWithFaceNormals) {
  const PreprocessingParams p = OfficialPreprocessing(4096);
  auto a = PreparePoints(Box(), nullptr, p, 11);
  auto b = PreparePoints(Box(), nullptr, p, 11);
  auto c = PreparePoints(Box(), nullptr, p, 12);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok()) << a.status().ToString();
  ASSERT_EQ(a->rows.size(), 4096u * 6);
  EXPECT_EQ(a->rows, b->rows);
  EXPECT_NE(a->rows, c->rows);
  // Box [0,2]x[0,1]x[0,1] -> centre (1, .5, .5), scale 0.95: x in +-0.95, y and z in +-0.475.
  EXPECT_EQ(a->transform.scale, 0.95);
  const double h16 = 1e-3;  // float16 spacing near 1 is 2^-10
  std::set<std::array<float, 6>> distinct;
  for (size_t i = 0; i < 4096; ++i) {
    const float* r = &a->rows[6 * i];
    for (int k = 0; k < 6; ++k) EXPECT_EQ(RoundToFloat16(r[k]), static_cast<double>(r[k])) << i;
    const double len = std::sqrt(double(r[3]) * r[3] + double(r[4]) * r[4] + double(r[5]) * r[5]);
    EXPECT_NEAR(len, 1.0, h16);
    // Face normal of an axis-aligned face: one component +-1, and the point on that face.
    int axis = -1;
    for (int k = 0; k < 3; ++k)
      if (std::fabs(r[3 + k]) > 0.5) axis = k;
    ASSERT_GE(axis, 0);
    const double half = axis == 0 ? 0.95 : 0.475;
    EXPECT_NEAR(r[axis], r[3 + axis] > 0 ? half : -half, h16) << i;
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::fabs(r[k]), (k == 0 ? 0.95 : 0.475) + h16);
    distinct.insert({r[0], r[1], r[2], r[3], r[4], r[5]});
  }
  EXPECT_GT(distinct.size(), 4000u);  // drawn without replacement from 50,000 samples
}

TEST(PointPreprocessing, OfficialMergesNearDuplicateVerticesBeforeSampling) {
  // The box with its top face split off onto copies of its corners moved by 1e-3 (< 1 % of
  // the diagonal): after merging, the surface is the same closed box. Without merging the
  // moved copies would widen the bounding box and shift the normalisation.
  IoMesh m = Box();
  for (int v = 4; v < 8; ++v) {
    auto p = m.positions[static_cast<size_t>(v)];
    p[0] += 1e-3;
    m.positions.push_back(p);
  }
  m.triangles[2] = {8, 9, 10};
  m.triangles[3] = {8, 10, 11};
  VertexMergeReport rep;
  IoMesh merged = MergeCloseVertices(m, 0.01 * ReferencedBoundingBoxDiagonal(m), &rep);
  EXPECT_EQ(rep.vertices_after, 8);
  EXPECT_EQ(rep.faces_after, 12);
  auto r = PreparePoints(m, nullptr, OfficialPreprocessing(512), 3);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->transform.center[0], 1.0);  // the moved copies (x up to 2.001) were merged away
  PreprocessingParams no_merge = OfficialPreprocessing(512);
  no_merge.merge_distance_fraction = 0;
  auto u = PreparePoints(m, nullptr, no_merge, 3);
  ASSERT_TRUE(u.ok());
  EXPECT_NEAR(u->transform.center[0], 1.0005, 1e-12);
}

TEST(PointPreprocessing, SilkKindIsPlainSurfaceSampling) {
  const IoMesh box = Box();
  auto r = PreparePoints(box, nullptr, SilkPreprocessing(0.9, 300), 42);
  ASSERT_TRUE(r.ok());
  auto t = ComputeNormalization(box, 0.9);
  ASSERT_TRUE(t.ok());
  auto s = SampleSurface(ApplyNormalization(box, *t), 300, 42);
  ASSERT_TRUE(s.ok());
  ASSERT_EQ(r->rows.size(), 300u * 6);
  for (size_t i = 0; i < 300; ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(r->rows[6 * i + k], static_cast<float>((*s)[i].position[k]));
      EXPECT_EQ(r->rows[6 * i + 3 + k], static_cast<float>((*s)[i].normal[k]));
    }
}

TEST(PointPreprocessing, PointCloudsAndErrors) {
  IoMesh cloud;
  std::vector<std::array<double, 3>> normals;
  for (int i = 0; i < 100; ++i) {
    cloud.positions.push_back({i * 0.1, std::sin(i * 1.0), 0});
    normals.push_back({0, 0, 2});
  }
  auto r = PreparePoints(cloud, &normals, OfficialPreprocessing(64), 1);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->rows.size(), 64u * 6);
  for (size_t i = 0; i < 64; ++i) EXPECT_EQ(r->rows[6 * i + 5], 1.0f);  // rescaled to unit
  auto all = PreparePoints(cloud, &normals, OfficialPreprocessing(4096), 1);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->rows.size(), 100u * 6);  // fewer than n_points: all of them
  PreprocessingParams bad = OfficialPreprocessing(4096);
  bad.surface_samples = -3;
  auto e = PreparePoints(Box(), nullptr, bad, 1);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("preprocessing.surface_samples"), std::string::npos);
  bad = OfficialPreprocessing(0);
  EXPECT_NE(ValidatePreprocessing(bad).message().find("preprocessing.n_points"), std::string::npos);
  IoMesh sliver;
  sliver.positions = {{0, 0, 0}, {0.005, 0, 0}, {1, 1, 0}};
  sliver.triangles = {{0, 1, 2}};
  auto s = PreparePoints(sliver, nullptr, OfficialPreprocessing(16), 1);
  ASSERT_FALSE(s.ok());  // merging collapses the only face
  EXPECT_NE(s.status().message().find("area"), std::string::npos);
}

// Issue 35 item 12: clouds at 1e-100 and 1e100 normalise to the rows of the unit-scale cloud
// (the normalisation is scale-free up to rounding); beyond a double's range (a centre that
// overflows, an extent that is denormal) they are refused with a message, not written as garbage.
TEST(PointPreprocessing, ExtremeScalesNormaliseOrAreRefused) {
  IoMesh cloud;
  std::vector<std::array<double, 3>> normals;
  for (int i = 0; i < 200; ++i) {
    cloud.positions.push_back({std::cos(i * 0.3), std::sin(i * 0.7), i * 0.01});
    normals.push_back({0, 0, 1});
  }
  auto unit = PreparePoints(cloud, &normals, SilkPreprocessing(0.95, 128), 4);
  ASSERT_TRUE(unit.ok());
  for (double scale : {1e-100, 1e100, 1e-300, 1e300}) {
    IoMesh scaled = cloud;
    for (auto& p : scaled.positions)
      for (double& x : p) x *= scale;
    auto r = PreparePoints(scaled, &normals, SilkPreprocessing(0.95, 128), 4);
    ASSERT_TRUE(r.ok()) << scale << ": " << r.status().ToString();
    ASSERT_EQ(r->rows.size(), unit->rows.size());
    for (size_t i = 0; i < r->rows.size(); ++i) EXPECT_NEAR(r->rows[i], unit->rows[i], 1e-6) << scale << " " << i;
  }
  for (double scale : {1e307, 1e-310}) {  // near 1.5e308: a centre of inf; a denormal extent (scale overflows)
    IoMesh scaled = cloud;
    for (auto& p : scaled.positions)
      for (double& x : p) x = x * scale + (scale > 1 ? 1.5e308 : 0);
    auto r = PreparePoints(scaled, &normals, SilkPreprocessing(0.95, 128), 4);
    ASSERT_FALSE(r.ok()) << scale;
    EXPECT_NE(r.status().message().find("coordinates out of range"), std::string::npos) << r.status().ToString();
  }
}

}  // namespace
}  // namespace silk
