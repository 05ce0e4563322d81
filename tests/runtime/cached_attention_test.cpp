// CachedAttention (runtime/attention), the kernel behind the ai.silk op of fp16-cache decoders:
// against a plain double-precision reference, vectorized rows against scalar ones, and float16
// rounding against onnxruntime's own conversion (an independent implementation).
#include "runtime/attention/cached_attention.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <onnxruntime_cxx_api.h>

#include "runtime/attention/attention_rows.h"

namespace silk {
namespace {

float Widen(const void* cache, CacheElement e, size_t i) {
  if (e == CacheElement::kFloat32) return static_cast<const float*>(cache)[i];
  return Ort::Float16_t::FromBits(static_cast<const uint16_t*>(cache)[i]).ToFloat();
}

struct Case {
  AttentionShape shape;
  std::vector<float> q, k, v, out;
  std::vector<unsigned char> key_cache, value_cache;
  AttentionBuffers buffers(CacheElement) {
    AttentionBuffers b;
    b.q = q.data(), b.k = k.data(), b.v = v.data(), b.out = out.data();
    b.key_cache = key_cache.data(), b.value_cache = value_cache.data();
    return b;
  }
};

// Random inputs; cache rows [0, past) filled with random values of the element type, the rest
// with a sentinel byte so a write outside [past, past + chunk) shows.
Case MakeCase(AttentionShape s, CacheElement e, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, 1.0f);
  Case c;
  c.shape = s;
  const int64_t qn = s.chunk * s.heads * s.head_dim, kn = s.chunk * s.kv_heads * s.head_dim;
  for (auto* vec : {&c.q}) for (int64_t i = 0; i < qn; ++i) vec->push_back(n(rng) * 0.3f);
  for (auto* vec : {&c.k, &c.v}) for (int64_t i = 0; i < kn; ++i) vec->push_back(n(rng));
  c.out.assign(static_cast<size_t>(qn), std::nanf(""));
  const size_t eb = e == CacheElement::kFloat16 ? 2 : 4, elems = s.kv_heads * s.capacity * s.head_dim;
  for (auto* cache : {&c.key_cache, &c.value_cache}) {
    cache->assign(elems * eb, 0xA5);
    for (int64_t h = 0; h < s.kv_heads; ++h)
      for (int64_t p = 0; p < s.past; ++p)
        for (int64_t d = 0; d < s.head_dim; ++d) {
          const size_t i = static_cast<size_t>((h * s.capacity + p) * s.head_dim + d);
          const float x = n(rng);
          if (eb == 4) std::memcpy(cache->data() + i * 4, &x, 4);
          else { const uint16_t bits = Ort::Float16_t(x).val; std::memcpy(cache->data() + i * 2, &bits, 2); }
        }
  }
  return c;
}

// softmax(scale q.k) v over the cache as the kernel left it, in double.
std::vector<double> Reference(const Case& c, CacheElement e) {
  const AttentionShape& s = c.shape;
  std::vector<double> out(c.out.size());
  for (int64_t t = 0; t < s.chunk; ++t)
    for (int64_t h = 0; h < s.heads; ++h) {
      const int64_t kvh = h / (s.heads / s.kv_heads), len = s.past + t + 1;
      std::vector<double> w(static_cast<size_t>(len));
      double top = -1e300, sum = 0;
      for (int64_t j = 0; j < len; ++j) {
        double dot = 0;
        for (int64_t d = 0; d < s.head_dim; ++d)
          dot += double(c.q[(t * s.heads + h) * s.head_dim + d]) *
                 Widen(c.key_cache.data(), e, (kvh * s.capacity + j) * s.head_dim + d);
        w[j] = s.scale * dot;
        top = std::max(top, w[j]);
      }
      for (double& x : w) sum += (x = std::exp(x - top));
      for (int64_t d = 0; d < s.head_dim; ++d) {
        double acc = 0;
        for (int64_t j = 0; j < len; ++j)
          acc += w[j] * Widen(c.value_cache.data(), e, (kvh * s.capacity + j) * s.head_dim + d);
        out[(t * s.heads + h) * s.head_dim + d] = acc / sum;
      }
    }
  return out;
}

void Serial(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = count; i-- > 0;) work(state, i);  // reversed: tasks must not depend on order
}

void ExpectMatchesReference(AttentionShape s, CacheElement e, RowKernels kernels) {
  Case c = MakeCase(s, e, 7);
  const std::vector<unsigned char> before = c.key_cache;
  CachedAttention(s, e, c.buffers(e), Serial, nullptr, kernels);
  const std::vector<double> ref = Reference(c, e);
  double worst = 0;
  for (size_t i = 0; i < ref.size(); ++i) worst = std::max(worst, std::fabs(ref[i] - c.out[i]));
  EXPECT_LT(worst, 2e-5) << "heads " << s.heads << "/" << s.kv_heads << " dim " << s.head_dim << " chunk " << s.chunk
                         << " past " << s.past;
  // The chunk's keys landed in rows [past, past + chunk), rounded as onnxruntime rounds; nothing else moved.
  const size_t eb = e == CacheElement::kFloat16 ? 2 : 4;
  for (int64_t h = 0; h < s.kv_heads; ++h)
    for (int64_t p = 0; p < s.capacity; ++p)
      for (int64_t d = 0; d < s.head_dim; ++d) {
        const size_t i = static_cast<size_t>((h * s.capacity + p) * s.head_dim + d);
        if (p < s.past || p >= s.past + s.chunk) {
          ASSERT_EQ(std::memcmp(c.key_cache.data() + i * eb, before.data() + i * eb, eb), 0) << "row " << p;
          continue;
        }
        const float src = c.k[((p - s.past) * s.kv_heads + h) * s.head_dim + d];
        const float want = e == CacheElement::kFloat16 ? Ort::Float16_t(src).ToFloat() : src;
        ASSERT_EQ(Widen(c.key_cache.data(), e, i), want) << "row " << p << " dim " << d;
      }
}

const AttentionShape kShapes[] = {
    {4, 2, 64, 3, 37, 50, 0.125f},    // grouped heads, a chunk after a prefix
    {2, 2, 12, 1, 0, 5, 0.3f},        // head_dim not a multiple of 8: the scalar rows
    {16, 16, 64, 1, 1000, 1001, 10.0f},  // the release network's heads and scale, deep
    {3, 1, 24, 5, 0, 5, 1.0f},        // the first chunk, one kv head
};

TEST(CachedAttention, MatchesReferenceWithEveryRowKernel) {
  for (const AttentionShape& s : kShapes)
    for (CacheElement e : {CacheElement::kFloat32, CacheElement::kFloat16})
      for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) ExpectMatchesReference(s, e, k);
}

TEST(CachedAttention, VectorizedRowsAgreeWithScalarRows) {
  if (!CachedAttentionVectorized()) GTEST_SKIP() << "this CPU has no AVX2/FMA/F16C";
  for (CacheElement e : {CacheElement::kFloat32, CacheElement::kFloat16}) {
    Case a = MakeCase(kShapes[2], e, 3), b = MakeCase(kShapes[2], e, 3);
    CachedAttention(a.shape, e, a.buffers(e), Serial, nullptr, RowKernels::kBest);
    CachedAttention(b.shape, e, b.buffers(e), Serial, nullptr, RowKernels::kScalar);
    EXPECT_EQ(a.key_cache, b.key_cache);  // same rounding of the new rows
    double worst = 0;
    for (size_t i = 0; i < a.out.size(); ++i) worst = std::max(worst, double(std::fabs(a.out[i] - b.out[i])));
    EXPECT_LT(worst, 5e-5);  // float sums in another order (each is within 2e-5 of the reference)
  }
}

// Scores far apart (one key dominates, the others underflow exp) stay finite and pick that key.
TEST(CachedAttention, SharpSoftmaxIsFinite) {
  AttentionShape s{1, 1, 16, 1, 40, 41, 1000.0f};
  for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) {
    Case c = MakeCase(s, CacheElement::kFloat32, 11);
    CachedAttention(s, CacheElement::kFloat32, c.buffers(CacheElement::kFloat32), Serial, nullptr, k);
    const std::vector<double> ref = Reference(c, CacheElement::kFloat32);
    for (size_t i = 0; i < ref.size(); ++i) {
      ASSERT_TRUE(std::isfinite(c.out[i]));
      EXPECT_NEAR(c.out[i], ref[i], 1e-4);
    }
  }
}

// float16 rounding of new rows: ties to even, subnormals, overflow, NaN, as onnxruntime converts.
TEST(CachedAttention, Float16RowsRoundLikeOnnxRuntime) {
  std::vector<float> xs = {0.0f, -0.0f, 1.0f, 1.0f + 1.0f / 2048, 1.0f + 3.0f / 2048, 65504.0f, 65519.0f, 65520.0f,
                           -70000.0f, 6.0e-8f, 3.0e-8f, 2.9e-8f, 1.0e-5f, -6.1e-5f, 6.103515625e-05f,
                           std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> mant(1.0f, 2.0f);
  std::uniform_int_distribution<int> ex(-30, 17);
  while (xs.size() % 8 != 0 || xs.size() < 20000) xs.push_back(std::ldexp(mant(rng), ex(rng)) * (rng() % 2 ? 1 : -1));
  for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) {
    const AttentionRows rows = AttentionRowsFor(CacheElement::kFloat16, static_cast<int64_t>(xs.size()), k);
    std::vector<uint16_t> got(xs.size());
    rows.store(xs.data(), got.data(), static_cast<int64_t>(xs.size()));
    for (size_t i = 0; i < xs.size(); ++i) {
      const uint16_t want = Ort::Float16_t(xs[i]).val;
      if (std::isnan(xs[i])) EXPECT_TRUE(Ort::Float16_t::FromBits(got[i]).IsNaN());
      else ASSERT_EQ(got[i], want) << "x = " << xs[i] << (k == RowKernels::kBest ? " (vectorized)" : " (scalar)");
    }
  }
}

}  // namespace
}  // namespace silk
