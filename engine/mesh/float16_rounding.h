// SPDX-License-Identifier: MIT
// Rounding doubles to the nearest IEEE half-precision value: the official pre-processing casts
// its sampled points and normals to float16 (official_network.md §4), and the network was trained
// on such values, so Silk reproduces the cast exactly (round to nearest, ties to even).
#pragma once

namespace silk {

// The float16 value nearest to x (ties to even), returned as a double; +-inf beyond the
// float16 range (65520 and up), NaN stays NaN, subnormal halves are honoured.
double RoundToFloat16(double x);

}  // namespace silk
