// The sampling chain: only legal ids, greedy/top-k/top-p semantics, seeded determinism, and
// draws that follow the softmax of the logits.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "runtime/sampler.h"
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
  Sampler s(p);
  const auto l = Logits();
  const TokenMask m = Legal();
  EXPECT_EQ(s.Sample(l.data(), &m), 10);
  EXPECT_EQ(s.Sample(l.data(), nullptr), 13);  // unconstrained: PAD never, even at 50
}

TEST(Sampler, TopKOneIsGreedy) {
  SamplingParams p;
  p.top_k = 1;
  p.seed = 9;
  Sampler s(p);
  const auto l = Logits();
  const TokenMask m = Legal();
  for (int i = 0; i < 50; ++i) EXPECT_EQ(s.Sample(l.data(), &m), 10);
}

TEST(Sampler, NeverIllegalAndFollowsSoftmax) {
  SamplingParams p;
  p.temperature = 1.0;
  p.seed = 1234;
  Sampler s(p);
  const auto l = Logits();
  const TokenMask m = Legal();
  std::map<int, int> counts;
  const int n = 20000;
  for (int i = 0; i < n; ++i) ++counts[s.Sample(l.data(), &m)];
  ASSERT_EQ(counts.size(), 3u);
  const double z = std::exp(2.0) + std::exp(1.0) + std::exp(0.0);
  const double expect[3] = {std::exp(2.0) / z, std::exp(1.0) / z, 1.0 / z};
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(counts[10 + k] / double(n), expect[k], 0.015) << k;
}

TEST(Sampler, TopPKeepsSmallestNucleus) {
  SamplingParams p;
  p.top_p = 0.6;  // p(10) = 0.665 >= 0.6: only id 10 survives
  p.seed = 3;
  Sampler s(p);
  const auto l = Logits();
  const TokenMask m = Legal();
  for (int i = 0; i < 200; ++i) EXPECT_EQ(s.Sample(l.data(), &m), 10);
  SamplingParams q = p;
  q.top_p = 0.9;  // 0.665 + 0.245 = 0.91: ids 10 and 11
  Sampler t(q);
  std::map<int, int> c;
  for (int i = 0; i < 2000; ++i) ++c[t.Sample(l.data(), &m)];
  EXPECT_EQ(c.size(), 2u);
  EXPECT_EQ(c.count(12), 0u);
}

TEST(Sampler, SameSeedSameDraws) {
  SamplingParams p;
  p.seed = 77;
  p.temperature = 1.5;
  p.top_k = 0;
  Sampler a(p), b(p);
  std::vector<float> l(vocab::k_model_vocab_size);
  for (size_t i = 0; i < l.size(); ++i) l[i] = std::sin(static_cast<float>(i));
  int differ_from_other_seed = 0;
  p.seed = 78;
  Sampler c(p);
  for (int i = 0; i < 100; ++i) {
    const int x = a.Sample(l.data(), nullptr);
    EXPECT_EQ(x, b.Sample(l.data(), nullptr));
    differ_from_other_seed += x != c.Sample(l.data(), nullptr);
  }
  EXPECT_GT(differ_from_other_seed, 50);
}

TEST(Sampler, EmptyOrSingleCandidate) {
  Sampler s(SamplingParams{});
  const auto l = Logits();
  TokenMask none;
  EXPECT_EQ(s.Sample(l.data(), &none), -1);
  TokenMask one;
  one.Set(4242);
  EXPECT_EQ(s.Sample(l.data(), &one), 4242);
}

}  // namespace
}  // namespace silk
