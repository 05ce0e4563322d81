// SPDX-License-Identifier: MIT
// Best of N's parts with the tiny model: seed derivation, the score, and the choice among scored
// candidates (the session's runs of N: generation_session_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/splitmix64.h"
#include "runtime/candidates.h"
#include "runtime_test_util.h"

namespace silk {
namespace {

GenerateOptions Options(uint64_t seed, int32_t candidates) {
  GenerateOptions o;
  o.sampling.seed = seed;
  o.sampling.temperature = 0.8;
  o.sampling.top_k = 50;
  o.max_tokens = 300;
  o.candidates = candidates;
  return o;
}

TEST(Candidates, SeedDerivation) {
  EXPECT_EQ(CandidateSeed(12345, 0), 12345u);
  // SplitMix64's first output from state 0 (the published reference value): seed + 1 wraps to 0.
  EXPECT_EQ(CandidateSeed(~uint64_t{0}, 1), 0xE220A8397B1DCDAFull);
  std::set<uint64_t> seen;
  for (int32_t i = 0; i < 64; ++i) {
    seen.insert(CandidateSeed(7, i));
    EXPECT_EQ(CandidateSeed(7, i), CandidateSeed(7, i));
  }
  EXPECT_EQ(seen.size(), 64u);
}

class CandidatesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = testing::LoadTinyModel(1);
    ASSERT_TRUE(model_);
    points_ = testing::SamplePoints(*model_);
  }
  std::unique_ptr<Model> model_;
  std::vector<float> points_;
};

// The choice keeps the lowest score (the earliest on ties), a candidate with faces before one
// without, lists every entry in order, sums the times, and leaves a cancelled scoring undone.
TEST_F(CandidatesTest, TheChoiceKeepsTheLowestScore) {
  Generator gen(*model_);
  std::vector<GenerateResult> runs;
  for (uint64_t seed : {21, 22, 23}) {
    auto r = gen.Run(points_, Options(seed, 1));
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    ASSERT_GT(r->mesh.faces.size(), 0u) << seed;
    runs.push_back(std::move(*r));
  }
  GenerateResult empty;  // no faces: never chosen, whatever its score
  std::vector<double> scores;
  for (const auto& r : runs) scores.push_back(ScoreAgainstPoints(r.mesh, points_));
  CandidateChoice choice;
  GenerateResult copy = runs[0];
  EXPECT_EQ(choice.Add(&copy, 21, points_, [] { return true; }).code(), StatusCode::kCancelled);
  EXPECT_EQ(choice.size(), 0);
  EXPECT_EQ(copy.tokens, runs[0].tokens);  // left as it was
  ASSERT_TRUE(choice.Add(&empty, 20, points_, {}).ok());
  double generation_seconds = 0;
  for (size_t i = 0; i < runs.size(); ++i) {
    generation_seconds += runs[i].stats.generation_seconds;
    GenerateResult r = runs[i];
    ASSERT_TRUE(choice.Add(&r, 21 + i, points_, {}).ok());
  }
  const size_t want = static_cast<size_t>(std::min_element(scores.begin(), scores.end()) - scores.begin());
  const GenerateResult best = choice.Take();
  EXPECT_EQ(choice.size(), 0);
  ASSERT_EQ(best.stats.candidates.size(), 4u);
  EXPECT_TRUE(std::isinf(best.stats.candidates[0].score));
  EXPECT_EQ(best.stats.chosen_candidate, static_cast<int32_t>(want + 1));
  EXPECT_EQ(best.tokens, runs[want].tokens);
  for (size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(best.stats.candidates[i + 1].seed, 21 + i);
    EXPECT_EQ(best.stats.candidates[i + 1].score, scores[i]);
    EXPECT_EQ(best.stats.candidates[i + 1].tokens, static_cast<int64_t>(runs[i].tokens.size()));
  }
  EXPECT_NEAR(best.stats.generation_seconds, generation_seconds, 1e-9);
}

TEST_F(CandidatesTest, ScoreIsSmallerForTheInputItself) {
  // An independent check of the score's direction: the points themselves against a far mesh.
  TokenizerDecodedMesh far;
  far.positions = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  far.faces = {{0, 1, 2}};
  TokenizerDecodedMesh none;
  EXPECT_TRUE(std::isinf(ScoreAgainstPoints(none, points_)));
  const double s = ScoreAgainstPoints(far, points_);
  EXPECT_TRUE(std::isfinite(s));
  EXPECT_GT(s, 0.3);  // a corner patch at -1 against points spread over [-0.95, 0.95]
}

}  // namespace
}  // namespace silk
