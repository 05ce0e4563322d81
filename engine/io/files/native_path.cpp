// SPDX-License-Identifier: MIT
// UTF-8 <-> native paths: on Windows through core/windows_text.h's conversions (CP_UTF8), so a
// path with non-ASCII characters opens the same file whatever the process's code page is.
#include "io/files/native_path.h"

#ifdef _WIN32
#include "core/windows_text.h"
#endif

namespace silk {

#ifdef _WIN32
std::filesystem::path NativePath(const std::string& utf8) { return std::filesystem::path(WidePath(utf8)); }
std::string Utf8Path(const std::filesystem::path& path) { return Utf8FromWide(path.wstring()); }
#else
std::filesystem::path NativePath(const std::string& utf8) { return std::filesystem::path(utf8); }
std::string Utf8Path(const std::filesystem::path& path) { return path.string(); }
#endif

}  // namespace silk
