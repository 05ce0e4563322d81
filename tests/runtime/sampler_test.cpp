// SPDX-License-Identifier: MIT
// The sampling chain: only legal ids, greedy/top-k/top-p semantics, seeded determinism, and draws
// that follow the softmax of the logits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "runtime/sampling/sampler.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

std::vector<float> Logits() {
  std::vector<float> l(vocab::k_model_vocab_size, -5.0f);
  l[10] = 2.0f;
  l[11] = 1.0f;
  l[12] = 0.0f;
  l[13] = 3.0f;  // best overall, but not legal below
  l[vocab::k_pad_id] = 50.0f;
  return l;
}

TokenMask Legal() {
  TokenMask m;
  m.Set(10);
  m.Set(11);
  m.Set(12);
  return m;
}

TEST(Sampler, GreedyTakesBestLegalId) {
  SamplingParams p;
  p.temperature = 0;
  auto s = BuildSamplerChain({p});
  const auto l = Logits();
  const TokenMask m = Legal();
  EXPECT_EQ(s->Sample(l.data(), &m), 10);
  EXPECT_EQ(s->Sample(l.data(), nullptr), 13);  // unconstrained: PAD never, even at 50
}

TEST(Sampler, TopKOneIsGreedy) {
  SamplingParams p;
  p.top_k = 1;
  p.seed = 9;
  auto s = BuildSamplerChain({p});
  const auto l = Logits();
  const TokenMask m = Legal();
  for (int i = 0; i < 50; ++i) EXPECT_EQ(s->Sample(l.data(), &m), 10);
}

TEST(Sampler, NeverIllegalAndFollowsSoftmax) {
  SamplingParams p;
  p.temperature = 1.0;
  p.seed = 1234;
  auto s = BuildSamplerChain({p});
  const auto l = Logits();
  const TokenMask m = Legal();
  std::map<int, int> counts;
  const int n = 20000;
  for (int i = 0; i < n; ++i) ++counts[s->Sample(l.data(), &m)];
  ASSERT_EQ(counts.size(), 3u);
  const double z = std::exp(2.0) + std::exp(1.0) + std::exp(0.0);
  const double expect[3] = {std::exp(2.0) / z, std::exp(1.0) / z, 1.0 / z};
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(counts[10 + k] / double(n), expect[k], 0.015) << k;
}

TEST(Sampler, TopPKeepsSmallestNucleus) {
  SamplingParams p;
  p.top_p = 0.6;  // p(10) = 0.665 >= 0.6: only id 10 survives
  p.seed = 3;
  auto s = BuildSamplerChain({p});
  const auto l = Logits();
  const TokenMask m = Legal();
  for (int i = 0; i < 200; ++i) EXPECT_EQ(s->Sample(l.data(), &m), 10);
  SamplingParams q = p;
  q.top_p = 0.9;  // 0.665 + 0.245 = 0.91: ids 10 and 11
  auto t = BuildSamplerChain({q});
  std::map<int, int> c;
  for (int i = 0; i < 2000; ++i) ++c[t->Sample(l.data(), &m)];
  EXPECT_EQ(c.size(), 2u);
  EXPECT_EQ(c.count(12), 0u);
}

TEST(Sampler, SameSeedSameDraws) {
  SamplingParams p;
  p.seed = 77;
  p.temperature = 1.5;
  p.top_k = 0;
  auto a = BuildSamplerChain({p}), b = BuildSamplerChain({p});
  std::vector<float> l(vocab::k_model_vocab_size);
  for (size_t i = 0; i < l.size(); ++i) l[i] = std::sin(static_cast<float>(i));
  int differ_from_other_seed = 0;
  p.seed = 78;
  auto c = BuildSamplerChain({p});
  for (int i = 0; i < 100; ++i) {
    const int x = a->Sample(l.data(), nullptr);
    EXPECT_EQ(x, b->Sample(l.data(), nullptr));
    differ_from_other_seed += x != c->Sample(l.data(), nullptr);
  }
  EXPECT_GT(differ_from_other_seed, 50);
}

// A small, independent statement of the official chain (official_network.md §4), written from the
// description rather than from sampler.cpp: sort candidates by logit; top-k; normalised
// softmax at top_p_temperature; an id is removed when the cumulative probability up to the id
// BEFORE it exceeds top_p; then normalised softmax(logit / temperature) over the rest and the
// first id whose cumulative probability exceeds one SplitMix64 uniform.
int ReferenceOfficialDraw(const std::vector<float>& logits, const std::vector<int32_t>& candidates, int top_k,
                          double top_p, double top_p_temperature, double temperature, SplitMix64* rng) {
  std::vector<int32_t> ids = candidates;
  std::stable_sort(ids.begin(), ids.end(), [&](int32_t a, int32_t b) { return logits[a] > logits[b]; });
  if (top_k > 0 && ids.size() > static_cast<size_t>(top_k)) ids.resize(static_cast<size_t>(top_k));
  std::vector<double> p1(ids.size());
  double z1 = 0;
  for (size_t i = 0; i < ids.size(); ++i) z1 += p1[i] = std::exp((logits[ids[i]] - logits[ids[0]]) / top_p_temperature);
  std::vector<int32_t> kept;
  double cum = 0;
  for (size_t i = 0; i < ids.size(); ++i) {
    const double shifted = cum;  // cumulative probability of the ids before this one
    cum += p1[i] / z1;
    if (i == 0 || shifted <= top_p) kept.push_back(ids[i]);
  }
  std::vector<double> p2(kept.size());
  double z2 = 0;
  for (size_t i = 0; i < kept.size(); ++i) z2 += p2[i] = std::exp((logits[kept[i]] - logits[kept[0]]) / temperature);
  const double u = rng->Uniform();
  double run = 0;
  for (size_t i = 0; i < kept.size(); ++i) {
    run += p2[i] / z2;
    if (run > u) return kept[i];
  }
  return kept.back();
}

TEST(Sampler, OfficialChainMatchesIndependentReference) {
  std::vector<float> l(vocab::k_model_vocab_size);
  for (size_t i = 0; i < l.size(); ++i) l[i] = 3.0f * std::sin(0.37f * static_cast<float>(i)) + 0.001f * (i % 97);
  // Every 5th id is legal (a grammar-like mask, and fewer ids keep the sanitizer build quick).
  std::vector<int32_t> legal_ids;
  TokenMask mask;
  for (int32_t id = 0; id < vocab::k_model_vocab_size; id += 5) legal_ids.push_back(id), mask.Set(id);
  struct Setting {
    int top_k;
    double top_p, temperature;
  };
  for (const Setting& st :
       {Setting{50, 0.95, 0.5}, Setting{5, 0.5, 1.0}, Setting{0, 0.3, 0.7}, Setting{50, 0.999, 2.0}}) {
    SamplingParams p;
    p.top_k = st.top_k;
    p.top_p = st.top_p;
    p.temperature = st.temperature;
    p.top_p_temperature = 1.0;
    p.seed = 99;
    auto s = BuildSamplerChain({p});
    SplitMix64 rng(99);
    for (int i = 0; i < 100; ++i)
      ASSERT_EQ(s->Sample(l.data(), &mask),
                ReferenceOfficialDraw(l, legal_ids, st.top_k, st.top_p, 1.0, st.temperature, &rng))
          << "top_k " << st.top_k << " top_p " << st.top_p << " draw " << i;
  }
}

TEST(Sampler, OfficialTopPKeepsTheCrossingIdAndUsesItsOwnTemperature) {
  // Probabilities at temperature 1: 0.5, 0.3, 0.15, 0.05 (ids 20..23).
  std::vector<float> l(vocab::k_model_vocab_size, -1e4f);
  const double pr[4] = {0.5, 0.3, 0.15, 0.05};
  for (int k = 0; k < 4; ++k) l[20 + k] = static_cast<float>(std::log(pr[k]));
  TokenMask m;
  for (int k = 0; k < 4; ++k) m.Set(20 + k);
  SamplingParams p;
  p.top_p = 0.9;  // mass before ids: 0, 0.5, 0.8, 0.95 -> 20, 21, 22 kept (22 crosses 0.9), 23 dropped
  p.temperature = 0.5;
  p.top_p_temperature = 1.0;
  p.seed = 5;
  auto official = BuildSamplerChain({p});
  std::map<int, int> c;
  const int n = 20000;
  for (int i = 0; i < n; ++i) ++c[official->Sample(l.data(), &m)];
  EXPECT_EQ(c.count(23), 0u);
  // Draw at temperature 0.5 over {20, 21, 22}: proportional to 0.25, 0.09, 0.0225.
  const double z = 0.25 + 0.09 + 0.0225;
  EXPECT_NEAR(c[20] / double(n), 0.25 / z, 0.015);
  EXPECT_NEAR(c[22] / double(n), 0.0225 / z, 0.01);
  // Today's chain computes top-p at temperature 0.5 (0.69, 0.25, ...): id 22 never survives.
  p.top_p_temperature = 0;
  auto silk = BuildSamplerChain({p});
  for (int i = 0; i < 2000; ++i) EXPECT_NE(silk->Sample(l.data(), &m), 22);
  // The top id alone survives when it already exceeds top_p.
  p.top_p_temperature = 1.0;
  p.top_p = 0.4;
  auto only_top = BuildSamplerChain({p});
  for (int i = 0; i < 200; ++i) EXPECT_EQ(only_top->Sample(l.data(), &m), 20);
}

TEST(Sampler, EmptyOrSingleCandidate) {
  auto s = BuildSamplerChain({SamplingParams{}});
  const auto l = Logits();
  TokenMask none;
  EXPECT_EQ(s->Sample(l.data(), &none), -1);
  TokenMask one;
  one.Set(4242);
  EXPECT_EQ(s->Sample(l.data(), &one), 4242);
}

}  // namespace
}  // namespace silk
