// SPDX-License-Identifier: MIT
// A one-line progress bar on stderr (only when stderr is a terminal), redrawn at most ten
// times a second: the candidate (best of N), tokens so far / cap, components, tokens per second.
#pragma once
#include <chrono>
#include <cstdint>

#include "silk/silk.h"

namespace silkgen {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  void Update(const silk_generate_progress& p);
  void Finish();  // clears the line

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace silkgen
