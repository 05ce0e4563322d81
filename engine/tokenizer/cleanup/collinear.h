// SPDX-License-Identifier: MIT
// Zero-area test on grid positions (token_format.md §2.4 step 3): the integer cross product of two edge
// vectors is the zero vector. Such a triangle is never a processed face, so it is never a
// face to recover either.
#pragma once
#include <cstdint>

#include "tokenizer/cleanup/quantize.h"

namespace silk {

inline bool Collinear(const QVec& a, const QVec& b, const QVec& c) {
  const int64_t ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const int64_t vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  return uy * vz - uz * vy == 0 && uz * vx - ux * vz == 0 && ux * vy - uy * vx == 0;
}

}  // namespace silk
