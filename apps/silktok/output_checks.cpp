// SPDX-License-Identifier: MIT
// silktok's up-front output check (output_checks.h).
#include "output_checks.h"

#include "../common/app_errors.h"
#include "../common/file_roles.h"
#include "commands.h"

namespace silktok {

int CheckOutputs(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs) {
  silkapp::FileRoles roles;
  for (const std::string& in : inputs) roles.Reads(in, "the input");
  for (const std::string& out : outputs) {
    roles.Writes(out, "the output");
    try {
      silk_cpp::CheckOutputPath(out);
    } catch (const silk_cpp::Error& e) {
      silkapp::PrintError("silktok", e);
      return kExitFailure;
    }
  }
  if (std::string why = roles.Check(); !why.empty()) {
    silkapp::PrintError("silktok", SILK_ERR_INVALID_ARGUMENT, why);
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace silktok
