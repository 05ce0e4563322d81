// SPDX-License-Identifier: MIT
// The enum names of C API 1.4 (silk.h): every value of every public enum round-trips
// name <-> value, a value out of range is "unknown" (never NULL), and a name that is not one is
// refused naming the text and the accepted names, leaving *out untouched.
#include <gtest/gtest.h>

#include <cctype>
#include <climits>
#include <cstring>
#include <string>
#include <vector>

#include "silk/silk.h"

namespace {

struct EnumCase {
  const char* type;
  const char* (*name)(int32_t);
  silk_status (*from_name)(const char*, int32_t*);
  int32_t first;
  std::vector<std::string> names;  // the spelling silkgen's flags, model.json and the reports use
};

std::vector<EnumCase> Cases() {
  return {
      {"silk_log_level",
       silk_log_level_name,
       silk_log_level_from_name,
       SILK_LOG_DEBUG,
       {"debug", "info", "warn", "error"}},
      {"silk_mesh_format",
       silk_mesh_format_name,
       silk_mesh_format_from_name,
       SILK_FORMAT_BY_EXTENSION,
       {"by_extension", "obj", "ply", "glb"}},
      {"silk_window_rule",
       silk_window_rule_name,
       silk_window_rule_from_name,
       SILK_WINDOW_CANONICAL,
       {"canonical", "union"}},
      {"silk_hole_policy",
       silk_hole_policy_name,
       silk_hole_policy_from_name,
       SILK_HOLES_OFF,
       {"off", "report", "repair"}},
      {"silk_preprocess_kind",
       silk_preprocess_kind_name,
       silk_preprocess_kind_from_name,
       SILK_PREPROCESS_SILK,
       {"silk", "official"}},
      {"silk_decoder_precision",
       silk_decoder_precision_name,
       silk_decoder_precision_from_name,
       SILK_DECODER_DEFAULT,
       {"default", "int8", "fp32", "int4"}},
      {"silk_kv_precision",
       silk_kv_precision_name,
       silk_kv_precision_from_name,
       SILK_KV_DEFAULT,
       {"default", "fp32", "fp16", "int8"}},
      {"silk_arch", silk_arch_name, silk_arch_from_name, 0, {"silk", "official"}},
      {"silk_orientation", silk_orientation_name, silk_orientation_from_name, SILK_ORIENT_TOKENS, {"tokens", "input"}},
      {"silk_face_guidance",
       silk_face_guidance_name,
       silk_face_guidance_from_name,
       SILK_FACE_GUIDANCE_OFF,
       {"off", "hard", "soft"}},
      {"silk_advance_until", silk_advance_until_name, silk_advance_until_from_name, SILK_ADVANCE_IDS, {"ids", "layer"}},
      {"silk_candidate_state",
       silk_candidate_state_name,
       silk_candidate_state_from_name,
       SILK_CANDIDATE_WAITING,
       {"waiting", "running", "ended", "scored"}},
      {"silk_stop_reason",
       silk_stop_reason_name,
       silk_stop_reason_from_name,
       SILK_STOP_NONE,
       {"none", "eos", "max_tokens", "max_faces", "grammar_dead_end", "cancelled"}},
  };
}

TEST(EnumNames, EveryValueRoundTrips) {
  for (const EnumCase& e : Cases()) {
    SCOPED_TRACE(e.type);
    for (size_t i = 0; i < e.names.size(); ++i) {
      const int32_t value = e.first + static_cast<int32_t>(i);
      EXPECT_EQ(std::string(e.name(value)), e.names[i]);
      int32_t back = INT32_MIN;
      ASSERT_EQ(e.from_name(e.names[i].c_str(), &back), SILK_OK) << silk_last_error();
      EXPECT_EQ(back, value);
      EXPECT_STREQ(silk_last_error(), "");
    }
  }
}

TEST(EnumNames, OutOfRangeIsUnknownNeverNull) {
  for (const EnumCase& e : Cases()) {
    SCOPED_TRACE(e.type);
    const int32_t past = e.first + static_cast<int32_t>(e.names.size());
    for (int32_t v : {e.first - 1, past, past + 1, INT32_MIN, INT32_MAX}) {
      ASSERT_NE(e.name(v), nullptr);
      EXPECT_STREQ(e.name(v), "unknown") << v;
    }
  }
}

TEST(EnumNames, AStrangerNameIsRefusedNamingTheAcceptedOnes) {
  for (const EnumCase& e : Cases()) {
    SCOPED_TRACE(e.type);
    for (const char* bad : {"", "unknown", "Nope", " off"}) {
      int32_t out = 12345;
      EXPECT_EQ(e.from_name(bad, &out), SILK_ERR_INVALID_ARGUMENT) << bad;
      EXPECT_EQ(out, 12345) << "*out must stay unchanged";
      const std::string msg = silk_last_error();
      EXPECT_NE(msg.find(std::string("'") + bad + "' is not a " + e.type), std::string::npos) << msg;
      for (const std::string& n : e.names) EXPECT_NE(msg.find(n), std::string::npos) << msg;
    }
    // Names are exact: the upper-case spelling is not one.
    std::string upper = e.names[0];
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    int32_t out = 0;
    EXPECT_EQ(e.from_name(upper.c_str(), &out), SILK_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(e.from_name(nullptr, &out), SILK_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(e.from_name(e.names[0].c_str(), nullptr), SILK_ERR_INVALID_ARGUMENT);
  }
}

// The report's names come from the same tables (silk_generator_report's "repair" / "orient").
TEST(EnumNames, TheStopReasonNamesAreTheReportsAndNoneIsNotRunning) {
  EXPECT_STREQ(silk_stop_reason_name(SILK_STOP_NONE), "none");
  int32_t out = 0;
  EXPECT_EQ(silk_stop_reason_from_name("running", &out), SILK_ERR_INVALID_ARGUMENT);
}

}  // namespace
