// SPDX-License-Identifier: MIT
// Models by name through the C API (silk.h "models by name"): the models folder's rule
// ($SILK_MODELS, XDG_DATA_HOME, HOME), model names, the bundled model, a path winning over a name,
// silk_model_load taking a name, and silk_models_list's catalog; each with its failure message.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "silk/silk.hpp"
#include "support/test_paths.h"

namespace {

namespace fs = std::filesystem;

void SetEnv(const char* name, const std::string& value) {
#ifdef _WIN32
  _putenv_s(name, value.c_str());
#else
  setenv(name, value.c_str(), 1);
#endif
}
void UnsetEnv(const char* name) {
#ifdef _WIN32
  _putenv_s(name, "");
#else
  unsetenv(name);
#endif
}

// A scratch models folder (SILK_MODELS) holding a copy of the tiny test model as "tiny-a", and the
// previous environment restored afterwards.
class ModelFolders : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* v : {"SILK_MODELS", "XDG_DATA_HOME", "HOME"}) saved_[v] = std::getenv(v) ? std::getenv(v) : "\x01";
    root_ = fs::temp_directory_path() / ("silk_model_folders_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "models");
    fs::copy(silk::testing::SourcePath("tests/models/tiny"), root_ / "models" / "tiny-a");
    SetEnv("SILK_MODELS", (root_ / "models").string());
  }
  void TearDown() override {
    for (auto& [k, v] : saved_) v == "\x01" ? UnsetEnv(k.c_str()) : SetEnv(k.c_str(), v);
    fs::remove_all(root_);
  }
  static std::string Find(const std::string& arg) { return silk_cpp::FindModel(arg); }
  static std::string Error(silk_status (*f)(const char*, char*, size_t, size_t*), const char* arg, silk_status want) {
    char buf[8];
    EXPECT_EQ(f(arg, buf, sizeof(buf), nullptr), want) << arg;
    return silk_last_error();
  }
  fs::path root_;
  std::map<std::string, std::string> saved_;
};

TEST_F(ModelFolders, TheModelsFolderFollowsSilkModelsThenXdgThenHome) {
  EXPECT_EQ(silk_cpp::ModelsDir(), (root_ / "models").string());
  EXPECT_EQ(silk_cpp::ModelsDir("silksong"), (root_ / "models" / "silksong").string());
#ifndef _WIN32
  UnsetEnv("SILK_MODELS");
  SetEnv("XDG_DATA_HOME", "/data/xdg");
  EXPECT_EQ(silk_cpp::ModelsDir(), "/data/xdg/silk/models");
  SetEnv("XDG_DATA_HOME", "relative/xdg");  // the XDG spec: a relative value is ignored
  SetEnv("HOME", "/home/artist");
  EXPECT_EQ(silk_cpp::ModelsDir(), "/home/artist/.local/share/silk/models");
  UnsetEnv("XDG_DATA_HOME");
  UnsetEnv("HOME");
  char buf[256];
  EXPECT_EQ(silk_models_dir(nullptr, buf, sizeof(buf), nullptr), SILK_ERR_IO);
  EXPECT_NE(std::string(silk_last_error()).find("SILK_MODELS"), std::string::npos) << silk_last_error();
#endif
}

TEST_F(ModelFolders, ANameIsNeverAPath) {
  for (const char* bad : {"", "..", ".", "../tiny-a", "a/b", "a\\b", "C:x", ".hidden", "-rf", "sp ace"}) {
    const std::string e = Error(silk_models_dir, bad, SILK_ERR_INVALID_ARGUMENT);
    EXPECT_NE(e.find("is not a model name"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_NO_THROW(silk_cpp::ModelsDir(std::string(100, 'a').c_str()));
  Error(silk_models_dir, std::string(101, 'a').c_str(), SILK_ERR_INVALID_ARGUMENT);
}

TEST_F(ModelFolders, PathsFollowTheSizeQueryRule) {
  size_t need = 0;
  ASSERT_EQ(silk_models_dir("tiny-a", nullptr, 0, &need), SILK_OK);
  const std::string want = (root_ / "models" / "tiny-a").string();
  EXPECT_EQ(need, want.size() + 1);  // bytes with the NUL
  std::string buf(need - 1, 'x');
  EXPECT_EQ(silk_models_dir("tiny-a", buf.data(), need - 1, nullptr), SILK_ERR_BUFFER_TOO_SMALL);
  EXPECT_EQ(buf, std::string(need - 1, 'x'));  // nothing written
  EXPECT_EQ(silk_models_dir("tiny-a", nullptr, 4, nullptr), SILK_ERR_INVALID_ARGUMENT);
}

// A Windows build tree has no bundled model beside its test programs (the source-tree fallback is
// for Linux build trees: a cross-build's source path means nothing on the Windows machine).
bool BuildTreeHasNoBundledModel() {
#ifdef _WIN32
  return true;
#else
  return false;
#endif
}

TEST_F(ModelFolders, FindTakesTheBundledModelAPathOrAName) {
  char buf[4096];
  if (BuildTreeHasNoBundledModel()) {
    const std::string e = Error(silk_model_find, "", SILK_ERR_IO);
    EXPECT_NE(e.find("no bundled model found (looked in:"), std::string::npos) << e;
  } else {
    const std::string bundled = Find("");
    EXPECT_TRUE(fs::is_regular_file(fs::path(bundled) / "model.json")) << bundled;
    EXPECT_EQ(silk_cpp::ModelDefaultDir(), bundled);
    ASSERT_EQ(silk_model_find(nullptr, buf, sizeof(buf), nullptr), SILK_OK);
    EXPECT_EQ(bundled, buf);
  }
  EXPECT_EQ(Find("tiny-a"), (root_ / "models" / "tiny-a").string());
  const std::string tiny = silk::testing::SourcePath("tests/models/tiny");
  EXPECT_EQ(Find(tiny), tiny);
  EXPECT_EQ(Find("no/such/folder"), "no/such/folder");  // a path: the loader names it
  const std::string e = Error(silk_model_find, "silksong", SILK_ERR_IO);
  EXPECT_NE(e.find("'silksong' is neither a folder nor a model in " + (root_ / "models" / "silksong").string()),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("import-official --name silksong"), std::string::npos) << e;
}

TEST_F(ModelFolders, AnExistingFolderWinsOverAName) {
  const fs::path cwd = fs::current_path();
  fs::create_directories(root_ / "cwd" / "tiny-a");
  fs::current_path(root_ / "cwd");
  const std::string found = Find("tiny-a");
  fs::current_path(cwd);
  EXPECT_EQ(found, "tiny-a");  // the folder in the working folder, not the models folder's
}

TEST_F(ModelFolders, LoadTakesAName) {
  if (!silk_generation_available()) GTEST_SKIP() << "no onnxruntime";
  silk_cpp::Model m = silk_cpp::Model::Load("tiny-a");
  EXPECT_GT(m.info().n_layers, 0);
  silk_model* h = nullptr;
  EXPECT_EQ(silk_model_load("no-such-model", nullptr, &h), SILK_ERR_IO);
  EXPECT_EQ(h, nullptr);
  EXPECT_NE(std::string(silk_last_error()).find("silk_model_load: 'no-such-model' is neither a folder nor a model in"),
            std::string::npos)
      << silk_last_error();
}

TEST_F(ModelFolders, ListDescribesEachModelWithoutLoadingIt) {
  if (!silk_generation_available()) GTEST_SKIP() << "no onnxruntime";
  fs::create_directories(root_ / "models" / "broken");
  std::ofstream(root_ / "models" / "broken" / "model.json") << "{ not json";
  fs::create_directories(root_ / "models" / ".hidden");  // not a name: not listed
  const nlohmann::json c = nlohmann::json::parse(silk_cpp::ModelsListJson());
  EXPECT_EQ(c["models_dir"], (root_ / "models").string());
  const size_t first = BuildTreeHasNoBundledModel() ? 0 : 1;  // the bundled model is listed first
  ASSERT_EQ(c["models"].size(), first + 2) << c.dump(1);
  if (first == 1) {
    EXPECT_EQ(c["models"][0]["name"], "default");
    EXPECT_EQ(c["models"][0]["bundled"], true);
    EXPECT_EQ(c["models"][0]["dir"], silk_cpp::ModelDefaultDir());
  }
  const nlohmann::json& broken = c["models"][first];
  EXPECT_EQ(broken["name"], "broken");
  EXPECT_TRUE(broken.contains("error")) << broken.dump();
  const nlohmann::json& tiny = c["models"][first + 1];
  EXPECT_EQ(tiny["name"], "tiny-a");
  EXPECT_EQ(tiny["bundled"], false);
  EXPECT_EQ(tiny["arch"], "silk");
  EXPECT_EQ(tiny["decoders"], nlohmann::json::array({"fp32"}));
  EXPECT_EQ(tiny["kv_precisions"], nlohmann::json::array({"fp32", "fp16", "int8"}));
  uintmax_t bytes = 0;
  for (const auto& f : fs::directory_iterator(root_ / "models" / "tiny-a")) bytes += f.file_size();
  EXPECT_EQ(tiny["bytes"], bytes);
  silk_report* r = nullptr;
  EXPECT_EQ(silk_models_list(nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(silk_models_list(&r), SILK_OK);
  silk_report_destroy(r);
}

}  // namespace
