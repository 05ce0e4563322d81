// SPDX-License-Identifier: MIT
// What the C API generation tests share: the one-call generation from a silk_mesh or from rows
// of points through silk_generator_run, and a fixture holding the tiny test model and the sample.
#pragma once
#include <string>
#include <cmath>
#include <vector>
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>

#include "silk/silk.h"
#include "silk/silk.hpp"
#include "support/test_paths.h"

namespace silk::testing {

// n points of a Fibonacci sphere with outward normals (rows of x y z nx ny nz).
inline std::vector<double> FibonacciSphere(size_t n) {
  std::vector<double> pts(6 * n);
  for (size_t i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = 2.399963229728653 * i;
    const double xyz[3] = {r * std::cos(phi), r * std::sin(phi), z};
    for (int a = 0; a < 3; ++a) pts[6 * i + a] = pts[6 * i + 3 + a] = xyz[a];
  }
  return pts;
}

inline silk_status GenerateFromMesh(silk_generator* g, const silk_mesh* mesh, const silk_generate_params* p,
                                    silk_mesh** out, silk_tokens** tokens, silk_generate_stats* stats) {
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = mesh;
  return silk_generator_run(g, &in, p, out, tokens, stats);
}
inline silk_status GenerateFromPoints(silk_generator* g, const double* points, size_t rows,
                                      const silk_generate_params* p, silk_mesh** out, silk_tokens** tokens,
                                      silk_generate_stats* stats) {
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.points = points;
  in.point_rows = rows;
  return silk_generator_run(g, &in, p, out, tokens, stats);
}

// tests/models/tiny (one thread) and samples/torus_knot.obj, loaded once per test through
// silk.h; skipped where libsilk was built without onnxruntime.
class TinyModelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!silk_generation_available()) GTEST_SKIP() << "libsilk built without onnxruntime";
    silk_model_params o = silk_model_default_params();
    o.threads = 1;
    ASSERT_EQ(silk_model_load(SourcePath(ModelDir()).c_str(), &o, &model_), SILK_OK) << silk_last_error();
    ASSERT_EQ(silk_mesh_load(SourcePath("samples/torus_knot.obj").c_str(), nullptr, &mesh_), SILK_OK)
        << silk_last_error();
  }
  void TearDown() override {
    silk_mesh_destroy(mesh_);
    silk_model_destroy(model_);
  }
  // The model folder (relative to the source tree): the batch-1 tiny model unless a test needs
  // another (tests/models/tiny-rows: decoder contract v4, where best of N runs as rows).
  virtual std::string ModelDir() const { return "tests/models/tiny"; }
  // The default parameters with a seed and an id cap.
  static silk_generate_params Params(uint64_t seed, int32_t max_tokens = 120) {
    silk_generate_params p = silk_generate_default_params();
    p.seed = seed;
    p.max_tokens = max_tokens;
    return p;
  }
  silk_model* model_ = nullptr;
  silk_mesh* mesh_ = nullptr;
};

// TinyModelTest with a generator on the model and an input of the sample mesh (step-wise tests).
class TinyGeneratorTest : public TinyModelTest {
 protected:
  void SetUp() override {
    TinyModelTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    ASSERT_EQ(silk_generator_create(model_, &g_), SILK_OK);
    in_.mesh = mesh_;
  }
  void TearDown() override {
    silk_generator_destroy(g_);
    TinyModelTest::TearDown();
  }
  silk_generator* g_ = nullptr;
  silk_generate_input in_ = silk_cpp::Sized<silk_generate_input>();
};

}  // namespace silk::testing
