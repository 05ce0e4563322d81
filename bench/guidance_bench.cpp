// SPDX-License-Identifier: MIT
// Surface guidance and best-of-N scoring costs: building the guide (distance field) once per
// generation, restricting one K and one O mask per vertex, beside a baseline that only copies
// the mask (what any extra sampler stage pays); Chamfer scoring with the grid index beside
// brute-force nearest neighbours on the same sets.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/splitmix64.h"
#include "mesh/chamfer_distance.h"
#include "runtime/sampling/surface_guide.h"
#include "tokenizer/vocabulary_layout.h"

using namespace silk;
using Clock = std::chrono::steady_clock;

namespace {
double Seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// 4,096 points on a sphere of radius 0.9 (rows of 6 floats), like an encoder input.
std::vector<float> SpherePoints(SplitMix64* rng) {
  std::vector<float> rows;
  for (int i = 0; i < 4096; ++i) {
    double v[3], len = 0;
    for (double& x : v) x = 2 * rng->Uniform() - 1, len += x * x;
    len = std::sqrt(len) + 1e-12;
    for (double x : v) rows.push_back(static_cast<float>(0.9 * x / len));
    for (double x : v) rows.push_back(static_cast<float>(x / len));
  }
  return rows;
}
}  // namespace

int main() {
  SplitMix64 rng(1);
  const auto rows = SpherePoints(&rng);
  const int kBuilds = 5;
  auto t0 = Clock::now();
  for (int i = 0; i < kBuilds; ++i) SurfaceGuide g(rows, 2);
  std::printf("guide build (distance field, 128^3): %.1f ms per generation\n", 1e3 * Seconds(t0) / kBuilds);

  const SurfaceGuide guide(rows, 2);
  TokenMask k, o;
  k.SetRange(vocab::kKBegin, vocab::kKEnd);
  o.SetRange(vocab::kOBegin, vocab::kOEnd);
  const int kReps = 20000;
  uint64_t sink = 0;
  t0 = Clock::now();
  for (int i = 0; i < kReps; ++i) {
    TokenMask a = k, b = o;
    sink += static_cast<uint64_t>(a.Count() + b.Count());
  }
  const double base = Seconds(t0) / kReps;
  // Blocks near the surface (what the K stage lets through) and far ones (the O stage falls back).
  std::vector<int32_t> near, far;
  for (int32_t b = 0; b < 512; ++b) (guide.Within(guide.BlockDistance2(b)) ? near : far).push_back(vocab::kKBegin + b);
  for (const auto* blocks : {&near, &far}) {
    t0 = Clock::now();
    int fallbacks = 0;
    for (int i = 0; i < kReps; ++i) {
      TokenMask a = k, b = o;
      fallbacks += guide.RestrictBlocks(&a) ? 1 : 0;
      fallbacks += guide.RestrictOffsets((*blocks)[static_cast<size_t>(i) % blocks->size()], &b) ? 1 : 0;
      sink += static_cast<uint64_t>(a.Count() + b.Count());
    }
    std::printf(
        "per vertex (K + O, every id legal, %s blocks, %d%% fallbacks): guided %.2f us, baseline (copy + "
        "count) %.2f us\n",
        blocks == &near ? "near" : "far", 100 * fallbacks / (2 * kReps), 1e6 * Seconds(t0) / kReps, 1e6 * base);
  }

  std::vector<Point3> a, b;
  for (size_t i = 0; i + 6 <= rows.size(); i += 6) a.push_back({rows[i], rows[i + 1], rows[i + 2]});
  const auto rows2 = SpherePoints(&rng);
  for (size_t i = 0; i + 6 <= rows2.size(); i += 6) b.push_back({rows2[i], rows2[i + 1], rows2[i + 2]});
  t0 = Clock::now();
  const double fast = PointSetChamfer(a, b).value();
  const double grid_s = Seconds(t0);
  t0 = Clock::now();
  double ab = 0, ba = 0;
  for (int dir = 0; dir < 2; ++dir)
    for (const Point3& p : dir ? b : a) {
      double best = 1e300;
      for (const Point3& q : dir ? a : b)
        best = std::min(best,
                        (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
      (dir ? ba : ab) += std::sqrt(best);
    }
  const double brute_s = Seconds(t0);
  std::printf("Chamfer 4,096 x 4,096: grid index %.2f ms, brute force %.2f ms (same value: %s)\n", 1e3 * grid_s,
              1e3 * brute_s, std::fabs(fast - 0.5 * (ab / a.size() + ba / b.size())) < 1e-9 ? "yes" : "NO");
  return sink == 0 ? 1 : 0;
}
