// SPDX-License-Identifier: MIT
// Every path in Silk is UTF-8; Windows reads a narrow path in the ANSI code page, not UTF-8.
// The one place where a UTF-8 path becomes the operating system's path (and back): every
// engine file open, stat and folder walk goes through NativePath.
#pragma once
#include <filesystem>
#include <string>

namespace silk {

// The path std::filesystem / std::fstream / the OS take (UTF-16 on Windows, the bytes elsewhere).
std::filesystem::path NativePath(const std::string& utf8);
// Back to UTF-8, for messages and for paths handed on (e.g. a resolved folder).
std::string Utf8Path(const std::filesystem::path& path);

}  // namespace silk
