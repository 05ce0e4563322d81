// SPDX-License-Identifier: MIT
// Linux: dladdr on one of this module's own functions; Windows: GetModuleHandleExW(FROM_ADDRESS).
#include "io/files/module_folder.h"

#ifdef _WIN32
#include "core/windows_text.h"
#else
#include <dlfcn.h>
#include <limits.h>
#include <stdlib.h>
#endif

namespace silk {

#ifdef _WIN32
std::string ModuleFolder() {
  HMODULE module = nullptr;
  if (!GetModuleHandleExW(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                          reinterpret_cast<LPCWSTR>(&ModuleFolder), &module))
    return "";
  std::wstring w(32768, L'\0');
  w.resize(GetModuleFileNameW(module, w.data(), static_cast<DWORD>(w.size())));
  const size_t slash = w.find_last_of(L"\\/");
  return slash == std::wstring::npos ? "" : Utf8FromWide(w.substr(0, slash));
}
#else
std::string ModuleFolder() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&ModuleFolder), &info) || !info.dli_fname) return "";
  char buf[PATH_MAX];
  const std::string p = realpath(info.dli_fname, buf) ? std::string(buf) : std::string(info.dli_fname);
  const size_t slash = p.rfind('/');
  return slash == std::string::npos ? "" : p.substr(0, slash);
}
#endif

}  // namespace silk
