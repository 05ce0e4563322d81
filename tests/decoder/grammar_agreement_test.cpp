// SPDX-License-Identifier: MIT
// Exhaustive agreement of the legal mask with Accept: at every prefix of the 154 official
// streams and of 2,000 seeded random walks (default options, tight length caps, both window
// rules; the Slow label holds the 140 dev streams and the 2,000 walks, the normal run the 14
// golden streams and 25 walks), every one of the 10269 model ids is in LegalMask() iff
// Check(id) takes it. Check runs Accept's own code (Grammar::Step without committing); sampled
// probes confirm Check == Accept on a clone, so the agreement is about Accept itself. Mask and
// Accept both walk the rule table (decoder/grammar_rules.h), so this checks each class's bulk
// form against its per-id test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "decoder/random_walk.h"
#include "io/tokens/token_text.h"
#include "support/test_paths.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

// Every id at the current state; returns the first disagreeing id or -1.
int32_t FirstDisagreement(Grammar* g) {
  const TokenMask m = g->LegalMask();
  for (int32_t id = 0; id < TokenMask::kBits; ++id)
    if (m.Test(id) != g->Check(id, false).ok()) return id;
  return -1;
}

// Accepts `ids` one by one, checking every prefix (and the state after the last id).
void CheckEveryPrefix(const std::vector<int32_t>& ids, const GrammarOptions& opt, const std::string& what,
                      std::mt19937* probe_rng) {
  Grammar g(opt);
  for (size_t i = 0; i <= ids.size(); ++i) {
    const int32_t bad = FirstDisagreement(&g);
    ASSERT_EQ(bad, -1) << what << " prefix " << i << ": id " << bad << " mask " << g.LegalMask().Test(bad)
                       << " Check: " << g.Check(bad).message;
    if (probe_rng) {
      const int32_t probe = std::uniform_int_distribution<int32_t>(0, TokenMask::kBits - 1)(*probe_rng);
      Grammar c = g.Clone();
      ASSERT_EQ(g.Check(probe).ok(), c.Accept(probe).ok()) << what << " prefix " << i << " probe " << probe;
    }
    if (i == ids.size()) break;
    const Rejection r = g.Accept(ids[i]);
    ASSERT_TRUE(r.ok()) << what << " token " << i << ": " << r.message;
  }
}

std::vector<std::string> Streams(const char* dir) {
  std::vector<std::string> out;
  const std::string d = testing::SharedPath(dir);
  if (!std::filesystem::exists(d)) return out;
  for (const auto& e : std::filesystem::directory_iterator(d)) {
    const std::string p = e.path().string();
    if (p.size() > 11 && p.compare(p.size() - 11, 11, ".tokens.txt") == 0) out.push_back(p);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void CheckStreams(const char* dir, size_t expected) {
  const auto files = Streams(dir);
  ASSERT_EQ(files.size(), expected) << dir;
  GrammarOptions opt;
  opt.max_length = 0;  // some dev streams are longer than the model's cap
  for (const auto& f : files) {
    auto ids = ReadTokenText(f);
    ASSERT_TRUE(ids.ok()) << ids.status().ToString();
    CheckEveryPrefix(*ids, opt, f, nullptr);
  }
}

TEST(GrammarAgreement, GoldenStreamsEveryPrefixEveryId) { CheckStreams("spec/golden", 14); }

TEST(GrammarAgreementSlow, GoldenDevStreamsEveryPrefixEveryId) { CheckStreams("spec/golden-dev", 140); }

// Walks: a third with the default options, a third under caps 17..400 (the budget rules), a
// third under the union window rule; every fifth with larger layers and more X values.
void CheckWalks(uint64_t first_seed, int32_t count) {
  std::mt19937 probe_rng(static_cast<uint32_t>(first_seed));
  int64_t prefixes = 0;
  for (uint64_t seed = first_seed; seed < first_seed + static_cast<uint64_t>(count); ++seed) {
    GrammarOptions opt;
    if (seed % 3 == 1) opt.max_length = 17 + static_cast<int32_t>(seed * 37 % 384);
    if (seed % 3 == 2) opt.window_rule = WindowRule::kUnion;
    RandomWalkOptions wo;
    wo.max_components = 1;
    wo.max_layer_size = seed % 5 == 0 ? 24 : 8;
    wo.max_layers = 3;
    wo.extra_x = seed % 5 == 0 ? 0.3 : 0.05;
    std::mt19937_64 rng(seed);
    Grammar g(opt);
    const std::vector<int32_t> ids = RandomLegalWalk(&g, &rng, wo);
    ASSERT_TRUE(g.Ended()) << "seed " << seed;
    CheckEveryPrefix(ids, opt, "walk " + std::to_string(seed), &probe_rng);
    if (::testing::Test::HasFatalFailure()) return;
    prefixes += static_cast<int64_t>(ids.size()) + 1;
  }
  std::printf("%d walks, %lld prefixes, %lld ids checked\n", count, static_cast<long long>(prefixes),
              static_cast<long long>(prefixes) * TokenMask::kBits);
}

TEST(GrammarAgreement, RandomWalksEveryPrefixEveryId) { CheckWalks(0, 25); }

TEST(GrammarAgreementSlow, TwoThousandRandomWalksEveryPrefixEveryId) { CheckWalks(100000, 2000); }

}  // namespace
}  // namespace silk
