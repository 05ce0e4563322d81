// SPDX-License-Identifier: MIT
// Point clouds through the C API (silk.h only): silk_mesh_load gives a cloud without normals
// estimated ones (radial and outward on a sphere), keeps a cloud's own normals as read, reads
// XYZ, refuses what it cannot estimate from; silk_generator_copy_points returns the encoder's points
// in the input frame (= silk_points_prepare with the model's pre-processing, normalisation undone).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "silk/silk.h"
#include "support/capi_generate.h"
#include "support/test_paths.h"

namespace {

namespace fs = std::filesystem;

class CapiPointClouds : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("silk_capi_points_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  fs::path dir_;
};

// Fibonacci sphere of radius 2 about (1, 0, -1): rows "x y z".
std::vector<std::array<double, 3>> Sphere(int n) {
  std::vector<std::array<double, 3>> pts;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2.0 * i + 1) / n, rho = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
    pts.push_back({1 + 2 * rho * std::cos(phi), 2 * rho * std::sin(phi), -1 + 2 * z});
  }
  return pts;
}

std::vector<double> Normals(const silk_mesh* m) {
  size_t count = 0;
  EXPECT_EQ(silk_mesh_copy_normals(m, nullptr, 0, &count), SILK_OK) << silk_last_error();
  std::vector<double> n(count);
  EXPECT_EQ(silk_mesh_copy_normals(m, n.data(), n.size(), nullptr), SILK_OK) << silk_last_error();
  return n;
}

TEST_F(CapiPointClouds, CloudsWithoutNormalsGetOutwardEstimates) {
  const auto pts = Sphere(2000);
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 2000\nproperty double x\nproperty double y\n"
      "property double z\nend_header\n";
  std::string xyz = "# sphere\r\n";
  char buf[96];
  for (const auto& p : pts) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g", p[0], p[1], p[2]);
    ply += std::string(buf) + "\n";
    xyz += std::string(buf) + "\r\n";
  }
  for (const std::string& path : {Write("s.ply", ply), Write("s.xyz", xyz)}) {
    silk_mesh* m = nullptr;
    ASSERT_EQ(silk_mesh_load(path.c_str(), nullptr, &m), SILK_OK) << silk_last_error();
    size_t triangles = 1;
    EXPECT_EQ(silk_mesh_copy_triangles(m, nullptr, 0, &triangles), SILK_OK);
    EXPECT_EQ(triangles, 0u);
    ASSERT_EQ(silk_mesh_has_normals(m), 1) << path;
    const std::vector<double> n = Normals(m);
    for (size_t i = 0; i < pts.size(); ++i) {
      const double radial =
          ((pts[i][0] - 1) * n[3 * i] + pts[i][1] * n[3 * i + 1] + (pts[i][2] + 1) * n[3 * i + 2]) / 2;
      ASSERT_GT(radial, 0.99) << path << " point " << i;
    }
    silk_mesh_destroy(m);
  }
}

TEST_F(CapiPointClouds, OwnNormalsKeptAndRefusals) {
  const std::string given = Write("g.xyz", "0 0 0 0 0 1\n1 0 0 0.6 0.8 0\n0 1 0 0 -1 0\n");
  silk_mesh* m = nullptr;
  ASSERT_EQ(silk_mesh_load(given.c_str(), nullptr, &m), SILK_OK) << silk_last_error();
  EXPECT_EQ(Normals(m), (std::vector<double>{0, 0, 1, 0.6, 0.8, 0, 0, -1, 0}));
  silk_mesh_destroy(m);
  m = nullptr;
  const std::string two = Write("two.ply",
                                "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                "property float z\nend_header\n0 0 0\n1 0 0\n");
  EXPECT_EQ(silk_mesh_load(two.c_str(), nullptr, &m), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(m, nullptr);
  EXPECT_NE(
      std::string(silk_last_error()).find("two.ply: a point cloud without normals: cannot estimate normals from 2"),
      std::string::npos)
      << silk_last_error();
  silk_load_params lp = silk_load_default_params();
  lp.point_clouds = 0;  // the tokenizer's view: an XYZ file has no faces
  EXPECT_EQ(silk_mesh_load(given.c_str(), &lp, &m), SILK_ERR_PARSE);
  EXPECT_NE(std::string(silk_last_error()).find("no faces"), std::string::npos) << silk_last_error();
  const std::string bad = Write("bad.xyz", "0 0 0\n1 0 0 7\n");
  EXPECT_EQ(silk_mesh_load(bad.c_str(), nullptr, &m), SILK_ERR_PARSE);
  EXPECT_NE(std::string(silk_last_error()).find("bad.xyz:2: 4 values"), std::string::npos) << silk_last_error();
}

TEST_F(CapiPointClouds, GeneratorPointsAreThePreparedPointsInTheInputFrame) {
  if (!silk_generation_available()) GTEST_SKIP() << "libsilk built without onnxruntime";
  silk_model_params o = silk_model_default_params();
  o.threads = 1;
  silk_model* model = nullptr;
  ASSERT_EQ(silk_model_load(silk::testing::SourcePath("tests/models/tiny").c_str(), &o, &model), SILK_OK);
  silk_mesh* input = nullptr;
  ASSERT_EQ(silk_mesh_load(silk::testing::SourcePath("samples/torus_knot.obj").c_str(), nullptr, &input), SILK_OK);
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model, &g), SILK_OK);
  size_t count = 7;
  EXPECT_EQ(silk_generator_copy_points(g, nullptr, 0, &count), SILK_ERR_INVALID_ARGUMENT);  // nothing generated yet
  EXPECT_EQ(count, 0u);
  silk_generate_params p = silk_generate_default_params();
  p.seed = 5;
  p.max_tokens = 60;
  silk_mesh* out = nullptr;
  ASSERT_EQ(silk::testing::GenerateFromMesh(g, input, &p, &out, nullptr, nullptr), SILK_OK) << silk_last_error();
  EXPECT_EQ(silk_generator_copy_points(g, nullptr, 0, &count), SILK_OK);  // the size query
  ASSERT_EQ(count % 6, 0u);
  const size_t rows = count / 6;
  std::vector<double> pts(count);
  EXPECT_EQ(silk_generator_copy_points(g, pts.data(), count - 1, nullptr), SILK_ERR_BUFFER_TOO_SMALL);
  ASSERT_EQ(silk_generator_copy_points(g, pts.data(), pts.size(), &count), SILK_OK) << silk_last_error();
  silk_preprocess_params pp = silk_preprocess_default_params(SILK_PREPROCESS_SILK);
  ASSERT_EQ(silk_model_get_preprocess_params(model, &pp), SILK_OK);
  size_t n = 0;
  double t[4];
  std::vector<float> prepared(pts.size());
  ASSERT_EQ(silk_points_prepare(input, nullptr, 0, &pp, 5, prepared.data(), prepared.size(), &n, t), SILK_OK);
  ASSERT_EQ(n, count);
  EXPECT_EQ(static_cast<int32_t>(rows), pp.point_count);
  for (size_t i = 0; i < rows * 6; ++i) {
    const size_t a = i % 6;
    const double want = a < 3 ? prepared[i] / t[3] + t[a] : prepared[i];  // model = (input - c) * scale
    ASSERT_NEAR(pts[i], want, 1e-9 * (1 + std::fabs(want))) << "value " << i;
  }
  silk_mesh_destroy(out);
  silk_generator_destroy(g);
  silk_mesh_destroy(input);
  silk_model_destroy(model);
}

}  // namespace
