// SPDX-License-Identifier: MIT
// The binary's own folder comes from /proc/self/exe (Windows: GetModuleFileNameW), so the
// lookup works from any cwd.
#include "model_locate.h"

#ifdef _WIN32
#include <windows.h>
#else
#include <unistd.h>
#endif

#include <climits>

#include "../common/app_files.h"

namespace silkgen {

namespace {

#ifdef _WIN32
// Windows: GetModuleFileNameW, as UTF-8 (the encoding of every path Silk's API takes).
std::string ExeDir() {
  std::wstring w(32768, L'\0');
  w.resize(GetModuleFileNameW(nullptr, w.data(), static_cast<DWORD>(w.size())));
  const size_t slash = w.find_last_of(L"\\/");
  if (w.empty() || slash == std::wstring::npos) return "";
  const int n = WideCharToMultiByte(CP_UTF8, 0, w.data(), static_cast<int>(slash), nullptr, 0, nullptr, nullptr);
  std::string p(static_cast<size_t>(n), '\0');
  WideCharToMultiByte(CP_UTF8, 0, w.data(), static_cast<int>(slash), p.data(), n, nullptr, nullptr);
  return p;
}
#else
std::string ExeDir() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) return "";
  std::string p(buf, static_cast<size_t>(n));
  const size_t slash = p.rfind('/');
  return slash == std::string::npos ? "" : p.substr(0, slash);
}
#endif

}  // namespace

std::vector<std::string> DefaultModelCandidates() {
  std::vector<std::string> c;
  const std::string exe = ExeDir();
#ifdef SILK_INSTALLED_MODEL_REL
  if (!exe.empty()) c.push_back(exe + "/" + SILK_INSTALLED_MODEL_REL);
#endif
#ifdef SILK_SOURCE_MODEL_DIR
  c.push_back(SILK_SOURCE_MODEL_DIR);
#endif
  return c;
}

std::string DefaultModelDir() {
  for (const std::string& d : DefaultModelCandidates())
    if (silkapp::IsRegularFile(d + "/model.json")) return d;
  return "";
}

}  // namespace silkgen
