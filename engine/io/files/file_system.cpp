// Small file-system helpers (std::filesystem, no exceptions escaping).
#include "io/files/file_system.h"

#include <filesystem>
#include <system_error>

namespace silk {

bool IsDirectory(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec);
}

bool IsRegularFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

Status MakeDirectories(const std::string& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec || !IsDirectory(path)) return IoError(path + ": cannot create folder: " + ec.message());
  return Status::Ok();
}

}  // namespace silk
