// SPDX-License-Identifier: MIT
// Face guidance: the face score on known geometry, the stage against a brute-force reference
// built from the edge graph after each candidate id (every legal B id of random legal walks,
// hard and soft), and whole generations with the tiny model (off leaves the ids alone, the
// guided mask and penalties reach the trace, bad values are refused by name).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "decoder/grammar.h"
#include "decoder/random_walk.h"
#include "runtime/generation_stats.h"
#include "runtime/generator.h"
#include "runtime/sampling/face_guide.h"
#include "runtime/sampling/face_guide_stage.h"
#include "runtime/sampling/surface_guide.h"
#include "runtime_test_util.h"
#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/adjacency/between_layer_decoder.h"
#include "tokenizer/adjacency/self_layer_decoder.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

// Points (rows of 6 floats) on the plane through grid cell row y = 64, normals along y, every
// second cell in x and z.
std::vector<float> PlanePoints() {
  std::vector<float> rows;
  auto coord = [](int32_t cell) { return static_cast<float>((cell + 0.5) / 64.0 - 1.0); };
  for (int32_t x = 0; x < 128; x += 2)
    for (int32_t z = 0; z < 128; z += 2) rows.insert(rows.end(), {coord(x), coord(64), coord(z), 0.f, 1.f, 0.f});
  return rows;
}

std::shared_ptr<const FaceGuide> MakeGuide(const std::vector<float>& rows, double tolerance) {
  return std::make_shared<const FaceGuide>(std::make_shared<const SurfaceGuide>(rows, 1), rows, tolerance);
}

double Score(const FaceGuide& g, const QVec& a, const QVec& b, const QVec& c) {
  return g.FaceScore(a, b, c, g.NearestPoint(a), g.NearestPoint(b), g.NearestPoint(c));
}

TEST(FaceGuide, ScoresDistanceAndAngle) {
  const auto guide = MakeGuide(PlanePoints(), 2.0);
  // In the plane: on the surface, normal along the input's.
  EXPECT_LE(Score(*guide, {10, 64, 10}, {30, 64, 10}, {10, 64, 30}), 1.0);
  // Standing up from the plane: its top corner is 10 cells away and its normal is at 90 degrees.
  const double standing = Score(*guide, {10, 64, 10}, {30, 64, 10}, {20, 74, 10});
  EXPECT_GE(standing, 10.0 / 2.0 - 1e-9);
  // Near the plane but tilted by ~63 degrees (rise 2 over run 1): within the distance, past the angle limit.
  const double tilted = Score(*guide, {10, 64, 10}, {10, 64, 12}, {11, 66, 11});
  EXPECT_GT(tilted, 1.0);
  EXPECT_LE(guide->EdgeScore({10, 64, 10}, {40, 64, 40}), 1.0);
  EXPECT_NEAR(guide->EdgeScore({10, 64, 10}, {10, 70, 10}), 6.0 / 2.0, 1e-9);
  // A wider tolerance scales the distance part only.
  const auto loose = MakeGuide(PlanePoints(), 8.0);
  EXPECT_NEAR(loose->EdgeScore({10, 64, 10}, {10, 70, 10}), 6.0 / 8.0, 1e-9);
  EXPECT_GT(Score(*loose, {10, 64, 10}, {10, 64, 12}, {11, 66, 11}), 1.0);
  // Points without normals: distance alone (2.45 cells of 3 passes; the angle, 63 degrees, would not).
  auto no_normals = PlanePoints();
  for (size_t i = 0; i < no_normals.size(); i += 6) no_normals[i + 3] = no_normals[i + 4] = no_normals[i + 5] = 0;
  EXPECT_GT(Score(*MakeGuide(PlanePoints(), 3.0), {10, 64, 10}, {10, 64, 12}, {11, 66, 11}), 1.0);
  EXPECT_NEAR(Score(*MakeGuide(no_normals, 3.0), {10, 64, 10}, {10, 64, 12}, {11, 66, 11}), std::sqrt(6.0) / 3, 1e-6);
}

// Two faces on edge (x, y): side by side (flat), at the limit angle (90 deg), past it, on top of
// each other.
TEST(FaceGuide, FoldScoreIsTheAngleInsideThePair) {
  static_assert(kFaceFoldLimitDegrees == 90.0, "the figures below are for a 90 deg limit");
  const auto guide = MakeGuide(PlanePoints(), 2.0);
  const QVec x{10, 64, 10}, y{20, 64, 10}, p{15, 64, 20};
  EXPECT_NEAR(guide->FoldScore(x, y, p, {15, 64, 0}), 0.0, 1e-12);                     // 180 deg: flat
  EXPECT_NEAR(guide->FoldScore(x, y, p, {12, 74, 0}), 1 - std::sqrt(0.5), 1e-9);       // 135 deg
  EXPECT_NEAR(guide->FoldScore(x, y, p, {15, 74, 10}), 1.0, 1e-9);                     // 90 deg: the limit
  EXPECT_NEAR(guide->FoldScore(x, y, p, {12, 74, 20}), 1 + 3 * std::sqrt(0.5), 1e-9);  // 45 deg
  EXPECT_NEAR(guide->FoldScore(x, y, p, {25, 64, 30}), 1.0 + kFaceFoldSpan, 1e-9);     // 0 deg: folded
  // A fold is a fold whichever face came first, and wherever along the edge the corners lie.
  EXPECT_NEAR(guide->FoldScore(x, y, {12, 74, 20}, p), guide->FoldScore(x, y, p, {12, 74, 20}), 1e-12);
  EXPECT_NEAR(guide->FoldScore(y, x, p, {12, 74, 20}), guide->FoldScore(x, y, p, {12, 74, 20}), 1e-12);
  EXPECT_GT(guide->FoldScore(x, y, p, {15, 75, 11}), 1.0);  // 85 deg: just past a right angle
  EXPECT_LT(guide->FoldScore(x, y, p, {15, 75, 9}), 1.0);   // 95 deg: just short of it
  // Degenerate: a corner on the edge's line, or no edge.
  EXPECT_EQ(guide->FoldScore(x, y, p, {30, 64, 10}), 0.0);
  EXPECT_EQ(guide->FoldScore(x, x, p, {15, 74, 10}), 0.0);
}

// The edge graph once `id` is accepted, from the decoders of whole layers (built independently
// of the stage's per-column bookkeeping): the previous layer 0..n-1, the current layer's rows
// n..n+b (u = n+b, the vertex being written), then the layer before the previous one.
struct BruteGraph {
  int32_t n = 0, u = 0, total = 0;
  std::vector<char> adj;
  std::vector<QVec> pos;
  bool Edge(int32_t x, int32_t y) const { return adj[static_cast<size_t>(x) * total + y] != 0; }
};

BruteGraph GraphAfter(const Grammar& g, int32_t id) {
  Grammar h = g.Clone();
  EXPECT_TRUE(h.Accept(id).ok());
  const auto& layers = h.stream().components.back().layers;
  const StreamLayer &prev = layers[layers.size() - 2], &cur = layers.back();
  const StreamLayer* before = layers.size() > 2 ? &layers[layers.size() - 3] : nullptr;
  BruteGraph gr;
  gr.n = static_cast<int32_t>(prev.vertices.size());
  const int32_t b = static_cast<int32_t>(cur.vertices.size()) - 1;
  gr.u = gr.n + b;
  gr.total = gr.n + b + 1 + (before ? static_cast<int32_t>(before->vertices.size()) : 0);
  gr.adj.assign(static_cast<size_t>(gr.total) * gr.total, 0);
  for (const auto& v : prev.vertices) gr.pos.push_back(v.pos);
  for (const auto& v : cur.vertices) gr.pos.push_back(v.pos);
  if (before)
    for (const auto& v : before->vertices) gr.pos.push_back(v.pos);
  auto link = [&](int32_t x, int32_t y) { gr.adj[x * gr.total + y] = gr.adj[y * gr.total + x] = 1; };
  if (before) {
    auto self = DecodeSelfLayer(prev);
    EXPECT_TRUE(self.ok());
    for (const auto& [x, y] : *self) link(x, y);
    auto down = DecodeBetweenLayer(prev, static_cast<int32_t>(before->vertices.size()));
    EXPECT_TRUE(down.ok()) << down.status().ToString();
    for (const auto& [row, col] : *down) link(row, gr.n + b + 1 + col);
  }
  auto between = DecodeBetweenLayer(cur, gr.n);
  EXPECT_TRUE(between.ok()) << between.status().ToString();
  for (const auto& [row, col] : *between) link(gr.n + row, col);
  for (int32_t a = 0; a < b; ++a)
    for (int32_t j = a + 1; j <= b; ++j) {
      const int32_t d = j - a;
      const auto& ex = cur.vertices[a].extras;
      if (d <= 8 ? (cur.vertices[a].window >> (d - 1)) & 1 : std::count(ex.begin(), ex.end(), d - 1) > 0)
        link(gr.n + a, gr.n + j);
    }
  return gr;
}

// Triangle (p, q, r) of the graph against every other triangle (p, q, y) on its edge (p, q).
double BruteFolds(const BruteGraph& gr, int32_t p, int32_t q, int32_t r, const FaceGuide& guide) {
  double worst = 0;
  for (int32_t y = 0; y < gr.total; ++y)
    if (y != p && y != q && y != r && gr.Edge(p, y) && gr.Edge(q, y))
      worst = std::max(worst, guide.FoldScore(gr.pos[p], gr.pos[q], gr.pos[r], gr.pos[y]));
  return worst;
}

// The id's score by brute force: every triangle of the graph through one of its new edges
// (u, w), scored, and against every other triangle on each of its three edges (folds).
struct Brute {
  double score = 0, without_folds = 0;
};

Brute BruteScore(const Grammar& g, int32_t id, const FaceGuide& guide) {
  const BruteGraph gr = GraphAfter(g, id);
  // The id's own columns (a continuation's columns repeat none of the earlier ones).
  const int32_t s = (id - vocab::kBBegin) / 26, c = (id - vocab::kBBegin) % 26;
  const int32_t pattern = BetweenCasePattern(c), u = gr.u;
  Brute worst;
  for (int32_t p = 0; p <= 5; ++p) {
    if (p > 0 && !((pattern >> (p - 1)) & 1)) continue;
    const int32_t w = s + p;
    worst.without_folds = std::max(worst.without_folds, guide.EdgeScore(gr.pos[u], gr.pos[w]));
    for (int32_t x = 0; x < gr.total; ++x) {
      if (x == u || x == w || !gr.Edge(u, x) || !gr.Edge(w, x)) continue;
      worst.without_folds = std::max(worst.without_folds, Score(guide, gr.pos[u], gr.pos[w], gr.pos[x]));
      worst.score = std::max({worst.score, BruteFolds(gr, u, w, x, guide), BruteFolds(gr, w, x, u, guide),
                              BruteFolds(gr, u, x, w, guide)});
    }
  }
  worst.score = std::max(worst.score, worst.without_folds);
  return worst;
}

// Which ids the stage judges in the grammar's current state (none before the second layer).
bool Judged(Grammar& g, int32_t id) {
  const auto& comps = g.stream().components;
  if (comps.empty() || comps.back().layers.size() < 2 || g.Forced() >= 0) return false;
  const bool b = id >= vocab::kBBegin && id < vocab::kBEnd, k = id >= vocab::kKBegin && id < vocab::kKEnd;
  switch (g.phase()) {
    case GrammarPhase::kWantK:
      return k;
    case GrammarPhase::kWantO:
      return id >= vocab::kOBegin && id < vocab::kOEnd;
    case GrammarPhase::kWantS:
      return id >= vocab::kSBegin && id < vocab::kSEnd;
    case GrammarPhase::kAfterS:
      return b || (id >= vocab::kXBegin && id < vocab::kXEnd);
    case GrammarPhase::kAfterB:
      return b || k;
    default:
      return false;
  }
}

// The walk's own vertices as input points (x y z nx ny nz rows), so some faces pass.
std::vector<float> WalkPoints(const Grammar& g) {
  std::vector<float> rows;
  for (const auto& comp : g.stream().components)
    for (const auto& layer : comp.layers)
      for (const auto& v : layer.vertices)
        rows.insert(rows.end(),
                    {static_cast<float>((v.pos.x + 0.5) / 64 - 1), static_cast<float>((v.pos.y + 0.5) / 64 - 1),
                     static_cast<float>((v.pos.z + 0.5) / 64 - 1), 0.f, 0.f, 1.f});
  return rows;
}

struct WalkTally {
  int64_t exact_steps = 0, removed = 0, passing = 0, penalised = 0;
  int64_t folded = 0;           // ids a fold scores worst, past 1
  int64_t windows_removed = 0;  // S ids hard guidance removed (each with a later row linked twice)
};

// Where only B ids are judged (a row's first B): the stage's mask (hard) or penalties (soft) equal
// the brute-force scores' verdicts exactly.
void CheckFirstBExactly(const Grammar& replay, const TokenMask& legal, const SamplerCandidates& c, FaceGuidance mode,
                        const FaceGuide& guide, WalkTally* t) {
  std::vector<std::pair<double, int32_t>> brute;
  double best = HUGE_VAL;
  for (int32_t b = legal.Next(vocab::kBBegin); b >= 0 && b < vocab::kBEnd; b = legal.Next(b + 1)) {
    const Brute s = BruteScore(replay, b, guide);
    brute.push_back({s.score, b});
    best = std::min(best, s.score);
    t->folded += s.score > std::max(1.0, s.without_folds) ? 1 : 0;
  }
  // The trace's verdict: a fallback exactly when no legal B id passes (a rounding tie: either).
  if (std::fabs(best - 1) >= 1e-9) EXPECT_EQ(c.face, best <= 1 ? FaceVerdict::kPassed : FaceVerdict::kFallback) << best;
  if (mode == FaceGuidance::kHard) {
    const double keep = best <= 1 ? 1.0 : best * 1.25;
    for (const auto& [score, b] : brute) {
      if (std::fabs(score - keep) < 1e-9) continue;  // a rounding tie: either answer is right
      ASSERT_EQ(c.mask->Test(b), score <= keep) << "id " << b << " score " << score << " best " << best;
      t->removed += score <= keep ? 0 : 1;
    }
    t->passing += best <= 1 ? 1 : 0;
    return;
  }
  size_t k = 0;
  for (const auto& [score, b] : brute) {
    if (score <= 1 + 1e-9) continue;
    ASSERT_LT(k, c.penalties->size());
    EXPECT_EQ((*c.penalties)[k].first, b);
    EXPECT_NEAR((*c.penalties)[k].second, std::min(40.0, 4.0 * (score - 1)), 1e-4);
    ++k, ++t->penalised;
  }
  EXPECT_EQ(k, c.penalties->size());
}

// A window step (hard): a window that links no later row to a second row (each row it reaches
// has no earlier link) closes no face and stays; the empty window always stays. Counts removals.
void CheckWindows(const Grammar& replay, const TokenMask& legal, const TokenMask& guided, WalkTally* t) {
  const auto& vs = replay.stream().components.back().layers.back().vertices;
  const int32_t b = static_cast<int32_t>(vs.size()) - 1;
  auto linked = [&](int32_t a, int32_t j) {
    const int32_t d = j - a;
    if (d <= vocab::k_self_window) return ((vs[a].window >> (d - 1)) & 1) != 0;
    return std::find(vs[a].extras.begin(), vs[a].extras.end(), d - 1) != vs[a].extras.end();
  };
  for (int32_t id = legal.Next(vocab::kSBegin); id >= 0 && id < vocab::kSEnd; id = legal.Next(id + 1)) {
    bool second_link = false;
    for (int32_t d = 1; d <= vocab::k_self_window; ++d)
      if (((id - vocab::kSBegin) >> (d - 1)) & 1)
        for (int32_t a = 0; a < b && !second_link; ++a) second_link = linked(a, b + d);
    if (!second_link) EXPECT_TRUE(guided.Test(id)) << "window " << id - vocab::kSBegin;
    t->windows_removed += guided.Test(id) ? 0 : 1;
  }
}

// Every step of random legal walks. Where only B ids are judged (a row's first B), the stage's
// mask (hard) or penalties (soft) equal the brute-force scores' verdicts exactly; everywhere
// (positions and blocks too): ids not judged untouched, the mask never empty, and the counters.
TEST(FaceGuide, StageMatchesTheEdgeGraphOnRandomWalks) {
  std::mt19937_64 rng(5);
  RandomWalkOptions walk;
  walk.max_layers = 5;
  walk.max_layer_size = 14;
  WalkTally t;
  int64_t fallbacks = 0, narrowed_positions = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Grammar g;
    const std::vector<int32_t> ids = RandomLegalWalk(&g, &rng, walk);
    // Input points: the walk's own vertices (so some faces pass), tolerance 2..24 cells.
    const std::vector<float> rows = WalkPoints(g);
    const double tolerance = 2.0 + 22.0 * static_cast<double>(rng() % 1000) / 1000.0;
    const auto guide = MakeGuide(rows, tolerance);
    const FaceGuidance mode = trial % 2 ? FaceGuidance::kSoft : FaceGuidance::kHard;
    Grammar replay;
    GenerationStats stats;
    auto stage = MakeFaceGuideStage(guide.get(), mode, &replay, &stats);
    int64_t judged_steps = 0;
    for (int32_t id : ids) {
      const TokenMask legal = replay.LegalMask();
      bool any_judged = false;
      for (int32_t x = legal.Next(0); x >= 0 && !any_judged; x = legal.Next(x + 1)) any_judged = Judged(replay, x);
      SamplerCandidates c;
      c.forced = replay.Forced();
      c.mask = &legal;
      stage->Apply(&c);
      judged_steps += any_judged ? 1 : 0;
      if (!any_judged) {
        EXPECT_EQ(c.face, FaceVerdict::kNotJudged);
        EXPECT_EQ(c.mask, &legal);
        EXPECT_EQ(c.penalties, nullptr);
      } else if (mode == FaceGuidance::kHard) {
        ASSERT_NE(c.mask, nullptr);
        EXPECT_FALSE(c.mask->Empty());
        for (int32_t x = 0; x < TokenMask::kBits; ++x) {
          if (!Judged(replay, x) || !legal.Test(x)) {
            ASSERT_EQ(c.mask->Test(x), legal.Test(x)) << x;
          }
        }
        narrowed_positions += replay.phase() == GrammarPhase::kWantO && c.mask->Count() < legal.Count() ? 1 : 0;
        if (replay.phase() == GrammarPhase::kWantS) CheckWindows(replay, legal, *c.mask, &t);
      } else {
        EXPECT_EQ(c.mask, &legal);
        ASSERT_NE(c.penalties, nullptr);
        for (const auto& [x, amount] : *c.penalties) {
          EXPECT_TRUE(legal.Test(x) && Judged(replay, x)) << x;
          EXPECT_TRUE(amount > 0 && amount <= 40) << amount;
        }
      }
      if (any_judged && replay.phase() == GrammarPhase::kAfterS) {  // B ids alone: exact
        ++t.exact_steps;
        CheckFirstBExactly(replay, legal, c, mode, *guide, &t);
      }
      ASSERT_TRUE(replay.Accept(id).ok());
    }
    EXPECT_EQ(stats.face_guided_tokens, judged_steps);
    EXPECT_LE(stats.face_fallbacks, judged_steps);
    fallbacks += stats.face_fallbacks;
  }
  EXPECT_GT(t.exact_steps, 30);  // enough first-B steps in layers >= 2
  EXPECT_GT(t.removed, 0);       // ids removed,
  EXPECT_GT(t.passing, 0);       // steps where some id passed,
  EXPECT_GT(t.penalised, 0);
  EXPECT_GT(t.folded, 0);   // folds decide some ids
  EXPECT_GT(fallbacks, 0);  // and steps where none did
  EXPECT_GT(narrowed_positions, 0);
  EXPECT_GT(t.windows_removed, 0);  // windows judged by the later rows they link
}

GenerateOptions Options(uint64_t seed) {
  GenerateOptions o;
  o.sampling.seed = seed;
  o.sampling.temperature = 1.0;
  o.max_tokens = 300;
  o.record_trace = true;
  return o;
}

// Off (the default of GenerateOptions) gives the former ids; hard guidance narrows the traced
// legal sets of B steps; soft leaves them and records penalties.
TEST(FaceGuide, GenerationsOffHardSoft) {
  auto model = testing::LoadTinyModel(1);
  ASSERT_TRUE(model);
  const auto points = testing::SamplePoints(*model);
  Generator gen(*model);
  int64_t guided = 0, narrowed = 0, penalised = 0;
  for (uint64_t seed = 0; seed < 3; ++seed) {
    GenerateOptions o = Options(seed);
    auto off = gen.Run(points, o);
    ASSERT_TRUE(off.ok()) << off.status().ToString();
    EXPECT_EQ(off->stats.face_guided_tokens, 0);
    o.face_guidance = FaceGuidance::kHard;
    auto hard = gen.Run(points, o);
    ASSERT_TRUE(hard.ok()) << hard.status().ToString();
    guided += hard->stats.face_guided_tokens;
    // The hard run's legal sets: where it sampled a B id, the set is what the grammar allows
    // narrowed by the stage (replayed here with the grammar alone).
    Grammar g;
    for (const TraceStep& st : hard->trace) {
      if (!st.forced && st.id >= vocab::kBBegin && st.id < vocab::kBEnd) {
        int64_t traced = 0;
        for (const auto& [b, e] : st.legal) traced += e - b;
        narrowed += traced < g.LegalMask().Count() ? 1 : 0;
      }
      ASSERT_TRUE(g.Accept(st.id).ok());
    }
    o.face_guidance = FaceGuidance::kSoft;
    auto soft = gen.Run(points, o);
    ASSERT_TRUE(soft.ok()) << soft.status().ToString();
    for (const TraceStep& st : soft->trace) penalised += st.penalties.empty() ? 0 : 1;
    o.face_guidance = FaceGuidance::kOff;
    auto again = gen.Run(points, o);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again->tokens, off->tokens);  // the cached guide changes nothing when off
    o.unconstrained = true;                 // no mask: the setting is ignored
    o.face_guidance = FaceGuidance::kHard;
    auto loose = gen.Run(points, o);
    ASSERT_TRUE(loose.ok());
    EXPECT_EQ(loose->stats.face_guided_tokens, 0);
  }
  EXPECT_GT(guided, 0);
  EXPECT_GT(narrowed, 0);
  EXPECT_GT(penalised, 0);
}

TEST(FaceGuide, BadValuesAreRefusedByName) {
  GenerateOptions o;
  for (double t : {0.0, 0.4, 64.5, std::nan("")}) {
    o.face_tolerance = t;
    const Status s = CheckGenerateOptions(o);
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message().find("face_tolerance"), std::string::npos) << s.message();
  }
  o.face_tolerance = 2;
  o.face_guidance = static_cast<FaceGuidance>(3);
  const Status s = CheckGenerateOptions(o);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("face_guidance 3"), std::string::npos) << s.message();
  FaceGuidance g = FaceGuidance::kOff;
  EXPECT_TRUE(ParseFaceGuidanceName("soft", &g));
  EXPECT_EQ(g, FaceGuidance::kSoft);
  EXPECT_FALSE(ParseFaceGuidanceName("Hard", &g));
  EXPECT_EQ(g, FaceGuidance::kSoft);
}

}  // namespace
}  // namespace silk
