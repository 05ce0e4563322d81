// SPDX-License-Identifier: MIT
// Whole-token number parsing with strtod_l ("C" locale) and std::from_chars.
#include "io/files/number_parse.h"

#include <charconv>
#include <clocale>
#include <cstdlib>
#include <locale.h>
#include <string>

namespace silk {

#ifndef _WIN32
namespace {
locale_t CLocale() {
  static locale_t loc = newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
  return loc;
}
}  // namespace
#endif

bool ParseDoubleToken(std::string_view token, double* out) {
  if (token.empty()) return false;
  // strtod needs a terminated string; copy the token (numbers are short).
  char small[128];
  std::string big;
  const char* s;
  if (token.size() < sizeof(small)) {
    token.copy(small, token.size());
    small[token.size()] = '\0';
    s = small;
  } else {
    big.assign(token);
    s = big.c_str();
  }
  unsigned char c0 = static_cast<unsigned char>(s[0]);
  if (c0 == ' ' || (c0 >= '\t' && c0 <= '\r')) return false;  // strtod would skip it
  char* end = nullptr;
#ifdef _WIN32
  // Windows has no newlocale/strtod_l; MinGW-w64's own strtod (gdtoa, correctly rounded, '.'
  // unless the host program changed LC_NUMERIC), not the C runtime's.
  double v = __mingw_strtod(s, &end);
#else
  double v = strtod_l(s, &end, CLocale());
#endif
  if (end != s + token.size()) return false;
  *out = v;
  return true;
}

bool ParseInt64Token(std::string_view token, int64_t* out) {
  const char* b = token.data();
  const char* e = b + token.size();
  if (b != e && *b == '+') ++b;
  if (b == e) return false;
  int64_t v = 0;
  auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e) return false;
  *out = v;
  return true;
}

}  // namespace silk
