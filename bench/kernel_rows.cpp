// SPDX-License-Identifier: MIT
// kernel_rows: what one release-size INT4 decoder call costs in the ai.silk kernels when it takes
// R rows (decoder contract v4) instead of one: every layer's Int4MatMul products (self q/k/v/out,
// cross q/out, the GLU feed-forward in and out), CachedAttention over each row's own int8 cache at
// the given depth, CrossAttention over float16 cross K/V shared by the rows (the candidates of one
// mesh) or each row's own, and the float16 logits head; the rest of a call (norms, GELU, adds) is
// elementwise and left out. Prints ms per call, rows x calls per second and bytes per call
// (weights once, each row's cache, the cross K/V once per mesh) beside the R = 1 figures of the
// same run and the read-bandwidth bound for those bytes (bench_memory.h), and the process's CPU
// ms per call (with --threads 1 the figure a busy shared machine does not distort).
//
//   kernel_rows [--rows 1,2,4,8] [--depths 500,2000] [--calls 30] [--threads 2] [--cross shared|per-row]
//
// Shapes: docs/official_network.md (d_model 1024, 24 layers, 16 heads of 64, 261 cross rows,
// feed-forward 4096 with GLU, 10,269 logits), INT4 block 32. Weights are random: the kernels'
// cost does not depend on their values. Built with -DSILK_KERNEL_ROWS_ONE_ROW against a tree
// before contract v4 (bench/kernel_rows_baseline.py) it runs R = 1 alone: that tree's cost.
#include <time.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_memory.h"
#include "kernels/attention/cached_attention.h"
#include "kernels/attention/cross_attention.h"
#include "kernels/quant/half_matmul.h"
#include "kernels/quant/int4_matmul.h"

namespace {

using silk::bench::Clock;
using silk::bench::Since;

constexpr int64_t kModel = 1024, kLayers = 24, kHeads = 16, kHeadDim = 64, kCrossRows = 261, kVocab = 10269;
constexpr int64_t kFeedForward = 4096, kBlock = 32;

// A parallel-for over `threads` threads (the caller's and threads - 1 spinning workers), as
// onnxruntime's intra-op pool spins between the ops of a call.
class SpinPool {
 public:
  explicit SpinPool(int threads) {
    for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { Work(); });
  }
  ~SpinPool() {
    stop_ = true;
    for (std::thread& t : workers_) t.join();
  }
  static void For(void* self, void (*work)(void*, size_t), void* state, size_t count) {
    static_cast<SpinPool*>(self)->Run(work, state, count);
  }

 private:
  struct Job {
    void (*work)(void*, size_t);
    void* state;
    size_t count;
    std::atomic<size_t> next{0}, done{0};
  };
  static void Take(Job* j) {
    for (size_t i; (i = j->next.fetch_add(1)) < j->count; j->done.fetch_add(1)) j->work(j->state, i);
  }
  void Run(void (*work)(void*, size_t), void* state, size_t count) {
    Job job{work, state, count};
    job_.store(&job);
    epoch_.fetch_add(1);
    Take(&job);
    while (job.done.load() < count || active_.load() > 0) std::this_thread::yield();
    job_.store(nullptr);
  }
  void Work() {
    uint64_t seen = 0;
    while (!stop_) {
      const uint64_t e = epoch_.load();
      if (e == seen) {
        std::this_thread::yield();  // the machine may be shared: give the core up between jobs
        continue;
      }
      active_.fetch_add(1);
      Job* j = job_.load();
      if (j && epoch_.load() == e) Take(j);
      active_.fetch_sub(1);
      seen = e;
    }
  }
  std::vector<std::thread> workers_;
  std::atomic<Job*> job_{nullptr};
  std::atomic<uint64_t> epoch_{0};
  std::atomic<int> active_{0};
  std::atomic<bool> stop_{false};
};

// CPU seconds of the whole process (every thread; the pool's workers spin between jobs, so with
// --threads 1 it is the kernels' own time, unaffected by other processes on a shared machine).
double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Int4Weight {
  int64_t n, k;
  std::vector<uint8_t> packed;
  std::vector<float> scales;
  int64_t Bytes() const { return static_cast<int64_t>(packed.size() + 4 * scales.size()); }
};

Int4Weight RandomInt4(int64_t n, int64_t k, std::mt19937& rng) {
  Int4Weight w{n, k, std::vector<uint8_t>(static_cast<size_t>(n * k / 2)), std::vector<float>(n * k / kBlock)};
  for (uint8_t& b : w.packed) b = static_cast<uint8_t>(rng());
  for (float& s : w.scales) s = 0.001f + (rng() % 1000) * 1e-5f;
  return w;
}

// Every weight of the network, the caches of `rows` rows at `depth`, one call's activations.
struct Network {
  std::vector<Int4Weight> matmuls;                // per layer: q, k, v, out, cross q, cross out, ff in, ff out
  std::vector<uint16_t> logits;                   // [vocab, model] float16
  std::vector<std::vector<uint16_t>> cross;       // per layer: key then value [sources, heads, 261, 64]
  std::vector<std::vector<unsigned char>> cache;  // per layer: key then value [rows, heads, depth + 1, 68]
  int64_t rows = 1, depth = 0, sources = 1;
  std::vector<float> x, q, kv, wide, out, scores;

  Network(int64_t rows_, int64_t depth_, bool per_row_cross, std::mt19937& rng)
      : rows(rows_), depth(depth_), sources(per_row_cross ? rows_ : 1) {
    for (int64_t l = 0; l < kLayers; ++l) {
      for (int i = 0; i < 6; ++i) matmuls.push_back(RandomInt4(kModel, kModel, rng));
      matmuls.push_back(RandomInt4(2 * kFeedForward, kModel, rng));
      matmuls.push_back(RandomInt4(kModel, kFeedForward, rng));
      for (int kv = 0; kv < 2; ++kv) {
        cross.emplace_back(static_cast<size_t>(sources * kHeads * kCrossRows * kHeadDim));
        for (uint16_t& h : cross.back()) h = static_cast<uint16_t>(0x3000 + rng() % 0x0c00);
        // int8 rows of random values with a scale of 0.01 (rows past the depth: written by the call)
        cache.emplace_back(LayerCacheBytes(), 0);
        for (size_t i = 0; i < cache.back().size(); i += 68) {
          for (size_t j = 0; j < 64; ++j) cache.back()[i + j] = static_cast<unsigned char>(rng());
          const float scale = 0.01f;
          std::memcpy(&cache.back()[i + 64], &scale, 4);
        }
      }
    }
    logits.resize(static_cast<size_t>(kVocab * kModel));
    for (uint16_t& h : logits) h = static_cast<uint16_t>(0x2000 + rng() % 0x1000);
    std::normal_distribution<float> normal;
    x.resize(static_cast<size_t>(rows * kFeedForward));  // activations: [rows, up to 4096]
    for (float& v : x) v = normal(rng);
    q.resize(static_cast<size_t>(rows * kModel));  // queries: unit length per head of 64
    for (float& v : q) v = normal(rng) * 0.125f;
    kv.resize(static_cast<size_t>(2 * rows * kModel));  // the new position's key and value
    for (float& v : kv) v = normal(rng);
    wide.resize(static_cast<size_t>(rows * 2 * kFeedForward));
    out.resize(static_cast<size_t>(rows * kModel));
    scores.resize(static_cast<size_t>(rows * kVocab));
  }
  size_t LayerCacheBytes() const { return static_cast<size_t>(rows * kHeads * (depth + 1) * 68); }

  // Bytes one call reads: each weight once, the cross K/V once per source, each row's cache to its depth.
  int64_t Bytes() const {
    int64_t b = static_cast<int64_t>(logits.size() * 2);
    for (const Int4Weight& w : matmuls) b += w.Bytes();
    for (const auto& c : cross) b += static_cast<int64_t>(c.size() * 2);
    return b + kLayers * 2 * rows * kHeads * (depth + 1) * 68;
  }
};

void Product(const Int4Weight& w, const float* a, float* y, int64_t rows, SpinPool* pool) {
  silk::Int4MatMul({rows, w.k, w.n, kBlock}, a, w.packed.data(), w.scales.data(), y, SpinPool::For, pool);
}

// One decoder call of the network's rows, each one position at the network's depth.
// One decoder call of the network's rows, each one position at the network's depth. Every kernel
// reads fixed inputs of a decoder's magnitudes (activations ~N(0, 1), queries of unit length per
// head) and writes a scratch output: chained through 24 layers without the norms the products
// would drift to denormal or infinite values, whose arithmetic costs differ.
void Call(Network& net, SpinPool* pool) {
  const int64_t R = net.rows;
  std::vector<int64_t> past(static_cast<size_t>(R), net.depth), fresh(static_cast<size_t>(R), 1);
  std::vector<int32_t> source(static_cast<size_t>(R), 0);
  for (int64_t r = 0; r < R && net.sources == R; ++r) source[static_cast<size_t>(r)] = static_cast<int32_t>(r);
  const float *x = net.x.data(), *q = net.q.data(), *kv = net.kv.data();
  float *out = net.out.data(), *wide = net.wide.data();
  for (int64_t l = 0; l < kLayers; ++l) {
    const Int4Weight* w = &net.matmuls[static_cast<size_t>(l * 8)];
    for (int i = 0; i < 3; ++i) Product(w[i], x, wide + i * R * kModel, R, pool);  // q, k, v
    silk::AttentionShape s{kHeads, kHeads, kHeadDim, 1, net.depth, net.depth + 1, 10.0f};
#ifndef SILK_KERNEL_ROWS_ONE_ROW
    s.batch = R, s.row_past = past.data(), s.row_chunk = fresh.data();
#endif
    silk::AttentionBuffers b{q,
                             kv,
                             kv + R * kModel,
                             net.cache[static_cast<size_t>(2 * l)].data(),
                             net.cache[static_cast<size_t>(2 * l + 1)].data(),
                             out};
    silk::CachedAttention(s, silk::CacheElement::kInt8, b, SpinPool::For, pool);
    Product(w[3], x, wide, R, pool);  // self out
    Product(w[4], x, wide, R, pool);  // cross q
    silk::CrossAttentionShape c{kHeads, 1, kCrossRows, kHeadDim, 10.0f};
#ifndef SILK_KERNEL_ROWS_ONE_ROW
    c.batch = R, c.source = source.data();
#endif
    silk::CrossAttention(c, silk::CacheElement::kFloat16, q, net.cross[static_cast<size_t>(2 * l)].data(),
                         net.cross[static_cast<size_t>(2 * l + 1)].data(), out, SpinPool::For, pool);
    Product(w[5], x, wide, R, pool);  // cross out
    Product(w[6], x, wide, R, pool);  // feed-forward in (value and gate halves)
    Product(w[7], x, wide, R, pool);  // feed-forward out (K = 4096)
  }
  silk::HalfMatMul({R, kModel, kVocab}, x, net.logits.data(), net.scores.data(), SpinPool::For, pool);
}

std::vector<int64_t> List(const char* text) {
  std::vector<int64_t> v;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) v.push_back(std::atoll(item.c_str()));
  return v;
}

struct Args {
  std::vector<int64_t> rows = {1, 2, 4, 8}, depths = {500, 2000};
  int calls = 30, threads = 2;
  bool per_row_cross = false;
};

bool Parse(int argc, char** argv, Args* a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (!v) return false;
    ++i;
    if (k == "--rows")
      a->rows = List(v);
    else if (k == "--depths")
      a->depths = List(v);
    else if (k == "--calls")
      a->calls = std::atoi(v);
    else if (k == "--threads")
      a->threads = std::atoi(v);
    else if (k == "--cross")
      a->per_row_cross = std::string(v) == "per-row";
    else
      return false;
  }
  for (int64_t r : a->rows)
    if (r < 1 || r > 64) return false;
  for (int64_t d : a->depths)
    if (d < 0 || d > 10240) return false;
  return a->calls >= 1 && a->calls <= 10000 && a->threads >= 1 && a->threads <= 64 && !a->rows.empty();
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (!Parse(argc, argv, &a)) {
    std::fprintf(stderr,
                 "usage: kernel_rows [--rows 1,2,4,8 (1..64)] [--depths 500,2000 (0..10240)] [--calls 30] "
                 "[--threads 2] [--cross shared|per-row]\n");
    return 2;
  }
#ifdef SILK_KERNEL_ROWS_ONE_ROW
  a.rows = {1};
#endif
  SpinPool pool(a.threads);
  std::printf("release-size INT4 decoder kernels, int8 cache, float16 cross K/V %s, %d threads, %d calls\n",
              a.per_row_cross ? "per row" : "shared by the rows", a.threads, a.calls);
  std::printf("%6s %5s %9s %7s %12s %7s %9s %9s %6s %8s\n", "depth", "rows", "ms/call", "xR=1", "rows*calls/s", "xR=1",
              "MB/call", "bound ms", "%bound", "cpu ms");
  for (int64_t depth : a.depths) {
    double base_ms = 0, base_rate = 0;  // the first --rows entry's (1 by default)
    for (int64_t rows : a.rows) {
      std::mt19937 rng(1);
      Network net(rows, depth, a.per_row_cross, rng);
      const double bandwidth = silk::bench::ReadBandwidth(a.threads, net.Bytes());
      for (int i = 0; i < 3; ++i) Call(net, &pool);  // warm-up
      const auto t0 = Clock::now();
      const double cpu0 = ProcessCpuSeconds();
      for (int i = 0; i < a.calls; ++i) Call(net, &pool);
      const double ms = 1e3 * Since(t0) / a.calls, cpu_ms = 1e3 * (ProcessCpuSeconds() - cpu0) / a.calls;
      const double rate = rows * 1e3 / ms, bound = net.Bytes() / bandwidth / 1e6;
      if (base_ms == 0) base_ms = ms, base_rate = rate;
      std::printf("%6lld %5lld %9.2f %7.2f %12.1f %7.2f %9.1f %9.2f %5.0f%% %8.2f\n", static_cast<long long>(depth),
                  static_cast<long long>(rows), ms, ms / base_ms, rate, rate / base_rate, net.Bytes() / 1e6, bound,
                  100.0 * bound / ms, cpu_ms);
      std::fflush(stdout);
    }
  }
  return 0;
}
