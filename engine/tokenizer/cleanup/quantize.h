// SPDX-License-Identifier: MIT
// Quantization to the 128-bin grid and back (token_format.md §2.2). Bit-exact with the reference:
// one double addition, exact scaling, truncation toward zero.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace silk {

// Quantized grid position, each coordinate in [0, 127].
struct QVec {
  int32_t x = 0, y = 0, z = 0;
  friend bool operator==(const QVec& a, const QVec& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
  friend bool operator!=(const QVec& a, const QVec& b) { return !(a == b); }
};

// (y, z, x) lexicographic order used for all geometric tie-breaking (token_format.md §1.2).
inline bool LessYZX(const QVec& a, const QVec& b) {
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.x < b.x;
}

int32_t QuantizeCoord(double c);    // min(trunc((c + 1) * 64), 127); c must be finite and >= -1
double DequantizeCoord(int32_t q);  // (q + 0.5) / 128 * 2 - 1
// Grid positions -> cell centres in [-1, 1], each coordinate by DequantizeCoord.
std::array<double, 3> DequantizePosition(const QVec& q);
std::vector<std::array<double, 3>> DequantizePositions(const std::vector<QVec>& grid);

}  // namespace silk
