// SPDX-License-Identifier: MIT
// silkgen's progress line: one candidate as before; best of N decoded as rows reports its
// candidates in turns, and the line counts each candidate's share, how many run and how many are done.
#include <gtest/gtest.h>

#include <string>

#include "progress_bar.h"

namespace {

silk_generate_progress Report(int32_t candidate, int32_t candidates, int64_t tokens, int64_t max_tokens) {
  silk_generate_progress p{};
  p.struct_size = sizeof p;
  p.candidate = candidate;
  p.candidates = candidates;
  p.tokens = tokens;
  p.max_tokens = max_tokens;
  p.components = 1;
  p.seconds = 1;
  return p;
}

TEST(ProgressBar, OneCandidateShowsItsTokens) {
  silkgen::ProgressBar bar(false);
  const std::string line = bar.Line(Report(0, 1, 50, 100));
  EXPECT_EQ(line.find("candidates"), std::string::npos);
  EXPECT_NE(line.find("[###############...............] 50/100 tokens"), std::string::npos) << line;
}

TEST(ProgressBar, RowsCountEveryCandidate) {
  silkgen::ProgressBar bar(false);
  bar.Line(Report(0, 4, 1, 100));
  bar.Line(Report(1, 4, 1, 100));
  bar.Line(Report(0, 4, 100, 100));  // candidate 0 ended
  const std::string line = bar.Line(Report(1, 4, 50, 100));
  EXPECT_NE(line.find("candidates 1/4 done, 1 running"), std::string::npos) << line;
  // (1 + 0.5) / 4 of the run: 11 of 30 cells.
  EXPECT_NE(line.find("[###########..................."), std::string::npos) << line;
  // The next input's first report starts afresh.
  EXPECT_NE(bar.Line(Report(0, 4, 1, 100)).find("candidates 0/4 done, 1 running"), std::string::npos);
}

}  // namespace
