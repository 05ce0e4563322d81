// SPDX-License-Identifier: MIT
// CachedAttention and CrossAttention over a batch of rows (decoder contract v4): rows at different
// depths taking different counts of new positions (a forced run of several beside single steps),
// cross K/V shared by the rows of one mesh or each row's own. Every row's outputs and cache bytes
// must be bit for bit those of the same row run alone; padding positions output zeros and store
// nothing; inputs that do not fit together are refused with a message naming the problem.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "kernels/attention/attention_batch.h"
#include "kernels/attention/attention_rows.h"
#include "kernels/attention/cached_attention.h"
#include "kernels/attention/cross_attention.h"

namespace silk {
namespace {

void Backwards(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = count; i-- > 0;) work(state, i);  // tasks must not depend on order
}

std::vector<float> Normal(size_t n, std::mt19937& rng, float sigma = 1.0f) {
  std::normal_distribution<float> normal(0.0f, sigma);
  std::vector<float> v(n);
  for (float& x : v) x = normal(rng);
  return v;
}

struct Batch {
  std::vector<int64_t> past, chunk;  // per row
};

// One batched call against each row alone, for every cache element type.
void ExpectRowsAsAlone(AttentionShape s, const Batch& rows, CacheElement e) {
  std::mt19937 rng(static_cast<uint32_t>(s.heads * 7 + s.batch));
  const int64_t R = s.batch, T = s.chunk, D = s.head_dim, qw = s.heads * D, kw = s.kv_heads * D;
  const size_t rb = CacheRowBytes(e, D), block = static_cast<size_t>(s.kv_heads * s.capacity) * rb;
  const std::vector<float> q = Normal(static_cast<size_t>(R * T * qw), rng, 0.3f);
  const std::vector<float> k = Normal(static_cast<size_t>(R * T * kw), rng), v = Normal(k.size(), rng);
  std::vector<unsigned char> key(block * R, 0xA5), value(block * R, 0xA5);  // sentinel: a stray write shows
  const AttentionRows store = AttentionRowsFor(e, D, RowKernels::kScalar);
  for (auto* cache : {&key, &value})
    for (int64_t r = 0; r < R; ++r)
      for (int64_t h = 0; h < s.kv_heads; ++h)
        for (int64_t p = 0; p < rows.past[r]; ++p)
          store.store(Normal(static_cast<size_t>(D), rng).data(),
                      cache->data() + r * block + static_cast<size_t>(h * s.capacity + p) * rb, D);
  const std::vector<unsigned char> key0 = key, value0 = value;
  s.row_past = rows.past.data(), s.row_chunk = rows.chunk.data();
  std::vector<float> out(static_cast<size_t>(R * T * qw), NAN);
  CachedAttention(s, e, {q.data(), k.data(), v.data(), key.data(), value.data(), out.data()}, Backwards, nullptr);
  for (int64_t r = 0; r < R; ++r) {
    AttentionShape one = s;
    one.batch = 1, one.row_past = nullptr, one.row_chunk = nullptr, one.past = rows.past[r], one.chunk = rows.chunk[r];
    std::vector<unsigned char> k1(key0.begin() + r * block, key0.begin() + (r + 1) * block);
    std::vector<unsigned char> v1(value0.begin() + r * block, value0.begin() + (r + 1) * block);
    std::vector<float> o1(static_cast<size_t>(one.chunk * qw), NAN);
    CachedAttention(
        one, e, {q.data() + r * T * qw, k.data() + r * T * kw, v.data() + r * T * kw, k1.data(), v1.data(), o1.data()},
        Backwards, nullptr);
    const std::string where = "row " + std::to_string(r) + " (past " + std::to_string(rows.past[r]) + ", " +
                              std::to_string(rows.chunk[r]) + " new), element " + std::to_string(int(e));
    EXPECT_EQ(std::memcmp(out.data() + r * T * qw, o1.data(), o1.size() * 4), 0) << where << ": output differs";
    for (int64_t i = one.chunk * qw; i < T * qw; ++i) ASSERT_EQ(out[r * T * qw + i], 0.0f) << where << ": padding";
    EXPECT_EQ(std::memcmp(key.data() + r * block, k1.data(), block), 0) << where << ": key cache differs";
    EXPECT_EQ(std::memcmp(value.data() + r * block, v1.data(), block), 0) << where << ": value cache differs";
  }
}

constexpr CacheElement kElements[] = {CacheElement::kFloat32, CacheElement::kFloat16, CacheElement::kInt8};

TEST(AttentionBatch, CachedAttentionRowsAreBitIdenticalToEachRowAlone) {
  for (CacheElement e : kElements) {
    // Rows at depths 0 .. 300, single steps beside a forced run of 5 (the chunk) and one of 3.
    ExpectRowsAsAlone({4, 2, 64, 5, 0, 310, 0.125f, 4}, {{0, 37, 300, 5}, {5, 1, 3, 1}}, e);
    // The release network's heads and scale, eight rows each taking one position.
    ExpectRowsAsAlone({16, 16, 64, 1, 0, 700, 10.0f, 8}, {{0, 1, 2, 100, 257, 511, 600, 699}, {1, 1, 1, 1, 1, 1, 1, 1}},
                      e);
    // A head size without the vectorized rows; every row a run of 2.
    ExpectRowsAsAlone({2, 1, 12, 2, 0, 9, 0.3f, 3}, {{0, 4, 7}, {2, 2, 2}}, e);
  }
}

TEST(AttentionBatch, CrossAttentionRowsAreBitIdenticalToEachRowAlone) {
  const int64_t R = 4, H = 4, T = 2, M = 33, D = 64;
  std::mt19937 rng(17);
  const std::vector<float> q = Normal(static_cast<size_t>(R * H * T * D), rng);
  const std::vector<float> key = Normal(static_cast<size_t>(R * H * M * D), rng), value = Normal(key.size(), rng);
  std::vector<uint16_t> key16(key.size()), value16(value.size());
  AttentionRowsFor(CacheElement::kFloat16, static_cast<int64_t>(key.size()), RowKernels::kScalar)
      .store(key.data(), key16.data(), static_cast<int64_t>(key.size()));
  AttentionRowsFor(CacheElement::kFloat16, static_cast<int64_t>(value.size()), RowKernels::kScalar)
      .store(value.data(), value16.data(), static_cast<int64_t>(value.size()));
  struct Sources {
    std::vector<int32_t> of_row;  // empty: row b reads source b
    const char* what;
  };
  for (CacheElement e : {CacheElement::kFloat32, CacheElement::kFloat16})
    for (const Sources& src : {Sources{{0, 0, 0, 0}, "shared by every row"}, Sources{{}, "each row its own"},
                               Sources{{1, 0, 1, 3}, "rows of two meshes"}}) {
      const void* k = e == CacheElement::kFloat16 ? static_cast<const void*>(key16.data()) : key.data();
      const void* v = e == CacheElement::kFloat16 ? static_cast<const void*>(value16.data()) : value.data();
      CrossAttentionShape s{H, T, M, D, 0.7f};
      s.batch = R, s.source = src.of_row.empty() ? nullptr : src.of_row.data();
      std::vector<float> out(q.size(), NAN);
      CrossAttention(s, e, q.data(), k, v, out.data(), Backwards, nullptr);
      const size_t block = static_cast<size_t>(H * M) * CacheRowBytes(e, D);
      for (int64_t b = 0; b < R; ++b) {
        const int64_t from = src.of_row.empty() ? b : src.of_row[b];
        std::vector<float> one(static_cast<size_t>(H * T * D), NAN);
        CrossAttention({H, T, M, D, 0.7f}, e, q.data() + b * H * T * D, static_cast<const char*>(k) + from * block,
                       static_cast<const char*>(v) + from * block, one.data(), Backwards, nullptr);
        EXPECT_EQ(std::memcmp(out.data() + b * H * T * D, one.data(), one.size() * 4), 0)
            << src.what << ": row " << b << " differs from that row alone (element " << int(e) << ")";
      }
    }
}

// Plain inputs of a CachedAttention node with R rows of T positions, heads 4 / kv heads 2, head 8.
struct Inputs {
  AttentionInputs in;
  std::vector<int32_t> seqlens, fresh;
  Inputs(int64_t R, int64_t T, int64_t capacity, std::vector<int32_t> seq, std::vector<int32_t> news, int32_t total)
      : seqlens(std::move(seq)), fresh(std::move(news)) {
    in.heads = 4, in.kv_heads = 2, in.element = CacheElement::kFloat16;
    in.query = {R, T, 32}, in.key = in.value = {R, T, 16}, in.past_key = in.past_value = {R, 2, capacity, 8};
    in.seqlens_k = {static_cast<int64_t>(seqlens.size())}, in.total = {};
    in.seqlens = seqlens.data(), in.total_length = total;
    in.has_new_positions = !fresh.empty();
    in.new_positions_shape = {static_cast<int64_t>(fresh.size())}, in.new_positions = fresh.data();
  }
};

std::string Problem(const Inputs& x) {
  AttentionBatch b;
  return b.Resolve(x.in);
}

TEST(AttentionBatch, ResolvesEachRowsPastAndNewPositions) {
  Inputs x(3, 4, 50, {4, 40, 12}, {1, 4, 3}, 41);
  AttentionBatch b;
  ASSERT_EQ(b.Resolve(x.in), "");
  const AttentionShape& s = b.shape();
  EXPECT_EQ(s.batch, 3);
  EXPECT_EQ(s.chunk, 4);
  EXPECT_EQ(std::vector<int64_t>(s.row_past, s.row_past + 3), (std::vector<int64_t>{4, 37, 10}));
  EXPECT_EQ(std::vector<int64_t>(s.row_chunk, s.row_chunk + 3), (std::vector<int64_t>{1, 4, 3}));
  EXPECT_EQ(b.total(), 41);
  // Contract v3: one row, no new_positions: every position of the chunk is new.
  Inputs v3(1, 2, 9, {6}, {}, 7);
  ASSERT_EQ(b.Resolve(v3.in), "");
  EXPECT_EQ(b.shape().row_past[0], 5);
  EXPECT_EQ(b.shape().row_chunk[0], 2);
}

TEST(AttentionBatch, InputsThatDoNotFitTogetherAreRefusedWithAMessage) {
  struct Bad {
    Inputs x;
    const char* message;
  };
  Inputs short_cache(2, 1, 8, {3, 4}, {1, 1}, 5);
  short_cache.in.past_key = short_cache.in.past_value = {1, 2, 8, 8};
  Inputs bad_new_shape(2, 1, 8, {3, 4}, {1, 1, 1}, 5);
  Inputs bad_query(2, 1, 8, {3, 4}, {}, 5);
  bad_query.in.query = {2, 1, 30};
  const Bad cases[] = {
      {Inputs(2, 1, 8, {3}, {}, 4), "seqlens_k must have shape [2] (one per row)"},
      {Inputs(2, 2, 8, {3, 4}, {1, 0}, 5), "row 1: seqlens_k 4, 0 new positions (of 2) and a cache of 8 do not fit"},
      {Inputs(2, 2, 8, {3, 4}, {1, 3}, 5), "row 1: seqlens_k 4, 3 new positions (of 2)"},
      {Inputs(2, 1, 8, {3, 40}, {}, 41), "row 1: seqlens_k 40, 1 new positions (of 1) and a cache of 8 do not fit"},
      {Inputs(2, 1, 8, {3, -5}, {}, 4), "row 1: seqlens_k -5"},
      {Inputs(2, 1, 8, {3, 4}, {}, 9), "total_sequence_length 9"},
      {short_cache,
       "past_key/past_value have shapes [1, 2, 8, 8], [1, 2, 8, 8], expected [R, kv_heads, capacity, "
       "head_dim] = [2, 2, C, 8] (one cache block per row of the batch)"},
      {bad_new_shape, "new_positions has shape [3], expected [2] (one per row)"},
      {bad_query, "query has shape [2, 1, 30]"},
  };
  for (const Bad& c : cases) {
    const std::string got = Problem(c.x);
    EXPECT_NE(got.find(c.message), std::string::npos) << "got: " << got << "\nwanted: " << c.message;
  }
}

TEST(AttentionBatch, CrossAttentionSourcesThatDoNotFitAreRefusedWithAMessage) {
  CrossAttentionShape s;
  std::vector<int32_t> sources;
  const std::vector<int32_t> src = {0, 2};
  auto problem = [&](std::vector<int64_t> key, bool has_source, std::vector<int64_t> source_shape) {
    return ResolveCrossAttention({{2, 4, 1, 8}, key, key, source_shape, has_source, src.data()}, 1.0f, &s, &sources);
  };
  EXPECT_EQ(problem({1, 4, 9, 8}, false, {}), "");  // shared by both rows
  EXPECT_EQ(sources, (std::vector<int32_t>{0, 0}));
  EXPECT_EQ(problem({2, 4, 9, 8}, false, {}), "");  // each row its own
  EXPECT_EQ(sources, (std::vector<int32_t>{0, 1}));
  EXPECT_EQ(problem({3, 4, 9, 8}, true, {2}), "");
  EXPECT_EQ(sources, src);
  EXPECT_NE(problem({3, 4, 9, 8}, false, {}).find("S = R or 1 (or a source input)"), std::string::npos);
  EXPECT_EQ(problem({2, 4, 9, 8}, true, {2}), "source[1] is 2, not one of the 2 key/value sources");
  EXPECT_EQ(problem({3, 4, 9, 8}, true, {1, 2}), "source has shape [1, 2], expected [2] (one per row)");
  EXPECT_NE(problem({3, 5, 9, 8}, true, {2}).find("do not fit"), std::string::npos);
}

}  // namespace
}  // namespace silk
