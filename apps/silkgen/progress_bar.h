// SPDX-License-Identifier: MIT
// A one-line progress bar on stderr (only when stderr is a terminal), redrawn at most ten
// times a second: tokens so far / cap, components, tokens per second; with best of N, every
// candidate's share (candidates decoded as rows report in turns): how many run and how many are done.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "silk/silk.h"

namespace silkgen {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  void Update(const silk_generate_progress& p);
  void Finish();  // clears the line
  // Draws `line` (--batch --parallel's own), as often as Update draws.
  void Draw(const std::string& line);

  // The line for `p` after the earlier reports of the same run (also what the tests read).
  std::string Line(const silk_generate_progress& p);

 private:
  struct Share {
    int64_t tokens = 0, max_tokens = 0;
  };
  std::vector<Share> shares_;  // best of N: each candidate's last report
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace silkgen
