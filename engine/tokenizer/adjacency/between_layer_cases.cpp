// SPDX-License-Identifier: MIT
// The 26 between-layer window cases (token_format.md §7.2), built once from the situation rules.
#include "tokenizer/adjacency/between_layer_cases.h"

#include <array>

namespace silk {
namespace {

// Pattern strings p1..p5 in case order, straight from the spec's §7.2 table.
constexpr const char* kCasePatterns[kBetweenCases] = {"11111", "00000", "10000", "11000", "11100", "11110", "10111",
                                                      "10011", "10001", "11011", "11001", "11101", "10100", "10110",
                                                      "10010", "11010", "01111", "00111", "00011", "00001", "01000",
                                                      "01100", "01110", "00100", "00110", "00010"};

struct Tables {
  std::array<int32_t, kBetweenCases> pattern{};
  std::array<int32_t, kBetweenCases> last_one{};
  std::array<int32_t, 32> case_of{};
  Tables() {
    case_of.fill(-1);
    for (int c = 0; c < kBetweenCases; ++c) {
      int32_t bits = 0, last = 0;
      for (int p = 1; p <= kBetweenWindow; ++p) {
        if (kCasePatterns[c][p - 1] == '1') {
          bits |= 1 << (p - 1);
          last = p;
        }
      }
      pattern[c] = bits;
      last_one[c] = last;
      case_of[bits] = c;
    }
  }
};

const Tables& T() {
  static const Tables t;
  return t;
}

}  // namespace

int32_t BetweenCasePattern(int32_t c) { return T().pattern[c]; }
int32_t BetweenCaseLastOne(int32_t c) { return T().last_one[c]; }
int32_t BetweenCaseOfPattern(int32_t pattern) { return (pattern >= 0 && pattern < 32) ? T().case_of[pattern] : -1; }
bool BetweenCaseIsTruncating(int32_t c) { return (c >= 12 && c <= 15) || (c >= 20 && c <= 25); }
int32_t BetweenNextMinStart(int32_t s, int32_t c) {
  return BetweenCaseIsTruncating(c) ? s + BetweenCaseLastOne(c) + 2 : s + kBetweenWindow + 1;
}

}  // namespace silk
