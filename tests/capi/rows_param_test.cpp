// SPDX-License-Identifier: MIT
// silk_generate_params.rows (C API 1.5, issue 34): best of N's candidates decoded together. Its
// default is SILK_MODEL_VALUE (the model's sampling.rows, else libsilk's 8), the value resolved is
// the report's settings.rows, a value outside 1..64 is refused with the range table's message, a
// 1.3-1.4 caller's shorter params get the default and its shorter stats are not written past, and
// a model.json with a bad sampling.rows is refused at load naming the file and the field.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "silk/silk.h"
#include "silk/silk.hpp"
#include "support/capi_counts.h"
#include "support/capi_generate.h"
#include "support/test_paths.h"

namespace {

namespace fs = std::filesystem;

// The size silk_generate_params / silk_generate_stats had in C API 1.3-1.4 (before rows).
constexpr size_t kParams13 = offsetof(silk_generate_params, rows);
constexpr size_t kStats13 = offsetof(silk_generate_stats, rows);

// A copy of the tiny model whose model.json has "sampling": {<sampling>}.
fs::path TinyWithSampling(const std::string& tag, const std::string& sampling) {
  const fs::path src = silk::testing::SourcePath("tests/models/tiny");
  const fs::path dir = fs::temp_directory_path() / ("silk_rows_" + tag + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* f : {"encoder.onnx", "decoder.onnx"})
    fs::copy_file(src / f, dir / f, fs::copy_options::overwrite_existing);
  std::ifstream in(src / "model.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  EXPECT_EQ(json.find("\"sampling\""), std::string::npos) << "the tiny model names no sampling defaults";
  json.insert(json.find('{') + 1, "\n  \"sampling\": {" + sampling + "},");
  std::ofstream(dir / "model.json") << json;
  return dir;
}

class CapiRows : public silk::testing::TinyModelTest {
 protected:
  // The report of one run with `p` ("" and the status on failure).
  nlohmann::json Run(silk_model* model, const silk_generate_params* p, silk_generate_stats* st = nullptr) {
    silk_generator* g = nullptr;
    EXPECT_EQ(silk_generator_create(model, &g), SILK_OK);
    silk_mesh* out = nullptr;
    const silk_status s = silk::testing::GenerateFromMesh(g, mesh_, p, &out, nullptr, st);
    EXPECT_EQ(s, SILK_OK) << silk_last_error();
    std::string json;
    if (s == SILK_OK) {
      EXPECT_EQ(silk::testing::GeneratorReport(g, 0, &json), SILK_OK);
    }
    silk_mesh_destroy(out);
    silk_generator_destroy(g);
    return json.empty() ? nlohmann::json() : nlohmann::json::parse(json);
  }
};

TEST_F(CapiRows, OutOfRangeIsRefusedWithTheTablesMessage) {
  double lo = 0, hi = 0;
  int32_t zero_too = 1;
  ASSERT_EQ(silk_param_range("rows", &lo, &hi, &zero_too), SILK_OK) << silk_last_error();
  EXPECT_EQ(lo, 1);
  EXPECT_EQ(hi, 64);
  EXPECT_EQ(zero_too, 0);
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  for (int32_t bad : {0, 65, -2, INT32_MIN}) {
    silk_generate_params p = Params(1, 60);
    p.rows = bad;
    silk_mesh* out = nullptr;
    ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT) << bad;
    EXPECT_EQ(out, nullptr);
    const std::string message = silk_last_error();
    EXPECT_NE(message.find("rows " + std::to_string(bad) + " is not in [1, 64]"), std::string::npos) << message;
    ASSERT_EQ(silk_param_check("rows", bad), SILK_ERR_INVALID_ARGUMENT);
    EXPECT_NE(message.find(silk_last_error()), std::string::npos) << message;  // one rule, one text
  }
  EXPECT_EQ(silk_param_check("rows", 1), SILK_OK);
  EXPECT_EQ(silk_param_check("rows", 64), SILK_OK);
  silk_generator_destroy(g);
}

TEST_F(CapiRows, DefaultIsLibsilksAndAGivenValueIsReported) {
  EXPECT_EQ(silk_generate_default_params().rows, SILK_MODEL_VALUE);
  silk_generate_params p = Params(1);
  const nlohmann::json def = Run(model_, &p);
  ASSERT_TRUE(def.contains("settings")) << def.dump();
  EXPECT_EQ(def["settings"]["rows"], 8) << "the tiny model names no rows: libsilk's default";
  EXPECT_EQ(def["rows"], 1) << "one candidate uses one row";
  p.rows = 3;
  p.candidates = 2;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  const nlohmann::json three = Run(model_, &p, &st);
  ASSERT_TRUE(three.contains("settings")) << three.dump();
  EXPECT_EQ(three["settings"]["rows"], 3);
  EXPECT_EQ(three["rows"], st.rows);
  EXPECT_GE(st.rows, 1);
  EXPECT_LE(st.rows, 2) << "min(rows, N)";
}

TEST_F(CapiRows, AnOlderCallersShorterStructsGetTheDefaultAndAreNotWrittenPast) {
  // A 1.3-1.4 caller: its params end before rows; the bytes after them (here garbage the caller
  // never reserved) are not read, so rows is the model's, else 8.
  const fs::path dir = TinyWithSampling("model", "\"rows\": 3");
  silk_model_params o = silk_model_default_params();
  o.threads = 1;
  silk_model* m = nullptr;
  ASSERT_EQ(silk_model_load(dir.string().c_str(), &o, &m), SILK_OK) << silk_last_error();
  for (silk_model* model : {model_, m}) {
    silk_generate_params p = Params(1);
    p.rows = 65;  // past the 1.3 struct: never read
    p.struct_size = static_cast<uint32_t>(kParams13);
    alignas(silk_generate_stats) unsigned char stats[sizeof(silk_generate_stats)];
    std::memset(stats, 0xAB, sizeof stats);
    auto* st = reinterpret_cast<silk_generate_stats*>(stats);
    st->struct_size = static_cast<uint32_t>(kStats13);
    const nlohmann::json r = Run(model, &p, st);
    ASSERT_TRUE(r.contains("settings")) << r.dump();
    EXPECT_EQ(r["settings"]["rows"], model == m ? 3 : 8);
    EXPECT_GT(st->tokens, 0);
    for (size_t i = kStats13; i < sizeof stats; ++i) ASSERT_EQ(stats[i], 0xAB) << "written past the 1.3 size at " << i;
  }
  // A model's rows is what SILK_MODEL_VALUE takes; a given value wins over it.
  silk_generate_params p = Params(1);
  EXPECT_EQ(Run(m, &p)["settings"]["rows"], 3);
  p.rows = 1;
  EXPECT_EQ(Run(m, &p)["settings"]["rows"], 1);
  silk_model_destroy(m);
  fs::remove_all(dir);
}

TEST(CapiRowsModel, BadSamplingRowsIsRefusedAtLoadNamingTheFileAndField) {
  if (!silk_generation_available()) GTEST_SKIP();
  for (const char* bad : {"0", "65", "2.5", "\"8\""}) {
    const fs::path dir = TinyWithSampling("bad", std::string("\"rows\": ") + bad);
    silk_model* m = nullptr;
    EXPECT_NE(silk_model_load(dir.string().c_str(), nullptr, &m), SILK_OK) << bad;
    EXPECT_EQ(m, nullptr);
    const std::string message = silk_last_error();
    EXPECT_NE(message.find("model.json"), std::string::npos) << message;
    EXPECT_NE(message.find("rows"), std::string::npos) << message;
    if (std::string(bad) == "65") {
      EXPECT_NE(message.find("sampling.rows 65 is not in [1, 64]"), std::string::npos) << message;
    }
    silk_model_destroy(m);
    fs::remove_all(dir);
  }
}

}  // namespace
