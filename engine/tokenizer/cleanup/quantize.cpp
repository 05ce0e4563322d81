// SPDX-License-Identifier: MIT
// Quantization to the 128-bin grid and back (token_format.md §2.2).
#include "tokenizer/cleanup/quantize.h"

#include "tokenizer/vocabulary_layout.h"

namespace silk {

int32_t QuantizeCoord(double c) {
  // ((c + 1.0) * 128) / 2: the addition is the only rounding step; *128 and /2 are exact.
  const double t = ((c + 1.0) * vocab::k_quant_bins) / 2.0;
  int32_t q = static_cast<int32_t>(t);  // truncation toward zero
  if (q > vocab::k_quant_bins - 1) q = vocab::k_quant_bins - 1;
  if (q < 0) q = 0;  // inputs below -1 are outside the format; clamp instead of UB
  return q;
}

double DequantizeCoord(int32_t q) { return (q + 0.5) / vocab::k_quant_bins * 2.0 - 1.0; }

std::array<double, 3> DequantizePosition(const QVec& q) {
  return {DequantizeCoord(q.x), DequantizeCoord(q.y), DequantizeCoord(q.z)};
}

std::vector<std::array<double, 3>> DequantizePositions(const std::vector<QVec>& grid) {
  std::vector<std::array<double, 3>> out;
  out.reserve(grid.size());
  for (const QVec& q : grid) out.push_back(DequantizePosition(q));
  return out;
}

}  // namespace silk
