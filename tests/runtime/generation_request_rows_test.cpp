// SPDX-License-Identifier: MIT
// Best of N's `rows` setting resolved (runtime/generation_request.h): the caller's value, else the
// model's (model.json sampling.rows), else libsilk's kDefaultRows; a value outside 1..64 refused
// with the table's message naming the field, and GenerateOptions checked by the same table.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "runtime/generation_request.h"
#include "runtime/sampling/generation_ranges.h"

namespace silk {
namespace {

TEST(GenerationRequestRows, CallersThenModelsThenLibsilksDefault) {
  ModelConfig cfg;
  GenerationRequest r;
  auto plan = ResolveRequest(r, cfg);
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  EXPECT_EQ(plan->options.rows, kDefaultRows);  // neither names it
  cfg.rows = 3;
  plan = ResolveRequest(r, cfg);
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  EXPECT_EQ(plan->options.rows, 3);  // the model's
  r.rows = 1;
  plan = ResolveRequest(r, cfg);
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  EXPECT_EQ(plan->options.rows, 1);  // the caller's, over the model's
  r.rows = 64;
  plan = ResolveRequest(r, cfg);
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  EXPECT_EQ(plan->options.rows, 64);
}

TEST(GenerationRequestRows, OutOfRangeIsRefusedNamingTheField) {
  const ModelConfig cfg;
  for (int32_t bad : {0, 65, -2}) {
    GenerationRequest r;
    r.rows = bad;
    const auto plan = ResolveRequest(r, cfg);
    ASSERT_FALSE(plan.ok()) << bad;
    EXPECT_EQ(plan.status().code(), StatusCode::kInvalidArgument);
    EXPECT_EQ(plan.status().message().rfind("rows " + std::to_string(bad) + " is not in [1, 64]", 0), 0u)
        << plan.status().message();
  }
  GenerateOptions o;
  o.rows = 65;
  const Status s = CheckGenerateOptions(o);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("rows 65 is not in [1, 64]"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace silk
