// SPDX-License-Identifier: MIT
// matmul_rows: what one Int4MatMul and one HalfMatMul cost per activation row when they take R
// rows, on one thread: Int4MatMul at the release decoder's two product shapes (K 1024 -> N 4096,
// K 4096 -> N 1024, block 32), HalfMatMul at the logits heads (K 96 -> N 10,269, the bundled
// model; K 1024 -> N 10,269, the release network), so a kernel's per-row cost is seen without the
// rest of a decoder call or a second thread; the minimum of many calls, which a busy shared
// machine distorts least. R = 1 of the same run is the baseline of the "x R=1" column (rows x
// calls per second).
//
//   matmul_rows [--calls 60]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <random>
#include <vector>

#include "kernels/quant/half_matmul.h"
#include "kernels/quant/int4_matmul.h"

namespace {

struct Shape {
  int64_t k, n;
};

using Clock = std::chrono::steady_clock;

// Activation rows in [-1, 1).
std::vector<float> Activations(std::mt19937* rng, int64_t rows, int64_t k) {
  std::vector<float> a(static_cast<size_t>(rows * k));
  for (float& x : a) x = static_cast<float>((*rng)() % 1000) / 500.0f - 1.0f;
  return a;
}

// Minimum ms of `calls` runs of product().
template <typename Product>
double MinMs(int calls, const Product& product) {
  double best = 1e30;
  for (int c = 0; c < calls; ++c) {
    const auto t0 = Clock::now();
    product();
    best = std::min(best, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return best;
}

// Minimum ms of `calls` Int4MatMul products of `rows` activation rows.
double Int4MinMs(const Shape& sh, int64_t rows, int calls) {
  std::mt19937 rng(1);
  std::vector<uint8_t> packed(static_cast<size_t>(sh.n * sh.k / 2));
  for (uint8_t& b : packed) b = static_cast<uint8_t>(rng());
  const std::vector<float> scales(static_cast<size_t>(sh.n * sh.k / 32), 0.01f), a = Activations(&rng, rows, sh.k);
  std::vector<float> out(static_cast<size_t>(rows * sh.n));
  return MinMs(calls, [&] {
    silk::Int4MatMul({rows, sh.k, sh.n, 32}, a.data(), packed.data(), scales.data(), out.data(), nullptr, nullptr);
  });
}

// The same for HalfMatMul (float16 weights in [-2, 2]).
double HalfMinMs(const Shape& sh, int64_t rows, int calls) {
  std::mt19937 rng(1);
  std::vector<uint16_t> w(static_cast<size_t>(sh.n * sh.k));
  for (uint16_t& h : w) h = static_cast<uint16_t>(0x3c00 ^ (rng() & 0x83ff));  // sign and mantissa random
  const std::vector<float> a = Activations(&rng, rows, sh.k);
  std::vector<float> out(static_cast<size_t>(rows * sh.n));
  return MinMs(calls, [&] { silk::HalfMatMul({rows, sh.k, sh.n}, a.data(), w.data(), out.data(), nullptr, nullptr); });
}

// One table row per R in 1, 2, 4, 8 for each shape.
void Table(const char* kernel, std::initializer_list<Shape> shapes, double (*min_ms)(const Shape&, int64_t, int),
           int calls) {
  for (const Shape& sh : shapes) {
    double one = 0.0;
    for (int64_t rows : {1, 2, 4, 8}) {
      const double ms = min_ms(sh, rows, calls);
      if (rows == 1) one = ms;
      std::printf("%-10s %5lld  %5lld  %4lld  %6.3f  %6.3f  %5.2f\n", kernel, static_cast<long long>(sh.k),
                  static_cast<long long>(sh.n), static_cast<long long>(rows), ms, ms / static_cast<double>(rows),
                  one * static_cast<double>(rows) / ms);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int calls = 60;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--calls") != 0) {
      std::fprintf(stderr, "matmul_rows: unknown argument '%s' (usage: matmul_rows [--calls N])\n", argv[i]);
      return 2;
    }
    if (i + 1 >= argc || std::atoi(argv[i + 1]) <= 0 || std::atoi(argv[i + 1]) > 100000) {
      std::fprintf(stderr, "matmul_rows: --calls needs a count in [1, 100000], got '%s'\n",
                   i + 1 < argc ? argv[i + 1] : "");
      return 2;
    }
    calls = std::atoi(argv[++i]);
  }
  std::printf("Int4MatMul (block 32) and HalfMatMul, 1 thread, minimum of %d calls\n", calls);
  std::printf("kernel         K      N  rows      ms  ms/row  x R=1 rows*calls/s\n");
  Table("Int4MatMul", {Shape{1024, 4096}, Shape{4096, 1024}}, Int4MinMs, calls);
  Table("HalfMatMul", {Shape{96, 10269}, Shape{1024, 10269}}, HalfMinMs, calls);
  return 0;
}
