// SPDX-License-Identifier: MIT
// Carriage-return redraw; nothing is printed when stderr is redirected (logs stay clean).
#include "progress_bar.h"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace silkgen {

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}

void ProgressBar::Update(const silk_generate_progress& p) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  constexpr int kWidth = 30;
  const double frac = p.max_tokens > 0 ? static_cast<double>(p.tokens) / p.max_tokens : 0;
  const int fill = static_cast<int>(frac * kWidth);
  std::string bar(static_cast<size_t>(fill), '#');
  bar.resize(kWidth, '.');
  const std::string candidate =
      p.candidates > 1 ? "candidate " + std::to_string(p.candidate + 1) + "/" + std::to_string(p.candidates) + "  "
                       : "";
  std::fprintf(stderr, "\r%s[%s] %lld/%lld tokens  %d part(s)  %.1f tok/s ", candidate.c_str(), bar.c_str(),
               static_cast<long long>(p.tokens), static_cast<long long>(p.max_tokens), p.components,
               p.seconds > 0 ? p.tokens / p.seconds : 0.0);
  std::fflush(stderr);
}

void ProgressBar::Finish() {
  if (!enabled_ || !drawn_) return;
  std::fprintf(stderr, "\r%80s\r", "");
  std::fflush(stderr);
}

}  // namespace silkgen
