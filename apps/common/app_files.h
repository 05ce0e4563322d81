// SPDX-License-Identifier: MIT
// The apps' own file-system calls (libsilk opens the meshes, models and token files itself):
// folder checks and the input-exists check of the command line (libsilk writes every output,
// silk_file_write), all on
// UTF-8 paths (std::filesystem::u8path: Windows reads a plain narrow path in the ANSI code page).
#pragma once
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <string>

namespace silkapp {

// The last component of a path ("/" or, on Windows, "\\" or "/" separates; "C:x" counts too).
std::string FileName(const std::string& path);
bool IsRegularFile(const std::string& path);
// A UTF-8 path as a std::filesystem::path (u8path) and back (u8string), for the apps' own
// folder walks and path arithmetic.
std::filesystem::path FsPath(const std::string& utf8);
std::string Utf8(const std::filesystem::path& path);
// std::fopen of a UTF-8 path (_wfopen on Windows); nullptr and errno on failure.
std::FILE* OpenFile(const std::string& utf8, const char* mode);
bool IsDirectory(const std::string& path);
// mkdir -p; "" when done (or already a folder), else the reason.
std::string MakeDirectories(const std::string& path);
// CLI::ExistingFile for UTF-8 paths (CLI11's own check reads the path in the ANSI code page).
CLI::Validator ExistingFile();

}  // namespace silkapp
