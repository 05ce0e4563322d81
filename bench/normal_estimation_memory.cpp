// SPDX-License-Identifier: MIT
// Peak memory and time of normal estimation per point (issue 35: it cost ~390 bytes per point;
// the aim is <= 150), on torus samples of each given size, each in a fresh process: the peak
// resident set above the input points (VmHWM after clear_refs, Linux), and the wall time.
//   build/bench/normal_estimation_memory 100000 1000000 2000000
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "core/splitmix64.h"
#include "mesh/normal_estimation.h"

namespace {

// A field of /proc/self/status in bytes ("VmRSS", "VmHWM").
long long StatusBytes(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field + ":", 0) == 0) return std::atoll(line.c_str() + field.size() + 1) * 1024;
  return -1;
}

int Measure(long n) {
  silk::SplitMix64 rng(7);
  std::vector<silk::Point3> pts(static_cast<size_t>(n));
  for (auto& p : pts) {
    const double a = rng.Uniform() * 6.283185307179586, b = rng.Uniform() * 6.283185307179586;
    p = {(2 + 0.7 * std::cos(b)) * std::cos(a), (2 + 0.7 * std::cos(b)) * std::sin(a), 0.7 * std::sin(b)};
  }
  std::ofstream("/proc/self/clear_refs") << "5";  // VmHWM := VmRSS
  const long long base = StatusBytes("VmRSS");
  const auto t0 = std::chrono::steady_clock::now();
  auto normals = silk::EstimateNormals(pts);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const long long peak = StatusBytes("VmHWM");
  if (!normals.ok()) return std::printf("%ld points: %s\n", n, normals.status().ToString().c_str()), 1;
  std::printf("%9ld points: %6.1f bytes/point above the input (%lld MB peak above %lld MB), %.2f s, %.2f us/point\n", n,
              double(peak - base) / n, (peak - base) >> 20, base >> 20, s, 1e6 * s / n);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return std::fprintf(stderr, "usage: %s N [N ...]\n", argv[0]), 2;
  int failed = 0;
  for (int i = 1; i < argc; ++i) {
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid == 0) {
      const int rc = Measure(std::atol(argv[i]));
      std::fflush(stdout);
      std::_Exit(rc);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    failed += !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  return failed ? 1 : 0;
}
