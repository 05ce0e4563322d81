// C API: the shared field checks of the params structs, so every flag, enum and sampling value
// is refused the same way, with a message naming the field and the value given (issue 20).
#include <cmath>
#include <sstream>
#include <string>

#include "capi/capi_internal.h"

namespace silk::capi {

std::string ValueText(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

Status CheckFlag(const char* field, int32_t value) {
  if (value == 0 || value == 1) return Status::Ok();
  return InvalidArgument(std::string(field) + " " + std::to_string(value) + " takes 0 or 1");
}

Status CheckEnum(const char* field, int32_t value, int32_t lo, int32_t hi, const char* type) {
  if (value >= lo && value <= hi) return Status::Ok();
  return InvalidArgument(std::string(field) + " " + std::to_string(value) + " is not a " + type + " (" +
                         std::to_string(lo) + ".." + std::to_string(hi) + ")");
}

Status CheckModelValueOr(const char* field, double value, double hi) {
  if (value == SILK_MODEL_VALUE || (std::isfinite(value) && value >= 0 && value <= hi)) return Status::Ok();
  const std::string range = std::isinf(hi) ? "a finite value >= 0" : "a value in [0, " + ValueText(hi) + "]";
  return InvalidArgument(std::string(field) + " " + ValueText(value) + " is neither SILK_MODEL_VALUE (-1: the model's) nor " +
                         range);
}

}  // namespace silk::capi
