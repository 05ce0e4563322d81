// SPDX-License-Identifier: MIT
// Numbers in hand-written JSON text: printf's "nan" / "inf" are not JSON (every reader then
// refuses the whole document), so a non-finite value is written as null, which is also what
// nlohmann::json's dump() writes for NaN and Infinity.
#pragma once

#include <string>

namespace silk {

// `value` printed with %.*g at `significant_digits` (9 reads a float back exactly, 17 a double),
// or "null" when it is NaN or +-Inf.
std::string JsonNumber(double value, int significant_digits = 17);

}  // namespace silk
