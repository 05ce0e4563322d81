// SPDX-License-Identifier: MIT
// GenerationSession with the tiny model: N = 1 is the plain run; best of N equals N plain runs
// with the derived seeds scored and chosen independently here; stepping by layers crosses the
// candidates; a cancel in a later candidate leaves a usable Finish; request resolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "runtime/candidates.h"
#include "runtime/generation_session.h"
#include "runtime_test_util.h"
#include "session_run.h"

namespace silk {
namespace {

GenerationRequest Request(uint64_t seed, int32_t candidates) {
  GenerationRequest r;
  r.seed = seed;
  r.temperature = 0.8;
  r.top_k = 50;
  r.max_tokens = 300;
  r.candidates = candidates;
  r.rows = 1;  // one candidate after another (rows: candidate_rows_test.cpp)
  return r;
}

class SessionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = testing::LoadTinyModel(1);
    ASSERT_TRUE(model_);
    input_ = testing::SampleMeshInput();
    ASSERT_FALSE(input_.mesh.positions.empty());
  }
  // Start + Advance(max_ids, until) until done + Finish.
  SessionResult RunSession(GenerationSession* s, const GenerationRequest& r, int32_t max_ids = 1 << 30,
                           AdvanceUntil until = AdvanceUntil::kIds, const GenerateCallbacks& cb = {}) {
    return testing::RunSession(s, r, input_, max_ids, until, cb);
  }
  std::unique_ptr<Model> model_;
  GenerationInput input_;
};

// What best of N must return, built from plain Generator runs: candidate i = the plain run with
// CandidateSeed(seed, i), scored against the points; the lowest score wins (earliest on ties, a
// mesh with faces before one without).
struct Reference {
  std::vector<GenerateResult> runs;
  std::vector<double> scores;
  size_t chosen = 0;
};

Reference BestOfN(const Model& model, const std::vector<float>& points, GenerateOptions o, int32_t n) {
  Reference ref;
  Generator gen(model);
  const uint64_t seed = o.sampling.seed;
  for (int32_t i = 0; i < n; ++i) {
    o.sampling.seed = CandidateSeed(seed, i);
    auto r = gen.Run(points, o);
    EXPECT_TRUE(r.ok());
    ref.scores.push_back(ScoreAgainstPoints(r->mesh, points));
    const auto key = [&](size_t k) {
      return std::make_pair(ref.runs.size() > k && ref.runs[k].mesh.faces.empty(), ref.scores[k]);
    };
    ref.runs.push_back(std::move(*r));
    if (key(static_cast<size_t>(i)) < key(ref.chosen)) ref.chosen = static_cast<size_t>(i);
  }
  return ref;
}

TEST_F(SessionTest, OneCandidateIsThePlainRun) {
  GenerationSession s(*model_);
  const SessionResult got = RunSession(&s, Request(4, 1));
  Generator gen(*model_);
  auto plain = gen.Run(s.points(), s.plan().options);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(s.points(), testing::SamplePoints(*model_, 4));  // the model's pre-processing, seeded
  EXPECT_EQ(got.generation.tokens, plain->tokens);
  EXPECT_EQ(got.generation.mesh.faces, plain->mesh.faces);
  EXPECT_EQ(got.generation.stats.stop_reason, plain->stats.stop_reason);
  ASSERT_EQ(got.generation.stats.candidates.size(), 1u);
  EXPECT_EQ(got.generation.stats.candidates[0].seed, 4u);
  EXPECT_EQ(got.generation.stats.candidates[0].score, ScoreAgainstPoints(plain->mesh, s.points()));
  EXPECT_EQ(got.output.triangles.size(), plain->mesh.faces.size());
  EXPECT_GT(got.generation.stats.seconds.load_input, 0);
}

TEST_F(SessionTest, BestOfNIsTheClosestOfThePlainRuns) {
  for (uint64_t seed : {11, 12}) {
    GenerationSession s(*model_);
    const SessionResult got = RunSession(&s, Request(seed, 3));
    const Reference ref = BestOfN(*model_, s.points(), s.plan().options, 3);
    const GenerateResult& want = ref.runs[ref.chosen];
    EXPECT_EQ(got.generation.stats.chosen_candidate, static_cast<int32_t>(ref.chosen)) << seed;
    EXPECT_EQ(got.generation.tokens, want.tokens) << seed;
    EXPECT_EQ(got.generation.mesh.faces, want.mesh.faces) << seed;
    EXPECT_EQ(got.generation.mesh.face_component, want.mesh.face_component) << seed;
    ASSERT_EQ(got.generation.stats.candidates.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
      const CandidateScore& c = got.generation.stats.candidates[i];
      EXPECT_EQ(c.seed, CandidateSeed(seed, static_cast<int32_t>(i)));
      EXPECT_EQ(c.score, ref.scores[i]);
      EXPECT_EQ(c.tokens, static_cast<int64_t>(ref.runs[i].tokens.size()));
      EXPECT_EQ(c.faces, static_cast<int32_t>(ref.runs[i].mesh.faces.size()));
    }
  }
}

// Stepping by layers: each call stops at a completed layer or a candidate's end; the preview
// grows within a candidate, starts again with the next, and the result is the one-go result.
TEST_F(SessionTest, LayerStepsCrossCandidates) {
  GenerationSession whole(*model_);
  const SessionResult want = RunSession(&whole, Request(5, 3));
  GenerationSession s(*model_);
  std::vector<int32_t> seen_candidates;
  GenerateCallbacks cb;
  cb.progress = [&](const GenerateProgress& p) {
    EXPECT_EQ(p.candidates, 3);
    if (seen_candidates.empty() || seen_candidates.back() != p.candidate) seen_candidates.push_back(p.candidate);
  };
  ASSERT_TRUE(s.Start(Request(5, 3), input_, cb).ok());
  size_t last_faces = 0;
  int32_t last_candidate = 0, steps = 0;
  while (!s.done()) {
    ASSERT_TRUE(s.Advance(100000, AdvanceUntil::kLayer).ok());
    ++steps;
    auto preview = s.Preview();
    ASSERT_TRUE(preview.ok());
    if (s.candidate() == last_candidate) {
      EXPECT_GE(preview->grid.faces.size(), last_faces);
    }
    EXPECT_EQ(preview->output.triangles.size(), preview->grid.faces.size());
    last_faces = preview->grid.faces.size();
    last_candidate = s.candidate();
  }
  EXPECT_EQ(last_candidate, 2);
  EXPECT_GT(steps, 6);
  EXPECT_EQ(seen_candidates, (std::vector<int32_t>{0, 1, 2}));
  auto got = s.Finish();
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->generation.tokens, want.generation.tokens);
  EXPECT_EQ(got->generation.stats.chosen_candidate, want.generation.stats.chosen_candidate);
  EXPECT_FALSE(s.active());
}

// A cancel in candidate 1 of 3 ends the run: done, and Finish returns the closer of candidate 0
// (complete) and candidate 1 (its completed layers), stop reason kCancelled.
TEST_F(SessionTest, CancelInALaterCandidateLeavesAUsableFinish) {
  GenerationSession s(*model_);
  int polls_in_1 = 0;
  GenerateCallbacks cb;
  cb.cancel = [&] { return s.candidate() == 1 && ++polls_in_1 > 40; };
  ASSERT_TRUE(s.Start(Request(6, 3), input_, cb).ok());
  const Status st = s.Advance(1 << 30);
  EXPECT_EQ(st.code(), StatusCode::kCancelled) << st.ToString();
  EXPECT_TRUE(s.done());
  EXPECT_EQ(s.candidate(), 1);
  EXPECT_EQ(s.stats().stop_reason, StopReason::kCancelled);
  EXPECT_TRUE(s.Advance(10).ok());  // nothing more runs
  EXPECT_EQ(s.candidate(), 1);
  auto got = s.Finish();
  ASSERT_TRUE(got.ok()) << got.status().ToString();
  const GenerationStats& gs = got->generation.stats;
  EXPECT_EQ(gs.stop_reason, StopReason::kCancelled);
  ASSERT_EQ(gs.candidates.size(), 2u);
  const Reference ref = BestOfN(*model_, s.points(), s.plan().options, 1);
  EXPECT_EQ(gs.candidates[0].score, ref.scores[0]);
  EXPECT_EQ(gs.candidates[1].tokens, 39);  // polls in candidate 1: its encoder's, then one before each id
  const size_t chosen = gs.candidates[1].faces > 0 && gs.candidates[1].score < gs.candidates[0].score ? 1 : 0;
  EXPECT_EQ(gs.chosen_candidate, static_cast<int32_t>(chosen));
  EXPECT_EQ(got->output.triangles.size(), static_cast<size_t>(gs.faces));
}

TEST(GenerationRequest, UnsetValuesAreTheModelsAndBadValuesAreNamed) {
  ModelConfig cfg;
  cfg.sampling.temperature = 1.6;
  cfg.sampling.top_k = 7;
  cfg.candidates = 8;
  cfg.preprocessing = OfficialPreprocessing(2048);
  GenerationRequest r;
  r.seed = 3;
  auto plan = ResolveRequest(r, cfg);
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  EXPECT_EQ(plan->options.sampling.temperature, 1.6);
  EXPECT_EQ(plan->options.sampling.top_k, 7);
  EXPECT_EQ(plan->options.sampling.seed, 3u);
  EXPECT_EQ(plan->options.candidates, 8);
  EXPECT_EQ(plan->preprocessing.kind, PreprocessingKind::kOfficial);
  EXPECT_EQ(plan->preprocessing.n_points, 2048);
  EXPECT_STREQ(plan->preprocessing_name(), "official");
  r.temperature = 0;
  r.candidates = 2;
  r.n_points = 512;
  r.preprocessing = PreprocessingKind::kSilk;
  plan = ResolveRequest(r, cfg);
  ASSERT_TRUE(plan.ok());
  EXPECT_EQ(plan->options.sampling.temperature, 0);
  EXPECT_EQ(plan->options.candidates, 2);
  EXPECT_EQ(plan->preprocessing.kind, PreprocessingKind::kSilk);
  EXPECT_EQ(plan->preprocessing.n_points, 512);
  struct Case {
    const char* what;
    void (*set)(GenerationRequest*);
  };
  const Case bad[] = {{"temperature nan", [](GenerationRequest* q) { q->temperature = std::nan(""); }},
                      {"temperature -0.5", [](GenerationRequest* q) { q->temperature = -0.5; }},
                      {"top_p 1.5", [](GenerationRequest* q) { q->top_p = 1.5; }},
                      {"top_p_temperature inf",
                       [](GenerationRequest* q) { q->top_p_temperature = std::numeric_limits<double>::infinity(); }},
                      {"top_k -2", [](GenerationRequest* q) { q->top_k = -2; }},
                      {"candidates 0", [](GenerationRequest* q) { q->candidates = 0; }},
                      {"candidates 65", [](GenerationRequest* q) { q->candidates = 65; }},
                      {"temperature 150", [](GenerationRequest* q) { q->temperature = 150; }},
                      {"point_count -3", [](GenerationRequest* q) { q->n_points = -3; }},
                      {"max_faces -1", [](GenerationRequest* q) { q->max_faces = -1; }},
                      {"max_tokens 13", [](GenerationRequest* q) { q->max_tokens = 13; }},
                      {"surface_tolerance 128", [](GenerationRequest* q) { q->surface_tolerance = 128; }}};
  for (const Case& c : bad) {
    GenerationRequest q;
    c.set(&q);
    const auto p = ResolveRequest(q, cfg);
    ASSERT_FALSE(p.ok()) << c.what;
    EXPECT_NE(p.status().message().find(c.what), std::string::npos) << p.status().message();
  }
}

}  // namespace
}  // namespace silk
