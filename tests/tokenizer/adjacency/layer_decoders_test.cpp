// SPDX-License-Identifier: MIT
// Self-layer and between-layer decoding against hand-derived cases of the spec's worked
// examples (§13.1 cube, §13.2 torus_12x8 layer 4) plus the validation errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "tokenizer/face_compare.h"
#include "support/test_paths.h"
#include "tokenizer/adjacency/between_layer_decoder.h"
#include "tokenizer/adjacency/self_layer_decoder.h"
#include "tokenizer/tokenizer.h"

namespace silk {
namespace {

using Pairs = std::vector<std::pair<int32_t, int32_t>>;

StreamLayer LayerOf(const std::vector<int32_t>& windows, const std::vector<std::vector<BetweenToken>>& between) {
  StreamLayer l;
  for (size_t i = 0; i < windows.size(); ++i) {
    StreamVertex v;
    v.window = windows[i];
    v.between = between[i];
    l.vertices.push_back(v);
  }
  return l;
}

TEST(SelfLayerDecoder, CubeLayerOneIsASixRing) {
  // §13.1: six vertices, each w = 17 (d = 1 and d = 5).
  auto p = DecodeSelfLayer(LayerOf(std::vector<int32_t>(6, 17), std::vector<std::vector<BetweenToken>>(6)));
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(*p, (Pairs{{0, 1}, {0, 5}, {1, 2}, {2, 3}, {3, 4}, {4, 5}}));
}

TEST(BetweenLayerDecoder, CubeLayerTwoSeesAllOfLayerOne) {
  // §13.1: layer 2 = one vertex, token 459 (s = 0, case 0 = 11111) over 6 previous vertices.
  auto p = DecodeBetweenLayer(LayerOf({0}, {{BetweenToken{0, 0}}}), 6);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(*p, (Pairs{{0, 0}, {0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}}));
  auto one = DecodeBetweenLayer(LayerOf({17, 17}, {{BetweenToken{0, 1}}, {BetweenToken{0, 1}}}), 1);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(*one, (Pairs{{0, 0}, {1, 0}}));
}

// §13.2: torus_12x8 layer 4 (23 vertices over 18), read from the golden token file.
class TorusLayerFour : public ::testing::Test {
 protected:
  void SetUp() override {
    auto ids = testing::ReadIds(testing::SharedPath("spec/golden/torus_12x8.tokens.txt"));
    auto s = ReadTokenStream(ids);
    ASSERT_TRUE(s.ok());
    layer = s->components[0].layers[4];
    prev = static_cast<int32_t>(s->components[0].layers[3].vertices.size());
  }
  std::set<int32_t> SelfNeighbours(const Pairs& p, int32_t i) {
    std::set<int32_t> n;
    for (auto [a, b] : p) {
      if (a == i) n.insert(b);
      if (b == i) n.insert(a);
    }
    return n;
  }
  std::set<int32_t> PrevColumns(const Pairs& p, int32_t i) {
    std::set<int32_t> n;
    for (auto [a, b] : p)
      if (a == i) n.insert(b);
    return n;
  }
  StreamLayer layer;
  int32_t prev = 0;
};

TEST_F(TorusLayerFour, SelfLayerNeighboursIncludingExtraTokens) {
  ASSERT_EQ(layer.vertices.size(), 23u);
  EXPECT_EQ(layer.vertices[6].extras, (std::vector<int32_t>{12}));
  EXPECT_EQ(layer.vertices[18].window, 0);
  auto p = DecodeSelfLayer(layer);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(SelfNeighbours(*p, 0), (std::set<int32_t>{1, 22}));
  EXPECT_EQ(SelfNeighbours(*p, 6), (std::set<int32_t>{5, 7, 19}));
  EXPECT_EQ(SelfNeighbours(*p, 7), (std::set<int32_t>{6, 8, 18, 19}));
  EXPECT_EQ(SelfNeighbours(*p, 8), (std::set<int32_t>{7, 9, 18}));
  EXPECT_EQ(SelfNeighbours(*p, 18), (std::set<int32_t>{7, 8, 17}));
  EXPECT_EQ(SelfNeighbours(*p, 19), (std::set<int32_t>{6, 7, 20}));
  EXPECT_EQ(SelfNeighbours(*p, 22), (std::set<int32_t>{0, 21}));
  // 22 ring edges (18-19 missing) + 6-19, 7-18, 7-19, 8-18.
  EXPECT_EQ(p->size(), 26u);
}

TEST_F(TorusLayerFour, BetweenLayerColumnsIncludingMultiTokenRows) {
  ASSERT_EQ(prev, 18);
  auto p = DecodeBetweenLayer(layer, prev);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(PrevColumns(*p, 0), (std::set<int32_t>{0, 17}));
  EXPECT_EQ(PrevColumns(*p, 1), (std::set<int32_t>{0, 1}));
  EXPECT_EQ(PrevColumns(*p, 3), (std::set<int32_t>{2}));
  EXPECT_EQ(PrevColumns(*p, 7), (std::set<int32_t>{5, 14}));
  EXPECT_EQ(PrevColumns(*p, 18), (std::set<int32_t>{13, 14}));
  EXPECT_EQ(PrevColumns(*p, 22), (std::set<int32_t>{17}));
}

TEST(SelfLayerDecoder, RejectsWhatTheEncoderNeverEmits) {
  // Window bit 2 (d = 3) in a layer of 3 vertices.
  auto a = DecodeSelfLayer(LayerOf({4, 0, 0}, std::vector<std::vector<BetweenToken>>(3)));
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("points past the end"), std::string::npos);
  // Extra value 9 in a layer of 18 (max N-10 = 8).
  StreamLayer l = LayerOf(std::vector<int32_t>(18, 0), std::vector<std::vector<BetweenToken>>(18));
  l.vertices[3].extras = {9};
  auto b = DecodeSelfLayer(l);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("outside [8, N-10]"), std::string::npos);
  l.vertices[3].extras = {8};
  auto c = DecodeSelfLayer(l);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(*c, (Pairs{{3, 12}}));
}

TEST(BetweenLayerDecoder, RejectsSegmentsPastThePreviousLayer) {
  // Case 0 (11111) from column 0 needs 6 previous vertices.
  auto a = DecodeBetweenLayer(LayerOf({0}, {{BetweenToken{0, 0}}}), 5);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("reaches past the previous layer"), std::string::npos);
  auto b = DecodeBetweenLayer(LayerOf({0}, {{}}), 5);
  ASSERT_FALSE(b.ok());
  auto c = DecodeBetweenLayer(LayerOf({0}, {{BetweenToken{0, 1}, BetweenToken{3, 1}}}), 9);
  ASSERT_FALSE(c.ok());  // continuation must start at >= 6
  // Truncating case 12 (10100, last one at 3) allows a continuation at 0 + 3 + 2 = 5.
  auto d = DecodeBetweenLayer(LayerOf({0}, {{BetweenToken{0, 12}, BetweenToken{5, 1}}}), 9);
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(*d, (Pairs{{0, 0}, {0, 1}, {0, 3}, {0, 5}}));
}

}  // namespace
}  // namespace silk
