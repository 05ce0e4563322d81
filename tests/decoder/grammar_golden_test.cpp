// SPDX-License-Identifier: MIT
// Every official token stream (spec/golden, spec/golden-dev) is accepted token by token, each
// token is in the legal mask before it is accepted, EOS is legal exactly at the end, and the
// machine's faithful mesh (VertexFanPolicy::kKeep) equals the tokenizer's DecodeTokens on the
// same ids, and the default mesh splits exactly the vertices with two or more fans, nothing else.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "io/tokens/token_text.h"
#include "mesh/vertex_fans.h"
#include "support/test_paths.h"
#include "tokenizer/tokenizer.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

std::vector<std::string> OfficialStreams() {
  std::vector<std::string> out;
  for (const char* dir : {"spec/golden", "spec/golden-dev"}) {
    const std::string d = testing::SharedPath(dir);
    if (!std::filesystem::exists(d)) continue;
    for (const auto& e : std::filesystem::directory_iterator(d)) {
      const std::string p = e.path().string();
      if (p.size() > 11 && p.compare(p.size() - 11, 11, ".tokens.txt") == 0) out.push_back(p);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(GrammarGolden, AllOfficialStreamsAccepted) {
  const auto files = OfficialStreams();
  ASSERT_EQ(files.size(), 154u);
  size_t tokens = 0, mesh_compared = 0, meshes_with_bowties = 0;
  int64_t bowties = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f);
    auto ids = ReadTokenText(f);
    ASSERT_TRUE(ids.ok()) << ids.status().ToString();
    GrammarOptions opt;
    opt.max_length = 0;  // some dev streams exceed the model's 10240 (token_format.md §9 rejects them for training)
    Grammar g(opt);
    for (size_t i = 0; i < ids->size(); ++i) {
      const int32_t id = (*ids)[i];
      ASSERT_TRUE(g.LegalMask().Test(id)) << "position " << i << " id " << id << " not in the legal mask";
      ASSERT_EQ(g.LegalMask().Test(vocab::k_eos_id), i > 0 && (*ids)[i - 1] == vocab::kEBegin) << "position " << i;
      Rejection r = g.Accept(id);
      ASSERT_TRUE(r.ok()) << r.message;
    }
    ASSERT_TRUE(g.CanEnd());
    ASSERT_TRUE(g.LegalMask().Test(vocab::k_eos_id));
    tokens += ids->size();
    // Under the model's length limit the same stream is legal iff it fits (EOS included).
    size_t pos = 0;
    Rejection lim = CheckTokens(*ids, GrammarOptions{}, &pos);
    if (ids->size() + 1 <= 10240) {
      EXPECT_TRUE(lim.ok()) << lim.message;
    } else {
      EXPECT_EQ(lim.reason, RejectReason::kTooLong);
    }
    ASSERT_TRUE(g.Accept(vocab::k_eos_id).ok());
    // Mesh equality with the tokenizer's decoder.
    auto dec = DecodeTokens(*ids);
    ASSERT_TRUE(dec.ok()) << dec.status().ToString();
    MeshBuildReport rep;
    MeshBuildOptions keep;
    keep.vertex_fans = VertexFanPolicy::kKeep;
    auto mine = BuildMeshSoFar(g, keep, &rep);
    ASSERT_TRUE(mine.ok()) << mine.status().ToString();
    ASSERT_EQ(mine->positions, dec->positions);
    ASSERT_EQ(mine->faces.size() + rep.dropped_degenerate, dec->faces.size());
    if (rep.dropped_degenerate == 0) {
      EXPECT_EQ(mine->faces, dec->faces);
      EXPECT_EQ(mine->face_component, dec->face_component);
    }
    EXPECT_EQ(mine->components, dec->components);
    // Default: the vertex-fan rule splits each bowtie vertex of the official mesh once per extra
    // fan; faces keep their order and count, positions only gain the copies.
    const VertexFans fans = ComputeVertexFans(dec->faces, static_cast<int32_t>(dec->positions.size()));
    int64_t extra_fans = 0;
    for (int32_t n : fans.fans_per_vertex) extra_fans += n > 1 ? n - 1 : 0;
    MeshBuildReport split_rep;
    auto split = BuildMeshSoFar(g, MeshBuildOptions{}, &split_rep);
    ASSERT_TRUE(split.ok()) << split.status().ToString();
    EXPECT_EQ(split_rep.nonmanifold_vertices, fans.nonmanifold_vertices);
    EXPECT_EQ(split_rep.vertices_split, fans.nonmanifold_vertices);
    EXPECT_EQ(split_rep.vertex_copies, extra_fans);
    EXPECT_EQ(split->faces.size(), mine->faces.size());
    EXPECT_EQ(split->positions.size(), mine->positions.size() + static_cast<size_t>(extra_fans));
    EXPECT_EQ(CheckMeshGuarantees(*split), "");
    meshes_with_bowties += fans.nonmanifold_vertices > 0;
    bowties += fans.nonmanifold_vertices;
    ++mesh_compared;
  }
  std::printf("official streams: %zu meshes with vertices of two or more fans, %lld such vertices\n",
              meshes_with_bowties, static_cast<long long>(bowties));
  EXPECT_GT(tokens, 100000u);
  EXPECT_EQ(mesh_compared, 154u);
}

}  // namespace
}  // namespace silk
