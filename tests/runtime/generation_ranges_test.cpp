// SPDX-License-Identifier: MIT
// The generation settings' one range table (runtime/sampling/generation_ranges.h): each setting's
// ends accepted, the values just past them refused with a message naming the setting, the value
// and the range, and the C API's silk_param_range / silk_param_check reading the same table.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "runtime/sampling/generation_ranges.h"
#include "silk/silk.h"

namespace silk {
namespace {

TEST(GenerationRanges, EndsAcceptedAndPastThemRefusedWithTheRange) {
  struct Case {
    const char* name;
    double ok_lo, ok_hi, below, above;
    const char* message_above;
  };
  const Case cases[] = {
      {"temperature", 0, 100, -0.5, 150, "temperature 150 is not in [0, 100] (0 = greedy)"},
      {"top_k", 0, 10269, -1, 10270, "top_k 10270 is not in [0, 10269]"},
      {"top_p", 0, 1, -0.1, 1.5, "top_p 1.5 is not in [0, 1] (1 = off)"},
      {"top_p_temperature", 0, 100, -0.25, 101, "top_p_temperature 101 is not in [0, 100]"},
      {"max_tokens", 14, INT32_MAX, 13, -1, "max_tokens -1 is not 0 or at least 14"},
      {"max_faces", 0, INT32_MAX, -1, -2, "max_faces -2 is not at least 0 (0 = off)"},
      {"surface_tolerance", 0, 127, -1, 128, "surface_tolerance 128 is not in [0, 127]"},
      {"face_tolerance", 0.5, 64, 0.2, 65, "face_tolerance 65 is not in [0.5, 64] (cells of 128)"},
      {"candidates", 1, 64, 0, 65, "candidates 65 is not in [1, 64]"},
      {"rows", 1, 64, 0, 65, "rows 65 is not in [1, 64]"},
      {"point_count", 1, 1 << 20, -3, (1 << 20) + 1, "point_count 1048577 is not 0 or in [1, 1048576]"},
      {"threads", 0, 64, -1, 1e9, "threads 1000000000 is not in [0, "},
  };
  for (const Case& c : cases) {
    const auto r = FindSetting(c.name);
    ASSERT_TRUE(r) << c.name;
    EXPECT_TRUE(CheckSetting(*r, c.ok_lo).ok()) << c.name;
    EXPECT_TRUE(CheckSetting(*r, c.ok_hi).ok()) << c.name;
    for (double bad : {c.below, c.above, std::nan("")}) {
      const Status s = CheckSetting(*r, bad);
      ASSERT_FALSE(s.ok()) << c.name << " " << bad;
      EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
      EXPECT_EQ(s.message().rfind(std::string(c.name) + " ", 0), 0u) << s.message();
    }
    const std::string above = CheckSetting(*r, c.above).message();
    EXPECT_EQ(above.rfind(c.message_above, 0), 0u) << above;
  }
  EXPECT_FALSE(FindSetting("temprature"));
  EXPECT_FALSE(FindSetting(""));
}

TEST(GenerationRanges, ZeroIsValidOnlyWhereItMeansTheModelsOrOff) {
  EXPECT_TRUE(CheckSetting(ranges::kMaxTokens, 0).ok());
  EXPECT_TRUE(CheckSetting(ranges::kPointCount, 0).ok());
  EXPECT_FALSE(CheckSetting(ranges::kCandidates, 0).ok());
  EXPECT_FALSE(CheckSetting(ranges::kRows, 0).ok());
  EXPECT_FALSE(CheckSetting(ranges::kFaceTolerance, 0).ok());
  EXPECT_FALSE(CheckSetting(ranges::kMaxTokens, kMinMeshTokens - 1).ok());
  EXPECT_TRUE(CheckSetting(ranges::kMaxTokens, kMinMeshTokens).ok());
  EXPECT_FALSE(CheckSetting(ranges::kTemperature, std::numeric_limits<double>::infinity()).ok());
}

// The C API answers from the same table, with the same message.
TEST(GenerationRanges, CApiReadsTheSameTable) {
  double lo = -1, hi = -1;
  int32_t zero_too = -1;
  ASSERT_EQ(silk_param_range("temperature", &lo, &hi, &zero_too), SILK_OK) << silk_last_error();
  EXPECT_EQ(lo, ranges::kTemperature.lo);
  EXPECT_EQ(hi, ranges::kTemperature.hi);
  EXPECT_EQ(zero_too, 0);
  ASSERT_EQ(silk_param_range("max_tokens", &lo, nullptr, &zero_too), SILK_OK);
  EXPECT_EQ(lo, kMinMeshTokens);
  EXPECT_EQ(zero_too, 1);
  ASSERT_EQ(silk_param_range("threads", nullptr, &hi, nullptr), SILK_OK);
  EXPECT_EQ(hi, ranges::Threads().hi);
  EXPECT_EQ(silk_param_check("top_k", 50), SILK_OK);
  EXPECT_EQ(silk_param_check("temperature", 150), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(silk_last_error()), CheckSetting(ranges::kTemperature, 150).message());
  EXPECT_EQ(silk_param_check("temperature", SILK_MODEL_VALUE), SILK_ERR_INVALID_ARGUMENT);  // not a value
  EXPECT_EQ(silk_param_range("temprature", &lo, &hi, nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(silk_last_error()).find("'temprature' is not a generation setting"), std::string::npos);
  EXPECT_EQ(silk_param_check(nullptr, 1), SILK_ERR_INVALID_ARGUMENT);
}

}  // namespace
}  // namespace silk
