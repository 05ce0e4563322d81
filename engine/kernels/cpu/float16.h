// SPDX-License-Identifier: MIT
// IEEE binary16 (float16) conversions shared by libsilk's CPU kernels: float16 KV cache rows
// and Int4MatMul's float16 block scales.
#pragma once
#include <cstdint>

namespace silk {

// Exact.
float HalfToFloat(uint16_t h);
// Round to nearest, ties to even; overflow to infinity, NaN stays NaN.
uint16_t FloatToHalf(float f);

}  // namespace silk
