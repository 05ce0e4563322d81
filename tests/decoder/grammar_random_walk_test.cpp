// SPDX-License-Identifier: MIT
// Seeded property test: random legal walks (ids drawn from the legal masks) always end with
// EOS, CheckTokens accepts them, and their meshes satisfy the guarantees of grammar.h, the
// vertex-manifold one included (checked by CheckMeshGuarantees and by an independent flood fill
// below). Even seeds build with the hole policy off (bowties split), odd ones with kRepair (gaps
// between fans closed first).
// A failing walk is written to $TMPDIR/silk_walk_<seed>.tokens.txt for `silktok check`.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "decoder/random_walk.h"
#include "io/tokens/token_text.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

// Independent of mesh/vertex_fans: for each vertex, flood-fill its faces through faces that
// share a second corner; more than one region is a bowtie. Returns the number of such vertices.
int32_t BowtieVertices(const TokenizerDecodedMesh& mesh) {
  std::vector<std::vector<int32_t>> at(mesh.positions.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int32_t v : mesh.faces[f]) at[v].push_back(static_cast<int32_t>(f));
  int32_t bad = 0;
  for (size_t v = 0; v < at.size(); ++v) {
    const auto& fs = at[v];
    if (fs.size() < 2) continue;
    std::vector<char> seen(fs.size(), 0);
    std::vector<size_t> stack{0};
    seen[0] = 1;
    size_t reached = 1;
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      for (size_t j = 0; j < fs.size(); ++j) {
        if (seen[j]) continue;
        int32_t shared = 0;
        for (int32_t a : mesh.faces[fs[i]])
          for (int32_t b : mesh.faces[fs[j]]) shared += a == b && a != static_cast<int32_t>(v);
        if (shared > 0) {
          seen[j] = 1;
          ++reached;
          stack.push_back(j);
        }
      }
    }
    bad += reached != fs.size();
  }
  return bad;
}

std::string Dump(uint64_t seed, const std::vector<int32_t>& ids) {
  const char* tmp = std::getenv("TMPDIR");
  const std::string path = std::string(tmp ? tmp : "/tmp") + "/silk_walk_" + std::to_string(seed) + ".tokens.txt";
  std::ofstream(path) << FormatTokenText(ids);
  return path;
}

void RunWalks(uint64_t first_seed, int32_t count, const RandomWalkOptions& wo, bool check_mask) {
  int64_t faces = 0, tokens = 0, split = 0, gaps = 0;
  for (int32_t k = 0; k < count; ++k) {
    const uint64_t seed = first_seed + static_cast<uint64_t>(k);
    std::mt19937_64 rng(seed);
    Grammar g;
    std::vector<int32_t> ids = RandomLegalWalk(&g, &rng, wo);
    ASSERT_TRUE(g.Ended()) << "walk did not end; replay: " << Dump(seed, ids);
    tokens += static_cast<int64_t>(ids.size());
    std::vector<int32_t> body(ids.begin(), ids.end() - 1);
    size_t pos = 0;
    Rejection r = CheckTokens(ids, GrammarOptions{}, &pos, false);
    ASSERT_TRUE(r.ok()) << r.message << "; replay: " << Dump(seed, ids);
    MeshBuildOptions mo;
    mo.holes = seed % 2 ? HolePolicy::kRepair : HolePolicy::kOff;
    MeshBuildReport rep;
    auto mesh = BuildMeshSoFar(g, mo, &rep);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString() << "; replay: " << Dump(seed, ids);
    const std::string why = CheckMeshGuarantees(*mesh);
    ASSERT_EQ(why, "") << "replay: " << Dump(seed, ids);
    ASSERT_EQ(BowtieVertices(*mesh), 0) << "replay: " << Dump(seed, ids);
    split += rep.vertices_split;
    gaps += rep.fan_gaps_closed;
    int32_t c_tokens = 0;
    for (int32_t id : body) c_tokens += id == vocab::kCBegin;
    ASSERT_EQ(mesh->components, c_tokens);
    faces += static_cast<int64_t>(mesh->faces.size());
    if (check_mask) {
      // Mask == Accept for a sample of ids at every step; at every U/E the cached incremental
      // mesh (closed components reused) equals the mesh built from scratch.
      Grammar h;
      MeshBuildCache cache;
      std::mt19937 pick(static_cast<uint32_t>(seed));
      for (int32_t id : ids) {
        if (h.size() > 0 && (h.tokens().back() == vocab::kUBegin || h.tokens().back() == vocab::kEBegin)) {
          MeshBuildReport with_cache, fresh;
          auto a = BuildMeshSoFar(h, mo, &with_cache, &cache);
          auto b = BuildMeshSoFar(h, mo, &fresh);
          ASSERT_TRUE(a.ok() && b.ok());
          ASSERT_EQ(a->faces, b->faces) << "replay: " << Dump(seed, ids);
          ASSERT_EQ(a->positions, b->positions);
          ASSERT_EQ(with_cache.vertices_split, fresh.vertices_split);
          ASSERT_EQ(with_cache.holes.size(), fresh.holes.size());
        }
        const TokenMask m = h.LegalMask();
        for (int t = 0; t < 6; ++t) {
          const int32_t probe = std::uniform_int_distribution<int32_t>(0, TokenMask::kBits - 1)(pick);
          Grammar c = h.Clone();
          ASSERT_EQ(m.Test(probe), c.Accept(probe).ok()) << "probe " << probe << "; replay: " << Dump(seed, ids);
        }
        ASSERT_TRUE(h.Accept(id).ok());
      }
    }
  }
  EXPECT_GT(faces, count);  // every component has faces
  if (count >= 100) {       // the rule is exercised both ways, not vacuously satisfied
    EXPECT_GT(split, 0);
    EXPECT_GT(gaps, 0);
  }
  std::printf("%d walks: %lld tokens, %lld faces, %lld vertices split, %lld fan gaps closed\n", count,
              static_cast<long long>(tokens), static_cast<long long>(faces), static_cast<long long>(split),
              static_cast<long long>(gaps));
  ::testing::Test::RecordProperty("tokens", std::to_string(tokens));
}

TEST(GrammarRandomWalk, MaskMatchesAccept) { RunWalks(1000, 100, RandomWalkOptions{}, true); }

TEST(GrammarRandomWalk, LargeLayersWithExtras) {
  RandomWalkOptions wo;
  wo.max_layer_size = 40;
  wo.max_layers = 3;
  wo.extra_x = 0.3;
  RunWalks(50000, 30, wo, true);
}

TEST(GrammarRandomWalkSlow, TenThousandWalksSatisfyGuarantees) {
  RandomWalkOptions wo;
  wo.max_layer_size = 8;
  wo.max_layers = 4;
  RunWalks(1, 10000, wo, false);
}

}  // namespace
}  // namespace silk
