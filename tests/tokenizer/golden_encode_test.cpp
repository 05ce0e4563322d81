// SPDX-License-Identifier: MIT
// The 14 official goldens (shared/spec/golden): our encoder must reproduce the official
// token ids exactly.
#include <gtest/gtest.h>

#include "mesh/normalize.h"
#include "support/golden_files.h"
#include "support/test_paths.h"
#include "tokenizer/tokenizer.h"

namespace silk {
namespace {

class GoldenEncode : public ::testing::TestWithParam<std::string> {};

TEST_P(GoldenEncode, TokensMatchOfficial) {
  const std::string name = GetParam();
  IoMesh raw;
  ASSERT_TRUE(testing::ReadPlainObj(testing::SharedPath("spec/golden/" + name + ".obj"), &raw));
  std::vector<int32_t> expected;
  ASSERT_TRUE(testing::ReadTokenFile(testing::SharedPath("spec/golden/" + name + ".tokens.txt"), &expected));
  auto norm = NormalizeMesh(raw);
  ASSERT_TRUE(norm.ok()) << norm.status().ToString();
  auto enc = EncodeMesh(*norm);
  ASSERT_TRUE(enc.ok()) << enc.status().ToString();
  ASSERT_EQ(enc->tokens.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(enc->tokens[i], expected[i]) << "at token " << i;
  EXPECT_EQ(enc->stats.tokens, static_cast<int64_t>(expected.size()));
}

INSTANTIATE_TEST_SUITE_P(Official, GoldenEncode, ::testing::ValuesIn(testing::GoldenNames()),
                         [](const auto& info) { return info.param; });

TEST(GoldenEncode, AllFourteenPresent) { EXPECT_EQ(testing::GoldenNames().size(), 14u); }

}  // namespace
}  // namespace silk
