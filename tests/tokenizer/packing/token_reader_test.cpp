// SPDX-License-Identifier: MIT
// The token reader accepts exactly the encoder's grammar (token_format.md §8.3, §11): every golden
// parses, and each malformed variant is rejected with the position and reason of the fault.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tokenizer/face_compare.h"
#include "support/test_paths.h"
#include "tokenizer/packing/token_reader.h"
#include "tokenizer/tokenizer.h"

namespace silk {
namespace {

// Tetrahedron golden: C root U three layer-1 vertices (K O S B) E.
const std::vector<int32_t> kTetra = {0,    5659, 6990, 1,    5659 + 448, 9294, 206, 460, 5666,
                                     6999, 206,  460,  5715, 7134,       206,  460, 2};

TEST(TokenReader, ParsesTetrahedron) {
  auto s = ReadTokenStream(kTetra);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  ASSERT_EQ(s->components.size(), 1u);
  ASSERT_EQ(s->components[0].layers.size(), 2u);
  EXPECT_EQ(s->components[0].layers[1].vertices.size(), 3u);
  EXPECT_EQ(s->components[0].layers[1].vertices[0].window, 3);
  EXPECT_EQ(s->components[0].layers[1].vertices[0].between[0], (BetweenToken{0, 1}));
  EXPECT_EQ(s->components[0].layers[0].vertices[0].pos, (QVec{3, 3, 3}));
}

TEST(TokenReader, ParsesEveryGolden) {
  for (const char* name :
       {"tetrahedron", "cube", "octahedron", "torus", "grid", "two_components", "nonmanifold_book", "cylinder_capped",
        "open_tube", "cube_one_flipped", "dirty_cube", "icosphere2", "torus_24x6", "torus_12x8"}) {
    auto ids = testing::ReadIds(testing::SharedPath(std::string("spec/golden/") + name + ".tokens.txt"));
    auto s = ReadTokenStream(ids);
    EXPECT_TRUE(s.ok()) << name << ": " << s.status().ToString();
  }
}

struct BadCase {
  const char* what;
  std::vector<int32_t> ids;
  const char* expected;  // substring of the message
};

std::vector<int32_t> Edit(std::vector<int32_t> v, size_t pos, int32_t id) {
  v[pos] = id;
  return v;
}
std::vector<int32_t> Insert(std::vector<int32_t> v, size_t pos, int32_t id) {
  v.insert(v.begin() + static_cast<long>(pos), id);
  return v;
}

class TokenReaderRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(TokenReaderRejects, WithPositionedMessage) {
  auto s = ReadTokenStream(GetParam().ids);
  ASSERT_FALSE(s.ok()) << GetParam().what;
  EXPECT_EQ(s.status().code(), StatusCode::kParseError);
  EXPECT_NE(s.status().message().find(GetParam().expected), std::string::npos)
      << GetParam().what << ": " << s.status().message();
}

INSTANTIATE_TEST_SUITE_P(
    Table, TokenReaderRejects,
    ::testing::Values(
        BadCase{"empty", {}, "empty token stream"},
        BadCase{"starts with U", {1}, "token 0 (id 1): layer end U where C"},
        BadCase{"negative id", Edit(kTetra, 5, -1), "token 5 (id -1): not a token id"},
        BadCase{"id past vocabulary", Edit(kTetra, 9, 10267), "token 9 (id 10267): not a token id"},
        BadCase{"B before S", Edit(kTetra, 6, 460),
                "token 6 (id 460): between-layer token before the vertex's S token"},
        BadCase{"X before S", Edit(kTetra, 6, 11), "token 6 (id 11): self-layer extra token before the vertex's S"},
        BadCase{"E after root", Edit(kTetra, 3, 2), "token 3 (id 2): component end E where U"},
        BadCase{"second root vertex", Edit(kTetra, 3, 5659), "token 3 (id 5659): block token K where U"},
        BadCase{"O without K", Edit(kTetra, 4, 6171),
                "token 4 (id 6171): offset token O where a vertex's block token K"},
        BadCase{"layer 1 B other than 460", Edit(kTetra, 7, 459),
                "token 7 (id 459): a layer-1 vertex's B token must be 460"},
        BadCase{"second B in layer 1", Insert(kTetra, 8, 460), "token 8 (id 460): a layer-1 vertex has exactly one B"},
        BadCase{"vertex without B", Edit(kTetra, 7, 5666), "token 7 (id 5666): block token K where an X or B token"},
        BadCase{"window bit past layer end", Edit(kTetra, 6, 203 + 4),
                "token 6 (id 207): window bits point past the end"},
        BadCase{"X value below 8", Insert(kTetra, 7, 3 + 7), "token 7 (id 10): self-layer extra value 7 is below 8"},
        BadCase{"X value past small layer", Insert(kTetra, 7, 3 + 8),
                "token 7 (id 11): self-layer extra value 8 is out of range"},
        BadCase{"X after B", Insert(kTetra, 8, 11),
                "token 8 (id 11): self-layer extra token after the vertex's B tokens"},
        BadCase{"two S", Insert(kTetra, 7, 206), "token 7 (id 206): second S token"},
        BadCase{"missing E", std::vector<int32_t>(kTetra.begin(), kTetra.end() - 1), "ends inside component 0"},
        BadCase{"garbage after E", Insert(kTetra, 17, 5659), "token 17 (id 5659): block token K where C or the end"},
        BadCase{"E right after U", Insert(kTetra, 16, 1),
                "token 17 (id 2): component end E where a vertex's block token K"},
        BadCase{"layer 1 of one vertex",
                {0, 5659, 6990, 1, 6107, 9294, 203, 460, 2},
                "token 8 (id 2): layer 1 has 1 vertex"},
        // Layer 2 of the tetrahedron-like stream: a B segment past a 3-vertex previous layer.
        BadCase{"B segment past previous layer",
                Insert(Insert(Insert(Insert(Insert(Edit(kTetra, 16, 1), 17, 5659), 18, 6171), 19, 203), 20,
                              459 + 26 * 0 + 5),
                       21, 2),
                "token 20 (id 464): between-layer segment (start 0, case 5) reaches past the previous layer of 3"},
        BadCase{"B continuation overlapping the window",
                Insert(Insert(Insert(Insert(Insert(Insert(Edit(kTetra, 16, 1), 17, 5659), 18, 6171), 19, 203), 20,
                                     459 + 26 * 0 + 1),
                              21, 459 + 26 * 2 + 1),
                       22, 2),
                "token 21 (id 512): between-layer token starts at column 2"}),
    [](const ::testing::TestParamInfo<BadCase>& info) {
      std::string n = info.param.what;
      for (char& c : n)
        if (!isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

TEST(TokenReader, RejectsOverlongInputWithoutParsing) {
  std::vector<int32_t> ids(static_cast<size_t>(kMaxReadTokens) + 1, 0);
  auto s = ReadTokenStream(ids);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), StatusCode::kLimitExceeded);
}

TEST(TokenReader, RejectsLayerOverTwoHundredVertices) {
  std::vector<int32_t> ids = {0, 5659, 6171, 1};
  for (int i = 0; i < 201; ++i) {
    ids.insert(ids.end(), {5659, 6171 + i, 203, 460});
  }
  ids.push_back(2);
  auto s = ReadTokenStream(ids);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("token 804 (id 5659): layer 1 would exceed 200 vertices"), std::string::npos)
      << s.status().message();
}

}  // namespace
}  // namespace silk
