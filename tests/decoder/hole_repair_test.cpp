// SPDX-License-Identifier: MIT
// Hole detection and repair (token_format.md §12.2): a between-layer 1 cleared in a closed golden leaves
// a hole that policy "report" finds and policy "repair" closes (watertight again).
#include <gtest/gtest.h>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "io/tokens/token_text.h"
#include "support/test_paths.h"
#include "tokenizer/adjacency/between_layer_encoder.h"
#include "tokenizer/packing/token_writer.h"

namespace silk {
namespace {

Grammar Accepted(const std::vector<int32_t>& ids, WindowRule rule) {
  GrammarOptions o;
  o.window_rule = rule;
  Grammar g(o);
  for (int32_t id : ids) EXPECT_TRUE(g.Accept(id).ok());
  return g;
}

TEST(HoleRepair, ClearedBetweenColumnIsRepaired) {
  auto ids = ReadTokenText(testing::SharedPath("spec/golden/cube.tokens.txt"));
  ASSERT_TRUE(ids.ok());
  LayeredStream s = Accepted(*ids, WindowRule::kCanonical).stream();
  // Cube layer 2 (one vertex) sees all 6 ring vertices; drop column 2.
  auto& bt = s.components[0].layers[2].vertices[0].between;
  bt.clear();
  EncodeBetweenLayerRow(6, {0, 1, 3, 4, 5}, &bt);
  Grammar g = Accepted(WriteTokenStream(s), WindowRule::kUnion);
  ASSERT_TRUE(g.CanEnd());
  MeshBuildReport off_rep, rep;
  auto off = BuildMeshSoFar(g, MeshBuildOptions{HolePolicy::kReport, 8}, &off_rep);
  ASSERT_TRUE(off.ok());
  EXPECT_FALSE(IsWatertight(*off));
  ASSERT_EQ(off_rep.holes.size(), 1u);
  EXPECT_FALSE(off_rep.holes[0].repaired);
  auto fixed = BuildMeshSoFar(g, MeshBuildOptions{HolePolicy::kRepair, 8}, &rep);
  ASSERT_TRUE(fixed.ok());
  EXPECT_TRUE(IsWatertight(*fixed));
  EXPECT_EQ(CheckMeshGuarantees(*fixed), "");
  ASSERT_EQ(rep.holes.size(), 1u);
  EXPECT_TRUE(rep.holes[0].repaired);
  EXPECT_EQ(rep.holes[0].added_edges.size(), 1u);
  EXPECT_EQ(fixed->faces.size(), 12u);
}

TEST(HoleRepair, ClearedWindowBitIsReportedAndOred) {
  auto ids = ReadTokenText(testing::SharedPath("spec/golden/cube.tokens.txt"));
  ASSERT_TRUE(ids.ok());
  (*ids)[6] = 203 + 1;  // layer-1 row 0 drops its d=5 bit; row 5 still states the pair
  size_t pos = 0;
  EXPECT_EQ(CheckTokens(*ids, GrammarOptions{}, &pos).reason, RejectReason::kLayerNotClosable);
  Grammar g = Accepted(*ids, WindowRule::kUnion);
  ASSERT_EQ(g.window_findings().size(), 1u);
  EXPECT_EQ(g.window_findings()[0].row_a, 0);
  EXPECT_EQ(g.window_findings()[0].row_b, 5);
  auto mesh = BuildMeshSoFar(g, MeshBuildOptions{}, nullptr);
  ASSERT_TRUE(mesh.ok());
  EXPECT_TRUE(IsWatertight(*mesh));
}

}  // namespace
}  // namespace silk
