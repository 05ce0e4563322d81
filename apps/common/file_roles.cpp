// SPDX-License-Identifier: MIT
// FileRoles (file_roles.h): files compared by identity (device and inode; on Windows the volume
// serial number and file index), so symlinks, hard links, "..", "./" and case variants on a
// case-insensitive file system are all the same file; write targets that do not exist yet are
// compared with each other by their absolute, normalised spelling.
#include "file_roles.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <system_error>

#include "app_files.h"

#ifdef _WIN32
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <sys/stat.h>
#endif

namespace silkapp {
namespace {

using Identity = std::pair<uint64_t, uint64_t>;

// The file's identity, following symlinks; false when it does not exist (or cannot be asked).
bool IdentityOf(const std::string& path, Identity* id) {
#ifdef _WIN32
  HANDLE h = CreateFileW(FsPath(path).c_str(), 0, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                         OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
  if (h == INVALID_HANDLE_VALUE) return false;
  BY_HANDLE_FILE_INFORMATION info;
  const bool ok = GetFileInformationByHandle(h, &info) != 0;
  CloseHandle(h);
  if (!ok) return false;
  *id = {info.dwVolumeSerialNumber, (static_cast<uint64_t>(info.nFileIndexHigh) << 32) | info.nFileIndexLow};
  return true;
#else
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return false;
  *id = {static_cast<uint64_t>(st.st_dev), static_cast<uint64_t>(st.st_ino)};
  return true;
#endif
}

// The absolute, normalised spelling (case-folded on Windows) of a path that may not exist yet.
std::string Spelling(const std::string& path) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::weakly_canonical(FsPath(path), ec);
  if (ec) p = std::filesystem::absolute(FsPath(path), ec).lexically_normal();
  std::string s = Utf8(p);
#ifdef _WIN32
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
#endif
  return s;
}

std::string Clash(const std::string& writer_role, const std::string& writer, const std::string& other_role,
                  const std::string& other, const char* why) {
  return writer_role + " " + writer + " is " + other_role + " " + other + " (" + why + ")";
}

}  // namespace

void FileRoles::Reads(const std::string& path, const std::string& role) { reads_.push_back({path, role}); }

void FileRoles::Writes(const std::string& path, const std::string& role) { writes_.push_back({path, role}); }

std::string FileRoles::Check() const {
  std::map<Identity, const File*> read_ids;
  for (const File& r : reads_) {
    Identity id;
    if (IdentityOf(r.path, &id)) read_ids.emplace(id, &r);
  }
  std::map<Identity, const File*> write_ids;
  std::map<std::string, const File*> spellings;
  for (const File& w : writes_) {
    Identity id;
    if (IdentityOf(w.path, &id)) {
      if (auto it = read_ids.find(id); it != read_ids.end())
        return Clash(w.role, w.path, it->second->role, it->second->path, "the same file") +
               ": Silk never writes to a file it reads";
      if (auto [it, fresh] = write_ids.emplace(id, &w); !fresh)
        return Clash(w.role, w.path, it->second->role, it->second->path, "the same file") +
               ": two outputs cannot share a file";
    }
    if (auto [it, fresh] = spellings.emplace(Spelling(w.path), &w); !fresh)
      return Clash(w.role, w.path, it->second->role, it->second->path, "the same path") +
             ": two outputs cannot share a file";
  }
  return "";
}

}  // namespace silkapp
