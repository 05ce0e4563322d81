// SPDX-License-Identifier: MIT
// CachedAttention (kernels/attention), the kernel behind the ai.silk op of fp16/int8-cache decoders:
// against a plain double-precision reference, vectorized rows against scalar ones, float16
// rounding against onnxruntime's own conversion and int8 rows against the contract's formula
// computed here (both independent implementations).
#include "kernels/attention/cached_attention.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <onnxruntime_cxx_api.h>

#include "kernels/attention/attention_rows.h"
#include "kernels/cpu/cpu_features.h"

namespace silk {
namespace {

// Value d of cache row `row` (= kv_head * capacity + position), as the contract defines it.
float Widen(const std::vector<unsigned char>& cache, CacheElement e, int64_t head_dim, int64_t row, int64_t d) {
  const unsigned char* r = cache.data() + static_cast<size_t>(row) * CacheRowBytes(e, head_dim);
  if (e == CacheElement::kFloat32) {
    float x;
    std::memcpy(&x, r + 4 * d, 4);
    return x;
  }
  if (e == CacheElement::kFloat16) {
    uint16_t bits;
    std::memcpy(&bits, r + 2 * d, 2);
    return Ort::Float16_t::FromBits(bits).ToFloat();
  }
  float scale;
  std::memcpy(&scale, r + head_dim, 4);
  return static_cast<float>(static_cast<int8_t>(r[d])) * scale;
}

// The contract's int8 row, computed independently: scale = max|x| / 127, q = nearbyint(x / scale).
std::vector<unsigned char> Int8Row(const float* x, int64_t d) {
  float top = 0.0f;
  for (int64_t i = 0; i < d; ++i) top = std::fabs(x[i]) > top ? std::fabs(x[i]) : top;
  const float scale = top / 127.0f;
  std::vector<unsigned char> row(static_cast<size_t>(d) + 4, 0);
  for (int64_t i = 0; i < d && scale > 0.0f; ++i) {
    const long q = std::lround(std::nearbyint(x[i] / scale));
    row[i] = static_cast<unsigned char>(static_cast<int8_t>(q < -127 ? -127 : q > 127 ? 127 : q));
  }
  std::memcpy(row.data() + d, &scale, 4);
  return row;
}

// Cache row bytes of the element type for the float values x[0..d).
std::vector<unsigned char> RowOf(const float* x, int64_t d, CacheElement e) {
  if (e == CacheElement::kInt8) return Int8Row(x, d);
  std::vector<unsigned char> row(CacheRowBytes(e, d));
  for (int64_t i = 0; i < d; ++i) {
    if (e == CacheElement::kFloat32)
      std::memcpy(row.data() + 4 * i, &x[i], 4);
    else {
      const uint16_t bits = Ort::Float16_t(x[i]).val;
      std::memcpy(row.data() + 2 * i, &bits, 2);
    }
  }
  return row;
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
  for (auto* vec : {&c.q})
    for (int64_t i = 0; i < qn; ++i) vec->push_back(n(rng) * 0.3f);
  for (auto* vec : {&c.k, &c.v})
    for (int64_t i = 0; i < kn; ++i) vec->push_back(n(rng));
  c.out.assign(static_cast<size_t>(qn), std::nanf(""));
  const size_t rb = CacheRowBytes(e, s.head_dim);
  std::vector<float> x(static_cast<size_t>(s.head_dim));
  for (auto* cache : {&c.key_cache, &c.value_cache}) {
    cache->assign(static_cast<size_t>(s.kv_heads * s.capacity) * rb, 0xA5);
    for (int64_t h = 0; h < s.kv_heads; ++h)
      for (int64_t p = 0; p < s.past; ++p) {
        for (float& xi : x) xi = n(rng);
        const std::vector<unsigned char> row = RowOf(x.data(), s.head_dim, e);
        std::memcpy(cache->data() + static_cast<size_t>(h * s.capacity + p) * rb, row.data(), rb);
      }
  }
  return c;
}

// The query as the contract's int8-row scores use it: rounded to int16 steps of max|q| / 32767
// (nearest even), computed here independently.
std::vector<double> Int16Query(const float* q, int64_t d) {
  float top = 0.0f;
  for (int64_t i = 0; i < d; ++i) top = std::max(top, std::fabs(q[i]));
  std::vector<double> r(static_cast<size_t>(d), 0.0);
  for (int64_t i = 0; i < d && top > 0.0f; ++i) r[i] = std::nearbyint(q[i] * (32767.0f / top)) * double(top / 32767.0f);
  return r;
}

// softmax(scale q.k) v over the cache as the kernel left it, in double (int8 rows: with the
// query rounded as above).
std::vector<double> Reference(const Case& c, CacheElement e) {
  const AttentionShape& s = c.shape;
  std::vector<double> out(c.out.size());
  for (int64_t t = 0; t < s.chunk; ++t)
    for (int64_t h = 0; h < s.heads; ++h) {
      const int64_t kvh = h / (s.heads / s.kv_heads), len = s.past + t + 1;
      const float* qh = &c.q[(t * s.heads + h) * s.head_dim];
      std::vector<double> q(qh, qh + s.head_dim);
      if (e == CacheElement::kInt8) q = Int16Query(qh, s.head_dim);
      std::vector<double> w(static_cast<size_t>(len));
      double top = -1e300, sum = 0;
      for (int64_t j = 0; j < len; ++j) {
        double dot = 0;
        for (int64_t d = 0; d < s.head_dim; ++d)
          dot += q[d] * Widen(c.key_cache, e, s.head_dim, kvh * s.capacity + j, d);
        w[j] = s.scale * dot;
        top = std::max(top, w[j]);
      }
      for (double& x : w) sum += (x = std::exp(x - top));
      for (int64_t d = 0; d < s.head_dim; ++d) {
        double acc = 0;
        for (int64_t j = 0; j < len; ++j) acc += w[j] * Widen(c.value_cache, e, s.head_dim, kvh * s.capacity + j, d);
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
                         << " past " << s.past << " element " << static_cast<int>(e);
  // The chunk's keys and values landed in rows [past, past + chunk), rounded as onnxruntime rounds
  // (float16) or quantized by the contract's formula (int8); nothing else moved.
  const size_t rb = CacheRowBytes(e, s.head_dim);
  for (int64_t h = 0; h < s.kv_heads; ++h)
    for (int64_t p = 0; p < s.capacity; ++p) {
      const size_t at = static_cast<size_t>(h * s.capacity + p) * rb;
      const bool fresh = p >= s.past && p < s.past + s.chunk;
      const std::vector<unsigned char> want =
          fresh ? RowOf(&c.k[((p - s.past) * s.kv_heads + h) * s.head_dim], s.head_dim, e)
                : std::vector<unsigned char>(before.begin() + at, before.begin() + at + rb);
      ASSERT_EQ(std::memcmp(c.key_cache.data() + at, want.data(), rb), 0) << "head " << h << " row " << p;
      if (fresh) {
        const std::vector<unsigned char> v = RowOf(&c.v[((p - s.past) * s.kv_heads + h) * s.head_dim], s.head_dim, e);
        ASSERT_EQ(std::memcmp(c.value_cache.data() + at, v.data(), rb), 0) << "value row " << p;
      }
    }
}

constexpr CacheElement kElements[] = {CacheElement::kFloat32, CacheElement::kFloat16, CacheElement::kInt8};

const AttentionShape kShapes[] = {
    {4, 2, 64, 3, 37, 50, 0.125f},       // grouped heads, a chunk after a prefix
    {2, 2, 12, 1, 0, 5, 0.3f},           // head_dim not a multiple of 8: the scalar rows
    {16, 16, 64, 1, 1000, 1001, 10.0f},  // the release network's heads and scale, deep
    {3, 1, 24, 5, 0, 5, 1.0f},           // the first chunk, one kv head
};

TEST(CachedAttention, MatchesReferenceWithEveryRowKernel) {
  for (const AttentionShape& s : kShapes)
    for (CacheElement e : kElements)
      for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) ExpectMatchesReference(s, e, k);
}

TEST(CachedAttention, VectorizedRowsAgreeWithScalarRows) {
  if (!CachedAttentionVectorized()) GTEST_SKIP() << "this CPU has no AVX2/FMA/F16C";
  for (CacheElement e : kElements) {
    Case a = MakeCase(kShapes[2], e, 3), b = MakeCase(kShapes[2], e, 3);
    CachedAttention(a.shape, e, a.buffers(e), Serial, nullptr, RowKernels::kBest);
    CachedAttention(b.shape, e, b.buffers(e), Serial, nullptr, RowKernels::kScalar);
    EXPECT_EQ(a.key_cache, b.key_cache);  // same rounding of the new rows
    double worst = 0;
    for (size_t i = 0; i < a.out.size(); ++i) worst = std::max(worst, double(std::fabs(a.out[i] - b.out[i])));
    EXPECT_LT(worst, 5e-5);  // float sums in another order (each is within 2e-5 of the reference)
  }
}

// int8 rows: the scores are exact integer dot products times float scales in one order, so the
// vectorized rows give the scalar rows' scores bit for bit (head sizes with and without AVX2's
// integer path); a query with a NaN gives NaN scores, a zero query zero scores.
TEST(CachedAttention, Int8ScoresAreTheSameOnEveryPath) {
  std::mt19937 rng(21);
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (int64_t d : {64, 16, 48, 8, 12, 528}) {
    const int64_t rows = 37, rb = static_cast<int64_t>(CacheRowBytes(CacheElement::kInt8, d));
    std::vector<unsigned char> cache(static_cast<size_t>(rows * rb));
    std::vector<float> x(static_cast<size_t>(d)), q(static_cast<size_t>(d));
    const AttentionRows best = AttentionRowsFor(CacheElement::kInt8, d, RowKernels::kBest);
    const AttentionRows scalar = AttentionRowsFor(CacheElement::kInt8, d, RowKernels::kScalar);
    for (int64_t j = 0; j < rows; ++j) {
      for (float& v : x) v = n(rng) * 100.0f;
      scalar.store(x.data(), cache.data() + j * rb, d);
    }
    for (float& v : q) v = n(rng);
    std::vector<float> a(rows), b(rows);
    best.dots(q.data(), cache.data(), rows, d, 0.3f, a.data());
    scalar.dots(q.data(), cache.data(), rows, d, 0.3f, b.data());
    EXPECT_EQ(a, b) << "head_dim " << d;
    q[1] = std::nanf("");
    best.dots(q.data(), cache.data(), rows, d, 0.3f, a.data());
    for (float v : a) EXPECT_TRUE(std::isnan(v));
    std::fill(q.begin(), q.end(), 0.0f);
    best.dots(q.data(), cache.data(), rows, d, 0.3f, a.data());
    for (float v : a) EXPECT_EQ(v, 0.0f);
  }
}

// The widest rows (512-bit where the CPU has AVX-512) give the 256-bit rows' bits: the weighted
// sums lane for lane in the same order, the float dot products with the same two accumulators, the
// int8 ones exact. Odd row counts take the float dot's one-row tail; head sizes that are not a
// multiple of 16 (or 32 for int8 scores) fall back to the 256-bit rows. (Equal by construction on
// a CPU without AVX-512.)
TEST(CachedAttention, WidestRowsGiveTheAvx2RowsBits) {
  std::mt19937 rng(5);
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (CacheElement e : {CacheElement::kFloat32, CacheElement::kFloat16, CacheElement::kInt8})
    for (int64_t d : {64, 16, 48, 96, 128})
      for (int64_t rows : {1, 2, 7, 37}) {
        const int64_t rb = static_cast<int64_t>(CacheRowBytes(e, d));
        const AttentionRows best = AttentionRowsFor(e, d, RowKernels::kBest);
        const AttentionRows avx2 = AttentionRowsFor(e, d, RowKernels::kAvx2);
        std::vector<unsigned char> cache(static_cast<size_t>(rows * rb));
        std::vector<float> x(static_cast<size_t>(d)), q(static_cast<size_t>(d)), w(static_cast<size_t>(rows));
        for (int64_t j = 0; j < rows; ++j) {
          for (float& v : x) v = n(rng) * 3.0f;
          avx2.store(x.data(), cache.data() + j * rb, d);
        }
        for (float& v : q) v = n(rng);
        for (float& v : w) v = std::fabs(n(rng));
        std::vector<float> a(static_cast<size_t>(rows)), b(static_cast<size_t>(rows));
        best.dots(q.data(), cache.data(), rows, d, 0.125f, a.data());
        avx2.dots(q.data(), cache.data(), rows, d, 0.125f, b.data());
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * 4), 0)
            << "dots, head_dim " << d << ", " << rows << " rows";
        std::vector<float> sa(static_cast<size_t>(d), 0.5f), sb(static_cast<size_t>(d), 0.5f);
        best.weighted_sum(w.data(), cache.data(), rows, d, 0.7f, sa.data());
        avx2.weighted_sum(w.data(), cache.data(), rows, d, 0.7f, sb.data());
        EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * 4), 0)
            << "weighted sum, head_dim " << d << ", " << rows << " rows";
      }
}

// Several queries over the same rows (the candidates of one mesh on its cross K/V): every query's
// scores and weighted sum are the bits of that query alone, for block-sized, shorter and ragged
// row counts and more queries than one pass holds. On a CPU with AVX-512 VNNI the float32 and
// float16 rows of head size 64 take the many-query rows (checked, so this test exercises them).
TEST(CachedAttention, ManyQueriesGetEachQuerysOwnBits) {
  std::mt19937 rng(9);
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (CacheElement e : {CacheElement::kFloat32, CacheElement::kFloat16, CacheElement::kInt8})
    for (int64_t d : {64, 16, 96}) {
      const AttentionRows best = AttentionRowsFor(e, d, RowKernels::kBest);
#ifdef SILK_KERNELS_X86
      if (CpuHasAvx512Vnni() && e != CacheElement::kInt8 && d == 64) {
        EXPECT_NE(best.dots_many, nullptr);
        EXPECT_NE(best.weighted_sum_many, nullptr);
      }
#endif
      for (int64_t rows : {1, 2, 15, 16, 17, 33, 261})
        for (int64_t queries : {1, 3, 8, 11}) {
          const int64_t rb = static_cast<int64_t>(CacheRowBytes(e, d));
          std::vector<unsigned char> cache(static_cast<size_t>(rows * rb));
          std::vector<float> x(static_cast<size_t>(d));
          for (int64_t j = 0; j < rows; ++j) {
            for (float& v : x) v = n(rng) * 3.0f;
            best.store(x.data(), cache.data() + j * rb, d);
          }
          std::vector<std::vector<float>> q, w, many_scores, many_sums, one_sums;
          std::vector<float> factor;
          for (int64_t i = 0; i < queries; ++i) {
            q.emplace_back(static_cast<size_t>(d)), w.emplace_back(static_cast<size_t>(rows));
            for (float& v : q.back()) v = n(rng);
            for (float& v : w.back()) v = std::fabs(n(rng));
            many_scores.emplace_back(static_cast<size_t>(rows), NAN);
            many_sums.emplace_back(static_cast<size_t>(d), 0.25f * static_cast<float>(i));
            factor.push_back(0.5f + static_cast<float>(i));
          }
          one_sums = many_sums;
          std::vector<const float*> qp, wp;
          std::vector<float*> sp, op;
          for (int64_t i = 0; i < queries; ++i)
            qp.push_back(q[i].data()), wp.push_back(w[i].data()), sp.push_back(many_scores[i].data()),
                op.push_back(many_sums[i].data());
          best.DotsOfMany(qp.data(), queries, cache.data(), rows, d, 0.125f, sp.data());
          best.WeightedSumsOfMany(wp.data(), queries, cache.data(), rows, d, factor.data(), op.data());
          for (int64_t i = 0; i < queries; ++i) {
            std::vector<float> scores(static_cast<size_t>(rows));
            best.dots(q[i].data(), cache.data(), rows, d, 0.125f, scores.data());
            best.weighted_sum(w[i].data(), cache.data(), rows, d, factor[i], one_sums[i].data());
            const std::string where = "element " + std::to_string(int(e)) + ", head_dim " + std::to_string(d) + ", " +
                                      std::to_string(rows) + " rows, query " + std::to_string(i) + " of " +
                                      std::to_string(queries);
            EXPECT_EQ(std::memcmp(scores.data(), many_scores[i].data(), scores.size() * 4), 0) << "dots, " << where;
            EXPECT_EQ(std::memcmp(one_sums[i].data(), many_sums[i].data(), one_sums[i].size() * 4), 0)
                << "weighted sum, " << where;
          }
        }
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
  std::vector<float> xs = {0.0f,
                           -0.0f,
                           1.0f,
                           1.0f + 1.0f / 2048,
                           1.0f + 3.0f / 2048,
                           65504.0f,
                           65519.0f,
                           65520.0f,
                           -70000.0f,
                           6.0e-8f,
                           3.0e-8f,
                           2.9e-8f,
                           1.0e-5f,
                           -6.1e-5f,
                           6.103515625e-05f,
                           std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::quiet_NaN()};
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
      if (std::isnan(xs[i]))
        EXPECT_TRUE(Ort::Float16_t::FromBits(got[i]).IsNaN());
      else
        ASSERT_EQ(got[i], want) << "x = " << xs[i] << (k == RowKernels::kBest ? " (vectorized)" : " (scalar)");
    }
  }
}

// int8 rows: ties to even, clamping, a zero row (scale 0), against the contract's formula.
TEST(CachedAttention, Int8RowsQuantizeByTheContract) {
  const int64_t d = 16;
  std::vector<std::vector<float>> rows = {
      std::vector<float>(d, 0.0f),                                                     // all zeros: scale 0
      {127, 2.5f, -3.5f, 0.5f, -0.5f, 1.5f, 126.5f, -127, 0, 64, -64, 3, 4, 5, 6, 7},  // scale 1: exact ties
      {1e-30f, -2e-30f, 5e-31f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1e-31f},           // tiny scale
  };
  std::mt19937 rng(9);
  std::normal_distribution<float> n(0.0f, 3.0f);
  for (int r = 0; r < 200; ++r) {
    rows.emplace_back(d);
    for (float& x : rows.back()) x = n(rng);
  }
  for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) {
    const AttentionRows prim = AttentionRowsFor(CacheElement::kInt8, d, k);
    for (const std::vector<float>& x : rows) {
      std::vector<unsigned char> got(d + 4, 0xA5);
      prim.store(x.data(), got.data(), d);
      ASSERT_EQ(got, Int8Row(x.data(), d)) << "x[1] = " << x[1] << (k == RowKernels::kBest ? " (vectorized)" : "");
    }
  }
  std::vector<unsigned char> ties(d + 4);
  AttentionRowsFor(CacheElement::kInt8, d, RowKernels::kBest).store(rows[1].data(), ties.data(), d);
  const int8_t want[] = {127, 2, -4, 0, 0, 2, 126, -127};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(static_cast<int8_t>(ties[i]), want[i]) << "index " << i;
}

// A zero key and value row (scale 0) attends like any other row: finite, weight of score 0.
TEST(CachedAttention, Int8ZeroRowsAttendFinitely) {
  AttentionShape s{2, 1, 8, 1, 3, 4, 1.0f};
  for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) {
    Case c = MakeCase(s, CacheElement::kInt8, 13);
    std::fill(c.k.begin(), c.k.end(), 0.0f);
    std::fill(c.v.begin(), c.v.end(), 0.0f);
    CachedAttention(s, CacheElement::kInt8, c.buffers(CacheElement::kInt8), Serial, nullptr, k);
    const size_t rb = CacheRowBytes(CacheElement::kInt8, 8);
    EXPECT_EQ(std::vector<unsigned char>(c.key_cache.begin() + 3 * rb, c.key_cache.begin() + 4 * rb),
              std::vector<unsigned char>(rb, 0));
    const std::vector<double> ref = Reference(c, CacheElement::kInt8);
    for (size_t i = 0; i < ref.size(); ++i) {
      ASSERT_TRUE(std::isfinite(c.out[i]));
      EXPECT_NEAR(c.out[i], ref[i], 2e-5);
    }
  }
}

TEST(CachedAttention, RowBytes) {
  EXPECT_EQ(CacheRowBytes(CacheElement::kFloat32, 64), 256u);
  EXPECT_EQ(CacheRowBytes(CacheElement::kFloat16, 64), 128u);
  EXPECT_EQ(CacheRowBytes(CacheElement::kInt8, 64), 68u);
  EXPECT_EQ(CacheRowElements(CacheElement::kInt8, 64), 68);
}

}  // namespace
}  // namespace silk
