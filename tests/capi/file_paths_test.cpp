// SPDX-License-Identifier: MIT
// Paths and files as each platform has them, through the public API: UTF-8 paths with non-ASCII
// characters (a folder "Ünïcødé 形状" holding the mesh, the model and the outputs), CRLF text
// files, outputs replacing existing files; on Windows (run under Wine by scripts/test_windows.sh)
// also backslashes, drive letters, and files held open by another handle. Windows enforces
// sharing per open handle, whichever process holds it, so a handle held here stands for another
// program's (an editor, a viewer, Blender).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/files/native_path.h"
#include "io/tokens/token_text.h"
#include "silk/silk.h"
#include "support/test_paths.h"

#ifdef _WIN32
#include <windows.h>
#else
#include <unistd.h>
#endif

namespace {

namespace fs = std::filesystem;

const char* const kUnicodeFolder = u8"Ünïcødé 形状";

int ProcessId() {
#ifdef _WIN32
  return static_cast<int>(GetCurrentProcessId());
#else
  return static_cast<int>(getpid());
#endif
}

// <temp>/silk-paths-<pid>, removed when the test program ends.
const std::string& TempBase() {
  struct Base {
    std::string path = silk::Utf8Path(fs::temp_directory_path()) + "/silk-paths-" + std::to_string(ProcessId());
    ~Base() {
      std::error_code ec;
      fs::remove_all(silk::NativePath(path), ec);
    }
  };
  static const Base base;
  return base.path;
}

// A fresh folder <temp>/silk-paths-<pid>/<name> (UTF-8 path).
std::string TempFolder(const std::string& name) {
  const std::string dir = TempBase() + "/" + name;
  std::error_code ec;
  fs::remove_all(silk::NativePath(dir), ec);
  fs::create_directories(silk::NativePath(dir));
  return dir;
}

// A writable copy (the shared spec files are read-only, which Windows would keep on the copy and
// then refuse to delete).
void CopyWritable(const std::string& from, const std::string& to) {
  fs::copy_file(silk::NativePath(from), silk::NativePath(to), fs::copy_options::overwrite_existing);
  fs::permissions(silk::NativePath(to), fs::perms::owner_write, fs::perm_options::add);
}

std::string ReadAll(const std::string& path) {
  std::ifstream f(silk::NativePath(path), std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void WriteAll(const std::string& path, const std::string& bytes) {
  std::ofstream f(silk::NativePath(path), std::ios::binary | std::ios::trunc);
  f << bytes;
}

std::string WithCrlf(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

std::vector<int32_t> GoldenIds(const std::string& name) {
  auto ids = silk::ReadTokenText(silk::testing::SharedPath("spec/golden/" + name + ".tokens.txt"));
  EXPECT_TRUE(ids.ok()) << ids.status().ToString();
  return ids.ok() ? *ids : std::vector<int32_t>{};
}

std::vector<int32_t> Ids(const silk_tokens* t) {
  size_t n = 0;
  EXPECT_EQ(silk_tokens_copy(t, nullptr, 0, &n), SILK_OK);
  std::vector<int32_t> ids(n);
  if (n) {
    EXPECT_EQ(silk_tokens_copy(t, ids.data(), n, &n), SILK_OK);
  }
  return ids;
}

// Loads a mesh file and encodes it; the ids, or none on failure (with the library's message).
std::vector<int32_t> EncodeFile(const std::string& path) {
  silk_mesh* mesh = nullptr;
  if (silk_mesh_load(path.c_str(), nullptr, &mesh) != SILK_OK) {
    ADD_FAILURE() << path << ": " << silk_last_error();
    return {};
  }
  silk_tokens* tokens = nullptr;
  EXPECT_EQ(silk_mesh_encode(mesh, nullptr, &tokens, nullptr), SILK_OK) << silk_last_error();
  std::vector<int32_t> ids = tokens ? Ids(tokens) : std::vector<int32_t>{};
  silk_tokens_destroy(tokens);
  silk_mesh_destroy(mesh);
  return ids;
}

std::vector<int32_t> LoadIds(const std::string& path) {
  silk_tokens* t = nullptr;
  if (silk_tokens_load(path.c_str(), &t) != SILK_OK) {
    ADD_FAILURE() << path << ": " << silk_last_error();
    return {};
  }
  std::vector<int32_t> ids = Ids(t);
  silk_tokens_destroy(t);
  return ids;
}

silk_status SaveIds(const std::vector<int32_t>& ids, const std::string& path) {
  silk_tokens* t = nullptr;
  EXPECT_EQ(silk_tokens_create(ids.data(), ids.size(), &t), SILK_OK);
  const silk_status s = silk_tokens_save(t, path.c_str());
  silk_tokens_destroy(t);
  return s;
}

// The names in a folder, as the file system spells them (UTF-16 on Windows, bytes elsewhere).
std::vector<fs::path::string_type> Names(const std::string& dir) {
  std::vector<fs::path::string_type> names;
  for (const auto& e : fs::directory_iterator(silk::NativePath(dir))) names.push_back(e.path().filename().native());
  return names;
}

bool HasName(const std::string& dir, const fs::path::string_type& name) {
  for (const auto& n : Names(dir))
    if (n == name) return true;
  return false;
}

TEST(FilePaths, NonAsciiFolderHoldsTheMeshAndTheOutputs) {
  const std::string dir = TempFolder(kUnicodeFolder);
  // The folder really carries the characters (not "??"): its name as the OS stores it.
#ifdef _WIN32
  EXPECT_TRUE(HasName(dir + "/..", L"\u00dcn\u00efc\u00f8d\u00e9 \u5f62\u72b6"));
#else
  EXPECT_TRUE(HasName(dir + "/..",
                      "\xc3\x9cn\xc3\xaf"
                      "c\xc3\xb8"
                      "d\xc3\xa9 \xe5\xbd\xa2\xe7\x8a\xb6"));
#endif
  const std::string mesh = dir + u8"/würfel 立方体.obj";
  CopyWritable(silk::testing::SharedPath("spec/golden/cube.obj"), mesh);
  const std::vector<int32_t> golden = GoldenIds("cube");
  ASSERT_FALSE(golden.empty());
  EXPECT_EQ(EncodeFile(mesh), golden);

  const std::string tokens = dir + u8"/würfel 立方体.tokens.txt";
  ASSERT_EQ(SaveIds(golden, tokens), SILK_OK) << silk_last_error();
  EXPECT_EQ(LoadIds(tokens), golden);

  for (const char* name : {u8"/出力.glb", u8"/出力.obj", u8"/出力.ply"}) {
    silk_mesh* m = nullptr;
    ASSERT_EQ(silk_mesh_load(mesh.c_str(), nullptr, &m), SILK_OK) << silk_last_error();
    const std::string out = dir + name;
    EXPECT_EQ(silk_mesh_save(m, out.c_str(), nullptr), SILK_OK) << out << ": " << silk_last_error();
    silk_mesh_destroy(m);
    EXPECT_EQ(EncodeFile(out), golden) << out;
  }
}

TEST(FilePaths, MissingNonAsciiFileIsNamedInTheMessage) {
  const std::string missing = TempFolder(kUnicodeFolder) + u8"/fehlt 缺失.obj";
  silk_mesh* m = nullptr;
  EXPECT_EQ(silk_mesh_load(missing.c_str(), nullptr, &m), SILK_ERR_IO);
  EXPECT_EQ(m, nullptr);
  EXPECT_NE(std::string(silk_last_error()).find(missing), std::string::npos) << silk_last_error();
}

TEST(FilePaths, CrlfTokenAndMeshFilesReadAsLf) {
  const std::string dir = TempFolder("crlf");
  const std::vector<int32_t> golden = GoldenIds("cube");
  const std::string tokens = dir + "/cube.tokens.txt";
  WriteAll(tokens, WithCrlf(ReadAll(silk::testing::SharedPath("spec/golden/cube.tokens.txt"))));
  ASSERT_NE(ReadAll(tokens).find("\r\n"), std::string::npos);
  EXPECT_EQ(LoadIds(tokens), golden);
  const std::string obj = dir + "/cube.obj";
  WriteAll(obj, WithCrlf(ReadAll(silk::testing::SharedPath("spec/golden/cube.obj"))));
  EXPECT_EQ(EncodeFile(obj), golden);
}

TEST(FilePaths, SavingReplacesAnExistingFile) {
  const std::string out = TempFolder(kUnicodeFolder) + "/out.tokens.txt";
  ASSERT_EQ(SaveIds({1, 2, 3}, out), SILK_OK) << silk_last_error();
  ASSERT_EQ(SaveIds({4, 5}, out), SILK_OK) << silk_last_error();  // NTFS: rename onto an existing file
  EXPECT_EQ(ReadAll(out), "4\n5\n");
}

TEST(FilePaths, NonAsciiModelFolderWithCrlfModelJson) {
  if (!silk_generation_available()) GTEST_SKIP() << "built without onnxruntime";
  const std::string dir = TempFolder(kUnicodeFolder) + u8"/modèle 模型";
  fs::create_directories(silk::NativePath(dir));
  const std::string tiny = silk::testing::SourcePath("tests/models/tiny");
  for (const char* f : {"encoder.onnx", "decoder.onnx"}) CopyWritable(tiny + "/" + f, dir + "/" + f);
  WriteAll(dir + "/model.json", WithCrlf(ReadAll(tiny + "/model.json")));
  ASSERT_NE(ReadAll(dir + "/model.json").find("\r\n"), std::string::npos);
  silk_model* model = nullptr;
  ASSERT_EQ(silk_model_load(dir.c_str(), nullptr, &model), SILK_OK) << silk_last_error();
  silk_model_info info{};
  info.struct_size = sizeof info;
  EXPECT_EQ(silk_model_get_info(model, &info), SILK_OK);
  EXPECT_STREQ(info.config, "test-tiny");
  silk_model_destroy(model);
}

#ifdef _WIN32
std::string Backslashed(std::string p) {
  for (char& c : p)
    if (c == '/') c = '\\';
  return p;
}

TEST(FilePaths, BackslashesAndDriveLetters) {
  const std::string golden_obj = Backslashed(silk::testing::SharedPath("spec/golden/cube.obj"));
  ASSERT_EQ(golden_obj.substr(1, 2), ":\\") << golden_obj;  // Z:\... under Wine
  EXPECT_EQ(EncodeFile(golden_obj), GoldenIds("cube"));
  const std::string out = Backslashed(TempFolder(kUnicodeFolder) + "/back.tokens.txt");
  ASSERT_EQ(out.find('/'), std::string::npos) << out;
  EXPECT_EQ(SaveIds({7, 8}, out), SILK_OK) << silk_last_error();
  EXPECT_EQ(LoadIds(out), (std::vector<int32_t>{7, 8}));
  if (silk_generation_available()) {
    silk_model* model = nullptr;
    EXPECT_EQ(silk_model_load(Backslashed(silk::testing::SourcePath("tests/models/tiny")).c_str(), nullptr, &model),
              SILK_OK)
        << silk_last_error();
    silk_model_destroy(model);
  }
}

// Another program's handle on `path` with the given sharing (released by the destructor).
struct HeldOpen {
  HANDLE h;
  HeldOpen(const std::string& path, DWORD access, DWORD share)
      : h(CreateFileW(silk::NativePath(path).c_str(), access, share, nullptr, OPEN_EXISTING, 0, nullptr)) {}
  ~HeldOpen() {
    if (h != INVALID_HANDLE_VALUE) CloseHandle(h);
  }
};

TEST(FilePaths, ReadsAFileAnotherProgramHasOpenForWriting) {
  const std::string mesh = TempFolder(kUnicodeFolder) + "/open.obj";
  CopyWritable(silk::testing::SharedPath("spec/golden/cube.obj"), mesh);
  HeldOpen editor(mesh, GENERIC_READ | GENERIC_WRITE, FILE_SHARE_READ | FILE_SHARE_WRITE);
  ASSERT_NE(editor.h, INVALID_HANDLE_VALUE);
  EXPECT_EQ(EncodeFile(mesh), GoldenIds("cube"));
}

TEST(FilePaths, FileLockedByAnotherProgramIsAnErrorNamingIt) {
  const std::string mesh = TempFolder(kUnicodeFolder) + "/locked.obj";
  CopyWritable(silk::testing::SharedPath("spec/golden/cube.obj"), mesh);
  HeldOpen exclusive(mesh, GENERIC_READ | GENERIC_WRITE, 0);
  ASSERT_NE(exclusive.h, INVALID_HANDLE_VALUE);
  silk_mesh* m = nullptr;
  EXPECT_EQ(silk_mesh_load(mesh.c_str(), nullptr, &m), SILK_ERR_IO);
  EXPECT_NE(std::string(silk_last_error()).find(mesh), std::string::npos) << silk_last_error();
}

TEST(FilePaths, ReplacingAnOutputAnotherProgramHoldsOpenFailsAndKeepsIt) {
  const std::string dir = TempFolder(kUnicodeFolder);
  const std::string out = dir + u8"/gehalten 保持.tokens.txt";
  ASSERT_EQ(SaveIds({1, 2, 3}, out), SILK_OK) << silk_last_error();
  {
    HeldOpen viewer(out, GENERIC_READ, FILE_SHARE_READ | FILE_SHARE_WRITE);  // no FILE_SHARE_DELETE
    ASSERT_NE(viewer.h, INVALID_HANDLE_VALUE);
    EXPECT_EQ(SaveIds({4, 5}, out), SILK_ERR_IO);
    const std::string msg = silk_last_error();
    EXPECT_NE(msg.find(out), std::string::npos) << msg;
    EXPECT_NE(msg.find("open in another program"), std::string::npos) << msg;
    EXPECT_EQ(ReadAll(out), "1\n2\n3\n");  // the old file, whole
    EXPECT_EQ(Names(dir).size(), 1u);      // no temporary file left behind
  }
  EXPECT_EQ(SaveIds({4, 5}, out), SILK_OK) << silk_last_error();  // closed: the replace goes through
  EXPECT_EQ(ReadAll(out), "4\n5\n");
}
#endif  // _WIN32

}  // namespace
