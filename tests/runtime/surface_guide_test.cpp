// SPDX-License-Identifier: MIT
// Surface guidance: the distance field against brute force, the K/O restriction against a
// brute-force reference (exact when some legal id is within the tolerance, nearest legal ids
// otherwise, never empty, other kinds untouched), and whole generations with the tiny model.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "core/splitmix64.h"
#include "decoder/grammar.h"
#include "runtime/generator.h"
#include "runtime/sampling/surface_guide.h"
#include "runtime_test_util.h"
#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

// n points (rows of 6 floats) at random positions in [-1, 1), some clustered on a plane.
std::vector<float> RandomPoints(SplitMix64* rng, int n) {
  std::vector<float> rows;
  const bool plane = rng->Uniform() < 0.5;
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) rows.push_back(plane && a == 1 ? 0.3f : static_cast<float>(2 * rng->Uniform() - 1));
    for (int a = 0; a < 3; ++a) rows.push_back(a == 2 ? 1.f : 0.f);
  }
  return rows;
}

std::vector<QVec> Cells(const std::vector<float>& rows) {
  std::vector<QVec> c;
  for (size_t i = 0; i < rows.size(); i += 6)
    c.push_back({QuantizeCoord(rows[i]), QuantizeCoord(rows[i + 1]), QuantizeCoord(rows[i + 2])});
  return c;
}

int32_t BruteCell(const std::vector<QVec>& occ, const QVec& q) {
  int32_t best = std::numeric_limits<int32_t>::max();
  for (const QVec& p : occ)
    best = std::min(best, (p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) + (p.z - q.z) * (p.z - q.z));
  return best;
}

// Nearest cell of a 16^3 block to an occupied cell: clamp the cell into the block's box.
int32_t BruteBlock(const std::vector<QVec>& occ, int32_t block) {
  const int32_t bx = (block / 64) * 16, by = ((block / 8) % 8) * 16, bz = (block % 8) * 16;
  int32_t best = std::numeric_limits<int32_t>::max();
  for (const QVec& p : occ) {
    const QVec c{std::clamp(p.x, bx, bx + 15), std::clamp(p.y, by, by + 15), std::clamp(p.z, bz, bz + 15)};
    best = std::min(best, (p.x - c.x) * (p.x - c.x) + (p.y - c.y) * (p.y - c.y) + (p.z - c.z) * (p.z - c.z));
  }
  return best;
}

TEST(SurfaceGuide, DistanceFieldIsExact) {
  SplitMix64 rng(1);
  for (int trial = 0; trial < 4; ++trial) {
    const auto rows = RandomPoints(&rng, 1 + static_cast<int>(rng.Uniform() * 40));
    const auto occ = Cells(rows);
    const SurfaceGuide guide(rows, 2);
    for (const QVec& p : occ) EXPECT_EQ(guide.CellDistance2(p), 0);
    for (int i = 0; i < 3000; ++i) {
      const QVec q{static_cast<int32_t>(rng.Next() % 128), static_cast<int32_t>(rng.Next() % 128),
                   static_cast<int32_t>(rng.Next() % 128)};
      ASSERT_EQ(guide.CellDistance2(q), BruteCell(occ, q)) << q.x << " " << q.y << " " << q.z;
    }
    for (int32_t b = 0; b < 512; ++b) ASSERT_EQ(guide.BlockDistance2(b), BruteBlock(occ, b)) << "block " << b;
  }
}

// A random mask: each id of [begin, end) with probability p, plus some ids of other kinds.
TokenMask RandomMask(SplitMix64* rng, int32_t begin, int32_t end, double p) {
  TokenMask m;
  for (int32_t id = begin; id < end; ++id)
    if (rng->Uniform() < p) m.Set(id);
  if (rng->Uniform() < 0.5) m.Set(vocab::kUBegin);
  if (rng->Uniform() < 0.5) m.Set(vocab::kBBegin + 7);
  return m;
}

// The restriction against the brute-force rule, for K (block < 0) or O (after `block`).
void CheckRestriction(const SurfaceGuide& guide, const std::vector<QVec>& occ, const TokenMask& legal, int32_t block,
                      int32_t tolerance) {
  const bool offsets = block >= 0;
  const int32_t begin = offsets ? vocab::kOBegin : vocab::kKBegin, end = offsets ? vocab::kOEnd : vocab::kKEnd;
  auto brute = [&](int32_t id) {
    return offsets ? BruteCell(occ, VertexOfTokens(block, id)) : BruteBlock(occ, id - vocab::kKBegin);
  };
  int32_t best = std::numeric_limits<int32_t>::max();
  bool within = false;
  for (int32_t id = begin; id < end; ++id)
    if (legal.Test(id)) {
      best = std::min(best, brute(id));
      within = within || brute(id) <= tolerance * tolerance;
    }
  TokenMask got = legal;
  const bool fallback = offsets ? guide.RestrictOffsets(block, &got) : guide.RestrictBlocks(&got);
  const bool any = best != std::numeric_limits<int32_t>::max();
  EXPECT_EQ(fallback, any && !within);
  if (!legal.Empty()) {
    EXPECT_FALSE(got.Empty());
  }
  for (int32_t id = 0; id < TokenMask::kBits; ++id) {
    if (id < begin || id >= end || !legal.Test(id)) {
      ASSERT_EQ(got.Test(id), legal.Test(id)) << "id " << id << " of another kind or illegal changed";
      continue;
    }
    const bool keep = within ? brute(id) <= tolerance * tolerance : brute(id) == best;
    ASSERT_EQ(got.Test(id), keep) << "id " << id << " d2 " << brute(id) << " tolerance " << tolerance;
  }
}

TEST(SurfaceGuide, RestrictsExactlyAndNeverEmpties) {
  SplitMix64 rng(3);
  int fallbacks = 0, restricted = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const auto rows = RandomPoints(&rng, 1 + static_cast<int>(rng.Uniform() * 30));
    const auto occ = Cells(rows);
    const int32_t tolerance = 1 + static_cast<int32_t>(rng.Next() % 4);
    const SurfaceGuide guide(rows, tolerance);
    // Sparse masks make the fallback common, dense ones the exact restriction.
    const double p = trial % 2 ? 0.02 : 0.6;
    const TokenMask k = RandomMask(&rng, vocab::kKBegin, vocab::kKEnd, p);
    CheckRestriction(guide, occ, k, -1, tolerance);
    const int32_t block = vocab::kKBegin + static_cast<int32_t>(rng.Next() % 512);
    const TokenMask o = RandomMask(&rng, vocab::kOBegin, vocab::kOEnd, p / 4);
    CheckRestriction(guide, occ, o, block, tolerance);
    TokenMask tk = k, to = o;
    fallbacks += guide.RestrictBlocks(&tk) ? 1 : 0;
    fallbacks += guide.RestrictOffsets(block, &to) ? 1 : 0;
    restricted += tk.Count() < k.Count() ? 1 : 0;
  }
  EXPECT_GT(fallbacks, 0);  // both branches were exercised
  EXPECT_GT(restricted, 0);
  // A mask without vertex ids is left alone.
  const auto rows = RandomPoints(&rng, 5);
  const SurfaceGuide guide(rows, 1);
  TokenMask other;
  other.Set(vocab::kUBegin);
  TokenMask copy = other;
  EXPECT_FALSE(guide.RestrictBlocks(&copy));
  EXPECT_EQ(copy.words(), other.words());
}

TEST(SurfaceGuide, DistanceTransformLine) {
  constexpr int32_t kFar = 1 << 28;
  int32_t f[10] = {kFar, kFar, 0, kFar, kFar, kFar, 5, kFar, kFar, kFar};
  DistanceTransform1D(f, 10, 1);
  const int32_t want[10] = {4, 1, 0, 1, 4, 6, 5, 6, 9, 14};  // min over sites of (q-s)^2 + f(s)
  for (int i = 0; i < 10; ++i) EXPECT_EQ(f[i], want[i]) << i;
  int32_t none[4] = {kFar, kFar, kFar, kFar};
  DistanceTransform1D(none, 4, 1);
  EXPECT_EQ(none[3], kFar);
}

// Every vertex of a guided constrained run lies within the tolerance of an input point's cell,
// or was counted as a fallback; unguided runs of the tiny model stray much more.
TEST(SurfaceGuide, GuidedGenerationStaysNearTheSurface) {
  auto model = testing::LoadTinyModel(1);
  ASSERT_TRUE(model);
  const auto points = testing::SamplePoints(*model);
  const int32_t tolerance = 2;
  const SurfaceGuide guide(points, tolerance);
  int64_t outside_guided = 0, outside_plain = 0, vertices_guided = 0;
  Generator gen(*model);
  for (uint64_t seed = 0; seed < 4; ++seed) {
    for (bool guided : {true, false}) {
      GenerateOptions o;
      o.sampling.seed = seed;
      o.sampling.temperature = 0.8;
      o.sampling.top_k = 50;
      o.max_tokens = 300;
      o.surface_tolerance = guided ? tolerance : 0;
      auto r = gen.Run(points, o);
      ASSERT_TRUE(r.ok()) << r.status().ToString();
      int64_t outside = 0, vertices = 0;
      for (size_t i = 0; i + 1 < r->tokens.size(); ++i) {
        const int32_t k = r->tokens[i], off = r->tokens[i + 1];
        if (k < vocab::kKBegin || k >= vocab::kKEnd) continue;
        ASSERT_TRUE(off >= vocab::kOBegin && off < vocab::kOEnd);
        ++vertices;
        outside += guide.Within(guide.CellDistance2(VertexOfTokens(k, off))) ? 0 : 1;
      }
      if (guided) {
        EXPECT_GT(r->stats.guided_tokens, 0);
        EXPECT_LE(outside, r->stats.guidance_fallbacks) << "seed " << seed;
        outside_guided += outside;
        vertices_guided += vertices;
      } else {
        EXPECT_EQ(r->stats.guided_tokens, 0);
        EXPECT_EQ(r->stats.guidance_fallbacks, 0);
        outside_plain += outside;
      }
    }
  }
  EXPECT_GT(vertices_guided, 20);
  EXPECT_LT(outside_guided, outside_plain);
}

TEST(SurfaceGuide, OffAndUnconstrainedLeaveTheIdsAlone) {
  auto model = testing::LoadTinyModel(1);
  ASSERT_TRUE(model);
  const auto points = testing::SamplePoints(*model);
  Generator gen(*model);
  GenerateOptions o;
  o.sampling.seed = 9;
  o.max_tokens = 200;
  o.unconstrained = true;
  auto plain = gen.Run(points, o);
  o.surface_tolerance = 3;  // no mask to restrict: ignored
  auto guided = gen.Run(points, o);
  ASSERT_TRUE(plain.ok() && guided.ok());
  EXPECT_EQ(plain->tokens, guided->tokens);
  EXPECT_EQ(guided->stats.guided_tokens, 0);
}

TEST(SurfaceGuide, BadValuesAreRefusedByName) {
  GenerateOptions o;
  for (int32_t t : {-1, 128}) {
    o.surface_tolerance = t;
    const Status s = CheckGenerateOptions(o);
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message().find("surface_tolerance " + std::to_string(t)), std::string::npos) << s.message();
  }
  o.surface_tolerance = 0;
  for (int32_t n : {0, -3, 65}) {
    o.candidates = n;
    const Status s = CheckGenerateOptions(o);
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message().find("candidates " + std::to_string(n)), std::string::npos) << s.message();
  }
}

}  // namespace
}  // namespace silk
