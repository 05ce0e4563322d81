// SPDX-License-Identifier: MIT
// model.json parsing: the committed tiny model is accepted, and every mismatch the contract
// names (format, versions, vocabulary, file names, dimensions) is refused with a message.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "io/files/file_bytes.h"
#include "runtime/model/model.h"
#include "runtime/model/model_config.h"
#include "runtime_test_util.h"

namespace silk {
namespace {

nlohmann::json TinyJson() {
  auto text = ReadFileBytes(testing::TinyModelDir() + "/model.json", 1 << 20);
  EXPECT_TRUE(text.ok());
  return nlohmann::json::parse(*text);
}

Status ParseWith(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = TinyJson();
  edit(j);
  auto r = ParseModelConfig(j.dump(), "model.json");
  return r.ok() ? Status::Ok() : r.status();
}

TEST(ModelConfig, TinyModelParses) {
  auto c = LoadModelConfig(testing::TinyModelDir());
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_EQ(c->bos_id, 10269);
  EXPECT_EQ(c->dims.n_layers, 2);
  EXPECT_EQ(c->dims.kv_row_floats(), 2 * 2 * 2 * 8);
  EXPECT_EQ(c->encoder_file, "encoder.onnx");
  EXPECT_TRUE(c->decoder_int8_file.empty());
}

TEST(ModelConfig, RefusesMismatches) {
  struct Case {
    const char* what;
    std::function<void(nlohmann::json&)> edit;
    const char* needle;
  };
  const std::vector<Case> cases = {
      {"format", [](auto& j) { j["format"] = "other"; }, "silk-model"},
      {"older model version", [](auto& j) { j["model_version"] = 1; }, "re-export"},
      {"newer model version", [](auto& j) { j["model_version"] = 5; }, "newer libsilk"},
      {"token format", [](auto& j) { j["token_format"] = "meshgpt"; }, "token_format"},
      {"token format version", [](auto& j) { j["token_format_version"] = 2; }, "token_format_version"},
      {"eos", [](auto& j) { j["vocab"]["eos_id"] = 5; }, "eos_id"},
      {"bos", [](auto& j) { j["vocab"]["bos_id"] = 0; }, "bos_id"},
      {"rows", [](auto& j) { j["vocab"]["embedding_rows"] = 10269; }, "embedding_rows"},
      {"missing dims", [](auto& j) { j.erase("dims"); }, "dims"},
      {"zero dim", [](auto& j) { j["dims"]["n_heads"] = 0; }, "positive"},
      {"head width", [](auto& j) { j["dims"]["head_dim"] = 4; }, "multiple of 8"},
      // Wrong JSON types are errors, never exceptions (found by model_config_fuzzer).
      {"file name type", [](auto& j) { j["files"]["encoder"] = 5; }, "not a string"},
      {"format type", [](auto& j) { j["format"] = 1; }, "not a string"},
      {"files type", [](auto& j) { j["files"] = "encoder.onnx"; }, "not an object"},
      {"int range", [](auto& j) { j["dims"]["d_model"] = 4294967312LL; }, "out of range"},
      {"too long", [](auto& j) { j["dims"]["max_seq_len"] = 20000; }, "max_seq_len"},
      {"file path", [](auto& j) { j["files"]["decoder"] = "../x.onnx"; }, "plain names"},
      {"bound", [](auto& j) { j["normalize_bound"] = 3; }, "normalize_bound"},
  };
  for (const Case& c : cases) {
    Status s = ParseWith(c.edit);
    EXPECT_FALSE(s.ok()) << c.what;
    EXPECT_NE(s.message().find(c.needle), std::string::npos) << c.what << ": " << s.message();
  }
  EXPECT_FALSE(ParseModelConfig("not json", "x").ok());
}

// model.json sampling.face_guidance / face_tolerance: absent gives libsilk's defaults, each
// mode is taken, and a bad mode, a tolerance out of [0.5, 64] or a wrong type is refused by name.
TEST(ModelConfig, FaceGuidanceFields) {
  auto plain = ParseModelConfig(TinyJson().dump(), "model.json");
  ASSERT_TRUE(plain.ok()) << plain.status().ToString();
  EXPECT_EQ(plain->face_guidance, kDefaultFaceGuidance);
  EXPECT_EQ(plain->face_tolerance, kDefaultFaceTolerance);
  for (const char* mode : {"off", "hard", "soft"}) {
    nlohmann::json j = TinyJson();
    j["sampling"]["face_guidance"] = mode;
    j["sampling"]["face_tolerance"] = 2.5;
    auto c = ParseModelConfig(j.dump(), "model.json");
    ASSERT_TRUE(c.ok()) << mode << ": " << c.status().ToString();
    EXPECT_STREQ(FaceGuidanceName(c->face_guidance), mode);
    EXPECT_EQ(c->face_tolerance, 2.5);
  }
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, const char*>> bad = {
      {[](auto& j) { j["sampling"]["face_guidance"] = "strong"; }, "face_guidance"},
      {[](auto& j) { j["sampling"]["face_guidance"] = 2; }, "not a string"},
      {[](auto& j) { j["sampling"]["face_tolerance"] = 0.25; }, "face_tolerance"},
      {[](auto& j) { j["sampling"]["face_tolerance"] = 65; }, "face_tolerance"},
  };
  for (const auto& [edit, needle] : bad) {
    Status s = ParseWith(edit);
    EXPECT_FALSE(s.ok()) << needle;
    EXPECT_NE(s.message().find(needle), std::string::npos) << s.message();
  }
}

// The committed tiny model is version 2: Silk's arch, Silk's pre-processing with its
// normalize_bound, silkgen's former sampling defaults, the fp32 decoder.
TEST(ModelConfig, Version2Defaults) {
  auto c = LoadModelConfig(testing::TinyModelDir());
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_EQ(c->model_version, 2);
  EXPECT_EQ(c->arch, ModelArch::kSilk);
  EXPECT_EQ(c->preprocessing.kind, PreprocessingKind::kSilk);
  EXPECT_EQ(c->preprocessing.normalize_bound, 0.95);
  EXPECT_EQ(c->preprocessing.n_points, c->dims.n_points);
  EXPECT_EQ(c->preprocessing.surface_samples, 0);
  EXPECT_FALSE(c->preprocessing.round_float16);
  EXPECT_EQ(c->sampling.temperature, 0.5);
  EXPECT_EQ(c->sampling.top_k, 50);
  EXPECT_EQ(c->sampling.top_p, 1.0);
  EXPECT_EQ(c->sampling.top_p_temperature, 0.0);
  EXPECT_EQ(c->candidates, 1);  // no sampling.candidates: one generation
  EXPECT_EQ(c->default_decoder, DecoderPrecision::kFp32);
  EXPECT_TRUE(c->external_data.empty());
  nlohmann::json j = TinyJson();
  j["normalize_bound"] = 0.5;
  auto b = ParseModelConfig(j.dump(), "model.json");
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(b->preprocessing.normalize_bound, 0.5);
}

nlohmann::json OfficialV3() {
  nlohmann::json j = TinyJson();
  j["model_version"] = 3;
  j["arch"] = "official";
  j.erase("normalize_bound");
  j["dims"] = {{"d_model", 32},    {"n_layers", 2},    {"n_heads", 2},      {"head_dim", 64},
               {"n_latents", 261}, {"n_points", 4096}, {"max_seq_len", 512}};
  j["preprocessing"] = {{"kind", "official"},       {"normalize_bound", 0.95}, {"merge_distance_fraction", 0.01},
                        {"surface_samples", 50000}, {"round_float16", true},   {"n_points", 4096}};
  j["sampling"] = {{"temperature", 0.5}, {"top_k", 50}, {"top_p", 0.95}, {"top_p_temperature", 1.0}};
  j["files"] = {{"encoder", "encoder.onnx"},           {"decoder", "decoder.onnx"},
                {"decoder_int8", "decoder.int8.onnx"}, {"decoder_int4", "decoder.int4.onnx"},
                {"default_decoder", "decoder_int4"},   {"external_data", {"decoder.onnx.data"}}};
  j["source"] = {{"file", "model.safetensors"}, {"sha256", "ab12"}, {"licence", "see the model card"}};
  return j;
}

TEST(ModelConfig, Version3Official) {
  auto c = ParseModelConfig(OfficialV3().dump(), "model.json");
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_EQ(c->arch, ModelArch::kOfficial);
  EXPECT_EQ(c->dims.d_model, 32);  // narrower than heads * head_dim: allowed for "official"
  const PreprocessingParams& p = c->preprocessing;
  EXPECT_EQ(p.kind, PreprocessingKind::kOfficial);
  EXPECT_EQ(p.merge_distance_fraction, 0.01);
  EXPECT_EQ(p.surface_samples, 50000);
  EXPECT_TRUE(p.round_float16);
  EXPECT_EQ(c->sampling.top_p, 0.95);
  EXPECT_EQ(c->sampling.top_p_temperature, 1.0);
  EXPECT_EQ(c->candidates, 1);
  EXPECT_EQ(c->default_decoder, DecoderPrecision::kInt4);
  EXPECT_EQ(c->DecoderFile(DecoderPrecision::kInt4), "decoder.int4.onnx");
  EXPECT_EQ(c->external_data, std::vector<std::string>{"decoder.onnx.data"});
  EXPECT_EQ(c->source_sha256, "ab12");
  // Without "preprocessing" an official model gets the official defaults; a silk one Silk's.
  nlohmann::json j = OfficialV3();
  j.erase("preprocessing");
  j.erase("sampling");
  auto d = ParseModelConfig(j.dump(), "model.json");
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_EQ(d->preprocessing.kind, PreprocessingKind::kOfficial);
  EXPECT_EQ(d->preprocessing.surface_samples, 50000);
  EXPECT_EQ(d->sampling.top_k, 50);
  // The model's best of N, 1..kMaxCandidates, read for any version.
  for (int version : {2, 3}) {
    nlohmann::json k = version == 2 ? TinyJson() : OfficialV3();
    k["sampling"]["candidates"] = 8;
    auto r = ParseModelConfig(k.dump(), "model.json");
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    EXPECT_EQ(r->candidates, 8);
    EXPECT_EQ(r->sampling.temperature, DefaultSamplingParams().temperature);  // the other fields keep theirs
    EXPECT_FALSE(r->rows.has_value());  // no sampling.rows: libsilk's default applies
    k["sampling"]["rows"] = 3;
    auto rows = ParseModelConfig(k.dump(), "model.json");
    ASSERT_TRUE(rows.ok()) << rows.status().ToString();
    EXPECT_EQ(rows->rows, std::optional<int32_t>(3));
  }
  // Fields a v3 file leaves out of "preprocessing" take the kind's defaults.
  j["preprocessing"] = {{"kind", "official"}, {"surface_samples", 8192}};
  auto e = ParseModelConfig(j.dump(), "model.json");
  ASSERT_TRUE(e.ok()) << e.status().ToString();
  EXPECT_EQ(e->preprocessing.surface_samples, 8192);
  EXPECT_TRUE(e->preprocessing.round_float16);
}

TEST(ModelConfig, Version3RefusesEveryBadField) {
  struct Case {
    const char* what;
    std::function<void(nlohmann::json&)> edit;
    const char* needle;
  };
  const std::vector<Case> cases = {
      {"arch value", [](auto& j) { j["arch"] = "gpt"; }, "arch \"gpt\""},
      {"arch type", [](auto& j) { j["arch"] = 2; }, "'arch' is not a string"},
      {"arch missing", [](auto& j) { j.erase("arch"); }, "arch"},
      {"silk dims",
       [](auto& j) {
         j["arch"] = "silk";
         j["preprocessing"]["kind"] = "silk";
       },
       "n_heads * head_dim"},
      {"preprocessing type", [](auto& j) { j["preprocessing"] = 1; }, "'preprocessing' is not an object"},
      {"kind", [](auto& j) { j["preprocessing"]["kind"] = "fancy"; }, "preprocessing.kind"},
      {"bound", [](auto& j) { j["preprocessing"]["normalize_bound"] = 1.5; }, "preprocessing.normalize_bound"},
      {"bound type", [](auto& j) { j["preprocessing"]["normalize_bound"] = "x"; }, "'normalize_bound' is not a number"},
      {"merge", [](auto& j) { j["preprocessing"]["merge_distance_fraction"] = -0.1; }, "merge_distance_fraction"},
      {"samples", [](auto& j) { j["preprocessing"]["surface_samples"] = -1; }, "surface_samples"},
      {"samples type", [](auto& j) { j["preprocessing"]["surface_samples"] = 1.5; }, "surface_samples"},
      {"round type", [](auto& j) { j["preprocessing"]["round_float16"] = 1; }, "round_float16"},
      {"points", [](auto& j) { j["preprocessing"]["n_points"] = 2048; }, "differs from dims.n_points"},
      {"sampling type", [](auto& j) { j["sampling"] = "hot"; }, "'sampling' is not an object"},
      {"temperature", [](auto& j) { j["sampling"]["temperature"] = -1; }, "sampling.temperature"},
      {"temperature 150", [](auto& j) { j["sampling"]["temperature"] = 150; },
       "sampling.temperature 150 is not in [0, 100]"},
      {"temperature type", [](auto& j) { j["sampling"]["temperature"] = "warm"; }, "'temperature' is not a number"},
      {"top_k", [](auto& j) { j["sampling"]["top_k"] = 20000; }, "sampling.top_k"},
      {"top_p", [](auto& j) { j["sampling"]["top_p"] = 1.5; }, "sampling.top_p 1.5 is not in [0, 1]"},
      {"top_p_temperature", [](auto& j) { j["sampling"]["top_p_temperature"] = -2; }, "sampling.top_p_temperature"},
      {"candidates 0", [](auto& j) { j["sampling"]["candidates"] = 0; }, "sampling.candidates 0 is not in [1, 64]"},
      {"candidates 65", [](auto& j) { j["sampling"]["candidates"] = 65; }, "sampling.candidates 65 is not in [1, 64]"},
      {"candidates type", [](auto& j) { j["sampling"]["candidates"] = 2.5; }, "candidates"},
      {"rows 0", [](auto& j) { j["sampling"]["rows"] = 0; }, "model.json: sampling.rows 0 is not in [1, 64]"},
      {"rows 65", [](auto& j) { j["sampling"]["rows"] = 65; }, "model.json: sampling.rows 65 is not in [1, 64]"},
      {"rows type", [](auto& j) { j["sampling"]["rows"] = 2.5; }, "integer field 'rows'"},
      {"int4 name", [](auto& j) { j["files"]["decoder_int4"] = "../d.onnx"; }, "plain names"},
      {"int4 type", [](auto& j) { j["files"]["decoder_int4"] = 4; }, "'decoder_int4' is not a string"},
      {"default decoder", [](auto& j) { j["files"]["default_decoder"] = "decoder_int2"; }, "files.default_decoder"},
      {"default decoder absent file", [](auto& j) { j["files"].erase("decoder_int4"); },
       "files.decoder_int4 is not given"},
      {"external data type", [](auto& j) { j["files"]["external_data"] = "x.data"; }, "files.external_data"},
      {"external data entry", [](auto& j) { j["files"]["external_data"] = {1}; }, "files.external_data"},
      {"external data path", [](auto& j) { j["files"]["external_data"] = {"/etc/passwd"}; }, "plain names"},
      {"source type", [](auto& j) { j["source"] = "hf"; }, "'source' is not an object"},
      {"source sha type", [](auto& j) { j["source"]["sha256"] = 5; }, "'sha256' is not a string"},
      {"latents", [](auto& j) { j["dims"]["n_latents"] = 1 << 20; }, "implausibly large"},
  };
  for (const Case& c : cases) {
    nlohmann::json j = OfficialV3();
    c.edit(j);
    auto r = ParseModelConfig(j.dump(), "model.json");
    ASSERT_FALSE(r.ok()) << c.what;
    EXPECT_NE(r.status().message().find(c.needle), std::string::npos) << c.what << ": " << r.status().message();
  }
}

TEST(ModelLoad, MissingFolderAndPrecisionsAreClearErrors) {
  auto m = Model::Load(testing::TinyModelDir() + "/nope");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("not found"), std::string::npos);
  for (auto [p, word] : {std::pair{DecoderPrecision::kInt8, "INT8"}, std::pair{DecoderPrecision::kInt4, "INT4"}}) {
    ModelLoadOptions o;
    o.decoder = p;
    auto q = Model::Load(testing::TinyModelDir(), o);
    ASSERT_FALSE(q.ok());
    EXPECT_NE(q.status().message().find(word), std::string::npos) << q.status().message();
  }
  auto fp = testing::LoadTinyModel(1);
  ASSERT_TRUE(fp);
  EXPECT_EQ(fp->precision(), DecoderPrecision::kFp32);
}

// files.kv_fp16 / files.kv_int8 / files.default_kv_precision: the fp16- and int8-cache variants of
// a decoder, the model's default, and the refusals (a variant without its decoder, an unknown precision, a default
// the default decoder cannot honour).
TEST(ModelConfig, KvPrecisionFiles) {
  auto c = LoadModelConfig(testing::TinyModelDir());
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_EQ(c->DecoderFile(DecoderPrecision::kFp32, KvPrecision::kFp16), "decoder.kv16.onnx");
  EXPECT_EQ(c->DecoderFile(DecoderPrecision::kFp32, KvPrecision::kFp32), "decoder.onnx");
  EXPECT_EQ(c->DecoderFile(DecoderPrecision::kFp32, KvPrecision::kInt8), "decoder.kv8.onnx");
  EXPECT_TRUE(c->DecoderFile(DecoderPrecision::kInt8, KvPrecision::kFp16).empty());
  EXPECT_TRUE(c->DecoderFile(DecoderPrecision::kInt8, KvPrecision::kInt8).empty());
  EXPECT_EQ(c->default_kv, KvPrecision::kFp32);  // absent: fp32
  auto fp16 = ParseModelConfig(
      [] {
        nlohmann::json j = TinyJson();
        j["files"]["default_kv_precision"] = "fp16";
        return j.dump();
      }(),
      "model.json");
  ASSERT_TRUE(fp16.ok()) << fp16.status().ToString();
  EXPECT_EQ(fp16->DefaultKv(DecoderPrecision::kFp32), KvPrecision::kFp16);
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, const char*>> bad = {
      {[](auto& j) { j["files"]["kv_fp16"]["decoder_int8"] = "d.int8.kv16.onnx"; }, "files.decoder_int8 is not"},
      {[](auto& j) { j["files"]["kv_fp16"]["decoder"] = "../x.onnx"; }, "plain names"},
      {[](auto& j) { j["files"]["kv_fp16"] = "decoder.kv16.onnx"; }, "not an object"},
      {[](auto& j) { j["files"]["default_kv_precision"] = "bf16"; }, "not one of \"fp32\", \"fp16\", \"int8\""},
      {[](auto& j) {
         j["files"].erase("kv_int8");
         j["files"]["default_kv_precision"] = "int8";
       },
       "no files.kv_int8 variant"},
      {[](auto& j) { j["files"]["kv_int8"]["decoder_int4"] = "d.int4.kv8.onnx"; },
       "files.kv_int8.decoder_int4 is given"},
      {[](auto& j) {
         j["files"].erase("kv_fp16");
         j["files"]["default_kv_precision"] = "fp16";
       },
       "no files.kv_fp16 variant"},
  };
  for (const auto& [edit, needle] : bad) {
    Status s = ParseWith(edit);
    ASSERT_FALSE(s.ok()) << needle;
    EXPECT_NE(s.message().find(needle), std::string::npos) << s.message();
  }
}

TEST(ModelLoad, KvPrecisionChoosesTheGraph) {
  auto fp16 = testing::LoadTinyModel(1, KvPrecision::kFp16);
  ASSERT_TRUE(fp16);
  EXPECT_EQ(fp16->kv_precision(), KvPrecision::kFp16);
  auto fp32 = testing::LoadTinyModel(1);
  ASSERT_TRUE(fp32);
  EXPECT_EQ(fp32->kv_precision(), KvPrecision::kFp32);
  ModelLoadOptions o;  // the model's: fp32 here (no default_kv_precision)
  auto dflt = Model::Load(testing::TinyModelDir(), o);
  ASSERT_TRUE(dflt.ok());
  EXPECT_EQ((*dflt)->kv_precision(), KvPrecision::kFp32);
}

TEST(ModelLoad, MissingKvVariantNamesPrecisionAndFolder) {
  const std::string dir = ::testing::TempDir() + "/kv_missing";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const char* f : {"model.json", "encoder.onnx", "decoder.onnx"})
    std::filesystem::copy_file(testing::TinyModelDir() + "/" + f, dir + "/" + f);
  ModelLoadOptions o;
  o.kv = KvPrecision::kFp16;
  // model.json names decoder.kv16.onnx, which this folder lacks: the file is named.
  auto gone = Model::Load(dir, o);
  ASSERT_FALSE(gone.ok());
  EXPECT_NE(gone.status().message().find("decoder.kv16.onnx"), std::string::npos) << gone.status().message();
  // A model without the variant: the precision and the folder are named.
  nlohmann::json j = TinyJson();
  j["files"].erase("kv_fp16");
  std::ofstream(dir + "/model.json") << j.dump();
  auto none = Model::Load(dir, o);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code(), StatusCode::kUnsupported);
  EXPECT_NE(none.status().message().find("fp16 KV cache"), std::string::npos) << none.status().message();
  EXPECT_NE(none.status().message().find(dir), std::string::npos) << none.status().message();
  // A variant whose caches are float32 (a wrong file) is refused by the type check.
  j["files"]["kv_fp16"] = {{"decoder", "decoder.onnx"}};
  std::ofstream(dir + "/model.json") << j.dump();
  auto wrong = Model::Load(dir, o);
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.status().message().find("float32, the contract needs float16"), std::string::npos)
      << wrong.status().message();
}

TEST(ModelLoad, ThreadsResolve) {
  auto m = testing::LoadTinyModel(0);
  ASSERT_TRUE(m);
  EXPECT_GE(m->threads(), 1);
  // One onnxruntime pool per process: the first load sized it, later requests do not resize it.
  auto one = testing::LoadTinyModel(1);
  ASSERT_TRUE(one);
  EXPECT_EQ(one->threads(), m->threads());
  ModelLoadOptions too_many;
  too_many.threads = 100000;
  auto refused = Model::Load(testing::TinyModelDir(), too_many);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("threads 100000"), std::string::npos) << refused.status().message();
}

}  // namespace
}  // namespace silk
