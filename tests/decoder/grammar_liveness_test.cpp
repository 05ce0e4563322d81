// SPDX-License-Identifier: MIT
// Liveness under a length cap (GrammarOptions::max_length): from every state reachable by
// accepting legal ids the legal mask is non-empty until EOS, and every walk ends with EOS at
// or before the cap. Seeded random legal walks under small caps (17..400), with the token
// class drawn first (so X-heavy rows, which demand large layers, are common), both window
// rules; plus the runtime's dead-end prefix (issue 6) as a regression.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

// Class ranges of the model vocabulary, in id order.
std::vector<std::pair<int32_t, int32_t>> ClassRanges() {
  return {{vocab::kCBegin, vocab::kCBegin + 1},  {vocab::kUBegin, vocab::kUBegin + 1},
          {vocab::kEBegin, vocab::kEBegin + 1},  {vocab::kXBegin, vocab::kXEnd},
          {vocab::kSBegin, vocab::kSEnd},        {vocab::kBBegin, vocab::kBEnd},
          {vocab::kBEnd, vocab::kKEnd},          {vocab::kKEnd, vocab::kOEnd},
          {vocab::k_eos_id, vocab::k_eos_id + 1}};
}

std::string Dump(const std::vector<int32_t>& ids) {
  std::string s;
  for (int32_t id : ids) s += std::to_string(id) + " ";
  return s;
}

// One walk under `cap`; returns the number of tokens, or -1 after a failed assertion.
int32_t Walk(uint64_t seed, int32_t cap, WindowRule rule, double stop_bias) {
  std::mt19937_64 rng(seed);
  GrammarOptions o;
  o.max_length = cap;
  o.window_rule = rule;
  Grammar g(o);
  const auto classes = ClassRanges();
  std::vector<int32_t> ids;
  while (!g.Ended()) {
    const TokenMask& m = g.LegalMask();
    EXPECT_FALSE(m.Empty()) << "dead end after " << ids.size() << " tokens, cap " << cap << ", phase "
                            << static_cast<int>(g.phase()) << "; ids: " << Dump(ids);
    if (m.Empty()) return -1;
    // Mask => Accept for the drawn id; Accept => mask for a few random probes.
    std::vector<std::vector<int32_t>> by_class;
    for (const auto& r : classes) {
      std::vector<int32_t> in;
      for (int32_t id = r.first; id < r.second; ++id)
        if (m.Test(id)) in.push_back(id);
      if (!in.empty()) by_class.push_back(std::move(in));
    }
    std::vector<int32_t>* pick = &by_class[std::uniform_int_distribution<size_t>(0, by_class.size() - 1)(rng)];
    // Some walks lean to ending (U/E/EOS are single ids) so caps are reached both ways.
    if (std::bernoulli_distribution(stop_bias)(rng))
      for (auto& c : by_class)
        if (c.size() == 1 && (c[0] == vocab::kEBegin || c[0] == vocab::k_eos_id)) pick = &c;
    const int32_t id = (*pick)[std::uniform_int_distribution<size_t>(0, pick->size() - 1)(rng)];
    for (int t = 0; t < 3; ++t) {
      const int32_t probe = std::uniform_int_distribution<int32_t>(0, TokenMask::kBits - 1)(rng);
      Grammar c = g.Clone();
      EXPECT_EQ(m.Test(probe), c.Accept(probe).ok()) << "probe " << probe << "; ids: " << Dump(ids);
    }
    const Rejection r = g.Accept(id);
    EXPECT_TRUE(r.ok()) << "mask admitted a refused id: " << r.message << "; ids: " << Dump(ids);
    if (!r.ok()) return -1;
    ids.push_back(id);
    EXPECT_LE(static_cast<int32_t>(ids.size()), cap);
  }
  EXPECT_EQ(ids.back(), vocab::k_eos_id);
  size_t pos = 0;
  const Rejection r = CheckTokens(ids, o, &pos);
  EXPECT_TRUE(r.ok()) << r.message << "; ids: " << Dump(ids);
  return static_cast<int32_t>(ids.size());
}

TEST(GrammarLiveness, RandomWalksUnderSmallCapsNeverDeadEnd) {
  const int32_t caps[] = {17, 18, 25, 40, 64, 100, 150, 233, 300, 400};
  int32_t walks = 0, at_cap = 0;
  for (WindowRule rule : {WindowRule::kCanonical, WindowRule::kUnion})
    for (int32_t cap : caps)
      for (uint64_t seed = 1; seed <= 40; ++seed) {
        const int32_t n = Walk(seed * 7919 + static_cast<uint64_t>(cap), cap, rule, seed % 2 ? 0.0 : 0.02);
        ASSERT_GE(n, 0) << "cap " << cap << " seed " << seed;
        ++walks;
        at_cap += n >= cap - 2;
      }
  EXPECT_GT(at_cap, walks / 10);  // the budget logic was exercised, not just short walks
  ::testing::Test::RecordProperty("walks_near_cap", std::to_string(at_cap));
}

// Issue 6 (engine/runtime): layer 1 after the S of row 15 under cap 300 had an empty mask;
// the only completion (echo X 53, B, 53 rows, E, EOS) uses exactly the 224 tokens left.
TEST(GrammarLiveness, RuntimeDeadEndPrefixIsForcedNotDead) {
  const std::vector<int32_t> ids = {
      0,    5835, 8758, 1,    6112, 9420, 220,  17,   21,   50,   62,   460,  6042, 9382, 218,  29,   50,   59,   62,
      460,  5866, 6486, 400,  18,   460,  6001, 9618, 440,  460,  6001, 7564, 408,  460,  5778, 6871, 264,  460,  5741,
      8033, 220,  460,  6112, 6765, 408,  460,  5860, 9931, 408,  460,  5661, 7450, 434,  460,  6112, 6779, 362,  460,
      6137, 9931, 352,  460,  6001, 6779, 432,  460,  5888, 6779, 298,  460,  6007, 9449, 256,  460,  5885, 7077, 446};
  GrammarOptions o;
  o.max_length = 300;
  Grammar g(o);
  for (int32_t id : ids) ASSERT_TRUE(g.Accept(id).ok());
  ASSERT_EQ(g.phase(), GrammarPhase::kAfterS);
  // Follow the forced/cheapest completion to EOS: the mask never empties.
  std::mt19937_64 rng(6);
  while (!g.Ended()) {
    const TokenMask& m = g.LegalMask();
    ASSERT_FALSE(m.Empty()) << "dead end at " << g.size();
    int32_t id = -1;
    for (int32_t t = 0; t < TokenMask::kBits && id < 0; ++t)
      if (m.Test(t) && t != vocab::kCBegin && t != vocab::kUBegin) id = t;
    ASSERT_TRUE(g.Accept(id).ok());
  }
  EXPECT_LE(static_cast<int32_t>(g.size()), 300);
}

}  // namespace
}  // namespace silk
