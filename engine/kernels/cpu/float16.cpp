// SPDX-License-Identifier: MIT
// IEEE binary16 <-> binary32 in plain C++: exact widening and round-to-nearest-even narrowing
// (what F16C does), for the ai.silk kernels' scalar rows and for CPUs without F16C.
#include "kernels/cpu/float16.h"

#include <cmath>
#include <cstring>

namespace silk {

float HalfToFloat(uint16_t h) {
  const uint32_t sign = static_cast<uint32_t>(h & 0x8000u) << 16, exp = (h >> 10) & 0x1fu, man = h & 0x3ffu;
  uint32_t bits;
  if (exp == 0x1f) {
    bits = sign | 0x7f800000u | (man << 13);
  } else if (exp != 0) {
    bits = sign | ((exp + 112) << 23) | (man << 13);
  } else if (man == 0) {
    bits = sign;
  } else {  // subnormal half: a normal float
    int e = -1;
    uint32_t m = man;
    do {
      ++e;
      m <<= 1;
    } while (!(m & 0x400u));
    bits = sign | static_cast<uint32_t>(112 - e) << 23 | ((m & 0x3ffu) << 13);
  }
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

uint16_t FloatToHalf(float f) {
  uint32_t x;
  std::memcpy(&x, &f, 4);
  const uint16_t sign = static_cast<uint16_t>((x >> 16) & 0x8000u);
  const uint32_t ax = x & 0x7fffffffu;
  if (ax >= 0x7f800000u) return sign | 0x7c00u | (ax > 0x7f800000u ? 0x200u : 0u);  // inf, nan
  if (ax >= 0x477ff000u) return sign | 0x7c00u;                                     // rounds past 65504
  if (ax < 0x38800000u) {  // below the smallest normal half: round onto the subnormal grid
    float scaled;
    const float a = std::fabs(f);
    scaled = a * 16777216.0f;  // 2^24: one subnormal step becomes 1
    return sign | static_cast<uint16_t>(std::nearbyint(scaled));
  }
  const uint32_t rounded = ax + 0xfffu + ((ax >> 13) & 1u);  // nearest, ties to even
  return sign | static_cast<uint16_t>((rounded - 0x38000000u) >> 13);
}

}  // namespace silk
