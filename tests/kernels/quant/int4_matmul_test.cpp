// SPDX-License-Identifier: MIT
// Int4MatMul (kernels/quant), the kernel behind the ai.silk op of INT4 decoders: against the exact
// product of the dequantized weights in double precision (within the bound that int8 activations
// allow, derived here), against the same int8 activations computed independently (to float
// rounding), vectorized rows against scalar ones, any block size and shape it accepts.
#include "kernels/quant/int4_matmul.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace silk {
namespace {

struct Case {
  int64_t m, k, n, block;
};

struct Weights {
  std::vector<uint8_t> packed;  // [n, k / block, block / 2]
  std::vector<float> scales;    // [n * k / block]
  // The contract's value of weight (row, col): (nibble - 8) * scale.
  double At(const Case& c, int64_t row, int64_t col) const {
    const uint8_t byte = packed[static_cast<size_t>(row * (c.k / 2) + col / 2)];
    const int q = col % 2 ? byte >> 4 : byte & 0x0f;
    return (q - 8) * static_cast<double>(scales[static_cast<size_t>(row * (c.k / c.block) + col / c.block)]);
  }
};

Weights RandomWeights(const Case& c, std::mt19937& rng) {
  Weights w;
  w.packed.resize(static_cast<size_t>(c.n * c.k / 2));
  for (auto& b : w.packed) b = static_cast<uint8_t>(rng());
  std::uniform_real_distribution<float> scale(0.001f, 0.05f);
  w.scales.resize(static_cast<size_t>(c.n * (c.k / c.block)));
  for (auto& s : w.scales) s = scale(rng);
  return w;
}

std::vector<float> RandomActivations(const Case& c, std::mt19937& rng) {
  std::normal_distribution<float> normal(0.0f, 2.0f);
  std::vector<float> a(static_cast<size_t>(c.m * c.k));
  for (auto& x : a) x = normal(rng);
  return a;
}

void Serial(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = 0; i < count; ++i) work(state, i);
}
void Backwards(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = count; i-- > 0;) work(state, i);
}

std::vector<float> Multiply(const Case& c, const std::vector<float>& a, const Weights& w, RowKernels kernels,
                            ParallelForFn pool = Serial) {
  std::vector<float> out(static_cast<size_t>(c.m * c.n), std::numeric_limits<float>::quiet_NaN());
  const Int4MatMulShape s{c.m, c.k, c.n, c.block};
  Int4MatMul(s, a.data(), w.packed.data(), w.scales.data(), out.data(), pool, nullptr, kernels);
  return out;
}

// The activation a[k] rounded the documented way: groups of 32, scale max|a| / 127, nearest even.
double Int8Activation(const std::vector<float>& a, int64_t row, int64_t k, int64_t col) {
  const float* g = a.data() + row * k + col / 32 * 32;
  float top = 0.0f;
  for (int i = 0; i < 32; ++i) top = std::max(top, std::fabs(g[i]));
  if (top == 0.0f) return 0.0;
  const float scale = top / 127.0f;
  return std::nearbyint(a[static_cast<size_t>(row * k + col)] * (127.0f / top)) * static_cast<double>(scale);
}

class Int4MatMulTest : public ::testing::TestWithParam<Case> {};

TEST_P(Int4MatMulTest, MatchesTheDequantizedProductWithinTheActivationRounding) {
  const Case c = GetParam();
  std::mt19937 rng(static_cast<unsigned>(c.k * 31 + c.n * 7 + c.block + c.m));
  const Weights w = RandomWeights(c, rng);
  const std::vector<float> a = RandomActivations(c, rng);
  const std::vector<float> best = Multiply(c, a, w, RowKernels::kBest), scalar = Multiply(c, a, w, RowKernels::kScalar);
  const std::vector<float> avx2 = Multiply(c, a, w, RowKernels::kAvx2);  // best's rows where the CPU has no wider ones
  for (int64_t m = 0; m < c.m; ++m)
    for (int64_t n = 0; n < c.n; ++n) {
      double exact = 0, rounded = 0, bound = 0, magnitude = 0;
      for (int64_t k = 0; k < c.k; ++k) {
        const double wk = w.At(c, n, k), ak = a[static_cast<size_t>(m * c.k + k)];
        const float* g = a.data() + m * c.k + k / 32 * 32;
        double top = 0;
        for (int i = 0; i < 32; ++i) top = std::max(top, static_cast<double>(std::fabs(g[i])));
        exact += wk * ak;
        rounded += wk * Int8Activation(a, m, c.k, k);
        bound += std::fabs(wk) * top / 127.0 / 2.0;  // half a step of the group's int8 grid
        magnitude += std::fabs(wk * ak);
      }
      const size_t i = static_cast<size_t>(m * c.n + n);
      const double float_rounding = 1e-5 * magnitude + 1e-6;
      EXPECT_NEAR(best[i], exact, bound * 1.001 + float_rounding) << "m " << m << " n " << n;
      EXPECT_NEAR(best[i], rounded, float_rounding) << "m " << m << " n " << n;
      EXPECT_NEAR(avx2[i], rounded, float_rounding) << "m " << m << " n " << n;
      EXPECT_NEAR(scalar[i], rounded, float_rounding) << "m " << m << " n " << n;
    }
}

TEST_P(Int4MatMulTest, TheOrderOfParallelWorkDoesNotMatter) {
  const Case c = GetParam();
  std::mt19937 rng(7);
  const Weights w = RandomWeights(c, rng);
  const std::vector<float> a = RandomActivations(c, rng);
  EXPECT_EQ(Multiply(c, a, w, RowKernels::kBest, Serial), Multiply(c, a, w, RowKernels::kBest, Backwards));
}

INSTANTIATE_TEST_SUITE_P(Shapes, Int4MatMulTest,
                         ::testing::Values(Case{1, 64, 1, 32}, Case{1, 1024, 37, 32}, Case{1, 96, 300, 32},
                                           Case{3, 256, 520, 32}, Case{1, 256, 33, 64}, Case{2, 512, 17, 128},
                                           Case{1, 32, 9, 32}, Case{0, 64, 5, 32}, Case{2, 768, 20, 192},
                                           Case{3, 4160, 7, 64}));

TEST(Int4MatMul, ZeroGroupsAndTinyValuesStayFinite) {
  const Case c{1, 128, 12, 32};
  std::mt19937 rng(3);
  const Weights w = RandomWeights(c, rng);
  std::vector<float> a(128, 0.0f);
  for (int i = 64; i < 96; ++i) a[i] = 1e-30f * static_cast<float>(i);  // a group of tiny values
  a[100] = -3.0f;
  for (RowKernels kernels : {RowKernels::kBest, RowKernels::kScalar}) {
    const std::vector<float> out = Multiply(c, a, w, kernels);
    for (int64_t n = 0; n < c.n; ++n) {
      EXPECT_TRUE(std::isfinite(out[n]));
      EXPECT_NEAR(out[n], w.At(c, n, 100) * -3.0, 1e-6) << n;  // only a[100] survives its group's rounding
    }
  }
}

TEST(Int4MatMul, NonFiniteActivationsDoNotCrash) {
  const Case c{1, 64, 4, 32};
  std::mt19937 rng(5);
  const Weights w = RandomWeights(c, rng);
  std::vector<float> a(64, 1.0f);
  a[3] = std::numeric_limits<float>::quiet_NaN();
  a[40] = std::numeric_limits<float>::infinity();
  for (RowKernels kernels : {RowKernels::kBest, RowKernels::kScalar}) Multiply(c, a, w, kernels);
}

// The activations' int8 groups decide every Int4MatMul output: the vectorized rounding must give
// plain C++'s bytes on ties (x.5 after scaling), signed zeros, denormals, NaN and infinities.
TEST(Int4MatMul, VectorizedActivationRoundingEqualsPlainCpp) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> a(32 * 8);
  std::mt19937 rng(3);
  std::normal_distribution<float> normal(0.0f, 2.0f);
  for (float& x : a) x = normal(rng);
  for (int i = 0; i < 32; ++i) a[i] = i == 0 ? 127.0f : static_cast<float>(i % 2 ? i : -i) + 0.5f;  // ties
  for (int i = 32; i < 64; ++i) a[i] = i % 3 ? -0.0f : std::numeric_limits<float>::denorm_min();
  a[70] = nan;   // a NaN among finite values: 0, the scale from the rest
  a[100] = inf;  // an infinity: scale inf, every value 0
  a[130] = -inf, a[131] = nan;
  std::fill(a.begin() + 160, a.begin() + 192, 0.0f);  // an all-zero group
  for (int i = 192; i < 224; ++i) a[i] = 1e-30f * static_cast<float>(i - 208);
  std::vector<int8_t> best(a.size()), plain(a.size());
  std::vector<float> best_scale(8), plain_scale(8);
  QuantizeInt4Activations(a.data(), static_cast<int64_t>(a.size()), best.data(), best_scale.data(), RowKernels::kBest);
  QuantizeInt4Activations(a.data(), static_cast<int64_t>(a.size()), plain.data(), plain_scale.data(),
                          RowKernels::kScalar);
  EXPECT_EQ(best, plain);
  for (int g = 0; g < 8; ++g) EXPECT_EQ(0, std::memcmp(&best_scale[g], &plain_scale[g], 4)) << "group " << g;
  EXPECT_EQ(plain[1], 2) << "1.5 rounds to the even 2";
  EXPECT_EQ(plain[2], -2) << "-1.5 rounds to the even -2";
  EXPECT_EQ(plain[70], 0);
  EXPECT_TRUE(std::isinf(plain_scale[3]));
}

TEST(Int4MatMul, ShapesItDoesNotComputeAreNamed) {
  const char* why = nullptr;
  EXPECT_TRUE(Int4ShapeSupported({1, 1024, 1024, 32}, &why));
  EXPECT_EQ(why, nullptr);
  EXPECT_TRUE(Int4ShapeSupported({1, 1024, 8, 128}, &why));
  EXPECT_FALSE(Int4ShapeSupported({1, 96, 8, 48}, &why));
  EXPECT_STREQ(why, "block_size must be 32 or a multiple of 64");
  EXPECT_FALSE(Int4ShapeSupported({1, 96, 8, 64}, &why));
  EXPECT_STREQ(why, "K must be a multiple of block_size");
  EXPECT_FALSE(Int4ShapeSupported({1, 0, 8, 32}, &why));
  EXPECT_STREQ(why, "K and N must be in [1, 2^31)");
  EXPECT_FALSE(Int4ShapeSupported({1, 64, int64_t{1} << 40, 32}, &why));
  EXPECT_STREQ(why, "K and N must be in [1, 2^31)");
  EXPECT_FALSE(Int4ShapeSupported({1, 64, 8, 16}, &why));
}

}  // namespace
}  // namespace silk
