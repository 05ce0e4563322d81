// SPDX-License-Identifier: MIT
// Small file-system helpers (std::filesystem on NativePath's UTF-8 paths, no exceptions escaping).
#include "io/files/file_system.h"

#include <filesystem>
#include <system_error>

#include "io/files/native_path.h"

namespace silk {

bool IsDirectory(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_directory(NativePath(path), ec);
}

bool IsRegularFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(NativePath(path), ec);
}

Status MakeDirectories(const std::string& path) {
  std::error_code ec;
  std::filesystem::create_directories(NativePath(path), ec);
  if (ec || !IsDirectory(path)) return IoError(path + ": cannot create folder: " + ec.message());
  return Status::Ok();
}

}  // namespace silk
