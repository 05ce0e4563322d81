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
  Draw(Line(p));  // every report counts, drawn or not
}

void ProgressBar::Draw(const std::string& line) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  std::fprintf(stderr, "\r%s ", line.c_str());
  std::fflush(stderr);
}

std::string ProgressBar::Line(const silk_generate_progress& p) {
  if (p.candidate == 0 && p.tokens <= 1) shares_.clear();  // a new run (batch: the next input)
  if (shares_.size() < static_cast<size_t>(p.candidates)) shares_.resize(static_cast<size_t>(p.candidates));
  if (p.candidate >= 0 && static_cast<size_t>(p.candidate) < shares_.size())
    shares_[static_cast<size_t>(p.candidate)] = Share{p.tokens, p.max_tokens};
  double frac = p.max_tokens > 0 ? static_cast<double>(p.tokens) / p.max_tokens : 0;
  std::string head;
  if (p.candidates > 1) {  // the whole run's share: each candidate counts 1/N
    int running = 0, done = 0;
    frac = 0;
    for (const Share& s : shares_) {
      const bool ended = s.max_tokens > 0 && s.tokens >= s.max_tokens;
      done += ended;
      running += s.tokens > 0 && !ended;
      frac += s.max_tokens > 0 ? static_cast<double>(s.tokens) / s.max_tokens / p.candidates : 0;
    }
    head = "candidates " + std::to_string(done) + "/" + std::to_string(p.candidates) + " done, " +
           std::to_string(running) + " running  ";
  }
  constexpr int kWidth = 30;
  std::string bar(static_cast<size_t>(frac * kWidth), '#');
  bar.resize(kWidth, '.');
  char tail[128];
  std::snprintf(tail, sizeof tail, "] %lld/%lld tokens  %d part(s)  %.1f tok/s", static_cast<long long>(p.tokens),
                static_cast<long long>(p.max_tokens), p.components, p.seconds > 0 ? p.tokens / p.seconds : 0.0);
  return head + "[" + bar + tail;
}

void ProgressBar::Finish() {
  if (!enabled_ || !drawn_) return;
  std::fprintf(stderr, "\r%80s\r", "");
  std::fflush(stderr);
}

}  // namespace silkgen
