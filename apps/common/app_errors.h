// SPDX-License-Identifier: MIT
// The one error line of silkgen and silktok, "<tool>: <kind>: <file>[:<line>]: <problem>", kind
// being libsilk's status name (silk_status_name: "invalid argument", "I/O error", "parse error",
// ...), for the library's errors and the few the tools find themselves alike.
#pragma once
#include <string>

#include "silk/silk.hpp"

namespace silkapp {

// "<kind>: <message>" (what a report or a summary line quotes).
std::string ErrorText(silk_status kind, const std::string& message);
// "<tool>: <kind>: <message>" on stderr.
void PrintError(const char* tool, silk_status kind, const std::string& message);
void PrintError(const char* tool, const silk_cpp::Error& e);

}  // namespace silkapp
