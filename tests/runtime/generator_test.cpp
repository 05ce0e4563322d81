// SPDX-License-Identifier: MIT
// Whole generations with the tiny model: determinism, grammar validity of every result,
// equivalence of the optimised paths (forced-token skipping, in-place cache) with the plain
// ones, caps, callbacks and unconstrained mode.
#include <gtest/gtest.h>

#include <cmath>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "runtime/generator.h"
#include "runtime_test_util.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

GenerateOptions Options(uint64_t seed, int32_t max_tokens = 300) {
  GenerateOptions o;
  o.sampling.seed = seed;
  o.sampling.temperature = 0.8;
  o.sampling.top_k = 50;
  o.max_tokens = max_tokens;
  return o;
}

class GeneratorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = testing::LoadTinyModel(1);
    ASSERT_TRUE(model_);
    points_ = testing::SamplePoints(*model_);
    ASSERT_FALSE(points_.empty());
  }
  GenerateResult Run(const GenerateOptions& o, Generator* g = nullptr) {
    Generator local(*model_);
    auto r = (g ? g : &local)->Run(points_, o);
    EXPECT_TRUE(r.ok()) << r.status().ToString();
    return r.ok() ? std::move(*r) : GenerateResult{};
  }
  std::unique_ptr<Model> model_;
  std::vector<float> points_;
};

TEST_F(GeneratorTest, SameSeedSameTokensAcrossRunsAndGenerators) {
  Generator reused(*model_);
  const auto a = Run(Options(5), &reused);
  const auto b = Run(Options(5), &reused);  // cache reused
  const auto c = Run(Options(5));           // fresh generator
  ASSERT_GT(a.tokens.size(), 10u);
  EXPECT_EQ(a.tokens, b.tokens);
  EXPECT_EQ(a.tokens, c.tokens);
  EXPECT_NE(a.tokens, Run(Options(6)).tokens);
  // The encoder runs once per input: the second run on the same points (best of N's next
  // candidate) reuses its output; other points run it again, and going back runs it again.
  EXPECT_GT(a.stats.seconds.encoder, 0.0);
  EXPECT_EQ(b.stats.seconds.encoder, 0.0);
  EXPECT_GT(c.stats.seconds.encoder, 0.0);
  std::vector<float> moved = points_;
  for (size_t i = 0; i < moved.size(); i += 6) moved[i] *= 0.5f;
  auto other = reused.Run(moved, Options(5));
  ASSERT_TRUE(other.ok()) << other.status().ToString();
  EXPECT_GT(other->stats.seconds.encoder, 0.0);
  EXPECT_NE(other->tokens, a.tokens);
  const auto back = Run(Options(5), &reused);
  EXPECT_GT(back.stats.seconds.encoder, 0.0);
  EXPECT_EQ(back.tokens, a.tokens);
}

// The grammar promises a non-empty legal set before EOS within the length budget (grammar.h,
// "Liveness"). Generation with a token cap leans on that promise; a dead end is a grammar bug.
TEST_F(GeneratorTest, GrammarStaysLiveUnderTheTokenBudget) {
  for (uint64_t seed = 0; seed < 6; ++seed) {
    const auto r = Run(Options(seed));
    EXPECT_NE(r.stats.stop_reason, StopReason::kGrammarDeadEnd) << "seed " << seed << ": " << r.stats.dead_end;
  }
}

TEST_F(GeneratorTest, EveryResultIsALegalSequenceAndAGoodMesh) {
  int ended = 0;
  for (uint64_t seed = 0; seed < 8; ++seed) {
    GenerateOptions o = Options(seed);
    o.record_trace = true;
    const auto r = Run(o);
    ASSERT_FALSE(r.tokens.empty());
    EXPECT_LE(r.tokens.size(), 300u);
    if (r.stats.stop_reason != StopReason::kEos) continue;
    ++ended;
    EXPECT_EQ(r.tokens.back(), vocab::k_eos_id);
    GrammarOptions go;
    go.max_length = 300;
    size_t pos = 0;
    Rejection rej = CheckTokens(r.tokens, go, &pos);
    EXPECT_TRUE(rej.ok()) << "seed " << seed << " at " << pos << ": " << rej.message;
    EXPECT_EQ(CheckMeshGuarantees(r.mesh), "") << "seed " << seed;
    EXPECT_GT(r.mesh.faces.size(), 0u);
    EXPECT_EQ(r.stats.tokens, static_cast<int64_t>(r.tokens.size()));
    EXPECT_EQ(r.stats.forced_tokens + r.stats.sampled_tokens, r.stats.tokens);
    // Forced ids skip the model: one decoder call per sampled id.
    EXPECT_EQ(r.stats.model_calls, r.stats.sampled_tokens);
    // BOS + every id before the last sampled one is in the cache; trailing forced ids are not.
    size_t trailing_forced = 0;
    for (size_t i = r.trace.size(); i > 0 && r.trace[i - 1].forced; --i) ++trailing_forced;
    const size_t last_sampled = r.trace.size() - trailing_forced;  // 1-based index of it
    EXPECT_EQ(r.stats.fed_positions, static_cast<int64_t>(last_sampled));
  }
  EXPECT_GE(ended, 3);
}

TEST_F(GeneratorTest, ThreadsDoNotChangeTokensOfTheTinyModel) {
  auto two = testing::LoadTinyModel(2);
  ASSERT_TRUE(two);
  Generator g(*two);
  auto r = g.Run(points_, Options(8));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->tokens, Run(Options(8)).tokens);
}

TEST_F(GeneratorTest, CapsAndCallbacks) {
  const auto small = Run(Options(4, 40));
  EXPECT_LE(small.tokens.size(), 40u);
  EXPECT_EQ(small.tokens.back(), vocab::k_eos_id);  // the grammar's budget closes in time

  bool capped = false;
  for (uint64_t seed = 0; seed < 6 && !capped; ++seed) {
    GenerateOptions o = Options(seed, 0);
    o.max_faces = 10;
    const auto faces = Run(o);
    if (faces.stats.stop_reason == StopReason::kGrammarDeadEnd) continue;  // see GrammarStaysLive...
    EXPECT_EQ(faces.stats.stop_reason, StopReason::kMaxFaces);
    EXPECT_LE(faces.stats.faces, 10);  // a hard cap (face_cap.h)
    EXPECT_GE(faces.stats.faces, 1);
    capped = true;
  }
  EXPECT_TRUE(capped);

  int64_t last = 0, calls = 0;
  bool increasing = true;
  GenerateCallbacks cb;
  cb.progress = [&](const GenerateProgress& p) {
    increasing = increasing && p.tokens > last;
    last = p.tokens;
    ++calls;
  };
  cb.cancel = [&]() { return calls >= 25; };
  Generator g(*model_);
  auto r = g.Run(points_, Options(4), cb);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kCancelled);
  EXPECT_TRUE(increasing);
  EXPECT_EQ(calls, 25);
}

TEST_F(GeneratorTest, UnconstrainedRecordsTheFirstIllegalId) {
  GenerateOptions o = Options(1, 60);
  o.unconstrained = true;
  const auto r = Run(o);
  EXPECT_EQ(r.stats.forced_tokens, 0);
  EXPECT_LE(r.tokens.size(), 60u);
  // A random model leaves the grammar quickly; the mesh is the legal prefix.
  ASSERT_GE(r.stats.illegal_at, 0);
  EXPECT_FALSE(r.stats.illegal_reason.empty());
  EXPECT_EQ(CheckMeshGuarantees(r.mesh), "");
}

TEST_F(GeneratorTest, BadArguments) {
  Generator g(*model_);
  EXPECT_FALSE(g.Run({}, Options(0)).ok());
  EXPECT_FALSE(g.Run(std::vector<float>(7, 0.f), Options(0)).ok());
  GenerateOptions o = Options(0);
  o.max_tokens = -1;
  EXPECT_FALSE(g.Run(points_, o).ok());
  o = Options(0);
  o.sampling.top_p = 1.5;
  EXPECT_EQ(g.Run(points_, o).status().code(), StatusCode::kInvalidArgument);
  o = Options(0);
  o.sampling.temperature = std::nan("");
  EXPECT_FALSE(g.Run(points_, o).ok());
}

}  // namespace
}  // namespace silk
