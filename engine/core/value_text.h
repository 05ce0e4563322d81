// SPDX-License-Identifier: MIT
// A number as messages show it ("-0.5", "nan", "inf"), so every "field value ..." message of
// the runtime and the C API writes a value the same way.
#pragma once
#include <sstream>
#include <string>

namespace silk {

inline std::string ValueText(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace silk
