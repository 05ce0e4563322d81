// SPDX-License-Identifier: MIT
// Model-folder confinement: lexical checks (absolute paths, "..") first, then the resolved
// path (std::filesystem::canonical, symlinks followed) must lie under the resolved folder.
#include "runtime/model/model_files.h"

#include <cctype>
#include <filesystem>
#include <set>

#include "io/files/native_path.h"
#include "runtime/model/onnx_external_data.h"

namespace silk {

namespace {

namespace fs = std::filesystem;

Status Refuse(const std::string& named_by, const std::string& what, const std::string& location,
              const std::string& why) {
  return ParseError(named_by + ": " + what + " '" + location + "' " + why +
                    " (a model folder's files must stay inside it)");
}

// The lexical part: relative, no "..", no backslash or NUL, not empty.
Status CheckLexically(const std::string& location, const std::string& named_by, const std::string& what) {
  if (location.empty()) return Refuse(named_by, what, location, "is empty");
  if (location.find('\0') != std::string::npos) return Refuse(named_by, what, location, "holds a NUL byte");
  if (location.find('\\') != std::string::npos) return Refuse(named_by, what, location, "holds a backslash");
  if (location[0] == '/' ||
      (location.size() > 1 && std::isalpha(static_cast<unsigned char>(location[0])) && location[1] == ':'))
    return Refuse(named_by, what, location, "is an absolute path");
  size_t begin = 0;
  while (begin <= location.size()) {
    size_t slash = location.find('/', begin);
    if (slash == std::string::npos) slash = location.size();
    if (location.compare(begin, slash - begin, "..") == 0)
      return Refuse(named_by, what, location, "climbs out with '..'");
    begin = slash + 1;
  }
  return Status::Ok();
}

bool IsUnder(const fs::path& file, const fs::path& folder) {
  auto f = file.begin();
  for (auto d = folder.begin(); d != folder.end(); ++d, ++f)
    if (f == file.end() || *f != *d) return false;
  return f != file.end();
}

}  // namespace

Status CheckInsideModelFolder(const std::string& dir, const std::string& location, const std::string& named_by,
                              const std::string& what) {
  SILK_RETURN_IF_ERROR(CheckLexically(location, named_by, what));
  std::error_code ec;
  const fs::path folder = fs::canonical(NativePath(dir), ec);
  if (ec) return IoError(dir + ": model folder cannot be resolved (" + ec.message() + ")");
  const fs::path file = fs::canonical(NativePath(dir) / NativePath(location), ec);
  if (ec) return IoError(named_by + ": " + what + " '" + location + "' is missing in the model folder");
  if (!IsUnder(file, folder))
    return Refuse(named_by, what, location, "leads outside the model folder (to " + Utf8Path(file) + ")");
  if (!fs::is_regular_file(file, ec)) return Refuse(named_by, what, location, "is not a regular file");
  return Status::Ok();
}

Status CheckModelFolderFiles(const std::string& dir, const ModelConfig& config,
                             const std::vector<std::string>& onnx_files) {
  const std::string json = dir + "/model.json";
  std::vector<std::string> named = onnx_files;
  named.insert(named.end(), config.external_data.begin(), config.external_data.end());
  for (const std::string& f : named) SILK_RETURN_IF_ERROR(CheckInsideModelFolder(dir, f, json, "file"));
  for (const std::string& f : onnx_files) {
    const std::string path = dir + "/" + f;
    std::set<std::string> checked;  // a large graph names one data file hundreds of times
    SILK_RETURN_IF_ERROR(ForEachExternalDataLocationInFile(path, [&](const std::string& location) -> Status {
      if (checked.count(location)) return Status::Ok();
      SILK_RETURN_IF_ERROR(CheckInsideModelFolder(dir, location, path, "external data location"));
      if (checked.size() < 4096) checked.insert(location);
      return Status::Ok();
    }));
  }
  return Status::Ok();
}

}  // namespace silk
