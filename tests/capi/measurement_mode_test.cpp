// SPDX-License-Identifier: MIT
// The generator's measurement mode outside silk.h (capi/capi_measurement.h): generation without
// the grammar mask, refused while a generation is in progress, reported in the stats and the
// report JSON (valid JSON also when no candidate has a face, so every score is infinite), and off
// again on request.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "capi/capi_measurement.h"
#include "silk/silk.h"
#include "support/capi_generate.h"

namespace {

using silk::capi::SetUnconstrained;

class MeasurementMode : public silk::testing::TinyModelTest {
 protected:
  // The one-call run's stats.
  silk_generate_stats Run(silk_generator* g, const silk_generate_params& p) {
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    silk_mesh* out = nullptr;
    EXPECT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, &st), SILK_OK) << silk_last_error();
    silk_mesh_destroy(out);
    return st;
  }
  // The generator's report of its last run (trace 1: with points and legal sets), parsed.
  static nlohmann::json Report(silk_generator* g, int32_t trace) {
    silk_report* r = nullptr;
    EXPECT_EQ(silk_generator_report(g, trace, &r), SILK_OK) << silk_last_error();
    nlohmann::json j = nlohmann::json::parse(r ? silk_report_json(r) : "null");  // throws on invalid JSON
    silk_report_destroy(r);
    return j;
  }
};

TEST_F(MeasurementMode, UnconstrainedRunsWithoutTheMaskAndReportsIt) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  EXPECT_EQ(SetUnconstrained(nullptr, true), SILK_ERR_INVALID_ARGUMENT);
  ASSERT_EQ(SetUnconstrained(g, true), SILK_OK) << silk_last_error();
  // A random model at a high temperature over every id: the first id is illegal, so no
  // candidate has a face and each Chamfer score is +inf, which the report writes as null.
  silk_generate_params p = Params(3, 14);
  p.temperature = 5.0;
  p.top_k = 0;
  p.candidates = 2;
  p.report_flags = SILK_GENERATE_RECORD_TRACE;
  silk_generate_stats st = Run(g, p);
  nlohmann::json report = Report(g, 0);
  EXPECT_EQ(st.forced_tokens, 0);  // no grammar, nothing forced
  EXPECT_GE(st.illegal_at, 0);
  EXPECT_EQ(st.faces, 0);
  EXPECT_TRUE(std::isinf(st.score));
  EXPECT_EQ(report["settings"]["unconstrained"], true);
  ASSERT_TRUE(report.contains("grammar")) << report.dump();
  EXPECT_EQ(report["grammar"]["first_illegal_token"], st.illegal_at);
  ASSERT_EQ(report["candidates"].size(), 2u);
  for (const auto& c : report["candidates"]) EXPECT_TRUE(c["score"].is_null()) << c.dump();
  const nlohmann::json trace = Report(g, 1);
  ASSERT_FALSE(trace["points"].empty());
  for (const auto& x : trace["points"]) EXPECT_TRUE(x.is_number_float()) << x.dump();
  // Off again: the mask is back (a forced id, every id legal, no "grammar" entry).
  ASSERT_EQ(SetUnconstrained(g, false), SILK_OK);
  st = Run(g, Params(3, 60));
  report = Report(g, 0);
  EXPECT_GT(st.forced_tokens, 0);
  EXPECT_EQ(st.illegal_at, -1);
  EXPECT_EQ(report["settings"]["unconstrained"], false);
  EXPECT_FALSE(report.contains("grammar"));
  silk_generator_destroy(g);
}

TEST_F(MeasurementMode, RefusedWhileAStepWiseGenerationIsInProgress) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = mesh_;
  const silk_generate_params p = Params(1, 60);
  ASSERT_EQ(silk_generator_start(g, &in, &p), SILK_OK) << silk_last_error();
  EXPECT_EQ(SetUnconstrained(g, true), SILK_ERR_BUSY);
  EXPECT_NE(std::string(silk_last_error()).find("in progress"), std::string::npos) << silk_last_error();
  silk_mesh* out = nullptr;
  ASSERT_EQ(silk_generator_finish(g, &out, nullptr, nullptr), SILK_OK) << silk_last_error();
  silk_mesh_destroy(out);
  EXPECT_EQ(SetUnconstrained(g, true), SILK_OK) << silk_last_error();
  silk_generator_destroy(g);
}

}  // namespace
