// SPDX-License-Identifier: MIT
// The lookup order and the name rule of model_folders.h; environment variables are read as UTF-8
// (Windows: _wgetenv), so a user folder with any characters works.
#include "io/files/model_folders.h"

#include <cstdlib>

#include "io/files/file_system.h"
#include "io/files/module_folder.h"
#include "io/files/native_path.h"

#ifdef _WIN32
#include "core/windows_text.h"
#endif

#ifndef SILK_LIB_TO_DATA_REL
#define SILK_LIB_TO_DATA_REL "../share"
#endif

namespace silk {

namespace {

constexpr size_t kMaxNameLength = 100;

// The variable's value as UTF-8, "" when unset.
std::string Env(const char* name) {
#ifdef _WIN32
  const wchar_t* v = _wgetenv(WidePath(name).c_str());
  return v ? Utf8FromWide(v) : std::string();
#else
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
#endif
}

bool IsAbsolute(const std::string& p) {
#ifdef _WIN32
  return (p.size() > 2 && p[1] == ':' && (p[2] == '\\' || p[2] == '/')) ||
         (p.size() > 1 && p[0] == '\\' && p[1] == '\\');
#else
  return !p.empty() && p[0] == '/';
#endif
}

#ifdef _WIN32
constexpr char kSep = '\\';
#else
constexpr char kSep = '/';
#endif

std::string Join(const std::string& folder, const std::string& rel) {
  if (folder.empty()) return rel;
  const char last = folder.back();
  return (last == '/' || last == '\\') ? folder + rel : folder + kSep + rel;
}

// The folder without "." and ".." steps, so messages and lists show a plain path.
std::string Normal(const std::string& path) { return Utf8Path(NativePath(path).lexically_normal()); }

}  // namespace

StatusOr<std::string> UserModelsDir() {
  if (std::string v = Env("SILK_MODELS"); !v.empty()) return v;
#ifdef _WIN32
  if (std::string v = Env("LOCALAPPDATA"); !v.empty()) return Join(v, "silk\\models");
  return IoError("no models folder: neither SILK_MODELS nor LOCALAPPDATA is set");
#else
  if (std::string v = Env("XDG_DATA_HOME"); IsAbsolute(v)) return Join(v, "silk/models");
  if (std::string v = Env("HOME"); !v.empty()) return Join(v, ".local/share/silk/models");
  return IoError("no models folder: none of SILK_MODELS, XDG_DATA_HOME or HOME is set");
#endif
}

Status CheckModelName(const std::string& name) {
  bool ok = !name.empty() && name.size() <= kMaxNameLength && name[0] != '.' && name[0] != '-';
  for (const char c : name)
    ok = ok && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
                c == '-');
  if (ok) return Status::Ok();
  return InvalidArgument("'" + name + "' is not a model name (1-" + std::to_string(kMaxNameLength) +
                         " of A-Z a-z 0-9 . _ -, not starting with '.' or '-'; a folder is given by its path)");
}

StatusOr<std::string> UserModelDir(const std::string& name) {
  if (Status s = CheckModelName(name); !s.ok()) return s;
  auto dir = UserModelsDir();
  if (!dir.ok()) return dir.status();
  return Join(*dir, name);
}

std::vector<std::string> BundledModelCandidates() {
  std::vector<std::string> c;
  const std::string own = ModuleFolder();
  if (!own.empty()) {
    c.push_back(Normal(Join(own, "../model")));
    c.push_back(Normal(Join(own, SILK_LIB_TO_DATA_REL "/silk/models/default")));
    c.push_back(Normal(Join(own, "models/default")));
  }
#ifdef SILK_SOURCE_MODEL_DIR
  c.push_back(SILK_SOURCE_MODEL_DIR);
#endif
  return c;
}

StatusOr<std::string> BundledModelDir() {
  std::string tried;
  for (const std::string& d : BundledModelCandidates()) {
    if (IsRegularFile(Join(d, "model.json"))) return d;
    tried += "\n  " + d;
  }
  return IoError("no bundled model found (looked in:" + tried + ")");
}

StatusOr<std::string> ResolveModelDir(const std::string& name_or_dir) {
  if (name_or_dir.empty()) return BundledModelDir();
  if (IsDirectory(name_or_dir) || !CheckModelName(name_or_dir).ok()) return name_or_dir;
  auto dir = UserModelDir(name_or_dir);
  if (!dir.ok()) return IoError("'" + name_or_dir + "' is not a folder, and " + dir.status().message());
  if (IsDirectory(*dir)) return *dir;
  return IoError("'" + name_or_dir + "' is neither a folder nor a model in " + *dir +
                 " (silk-export import-official --name " + name_or_dir +
                 " puts one there; SILK_MODELS moves the models folder)");
}

}  // namespace silk
