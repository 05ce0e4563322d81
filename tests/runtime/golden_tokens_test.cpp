// SPDX-License-Identifier: MIT
// The committed generation goldens (tests/models/golden/*.tokens.txt) checked without the
// runtime: each is a complete legal sequence under the run's 300-id budget and decodes to a
// mesh that keeps the grammar's structural guarantees (so a golden can only be updated to
// output that passes these checks; silkgen_golden compares silkgen's output with them).
#include <gtest/gtest.h>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "io/tokens/token_text.h"
#include "support/test_paths.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

TEST(GenerationGoldens, LegalCompleteAndWellFormed) {
  for (const char* name : {"torus_knot_s7", "points_s3"}) {
    auto ids = ReadTokenText(testing::SourcePath(std::string("tests/models/golden/") + name + ".tokens.txt"));
    ASSERT_TRUE(ids.ok()) << ids.status().ToString();
    ASSERT_FALSE(ids->empty());
    EXPECT_LE(ids->size(), 300u) << name;
    EXPECT_EQ(ids->back(), vocab::k_eos_id) << name;
    GrammarOptions go;
    go.max_length = 300;
    Grammar g(go);
    for (size_t i = 0; i < ids->size(); ++i) {
      Rejection r = g.Accept((*ids)[i]);
      ASSERT_TRUE(r.ok()) << name << " id " << i << ": " << r.message;
    }
    EXPECT_TRUE(g.Ended());
    MeshBuildReport report;
    auto mesh = BuildMesh(g.stream(), MeshBuildOptions{}, &report);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    EXPECT_GT(mesh->faces.size(), 100u) << name;
    EXPECT_EQ(CheckMeshGuarantees(*mesh), "") << name;
  }
}

}  // namespace
}  // namespace silk
