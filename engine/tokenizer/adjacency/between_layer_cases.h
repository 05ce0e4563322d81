// SPDX-License-Identifier: MIT
// The 26 between-layer window cases (token_format.md §7.2, "stars and bars"): the one table both the
// between-layer encoder and decoder (and the grammar) read, so they cannot disagree.
#pragma once
#include <cstdint>

#include "tokenizer/vocabulary_layout.h"

namespace silk {

inline constexpr int kBetweenWindow = vocab::k_between_window;  // W' = 5 (positions after the leading 1)
inline constexpr int kBetweenCases = vocab::k_between_cases;    // 26

// Window bits of case c: bit (p-1) = window position p (p = 1..5), i.e. column s+p.
int32_t BetweenCasePattern(int32_t c);
// Position (1..5) of the last 1 of case c's window; 0 for the all-zero case 1 (ℓ(c), §7.2).
int32_t BetweenCaseLastOne(int32_t c);
// Case of a 5-bit window, or -1 if the window is not one of the 26 cases.
int32_t BetweenCaseOfPattern(int32_t pattern);
// True for situations 5 and 7 (cases 12..15, 20..25): the next token of the row may start
// inside this token's window (token_format.md §7.3).
bool BetweenCaseIsTruncating(int32_t c);
// Smallest start column of the next token of the same row after token (s, c) (token_format.md §7.3).
int32_t BetweenNextMinStart(int32_t s, int32_t c);

}  // namespace silk
