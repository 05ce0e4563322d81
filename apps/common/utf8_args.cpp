// SPDX-License-Identifier: MIT
// GetCommandLineW + CommandLineToArgvW -> UTF-8 (Windows only).
#include "utf8_args.h"

#ifdef _WIN32
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#include <shellapi.h>

#include <string>
#include <vector>
#endif

namespace silkapp {

#ifdef _WIN32
void UseUtf8Arguments(int& argc, char**& argv) {
  SetConsoleOutputCP(CP_UTF8);
  int n = 0;
  wchar_t** wide = CommandLineToArgvW(GetCommandLineW(), &n);
  if (!wide) return;  // keep the ANSI arguments rather than none
  static std::vector<std::string> storage;
  static std::vector<char*> pointers;
  storage.clear();
  for (int i = 0; i < n; ++i) {
    const int len = WideCharToMultiByte(CP_UTF8, 0, wide[i], -1, nullptr, 0, nullptr, nullptr);
    std::string s(len > 0 ? static_cast<size_t>(len - 1) : 0, '\0');
    if (len > 1) WideCharToMultiByte(CP_UTF8, 0, wide[i], -1, s.data(), len, nullptr, nullptr);
    storage.push_back(std::move(s));
  }
  LocalFree(wide);
  pointers.clear();
  for (std::string& s : storage) pointers.push_back(s.data());
  pointers.push_back(nullptr);
  argc = n;
  argv = pointers.data();
}
#else
void UseUtf8Arguments(int&, char**&) {}
#endif

}  // namespace silkapp
