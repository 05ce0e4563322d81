// SPDX-License-Identifier: MIT
// C API: the one spelling of every public enum's values (silk.h, C API 1.4), one table per enum,
// so silkgen's options, the Python binding, the Blender add-on and the reports never re-spell them.
#include <cstring>
#include <string>

#include "capi/capi_internal.h"
#include "runtime/stop_reason.h"

namespace silk::capi {
namespace {

// An enum's names by value, from `first` on (silk.h enums are contiguous).
struct EnumNames {
  const char* type;  // for messages: "silk_kv_precision"
  int32_t first;
  const char* const* names;
  int32_t count;
};

template <size_t N>
constexpr EnumNames Table(const char* type, int32_t first, const char* const (&names)[N]) {
  return EnumNames{type, first, names, static_cast<int32_t>(N)};
}

constexpr const char* kLogLevels[] = {"debug", "info", "warn", "error"};
constexpr const char* kMeshFormats[] = {"by_extension", "obj", "ply", "glb"};
constexpr const char* kWindowRules[] = {"canonical", "union"};
constexpr const char* kHolePolicies[] = {"off", "report", "repair"};
constexpr const char* kPreprocessKinds[] = {"silk", "official"};
constexpr const char* kDecoderPrecisions[] = {"default", "int8", "fp32", "int4"};
constexpr const char* kKvPrecisions[] = {"default", "fp32", "fp16", "int8"};
constexpr const char* kArchs[] = {"silk", "official"};
constexpr const char* kOrientations[] = {"tokens", "input"};
constexpr const char* kFaceGuidances[] = {"off", "hard", "soft"};
constexpr const char* kAdvanceUntils[] = {"ids", "layer"};
constexpr const char* kCandidateStates[] = {"waiting", "running", "ended", "scored"};  // C API 1.5
// The generator's own names (runtime/stop_reason.h), value for value.
constexpr const char* kStopReasons[] = {
    StopReasonName(StopReason::kNone),           StopReasonName(StopReason::kEos),
    StopReasonName(StopReason::kMaxTokens),      StopReasonName(StopReason::kMaxFaces),
    StopReasonName(StopReason::kGrammarDeadEnd), StopReasonName(StopReason::kCancelled)};

constexpr EnumNames kLogLevel = Table("silk_log_level", SILK_LOG_DEBUG, kLogLevels);
constexpr EnumNames kMeshFormat = Table("silk_mesh_format", SILK_FORMAT_BY_EXTENSION, kMeshFormats);
constexpr EnumNames kWindowRule = Table("silk_window_rule", SILK_WINDOW_CANONICAL, kWindowRules);
constexpr EnumNames kHolePolicy = Table("silk_hole_policy", SILK_HOLES_OFF, kHolePolicies);
constexpr EnumNames kPreprocessKind = Table("silk_preprocess_kind", SILK_PREPROCESS_SILK, kPreprocessKinds);
constexpr EnumNames kDecoderPrecision = Table("silk_decoder_precision", SILK_DECODER_DEFAULT, kDecoderPrecisions);
constexpr EnumNames kKvPrecision = Table("silk_kv_precision", SILK_KV_DEFAULT, kKvPrecisions);
constexpr EnumNames kArch = Table("silk_arch", SILK_ARCH_SILK, kArchs);  // silk_model_info.arch
static_assert(SILK_ARCH_OFFICIAL == SILK_ARCH_SILK + 1, "kArchs lists silk_arch by value");
constexpr EnumNames kOrientation = Table("silk_orientation", SILK_ORIENT_TOKENS, kOrientations);
constexpr EnumNames kFaceGuidance = Table("silk_face_guidance", SILK_FACE_GUIDANCE_OFF, kFaceGuidances);
constexpr EnumNames kAdvanceUntil = Table("silk_advance_until", SILK_ADVANCE_IDS, kAdvanceUntils);
constexpr EnumNames kCandidateState = Table("silk_candidate_state", SILK_CANDIDATE_WAITING, kCandidateStates);
constexpr EnumNames kStopReason = Table("silk_stop_reason", SILK_STOP_NONE, kStopReasons);

static_assert(sizeof(kLogLevels) / sizeof(*kLogLevels) == SILK_LOG_ERROR + 1, "one name per silk_log_level");
static_assert(sizeof(kMeshFormats) / sizeof(*kMeshFormats) == SILK_FORMAT_GLB + 1, "one name per silk_mesh_format");
static_assert(sizeof(kWindowRules) / sizeof(*kWindowRules) == SILK_WINDOW_UNION + 1, "one name per silk_window_rule");
static_assert(sizeof(kHolePolicies) / sizeof(*kHolePolicies) == SILK_HOLES_REPAIR + 1, "one name per hole policy");
static_assert(sizeof(kPreprocessKinds) / sizeof(*kPreprocessKinds) == SILK_PREPROCESS_OFFICIAL + 1,
              "one name per silk_preprocess_kind");
static_assert(sizeof(kDecoderPrecisions) / sizeof(*kDecoderPrecisions) == SILK_DECODER_INT4 + 1,
              "one name per silk_decoder_precision");
static_assert(sizeof(kKvPrecisions) / sizeof(*kKvPrecisions) == SILK_KV_INT8 + 1, "one name per silk_kv_precision");
static_assert(sizeof(kOrientations) / sizeof(*kOrientations) == SILK_ORIENT_INPUT + 1, "one name per orientation");
static_assert(sizeof(kFaceGuidances) / sizeof(*kFaceGuidances) == SILK_FACE_GUIDANCE_SOFT + 1,
              "one name per silk_face_guidance");
static_assert(sizeof(kAdvanceUntils) / sizeof(*kAdvanceUntils) == SILK_ADVANCE_LAYER + 1,
              "one name per silk_advance_until");
static_assert(sizeof(kCandidateStates) / sizeof(*kCandidateStates) == SILK_CANDIDATE_SCORED + 1,
              "one name per silk_candidate_state");
static_assert(sizeof(kStopReasons) / sizeof(*kStopReasons) == SILK_STOP_CANCELLED - SILK_STOP_NONE + 1,
              "one name per silk_stop_reason");

const char* NameOf(const EnumNames& e, int32_t value) {
  const int64_t i = int64_t{value} - e.first;  // 64 bits: INT32_MAX - (-1) must not wrap
  return i >= 0 && i < e.count ? e.names[i] : "unknown";
}

// The value named `name` (exact match) into *out; otherwise SILK_ERR_INVALID_ARGUMENT naming the
// text and every accepted name, *out unchanged.
silk_status ValueOf(const char* function, const EnumNames& e, const char* name, int32_t* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(name && out, std::string(function) + ": name or out is NULL");
    for (int32_t i = 0; i < e.count; ++i)
      if (std::strcmp(name, e.names[i]) == 0) {
        *out = e.first + i;
        return Ok();
      }
    std::string known;
    for (int32_t i = 0; i < e.count; ++i) known += (i ? ", " : "") + std::string(e.names[i]);
    return SetError(SILK_ERR_INVALID_ARGUMENT,
                    std::string(function) + ": '" + name + "' is not a " + e.type + " (one of: " + known + ")");
  });
}

}  // namespace
}  // namespace silk::capi

#define SILK_ENUM_NAME_FUNCTIONS(prefix, table)                                                     \
  const char* prefix##_name(int32_t value) { return silk::capi::NameOf(silk::capi::table, value); } \
  silk_status prefix##_from_name(const char* name, int32_t* out) {                                  \
    return silk::capi::ValueOf(#prefix "_from_name", silk::capi::table, name, out);                 \
  }

extern "C" {
SILK_ENUM_NAME_FUNCTIONS(silk_log_level, kLogLevel)
SILK_ENUM_NAME_FUNCTIONS(silk_mesh_format, kMeshFormat)
SILK_ENUM_NAME_FUNCTIONS(silk_window_rule, kWindowRule)
SILK_ENUM_NAME_FUNCTIONS(silk_hole_policy, kHolePolicy)
SILK_ENUM_NAME_FUNCTIONS(silk_preprocess_kind, kPreprocessKind)
SILK_ENUM_NAME_FUNCTIONS(silk_decoder_precision, kDecoderPrecision)
SILK_ENUM_NAME_FUNCTIONS(silk_kv_precision, kKvPrecision)
SILK_ENUM_NAME_FUNCTIONS(silk_arch, kArch)
SILK_ENUM_NAME_FUNCTIONS(silk_orientation, kOrientation)
SILK_ENUM_NAME_FUNCTIONS(silk_face_guidance, kFaceGuidance)
SILK_ENUM_NAME_FUNCTIONS(silk_advance_until, kAdvanceUntil)
SILK_ENUM_NAME_FUNCTIONS(silk_stop_reason, kStopReason)
SILK_ENUM_NAME_FUNCTIONS(silk_candidate_state, kCandidateState)  // C API 1.5
}  // extern "C"
