// SPDX-License-Identifier: MIT
// The tools' error line (app_errors.h).
#include "app_errors.h"

#include <cstdio>

namespace silkapp {

std::string ErrorText(silk_status kind, const std::string& message) {
  return std::string(silk_status_name(kind)) + ": " + message;
}

void PrintError(const char* tool, silk_status kind, const std::string& message) {
  std::fprintf(stderr, "%s: %s\n", tool, ErrorText(kind, message).c_str());
}

void PrintError(const char* tool, const silk_cpp::Error& e) { PrintError(tool, e.status(), e.message()); }

}  // namespace silkapp
