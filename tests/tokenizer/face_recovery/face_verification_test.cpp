// SPDX-License-Identifier: MIT
// Face verification on the dev corpus: the official processed faces (minus unencodable ones)
// replay the encoder's layering per component; the recovered faces should score no worse.
// Reports how many components verify exactly, for the truth and for the decoder. The truth
// is mapped by coordinates, so coincident components and unencodable faces make its score > 0.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "tokenizer/face_compare.h"
#include "support/golden_files.h"
#include "support/test_paths.h"
#include "tokenizer/face_recovery/face_recovery.h"
#include "tokenizer/face_recovery/face_verification.h"
#include "tokenizer/packing/token_reader.h"
#include "tokenizer/truth_mapping.h"

namespace silk {
namespace {

TEST(GoldenDevVerifySlow, TruthReplaysAndRecoveryScoresNoWorse) {
  int comps = 0, truth_exact = 0, ours_exact = 0, worse = 0, truth_score = 0, ours_score = 0;
  for (const auto& name : testing::GoldenDevOkNames()) {
    const std::string base = testing::SharedPath("spec/golden-dev/" + name);
    auto stream = ReadTokens(testing::ReadIds(base + ".tokens.txt"));
    ASSERT_TRUE(stream.ok());
    auto processed = testing::ReadCoordFaces(base + ".processed.txt");
    auto unencodable = testing::ReadCoordFaces(base + ".unencodable.txt");
    for (size_t ci = 0; ci < stream->components.size(); ++ci) {
      const StreamComponent& comp = stream->components[ci];
      auto g = BuildComponentGraph(testing::LayersOfComponent(comp));
      ASSERT_TRUE(g.ok());
      const auto truth = testing::TruthOnGraph(*g, processed, unencodable);
      FaceRecoveryStats st;
      auto ours = RecoverFacesOfGraph(*g, &st);
      ASSERT_TRUE(ours.ok());
      const int ts = VerifyComponentFaces(*g, truth).Score();
      const int os = VerifyComponentFaces(*g, *ours).Score();
      ++comps;
      truth_exact += ts == 0;
      ours_exact += os == 0;
      truth_score += ts;
      ours_score += os;
      if (os > ts) {
        ++worse;
        std::printf("  %s comp %zu: truth score %d, recovered score %d (%d evaluations%s)\n", name.c_str(), ci, ts, os,
                    st.search_evaluations, st.search_budget_exhausted ? ", budget exhausted" : "");
      }
    }
  }
  std::printf(
      "golden-dev verify: %d components; truth replays exactly in %d (defects %d), recovery in %d "
      "(defects %d); recovery worse than truth in %d\n",
      comps, truth_exact, truth_score, ours_exact, ours_score, worse);
  // Measured (docs/decoder.md): 8,997 components replay exactly; the search ends above
  // the truth's score in 4 components (a repair needs two simultaneous changes). Regression
  // bounds, not the goal (worse = 0).
  EXPECT_GE(ours_exact, 8997);
  EXPECT_LE(worse, 4);
}

}  // namespace
}  // namespace silk
