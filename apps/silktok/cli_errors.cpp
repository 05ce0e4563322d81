// SPDX-License-Identifier: MIT
// silktok's error messages: the library's status name, then the message with its context.
#include "cli_errors.h"

#include "../common/app_errors.h"

namespace silktok {

silk_cpp::Error WithContext(const silk_cpp::Error& e, const std::string& prefix) {
  return AppError(e.status(), prefix + e.message());
}

silk_cpp::Error AppError(silk_status status, const std::string& message) {
  return silk_cpp::Error(status, silkapp::ErrorText(status, message), message);
}

void ReportError(const silk_cpp::Error& e) { silkapp::PrintError("silktok", e); }

}  // namespace silktok
