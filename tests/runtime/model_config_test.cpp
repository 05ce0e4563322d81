// model.json parsing: the committed tiny model is accepted, and every mismatch the contract
// names (format, versions, vocabulary, file names, dimensions) is refused with a message.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io/file_bytes.h"
#include "runtime/model.h"
#include "runtime/model_config.h"
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
      {"newer model version", [](auto& j) { j["model_version"] = 3; }, "newer libsilk"},
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

TEST(ModelLoad, MissingFolderAndInt8AreClearErrors) {
  auto m = Model::Load(testing::TinyModelDir() + "/nope");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("not found"), std::string::npos);
  ModelLoadOptions o;
  o.int8 = true;
  auto q = Model::Load(testing::TinyModelDir(), o);
  ASSERT_FALSE(q.ok());
  EXPECT_NE(q.status().message().find("INT8"), std::string::npos);
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
