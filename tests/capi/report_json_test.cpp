// SPDX-License-Identifier: MIT
// Every JSON text libsilk writes is valid JSON, also for non-finite figures (issue 20, finding 7):
// the reports are nlohmann::json dumps (NaN / Inf become null: checked here, since the reports
// rely on it) plus the trace's hand-written point list (core/json_number.h: null, never nan/inf).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/json_number.h"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(ReportJson, NlohmannDumpsNonFiniteNumbersAsNull) {
  nlohmann::ordered_json j;
  j["score"] = kInf;
  j["forced_share"] = kNaN;
  j["seconds"] = {{"total", -kInf}, {"encoder", 0.25}};
  for (int indent : {-1, 2}) {
    const std::string text = j.dump(indent);
    EXPECT_EQ(text.find("nan"), std::string::npos) << text;
    EXPECT_EQ(text.find("inf"), std::string::npos) << text;
    const nlohmann::json back = nlohmann::json::parse(text);  // throws on invalid JSON
    EXPECT_TRUE(back["score"].is_null());
    EXPECT_TRUE(back["forced_share"].is_null());
    EXPECT_TRUE(back["seconds"]["total"].is_null());
    EXPECT_EQ(back["seconds"]["encoder"].get<double>(), 0.25);
  }
}

TEST(ReportJson, JsonNumberWritesNullForNonFiniteValues) {
  EXPECT_EQ(silk::JsonNumber(kNaN), "null");
  EXPECT_EQ(silk::JsonNumber(kInf, 9), "null");
  EXPECT_EQ(silk::JsonNumber(-kInf, 9), "null");
  EXPECT_EQ(silk::JsonNumber(0), "0");
  EXPECT_EQ(silk::JsonNumber(-1.5, 9), "-1.5");
  const float f = 0.1f;  // 9 significant digits read a float back exactly
  EXPECT_EQ(static_cast<float>(std::stod(silk::JsonNumber(f, 9))), f);
  const std::string list =
      "[" + silk::JsonNumber(1.25, 9) + "," + silk::JsonNumber(kNaN, 9) + "," + silk::JsonNumber(1e-30, 9) + "]";
  const nlohmann::json back = nlohmann::json::parse(list);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[0].get<double>(), 1.25);
  EXPECT_TRUE(back[1].is_null());
  EXPECT_DOUBLE_EQ(back[2].get<double>(), 1e-30);
}

}  // namespace
