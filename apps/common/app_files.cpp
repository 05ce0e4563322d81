// SPDX-License-Identifier: MIT
// std::filesystem on u8path for the apps' file checks; one atomic text write.
#include "app_files.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#ifdef _WIN32
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <unistd.h>
#endif

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

namespace {

// Replaces `to` by `from`; "" or the reason.
std::string ReplaceFile(const std::string& from, const std::string& to) {
#ifdef _WIN32
  if (MoveFileExW(FsPath(from).c_str(), FsPath(to).c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH))
    return "";
  const DWORD err = GetLastError();
  if (err == ERROR_SHARING_VIOLATION || err == ERROR_ACCESS_DENIED || err == ERROR_LOCK_VIOLATION)
    return "cannot replace the file: it is open in another program or read-only (the old file is kept; error " +
           std::to_string(err) + ")";
  return "rename failed (error " + std::to_string(err) + ")";
#else
  std::error_code ec;
  fs::rename(FsPath(from), FsPath(to), ec);
  return ec ? "rename failed: " + ec.message() : "";
#endif
}
}  // namespace

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

std::string WriteFileAtomically(const std::string& path, const std::string& bytes) {
#ifdef _WIN32
  const std::string tmp = path + ".tmp." + std::to_string(GetCurrentProcessId());
#else
  const std::string tmp = path + ".tmp." + std::to_string(getpid());
#endif
  {
    std::ofstream f(FsPath(tmp), std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!f.flush()) {
      std::error_code ec;
      fs::remove(FsPath(tmp), ec);
      return "cannot write";
    }
  }
  const std::string why = ReplaceFile(tmp, path);
  if (!why.empty()) {
    std::error_code ec;
    fs::remove(FsPath(tmp), ec);
  }
  return why;
}

}  // namespace silkapp
