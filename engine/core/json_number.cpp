// SPDX-License-Identifier: MIT
// See json_number.h: one place that turns a number into JSON text.
#include "core/json_number.h"

#include <cmath>
#include <cstdio>

namespace silk {

std::string JsonNumber(double value, int significant_digits) {
  if (!std::isfinite(value)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.*g", significant_digits, value);
  return buf;
}

}  // namespace silk
