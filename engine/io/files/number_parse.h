// SPDX-License-Identifier: MIT
// Strict number parsing for the text readers: a token must be a whole number, nothing else.
// Doubles go through strtod in the "C" locale (correctly rounded, locale-independent) so the
// golden meshes read to the exact same doubles as the reference.
#pragma once
#include <cstdint>
#include <string_view>

namespace silk {

// Parses the whole token as a double (accepts nan/inf; callers reject non-finite values).
bool ParseDoubleToken(std::string_view token, double* out);

// Parses the whole token as a base-10 integer with optional sign.
bool ParseInt64Token(std::string_view token, int64_t* out);

}  // namespace silk
