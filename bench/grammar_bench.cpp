// SPDX-License-Identifier: MIT
// Grammar cost per token over the official dev streams: Accept alone, and LegalMask + Accept
// (what a constrained sampler pays per step), beside a baseline that only sums the ids.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "io/tokens/token_text.h"

using namespace silk;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "../shared/spec/golden-dev";
  std::vector<std::vector<int32_t>> streams;
  size_t total = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string p = e.path().string();
    if (p.size() < 11 || p.compare(p.size() - 11, 11, ".tokens.txt") != 0) continue;
    auto ids = ReadTokenText(p);
    if (!ids.ok()) continue;
    total += ids->size();
    streams.push_back(std::move(*ids));
  }
  GrammarOptions opt;
  opt.max_length = 0;
  auto run = [&](int mode) {
    const auto t0 = Clock::now();
    uint64_t sink = 0;
    for (const auto& ids : streams) {
      Grammar g(opt);
      for (int32_t id : ids) {
        if (mode == 0) {
          sink += static_cast<uint64_t>(id);
          continue;
        }
        if (mode == 2) sink += g.LegalMask().words()[0];
        if (!g.Accept(id).ok()) {
          std::fprintf(stderr, "refused\n");
          return -1.0;
        }
      }
      sink += g.size();
    }
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (sink == 42) std::printf(" ");
    return s;
  };
  std::printf("%zu streams, %zu tokens\n", streams.size(), total);
  const char* names[] = {"baseline (sum ids)", "accept", "mask + accept"};
  for (int mode = 0; mode < 3; ++mode) {
    double best = 1e9;
    for (int rep = 0; rep < 3; ++rep) best = std::min(best, run(mode));
    std::printf("%-20s %8.1f ns/token %10.2f M tokens/s\n", names[mode], 1e9 * best / total, total / best / 1e6);
  }
  return 0;
}
