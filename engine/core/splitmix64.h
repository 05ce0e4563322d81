// SPDX-License-Identifier: MIT
// SplitMix64: the one seeded random generator of generation (surface sampling, token
// sampling). Chosen because it is tiny and fully specified, so the Python reference loop in
// tests/models/ reproduces it bit for bit (std:: distributions are not portable).
#pragma once
#include <cstdint>

namespace silk {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed = 0) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1): the top 53 bits.
  double Uniform() { return static_cast<double>(Next() >> 11) * (1.0 / 9007199254740992.0); }

 private:
  uint64_t state_;
};

}  // namespace silk
