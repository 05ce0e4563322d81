// SPDX-License-Identifier: MIT
// Output path checks (output_path.h): the name by the platform's rules, then the folder.
#include "io/files/output_path.h"

#include <cctype>
#include <filesystem>
#include <system_error>

#include "io/files/native_path.h"

#ifndef _WIN32
#include <unistd.h>
#endif

namespace silk {
namespace {

Status Bad(const std::string& path, const std::string& why) {
  return InvalidArgument(path + ": cannot be an output file: " + why);
}

#ifdef _WIN32
// "CON", "nul.txt", "COM1.tar.gz", "LPT9 " : a device on every Windows folder.
bool IsReservedWindowsName(const std::string& name) {
  std::string base = name.substr(0, name.find('.'));
  while (!base.empty() && base.back() == ' ') base.pop_back();
  for (char& c : base) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (base == "CON" || base == "PRN" || base == "AUX" || base == "NUL" || base == "CONIN$" || base == "CONOUT$")
    return true;
  return base.size() == 4 && (base.compare(0, 3, "COM") == 0 || base.compare(0, 3, "LPT") == 0) &&
         std::isdigit(static_cast<unsigned char>(base[3]));
}

Status CheckWindowsName(const std::string& path, const std::string& name) {
  if (IsReservedWindowsName(name)) return Bad(path, "'" + name + "' is a reserved device name on Windows");
  for (char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || std::string("<>:\"|?*").find(c) != std::string::npos)
      return Bad(path,
                 "the file name holds a character Windows does not allow in names (<>:\"|?* or a control character)");
  if (name.back() == '.' || name.back() == ' ')
    return Bad(path, "a file name ending in a dot or space is not kept by Windows");
  if (NativePath(path).wstring().size() >= 260 && path.rfind("\\\\?\\", 0) != 0)
    return Bad(path, "longer than Windows' MAX_PATH (260 characters); prefix an absolute path with \\\\?\\");
  return Status::Ok();
}
#endif

size_t NameLimit(const std::string& folder) {
#ifdef _WIN32
  (void)folder;
  return 255;  // UTF-16 units on NTFS; counted in bytes here, which is never fewer
#else
  const long n = ::pathconf(folder.c_str(), _PC_NAME_MAX);
  return n > 0 ? static_cast<size_t>(n) : 255;
#endif
}

}  // namespace

Status CheckOutputPath(const std::string& path) {
  if (path.empty()) return InvalidArgument("empty output path");
  if (path.find('\0') != std::string::npos) return Bad(path, "the path holds a NUL byte");
  namespace fs = std::filesystem;
  const fs::path p = NativePath(path);
  const std::string name = Utf8Path(p.filename());
  if (name.empty() || name == "." || name == "..") return Bad(path, "names a folder, not a file");
  std::error_code ec;
  if (fs::is_directory(p, ec)) return Bad(path, "is a folder");
  fs::path folder = p.parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, ec))
    return IoError(path + ": cannot be an output file: its folder " + Utf8Path(folder) + " does not exist");
  const size_t limit = NameLimit(Utf8Path(folder));
  if (name.size() > limit)
    return Bad(path, "the file name is " + std::to_string(name.size()) +
                         " bytes; this file system holds names of at most " + std::to_string(limit));
#ifdef _WIN32
  SILK_RETURN_IF_ERROR(CheckWindowsName(path, name));
#endif
  return Status::Ok();
}

}  // namespace silk
