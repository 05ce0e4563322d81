// SPDX-License-Identifier: MIT
// CrossAttention (kernels/attention), the kernel behind the ai.silk op that attends over the
// point cloud's K/V: against a plain double-precision softmax attention over the rows as stored
// (float32, or float16 widened by onnxruntime's own conversion), vectorized rows against scalar
// ones, head sizes with and without the vectorized rows, any order of the parallel work.
#include "kernels/attention/cross_attention.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include <onnxruntime_cxx_api.h>

namespace silk {
namespace {

struct Case {
  int64_t heads, positions, rows, head_dim;
  float scale;
};

void Serial(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = 0; i < count; ++i) work(state, i);
}
void Backwards(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = count; i-- > 0;) work(state, i);
}

std::vector<float> Random(size_t n, std::mt19937& rng) {
  std::normal_distribution<float> normal;
  std::vector<float> v(n);
  for (auto& x : v) x = normal(rng);
  return v;
}

// Rows as the op receives them: float32 as they are, or float16 bits; `values` gets what they hold.
struct Rows {
  std::vector<float> f32;
  std::vector<uint16_t> f16;
  const void* data(CacheElement e) const {
    return e == CacheElement::kFloat16 ? static_cast<const void*>(f16.data()) : f32.data();
  }
};
Rows Store(const std::vector<float>& x, CacheElement e, std::vector<float>* values) {
  Rows r;
  r.f32 = x;
  *values = x;
  if (e == CacheElement::kFloat16)
    for (size_t i = 0; i < x.size(); ++i) {
      r.f16.push_back(Ort::Float16_t(x[i]).val);
      (*values)[i] = Ort::Float16_t::FromBits(r.f16.back()).ToFloat();
    }
  return r;
}

class CrossAttentionTest : public ::testing::TestWithParam<std::tuple<Case, CacheElement>> {};

TEST_P(CrossAttentionTest, MatchesADoublePrecisionSoftmaxAttention) {
  const Case c = std::get<0>(GetParam());
  const CacheElement e = std::get<1>(GetParam());
  std::mt19937 rng(static_cast<unsigned>(c.heads * 100 + c.rows + c.head_dim));
  const auto q = Random(c.heads * c.positions * c.head_dim, rng);
  std::vector<float> k, v;
  const Rows key = Store(Random(c.heads * c.rows * c.head_dim, rng), e, &k);
  const Rows value = Store(Random(c.heads * c.rows * c.head_dim, rng), e, &v);
  const CrossAttentionShape s{c.heads, c.positions, c.rows, c.head_dim, c.scale};
  std::vector<float> best(q.size(), NAN), scalar(q.size(), NAN), backwards(q.size(), NAN);
  CrossAttention(s, e, q.data(), key.data(e), value.data(e), best.data(), Serial, nullptr, RowKernels::kBest);
  CrossAttention(s, e, q.data(), key.data(e), value.data(e), scalar.data(), Serial, nullptr, RowKernels::kScalar);
  CrossAttention(s, e, q.data(), key.data(e), value.data(e), backwards.data(), Backwards, nullptr, RowKernels::kBest);
  EXPECT_EQ(best, backwards);
  for (int64_t h = 0; h < c.heads; ++h)
    for (int64_t t = 0; t < c.positions; ++t) {
      const float* qr = q.data() + (h * c.positions + t) * c.head_dim;
      std::vector<double> w(static_cast<size_t>(c.rows));
      double top = -INFINITY, sum = 0;
      for (int64_t j = 0; j < c.rows; ++j) {
        double dot = 0;
        for (int64_t d = 0; d < c.head_dim; ++d) dot += double(qr[d]) * k[(h * c.rows + j) * c.head_dim + d];
        w[j] = c.scale * dot;
        top = std::max(top, w[j]);
      }
      for (auto& x : w) sum += (x = std::exp(x - top));
      // float32 scores carry ~1e-7 of scale * |q||k| (about scale * head_dim here), which the
      // softmax passes on to the weights.
      const double tolerance = 2e-5 + 2e-7 * c.scale * c.head_dim;
      for (int64_t d = 0; d < c.head_dim; ++d) {
        double want = 0;
        for (int64_t j = 0; j < c.rows; ++j) want += w[j] / sum * v[(h * c.rows + j) * c.head_dim + d];
        const size_t i = static_cast<size_t>((h * c.positions + t) * c.head_dim + d);
        EXPECT_NEAR(best[i], want, tolerance) << "h " << h << " t " << t << " d " << d;
        EXPECT_NEAR(scalar[i], want, tolerance) << "h " << h << " t " << t << " d " << d;
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Shapes, CrossAttentionTest,
                         ::testing::Combine(::testing::Values(Case{16, 1, 261, 64, 10.0f}, Case{3, 4, 7, 16, 0.25f},
                                                              Case{2, 2, 1, 8, 1.0f}, Case{4, 1, 33, 12, 0.3f},
                                                              Case{1, 3, 300, 48, 0.144f}),
                                            ::testing::Values(CacheElement::kFloat32, CacheElement::kFloat16)));

TEST(CrossAttention, ASharpSoftmaxStaysFinite) {
  const CrossAttentionShape s{1, 1, 3, 8, 1e4f};
  std::vector<float> q(8, 1.0f), k(24, 0.0f), v(24, 0.0f), out(8, NAN);
  for (int d = 0; d < 8; ++d) k[8 + d] = 1.0f, v[8 + d] = 2.0f;  // row 1 wins by 8e4
  CrossAttention(s, CacheElement::kFloat32, q.data(), k.data(), v.data(), out.data(), Serial, nullptr);
  for (float x : out) EXPECT_FLOAT_EQ(x, 2.0f);
}

}  // namespace
}  // namespace silk
