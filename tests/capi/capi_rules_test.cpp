// SPDX-License-Identifier: MIT
// The C API 1.0 boundary rules (docs/c_api.md) checked on every function they apply to: the one
// size-query rule of the copy functions (including "too small writes nothing"), struct_size
// refused naming the struct, the size given and the size expected, and the version.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "silk/silk.h"
#include "silk/silk.hpp"
#include "support/test_paths.h"

namespace {

namespace fs = std::filesystem;

// A tetrahedron (4 vertices, 4 triangles) and a 3-point cloud with normals.
const std::vector<double> kXyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const std::vector<int32_t> kTris = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

silk_mesh* Tetrahedron() {
  silk_mesh* m = nullptr;
  EXPECT_EQ(silk_mesh_create(kXyz.data(), 4, kTris.data(), 4, &m), SILK_OK) << silk_last_error();
  return m;
}

silk_mesh* PointCloud(const fs::path& dir) {
  const std::string ply = (dir / "cloud.ply").string();
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                        "end_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 1 0 0\n";
  silk_mesh* m = nullptr;
  EXPECT_EQ(silk_mesh_load(ply.c_str(), nullptr, &m), SILK_OK) << silk_last_error();
  return m;
}

// One copy function seen through the rule: copy(out, capacity, out_count).
template <typename T>
using Copy = std::function<silk_status(T*, size_t, size_t*)>;

// The rule, for a function that must copy `want` (independently known elements).
template <typename T>
void ExpectSizeQueryRule(const char* name, const Copy<T>& copy, const std::vector<T>& want) {
  SCOPED_TRACE(name);
  size_t n = 12345;
  ASSERT_EQ(copy(nullptr, 0, &n), SILK_OK) << silk_last_error();  // the size query
  EXPECT_EQ(n, want.size());
  EXPECT_EQ(copy(nullptr, 0, nullptr), SILK_OK);               // out_count may be NULL
  EXPECT_EQ(copy(nullptr, 4, &n), SILK_ERR_INVALID_ARGUMENT);  // a buffer promised, none given
  if (!want.empty()) {
    const T sentinel = static_cast<T>(-7);
    std::vector<T> small(want.size() - 1, sentinel);
    n = 0;
    EXPECT_EQ(copy(small.data(), small.size(), &n), SILK_ERR_BUFFER_TOO_SMALL);
    EXPECT_EQ(n, want.size());  // the need, also on failure
    EXPECT_NE(std::string(silk_last_error()).find("need " + std::to_string(want.size())), std::string::npos)
        << silk_last_error();
    for (const T& v : small) EXPECT_EQ(v, sentinel);  // nothing written
  }
  std::vector<T> big(want.size() + 2, static_cast<T>(-7));
  ASSERT_EQ(copy(big.data(), big.size(), &n), SILK_OK) << silk_last_error();
  EXPECT_EQ(n, want.size());
  EXPECT_EQ(std::vector<T>(big.begin(), big.begin() + want.size()), want);
  EXPECT_EQ(big.back(), static_cast<T>(-7));  // nothing past the need
}

TEST(CapiRules, EveryMeshAndTokensCopyFollowsTheSizeQueryRule) {
  silk_mesh* m = Tetrahedron();
  ExpectSizeQueryRule<double>(
      "positions", [&](double* o, size_t c, size_t* n) { return silk_mesh_copy_positions(m, o, c, n); }, kXyz);
  ExpectSizeQueryRule<int32_t>(
      "triangles", [&](int32_t* o, size_t c, size_t* n) { return silk_mesh_copy_triangles(m, o, c, n); }, kTris);
  ExpectSizeQueryRule<int32_t>(
      "components", [&](int32_t* o, size_t c, size_t* n) { return silk_mesh_copy_triangle_components(m, o, c, n); },
      std::vector<int32_t>(4, 0));
  ExpectSizeQueryRule<double>("normals of a mesh",
                              [&](double* o, size_t c, size_t* n) { return silk_mesh_copy_normals(m, o, c, n); }, {});
  const fs::path dir = fs::temp_directory_path() / ("silk_capi_rules_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  silk_mesh* cloud = PointCloud(dir);
  ExpectSizeQueryRule<double>("normals of a cloud",
                              [&](double* o, size_t c, size_t* n) { return silk_mesh_copy_normals(cloud, o, c, n); },
                              {0, 0, 1, 0, 0, 1, 1, 0, 0});
  const std::vector<int32_t> ids = {1, 2, 3, 4, 5};
  silk_tokens* t = nullptr;
  ASSERT_EQ(silk_tokens_create(ids.data(), ids.size(), &t), SILK_OK);
  ExpectSizeQueryRule<int32_t>(
      "tokens", [&](int32_t* o, size_t c, size_t* n) { return silk_tokens_copy(t, o, c, n); }, ids);
  size_t n = 99;
  EXPECT_EQ(silk_tokens_copy(nullptr, nullptr, 0, &n), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(n, 0u);
  silk_tokens_destroy(t);
  silk_mesh_destroy(cloud);
  silk_mesh_destroy(m);
  fs::remove_all(dir);
}

TEST(CapiRules, PreparePointsFollowsTheSizeQueryRuleInFloats) {
  silk_mesh* m = Tetrahedron();
  silk_preprocess_params p = silk_preprocess_default_params(SILK_PREPROCESS_SILK);
  p.point_count = 16;
  std::vector<float> want(6 * 16);
  size_t n = 0;
  ASSERT_EQ(silk_points_prepare(m, nullptr, 0, &p, 3, want.data(), want.size(), &n, nullptr), SILK_OK)
      << silk_last_error();
  ExpectSizeQueryRule<float>(
      "silk_points_prepare",
      [&](float* o, size_t c, size_t* k) { return silk_points_prepare(m, nullptr, 0, &p, 3, o, c, k, nullptr); }, want);
  silk_mesh_destroy(m);
}

// One function given a struct whose struct_size is wrong: the status and the message's parts.
void ExpectSizeRefused(const char* type, size_t expected, const char* how, const std::function<silk_status()>& call) {
  SCOPED_TRACE(type);
  ASSERT_EQ(call(), SILK_ERR_INVALID_ARGUMENT);
  const std::string msg = silk_last_error();
  for (const std::string& part :
       {std::string(type) + ".struct_size 0", "expected " + std::to_string(expected), std::string(how)})
    EXPECT_NE(msg.find(part), std::string::npos) << "missing '" << part << "' in: " << msg;
}

#define SILK_REFUSED_PARAMS(type, defaults, call_with)                                                           \
  {                                                                                                              \
    type x = defaults;                                                                                           \
    x.struct_size = 0;                                                                                           \
    const std::string how = #defaults; /* the function's name, "(" included */                                   \
    ExpectSizeRefused(#type, sizeof(type), how.substr(0, how.find('(') + 1).c_str(), [&] { return call_with; }); \
  }
#define SILK_REFUSED_OUT(type, call_with)                                                   \
  {                                                                                         \
    type x{};                                                                               \
    ExpectSizeRefused(#type, sizeof(type), "sizeof(" #type ")", [&] { return call_with; }); \
  }

TEST(CapiRules, AWrongStructSizeIsRefusedNamingTheStruct) {
  silk_mesh* m = Tetrahedron();
  silk_tokens* t = nullptr;
  ASSERT_EQ(silk_mesh_encode(m, nullptr, &t, nullptr), SILK_OK) << silk_last_error();
  silk_mesh* out = nullptr;
  silk_tokens* out_t = nullptr;
  size_t n = 0;
  SILK_REFUSED_PARAMS(silk_load_params, silk_load_default_params(), silk_mesh_load("x.obj", &x, &out));
  SILK_REFUSED_PARAMS(silk_save_params, silk_save_default_params(), silk_mesh_save(m, "x.obj", &x));
  SILK_REFUSED_PARAMS(silk_encode_params, silk_encode_default_params(), silk_mesh_encode(m, &x, &out_t, nullptr));
  SILK_REFUSED_PARAMS(silk_decode_params, silk_decode_default_params(), silk_tokens_decode(t, &x, &out, nullptr));
  SILK_REFUSED_PARAMS(silk_check_params, silk_check_default_params(), [&] {
    silk_check_result r{};
    r.struct_size = sizeof r;
    return silk_tokens_check(t, &x, &r);
  }());
  SILK_REFUSED_PARAMS(silk_repair_params, silk_repair_default_params(),
                      silk_tokens_repair(t, &x, &out, nullptr, nullptr));
  SILK_REFUSED_PARAMS(silk_random_walk_params, silk_random_walk_default_params(),
                      silk_tokens_random_walk(&x, &out_t, nullptr));
  SILK_REFUSED_PARAMS(silk_preprocess_params, silk_preprocess_default_params(SILK_PREPROCESS_SILK),
                      silk_points_prepare(m, nullptr, 0, &x, 1, nullptr, 0, &n, nullptr));
  if (silk_generation_available()) {  // else every model call is SILK_ERR_UNSUPPORTED
    silk_model* model = nullptr;
    SILK_REFUSED_PARAMS(silk_model_params, silk_model_default_params(), silk_model_load("/nonexistent", &x, &model));
  }
  SILK_REFUSED_OUT(silk_encode_stats, silk_mesh_encode(m, nullptr, &out_t, &x));
  SILK_REFUSED_OUT(silk_decode_stats, silk_tokens_decode(t, nullptr, &out, &x));
  SILK_REFUSED_OUT(silk_roundtrip_report, silk_mesh_roundtrip(m, nullptr, &x));
  SILK_REFUSED_OUT(silk_check_result, silk_tokens_check(t, nullptr, &x));
  SILK_REFUSED_OUT(silk_repair_stats, silk_tokens_repair(t, nullptr, &out, &x, nullptr));
  SILK_REFUSED_OUT(silk_vocab_info, silk_vocab_get_info(&x));
  EXPECT_EQ(out, nullptr);  // nothing was made
  EXPECT_EQ(out_t, nullptr);
  silk_tokens_destroy(t);
  silk_mesh_destroy(m);
}

TEST(CapiRules, DefaultsCarryTheirSizeAndARightSizeIsAccepted) {
  EXPECT_EQ(silk_load_default_params().struct_size, sizeof(silk_load_params));
  EXPECT_EQ(silk_save_default_params().struct_size, sizeof(silk_save_params));
  EXPECT_EQ(silk_encode_default_params().struct_size, sizeof(silk_encode_params));
  EXPECT_EQ(silk_decode_default_params().struct_size, sizeof(silk_decode_params));
  EXPECT_EQ(silk_check_default_params().struct_size, sizeof(silk_check_params));
  EXPECT_EQ(silk_repair_default_params().struct_size, sizeof(silk_repair_params));
  EXPECT_EQ(silk_random_walk_default_params().struct_size, sizeof(silk_random_walk_params));
  EXPECT_EQ(silk_preprocess_default_params(SILK_PREPROCESS_OFFICIAL).struct_size, sizeof(silk_preprocess_params));
  EXPECT_EQ(silk_model_default_params().struct_size, sizeof(silk_model_params));
  silk_vocab_info v{};
  v.struct_size = sizeof v;
  ASSERT_EQ(silk_vocab_get_info(&v), SILK_OK) << silk_last_error();
  EXPECT_EQ(v.struct_size, sizeof v);     // the library keeps the caller's size
  EXPECT_EQ(v.format_vocab_size, 10267);  // token_format.md: ids 0..10266
  silk_mesh* m = Tetrahedron();
  silk_roundtrip_report r{};
  r.struct_size = sizeof r;
  ASSERT_EQ(silk_mesh_roundtrip(m, nullptr, &r), SILK_OK) << silk_last_error();
  EXPECT_EQ(r.tokens, 17);  // token_format.md §8.3
  silk_mesh_destroy(m);
}

// The generation structs (phase 2): params, input and stats refused naming the struct in every
// function taking them; the defaults and the progress the library passes carry their size.
TEST(CapiRules, GenerationStructsCarryAndCheckTheirSize) {
  EXPECT_EQ(silk_generate_default_params().struct_size, sizeof(silk_generate_params));
  if (!silk_generation_available()) GTEST_SKIP() << "libsilk without onnxruntime";
  silk_model* model = nullptr;
  ASSERT_EQ(silk_model_load(silk::testing::SourcePath("tests/models/tiny").c_str(), nullptr, &model), SILK_OK)
      << silk_last_error();
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model, &g), SILK_OK) << silk_last_error();
  silk_mesh* m = Tetrahedron();
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = m;
  silk_generate_params p = silk_generate_default_params();
  p.max_tokens = 40;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  silk_mesh* out = nullptr;
  silk_tokens* out_t = nullptr;
  SILK_REFUSED_PARAMS(silk_generate_params, silk_generate_default_params(),
                      silk_generator_run(g, &in, &x, &out, &out_t, &st));
  SILK_REFUSED_PARAMS(silk_generate_params, silk_generate_default_params(), silk_generator_start(g, &in, &x));
  SILK_REFUSED_OUT(silk_generate_input, silk_generator_run(g, &x, &p, &out, &out_t, &st));
  SILK_REFUSED_OUT(silk_generate_input, silk_generator_start(g, &x, &p));
  SILK_REFUSED_OUT(silk_generate_stats, silk_generator_run(g, &in, &p, &out, &out_t, &x));
  SILK_REFUSED_OUT(silk_generate_stats, silk_generator_get_stats(g, &x));
  EXPECT_EQ(out, nullptr);  // nothing was made
  EXPECT_EQ(out_t, nullptr);
  // Step-wise: finish refuses a wrong stats size too (the run stays finishable).
  ASSERT_EQ(silk_generator_start(g, &in, &p), SILK_OK) << silk_last_error();
  SILK_REFUSED_OUT(silk_generate_stats, silk_generator_finish(g, &out, nullptr, &x));
  ASSERT_EQ(silk_generator_finish(g, &out, nullptr, &st), SILK_OK) << silk_last_error();
  silk_mesh_destroy(out);
  // Right sizes: the run goes through, the library keeps the caller's size, the progress carries its own.
  uint32_t progress_size = 0;
  p.progress = [](const silk_generate_progress* pr, void* u) { *static_cast<uint32_t*>(u) = pr->struct_size; };
  p.user_data = &progress_size;
  ASSERT_EQ(silk_generator_run(g, &in, &p, &out, nullptr, &st), SILK_OK) << silk_last_error();
  EXPECT_EQ(st.struct_size, sizeof st);
  EXPECT_GT(st.tokens, 0);
  EXPECT_EQ(progress_size, sizeof(silk_generate_progress));
  silk_mesh_destroy(out);
  silk_mesh_destroy(m);
  silk_generator_destroy(g);
  silk_model_destroy(model);
}

TEST(CapiRules, TheHeaderVersionIsTheLibrarys) {
  EXPECT_STREQ(silk_version(), SILK_VERSION_STRING);
  const std::string parts = std::to_string(SILK_VERSION_MAJOR) + "." + std::to_string(SILK_VERSION_MINOR) + "." +
                            std::to_string(SILK_VERSION_PATCH);
  EXPECT_EQ(parts, SILK_VERSION_STRING);
  EXPECT_EQ(SILK_VERSION_NUMBER, SILK_VERSION_MAJOR * 10000 + SILK_VERSION_MINOR * 100 + SILK_VERSION_PATCH);
  EXPECT_EQ(SILK_VERSION_MAJOR, 1);  // C API 1.0 (docs/c_api.md)
}

}  // namespace
