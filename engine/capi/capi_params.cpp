// SPDX-License-Identifier: MIT
// C API: the shared field checks of the params structs, so every flag and enum is refused the
// same way, with a message naming the field and the value given (issue 20). Value ranges of the
// generation's settings are the runtime's one table (runtime/sampling/generation_ranges.h).
#include <string>

#include "capi/capi_internal.h"

namespace silk::capi {

Status CheckFlag(const char* field, int32_t value) {
  if (value == 0 || value == 1) return Status::Ok();
  return InvalidArgument(std::string(field) + " " + std::to_string(value) + " takes 0 or 1");
}

Status CheckEnum(const char* field, int32_t value, int32_t lo, int32_t hi, const char* type) {
  if (value >= lo && value <= hi) return Status::Ok();
  return InvalidArgument(std::string(field) + " " + std::to_string(value) + " is not a " + type + " (" +
                         std::to_string(lo) + ".." + std::to_string(hi) + ")");
}

}  // namespace silk::capi
