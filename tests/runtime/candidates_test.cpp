// Best of N with the tiny model: seed derivation, N = 1 equals a plain run, every candidate is
// the plain run of its seed, the returned one has the lowest score, scores are recomputable.
#include <gtest/gtest.h>

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

TEST_F(CandidatesTest, OneCandidateIsThePlainRun) {
  Generator gen(*model_);
  auto plain = gen.Run(points_, Options(4, 1));
  auto best = RunCandidates(&gen, points_, Options(4, 1));
  ASSERT_TRUE(plain.ok() && best.ok());
  EXPECT_EQ(plain->tokens, best->tokens);
  ASSERT_EQ(best->stats.candidates.size(), 1u);
  EXPECT_EQ(best->stats.candidates[0].seed, 4u);
  EXPECT_EQ(best->stats.chosen_candidate, 0);
}

TEST_F(CandidatesTest, TheReturnedCandidateHasTheLowestScore) {
  Generator gen(*model_);
  const int32_t n = 4;
  auto best = RunCandidates(&gen, points_, Options(11, n));
  ASSERT_TRUE(best.ok()) << best.status().ToString();
  const auto& c = best->stats.candidates;
  ASSERT_EQ(c.size(), static_cast<size_t>(n));
  const CandidateScore& chosen = c[static_cast<size_t>(best->stats.chosen_candidate)];
  // The returned mesh's own score, recomputed, is the reported one and the minimum.
  EXPECT_EQ(ScoreAgainstPoints(best->mesh, points_), chosen.score);
  std::set<std::vector<int32_t>> distinct;
  for (int32_t i = 0; i < n; ++i) {
    EXPECT_EQ(c[i].seed, CandidateSeed(11, i));
    if (c[i].faces > 0 || chosen.faces == 0) {
      EXPECT_LE(chosen.score, c[i].score) << "candidate " << i;
    }
    // Each candidate is exactly the plain run of its seed.
    auto r = gen.Run(points_, Options(c[i].seed, 1));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(static_cast<int64_t>(r->tokens.size()), c[i].tokens);
    EXPECT_EQ(static_cast<int32_t>(r->mesh.faces.size()), c[i].faces);
    EXPECT_EQ(ScoreAgainstPoints(r->mesh, points_), c[i].score);
    if (i == best->stats.chosen_candidate) {
      EXPECT_EQ(r->tokens, best->tokens);
    }
    distinct.insert(r->tokens);
  }
  EXPECT_GT(distinct.size(), 1u);  // the seeds really differ
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
