// SPDX-License-Identifier: MIT
// The runtime's own names (model.json's "fp16", sampling.face_guidance's "hard", the
// pre-processing kind) are the C API's enum names (silk.h 1.4), so model.json, the reports and
// every client spell each value alike.
#include <gtest/gtest.h>

#include "mesh/point_preprocessing.h"
#include "runtime/model/model_config.h"
#include "runtime/sampling/face_guide.h"
#include "silk/silk.h"

namespace {

TEST(EnumNamesRuntime, ModelJsonNamesAreTheCApis) {
  EXPECT_STREQ(silk::DecoderPrecisionName(silk::DecoderPrecision::kFp32),
               silk_decoder_precision_name(SILK_DECODER_FP32));
  EXPECT_STREQ(silk::DecoderPrecisionName(silk::DecoderPrecision::kInt8),
               silk_decoder_precision_name(SILK_DECODER_INT8));
  EXPECT_STREQ(silk::DecoderPrecisionName(silk::DecoderPrecision::kInt4),
               silk_decoder_precision_name(SILK_DECODER_INT4));
  EXPECT_STREQ(silk::KvPrecisionName(silk::KvPrecision::kFp32), silk_kv_precision_name(SILK_KV_FP32));
  EXPECT_STREQ(silk::KvPrecisionName(silk::KvPrecision::kFp16), silk_kv_precision_name(SILK_KV_FP16));
  EXPECT_STREQ(silk::KvPrecisionName(silk::KvPrecision::kInt8), silk_kv_precision_name(SILK_KV_INT8));
  EXPECT_STREQ(silk::FaceGuidanceName(silk::FaceGuidance::kOff), silk_face_guidance_name(SILK_FACE_GUIDANCE_OFF));
  EXPECT_STREQ(silk::FaceGuidanceName(silk::FaceGuidance::kHard), silk_face_guidance_name(SILK_FACE_GUIDANCE_HARD));
  EXPECT_STREQ(silk::FaceGuidanceName(silk::FaceGuidance::kSoft), silk_face_guidance_name(SILK_FACE_GUIDANCE_SOFT));
  EXPECT_STREQ(silk::PreprocessingKindName(silk::PreprocessingKind::kSilk),
               silk_preprocess_kind_name(SILK_PREPROCESS_SILK));
  EXPECT_STREQ(silk::PreprocessingKindName(silk::PreprocessingKind::kOfficial),
               silk_preprocess_kind_name(SILK_PREPROCESS_OFFICIAL));
}

}  // namespace
