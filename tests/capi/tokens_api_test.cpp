// SPDX-License-Identifier: MIT
// The tokenizer side of the C API as silktok and plug-ins use it: load as a mesh, encode
// statistics, decode with vertex splitting, round trip, grammar check, hole repair, random walks,
// save formats. Expected values come from the shared goldens (official tokenizer outputs), from
// an independent fan count written here, or from a fixture whose defect is known by construction.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "decoder/grammar.h"
#include "io/tokens/token_text.h"
#include "silk/silk.h"
#include "silk/silk.hpp"
#include "support/capi_counts.h"
#include "support/test_paths.h"
#include "tokenizer/adjacency/between_layer_encoder.h"
#include "tokenizer/packing/token_writer.h"

namespace {

namespace fs = std::filesystem;

std::vector<int32_t> GoldenIds(const std::string& name) {
  auto ids = silk::ReadTokenText(silk::testing::SharedPath("spec/golden/" + name + ".tokens.txt"));
  EXPECT_TRUE(ids.ok()) << ids.status().ToString();
  return ids.ok() ? *ids : std::vector<int32_t>{};
}

silk_tokens* MakeTokens(const std::vector<int32_t>& ids) {
  silk_tokens* t = nullptr;
  EXPECT_EQ(silk_tokens_create(ids.data(), ids.size(), &t), SILK_OK);
  return t;
}

std::vector<int32_t> Triangles(const silk_mesh* m) {
  std::vector<int32_t> v(3 * silk::testing::TriangleCount(m));
  if (!v.empty()) {
    EXPECT_EQ(silk_mesh_copy_triangles(m, v.data(), v.size(), nullptr), SILK_OK);
  }
  return v;
}

// Vertices whose incident faces form two or more edge-connected fans (written here, independent
// of the library's vertex_fans).
int VerticesWithSeveralFans(const std::vector<int32_t>& tris) {
  std::map<int32_t, std::vector<int>> faces_of;
  for (size_t f = 0; f < tris.size() / 3; ++f)
    for (int k = 0; k < 3; ++k) faces_of[tris[3 * f + k]].push_back(static_cast<int>(f));
  int several = 0;
  for (const auto& [v, fs] : faces_of) {
    std::vector<int> parent(fs.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    auto others = [&](int f) {
      std::vector<int32_t> o;
      for (int k = 0; k < 3; ++k)
        if (tris[3 * f + k] != v) o.push_back(tris[3 * f + k]);
      return o;
    };
    for (size_t a = 0; a < fs.size(); ++a)
      for (size_t b = a + 1; b < fs.size(); ++b) {
        const auto oa = others(fs[a]), ob = others(fs[b]);
        for (int32_t x : oa)
          if (std::find(ob.begin(), ob.end(), x) != ob.end())
            parent[find(static_cast<int>(a))] = find(static_cast<int>(b));
      }
    int roots = 0;
    for (size_t a = 0; a < fs.size(); ++a) roots += find(static_cast<int>(a)) == static_cast<int>(a);
    several += roots > 1;
  }
  return several;
}

TEST(CapiTokens, EncodeStatsCarryCleanupCountsAndPhaseTimes) {
  silk_mesh* m = nullptr;
  ASSERT_EQ(silk_mesh_load(silk::testing::SharedPath("spec/golden/dirty_cube.obj").c_str(), nullptr, &m), SILK_OK)
      << silk_last_error();
  silk_tokens* t = nullptr;
  silk_encode_stats st;
  std::memset(&st, 0xff, sizeof st);
  st.struct_size = sizeof st;
  ASSERT_EQ(silk_mesh_encode(m, nullptr, &t, &st), SILK_OK) << silk_last_error();
  EXPECT_EQ(silk::testing::TokenCount(t), GoldenIds("dirty_cube").size());  // the official ids' count
  EXPECT_EQ(st.tokens, static_cast<int64_t>(silk::testing::TokenCount(t)));
  // dirty_cube is unwelded (every quad has its own vertices) and has a 2-face component that is
  // dropped (spec/golden/make_inputs.py).
  EXPECT_GT(st.merged_vertices, 0);
  EXPECT_EQ(st.components_dropped_small, 1);
  for (double s : {st.seconds_quantize_cleanup, st.seconds_nonmanifold, st.seconds_orientation, st.seconds_components,
                   st.seconds_layering, st.seconds_codecs, st.seconds_packing}) {
    EXPECT_GE(s, 0);
    EXPECT_LE(s, st.seconds);
  }
  silk_tokens_destroy(t);
  silk_mesh_destroy(m);
}

// A PLY without faces: a point cloud by default (silkgen's input), the mesh reader's refusal
// when loaded as a mesh (the tokenizer's view, silktok).
TEST(CapiTokens, LoadAsMeshReadsAPlyAsTheTokenizerDoes) {
  const fs::path dir = fs::temp_directory_path() / ("silk_capi_tokens_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string ply = (dir / "cloud.ply").string();
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                        "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                        "end_header\n0 0 0 0 0 1\n";
  silk_mesh* m = nullptr;
  ASSERT_EQ(silk_mesh_load(ply.c_str(), nullptr, &m), SILK_OK) << silk_last_error();
  EXPECT_EQ(silk_mesh_has_normals(m), 1);
  silk_mesh_destroy(m);
  silk_load_params lp = silk_load_default_params();
  EXPECT_EQ(lp.point_clouds, 1);
  lp.point_clouds = 0;
  EXPECT_EQ(silk_mesh_load(ply.c_str(), &lp, &m), SILK_ERR_PARSE);
  EXPECT_EQ(m, nullptr);
  EXPECT_NE(std::string(silk_last_error()).find("no faces"), std::string::npos) << silk_last_error();
  lp.point_clouds = 2;
  EXPECT_EQ(silk_mesh_load(ply.c_str(), &lp, &m), SILK_ERR_INVALID_ARGUMENT);
  fs::remove_all(dir);
}

TEST(CapiTokens, DecodeSplitsEveryVertexWithSeveralFans) {
  int streams_with_bowties = 0;
  for (const auto& e : fs::directory_iterator(silk::testing::SharedPath("spec/golden-dev"))) {
    if (e.path().string().find(".tokens.txt") == std::string::npos) continue;
    silk_tokens* t = nullptr;
    ASSERT_EQ(silk_tokens_load(e.path().c_str(), &t), SILK_OK);
    silk_decode_params p = silk_decode_default_params();
    EXPECT_EQ(p.split_nonmanifold_vertices, 0);
    silk_mesh *keep = nullptr, *split = nullptr;
    silk_decode_stats ks = silk_cpp::Sized<silk_decode_stats>(), ss = ks;
    ASSERT_EQ(silk_tokens_decode(t, &p, &keep, &ks), SILK_OK) << e.path();
    p.split_nonmanifold_vertices = 1;
    ASSERT_EQ(silk_tokens_decode(t, &p, &split, &ss), SILK_OK) << e.path();
    const int bowties = VerticesWithSeveralFans(Triangles(keep));
    EXPECT_EQ(VerticesWithSeveralFans(Triangles(split)), 0) << e.path();
    EXPECT_EQ(ks.vertices_split, 0);
    EXPECT_EQ(ss.vertices_split, bowties) << e.path();
    EXPECT_EQ(static_cast<size_t>(ks.vertices), silk::testing::VertexCount(keep));
    EXPECT_GE(silk::testing::VertexCount(split), silk::testing::VertexCount(keep) + static_cast<size_t>(bowties));
    EXPECT_EQ(silk::testing::TriangleCount(split), silk::testing::TriangleCount(keep));
    EXPECT_EQ(ss.components, ks.components);
    streams_with_bowties += bowties > 0;
    silk_mesh_destroy(keep);
    silk_mesh_destroy(split);
    silk_tokens_destroy(t);
  }
  EXPECT_GT(streams_with_bowties, 0) << "no stream with a bowtie: the test would be vacuous";
}

TEST(CapiTokens, RoundTripOfTheGoldensIsExact) {
  for (const char* name : {"cube", "icosphere2", "nonmanifold_book", "cylinder_capped"}) {
    silk_mesh* m = nullptr;
    ASSERT_EQ(
        silk_mesh_load(silk::testing::SharedPath(std::string("spec/golden/") + name + ".obj").c_str(), nullptr, &m),
        SILK_OK);
    silk_roundtrip_report r = silk_cpp::Sized<silk_roundtrip_report>();
    ASSERT_EQ(silk_mesh_roundtrip(m, nullptr, &r), SILK_OK) << silk_last_error();
    EXPECT_EQ(r.tokens, static_cast<int64_t>(GoldenIds(name).size())) << name;
    EXPECT_EQ(r.exact, 1) << name;
    EXPECT_EQ(r.missing + r.reversed, 0) << name;
    EXPECT_EQ(r.recovered, r.representable_faces) << name;
    EXPECT_GT(r.decoded_faces, 0) << name;
    silk_mesh_destroy(m);
  }
  EXPECT_EQ(silk_mesh_roundtrip(nullptr, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
}

TEST(CapiTokens, CheckAcceptsGoldensAndNamesTheFirstIllegalId) {
  std::vector<int32_t> ids = GoldenIds("icosphere2");
  silk_tokens* t = MakeTokens(ids);
  silk_check_result r = silk_cpp::Sized<silk_check_result>();
  ASSERT_EQ(silk_tokens_check(t, nullptr, &r), SILK_OK);
  EXPECT_EQ(r.accepted, 1);
  EXPECT_EQ(r.position, -1);
  EXPECT_STREQ(r.message, "");
  silk_tokens_destroy(t);
  // The stream cut inside its component: incomplete at the end, unless a prefix is allowed.
  std::vector<int32_t> cut(ids.begin(), ids.begin() + 20);
  t = MakeTokens(cut);
  ASSERT_EQ(silk_tokens_check(t, nullptr, &r), SILK_OK);
  EXPECT_EQ(r.accepted, 0);
  EXPECT_EQ(r.position, 20);
  EXPECT_EQ(r.id, -1);
  EXPECT_STREQ(silk_reject_reason_name(r.reason), "incomplete");
  silk_check_params p = silk_check_default_params();
  EXPECT_EQ(p.max_length, 10240);
  p.allow_prefix = 1;
  ASSERT_EQ(silk_tokens_check(t, &p, &r), SILK_OK);
  EXPECT_EQ(r.accepted, 1);
  silk_tokens_destroy(t);
  // A PAD (never legal, token_format.md §9) at index 5.
  std::vector<int32_t> pad = ids;
  pad[5] = silk_cpp::Vocab().pad_id;
  t = MakeTokens(pad);
  ASSERT_EQ(silk_tokens_check(t, nullptr, &r), SILK_OK);
  EXPECT_EQ(r.accepted, 0);
  EXPECT_EQ(r.position, 5);
  EXPECT_EQ(r.id, silk_cpp::Vocab().pad_id);
  EXPECT_STREQ(silk_reject_reason_name(r.reason), "pad_token");
  EXPECT_NE(std::string(r.message).find("token 5"), std::string::npos) << r.message;
  // A length limit below the stream's length.
  p = silk_check_default_params();
  p.max_length = 10;
  silk_tokens_destroy(t);
  t = MakeTokens(ids);
  ASSERT_EQ(silk_tokens_check(t, &p, &r), SILK_OK);
  EXPECT_EQ(r.accepted, 0);
  EXPECT_STREQ(silk_reject_reason_name(r.reason), "too_long");
  p.window_rule = 7;
  EXPECT_EQ(silk_tokens_check(t, &p, &r), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_STREQ(silk_reject_reason_name(-1), "unknown");
  EXPECT_STREQ(silk_reject_reason_name(0), "none");
  silk_tokens_destroy(t);
}

// The cube golden with one between-layer 1 cleared (the vertex of layer 2 no longer sees ring
// vertex 2): its two faces at that edge go, leaving a 4-edge hole in 10 faces, by construction
// (as tests/decoder/hole_repair_test.cpp).
std::vector<int32_t> CubeWithHole() {
  silk::Grammar g;
  for (int32_t id : GoldenIds("cube")) EXPECT_TRUE(g.Accept(id).ok());
  silk::LayeredStream s = g.stream();
  auto& bt = s.components[0].layers[2].vertices[0].between;
  bt.clear();
  silk::EncodeBetweenLayerRow(6, {0, 1, 3, 4, 5}, &bt);
  return silk::WriteTokenStream(s);
}

TEST(CapiTokens, RepairClosesAKnownHoleAndReportsIt) {
  silk_tokens* t = MakeTokens(CubeWithHole());
  silk_repair_params p = silk_repair_default_params();
  EXPECT_EQ(p.holes, SILK_HOLES_REPAIR);
  EXPECT_EQ(p.max_fill_loop, 8);
  silk_mesh* m = nullptr;
  silk_repair_stats st = silk_cpp::Sized<silk_repair_stats>();
  silk_report* rep = nullptr;
  ASSERT_EQ(silk_tokens_repair(t, &p, &m, &st, &rep), SILK_OK) << silk_last_error();
  EXPECT_EQ(st.illegal_at, -1);
  EXPECT_EQ(st.tokens_accepted, static_cast<int64_t>(silk::testing::TokenCount(t)));
  EXPECT_EQ(st.holes_found, 1);
  EXPECT_EQ(st.holes_repaired, 1);
  EXPECT_EQ(st.watertight, 1);
  EXPECT_EQ(st.faces, 12);  // a cube again
  EXPECT_EQ(st.open_edges_after, 0);
  EXPECT_GT(st.open_edges_before, 0);
  const nlohmann::json j = nlohmann::json::parse(silk_report_json(rep));
  EXPECT_TRUE(j["illegal"].is_null());
  ASSERT_EQ(j["holes"].size(), 1u);
  EXPECT_EQ(j["holes"][0]["loop"].size(), 4u);
  EXPECT_TRUE(j["holes"][0]["repaired"].get<bool>());
  EXPECT_FALSE(j["holes"][0]["added_edges"].empty());
  EXPECT_EQ(j["faces"], st.faces);
  silk_report_destroy(rep);
  silk_mesh_destroy(m);
  // Report only: the hole stays.
  p.holes = SILK_HOLES_REPORT;
  ASSERT_EQ(silk_tokens_repair(t, &p, &m, &st, nullptr), SILK_OK);
  EXPECT_EQ(st.holes_found, 1);
  EXPECT_EQ(st.holes_repaired, 0);
  EXPECT_EQ(st.watertight, 0);
  EXPECT_EQ(st.faces, 10);
  silk_mesh_destroy(m);
  p.holes = 3;
  EXPECT_EQ(silk_tokens_repair(t, &p, &m, &st, nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(m, nullptr);
  silk_tokens_destroy(t);
}

TEST(CapiTokens, RepairStopsAtTheFirstIllegalId) {
  std::vector<int32_t> ids = GoldenIds("cube");
  ids.insert(ids.begin() + 30, silk_cpp::Vocab().pad_id);
  silk_tokens* t = MakeTokens(ids);
  silk_mesh* m = nullptr;
  silk_repair_stats st = silk_cpp::Sized<silk_repair_stats>();
  silk_report* rep = nullptr;
  ASSERT_EQ(silk_tokens_repair(t, nullptr, &m, &st, &rep), SILK_OK) << silk_last_error();
  EXPECT_EQ(st.illegal_at, 30);
  EXPECT_EQ(st.tokens_accepted, 30);
  const nlohmann::json j = nlohmann::json::parse(silk_report_json(rep));
  EXPECT_EQ(j["illegal"]["position"], 30);
  EXPECT_EQ(j["illegal"]["reason"], "pad_token");
  silk_report_destroy(rep);
  silk_mesh_destroy(m);
  silk_tokens_destroy(t);
}

TEST(CapiTokens, RandomWalksAreLegalSeededAndDecode) {
  silk_random_walk_params p = silk_random_walk_default_params();
  EXPECT_EQ(p.seed, 1u);
  std::vector<int32_t> first;
  for (uint64_t seed : {1, 2, 3, 1}) {
    p.seed = seed;
    silk_tokens* t = nullptr;
    silk_mesh* m = nullptr;
    ASSERT_EQ(silk_tokens_random_walk(&p, &t, &m), SILK_OK) << silk_last_error();
    std::vector<int32_t> ids(silk::testing::TokenCount(t));
    ASSERT_EQ(silk_tokens_copy(t, ids.data(), ids.size(), nullptr), SILK_OK);
    EXPECT_EQ(ids.back(), silk_cpp::Vocab().eos_id);
    silk_check_result r = silk_cpp::Sized<silk_check_result>();
    ASSERT_EQ(silk_tokens_check(t, nullptr, &r), SILK_OK);
    EXPECT_EQ(r.accepted, 1) << r.message;
    EXPECT_EQ(VerticesWithSeveralFans(Triangles(m)), 0);  // vertex fans resolved
    if (seed == 1 && first.empty()) {
      first = ids;
    } else if (seed == 1) {
      EXPECT_EQ(ids, first);  // same seed, same walk
    }
    silk_mesh_destroy(m);
    silk_tokens_destroy(t);
  }
  p.max_layer_size = 201;
  silk_tokens* t = nullptr;
  EXPECT_EQ(silk_tokens_random_walk(&p, &t, nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(t, nullptr);
}

TEST(CapiTokens, SaveWritesTheRequestedFormatAndComment) {
  const fs::path dir = fs::temp_directory_path() / ("silk_capi_save_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  silk_tokens* t = MakeTokens(GoldenIds("cube"));
  silk_decode_params dp = silk_decode_default_params();
  dp.grid_coordinates = 1;
  silk_mesh* m = nullptr;
  ASSERT_EQ(silk_tokens_decode(t, &dp, &m, nullptr), SILK_OK);
  silk_save_params sp = silk_save_default_params();
  EXPECT_EQ(sp.format, SILK_FORMAT_BY_EXTENSION);
  EXPECT_EQ(silk_mesh_save(m, (dir / "cube.mesh").c_str(), &sp), SILK_ERR_UNSUPPORTED);
  EXPECT_FALSE(fs::exists(dir / "cube.mesh"));
  sp.format = SILK_FORMAT_OBJ;
  sp.obj_comment = "line one\nline two";
  ASSERT_EQ(silk_mesh_save(m, (dir / "cube.mesh").c_str(), &sp), SILK_OK) << silk_last_error();
  std::ifstream in(dir / "cube.mesh");
  std::string l1, l2, l3;
  std::getline(in, l1);
  std::getline(in, l2);
  std::getline(in, l3);
  EXPECT_EQ(l1, "# line one");
  EXPECT_EQ(l2, "# line two");
  EXPECT_EQ(l3.rfind("v ", 0), 0u);
  EXPECT_EQ(l3.find('.'), std::string::npos) << l3;  // grid coordinates print as integers
  sp.format = 9;
  EXPECT_EQ(silk_mesh_save(m, (dir / "x.obj").c_str(), &sp), SILK_ERR_INVALID_ARGUMENT);
  silk_mesh_destroy(m);
  silk_tokens_destroy(t);
  fs::remove_all(dir);
}

}  // namespace
