// SPDX-License-Identifier: MIT
// silktok's one error format, "silktok: <kind>: <file>: <problem>", over the library's errors
// (silk_cpp::Error; the kind names are silk_status_name's) and the few the tool finds itself.
#pragma once
#include <string>

#include "silk/silk.hpp"

namespace silktok {

// The same error with `prefix` in front of its message (what() keeps "<kind>: " first).
silk_cpp::Error WithContext(const silk_cpp::Error& e, const std::string& prefix);
// An error silktok itself detects (a folder it cannot create), in the library's format.
silk_cpp::Error AppError(silk_status status, const std::string& message);
// "silktok: <kind>: <message>" on stderr.
void ReportError(const silk_cpp::Error& e);

}  // namespace silktok
