// SPDX-License-Identifier: MIT
// std::filesystem on u8path for the apps' file checks.
#include "app_files.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

namespace silkapp {

namespace fs = std::filesystem;

fs::path FsPath(const std::string& utf8) { return fs::u8path(utf8); }

std::string Utf8(const fs::path& path) { return path.u8string(); }

std::FILE* OpenFile(const std::string& utf8, const char* mode) {
#ifdef _WIN32
  const std::wstring wide_mode(mode, mode + std::char_traits<char>::length(mode));
  return _wfopen(FsPath(utf8).c_str(), wide_mode.c_str());
#else
  return std::fopen(utf8.c_str(), mode);
#endif
}

std::string FileName(const std::string& path) { return FsPath(path).filename().u8string(); }

bool IsRegularFile(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(FsPath(path), ec);
}

bool IsDirectory(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(FsPath(path), ec);
}

std::string MakeDirectories(const std::string& path) {
  std::error_code ec;
  fs::create_directories(FsPath(path), ec);
  if (IsDirectory(path)) return "";
  return ec ? ec.message() : "not a folder";
}

CLI::Validator ExistingFile() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        std::error_code ec;
        const fs::file_status st = fs::status(FsPath(path), ec);
        if (ec || !fs::exists(st)) return "File does not exist: " + path;
        if (fs::is_directory(st)) return "File is actually a directory: " + path;
        return "";
      },
      "FILE");
}

}  // namespace silkapp
