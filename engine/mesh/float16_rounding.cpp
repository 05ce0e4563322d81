// SPDX-License-Identifier: MIT
// Nearest float16 by scaling into the half's integer grid: every half in a binade [2^e, 2^(e+1))
// is a multiple of 2^(e-10) (subnormals: of 2^-24), so rounding x / step to an integer with
// std::nearbyint (ties to even in the default rounding mode) and scaling back is exact.
#include "mesh/float16_rounding.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace silk {

double RoundToFloat16(double x) {
  if (!std::isfinite(x) || x == 0) return x;
  const double a = std::fabs(x);
  int exp = 0;
  std::frexp(a, &exp);                          // a = m * 2^exp, m in [0.5, 1): a in [2^(exp-1), 2^exp)
  const int e = std::max(exp - 1, -14);         // half exponent of the binade (-14: subnormal grid)
  const double step = std::ldexp(1.0, e - 10);  // spacing of halves in that binade
  double r = std::nearbyint(a / step) * step;   // a / step is exact (power-of-two scaling)
  if (r > 65504.0) r = std::numeric_limits<double>::infinity();  // past the largest half
  return std::copysign(r, x);
}

}  // namespace silk
