// SPDX-License-Identifier: MIT
// What the benchmarks that set speed against the memory-bandwidth bound share
// (generation_bench, time_to_mesh): the read bandwidth of a working set of a given size, the
// last-level cache size, peak RSS, and the bytes of a decoder graph as stored.
#pragma once
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "runtime/model/model_config.h"

namespace silk::bench {

using Clock = std::chrono::steady_clock;
inline double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Read bandwidth (GB/s) for a working set of `bytes`: `threads` threads scanning disjoint parts
// of one buffer of that size with memchr for a byte that is not there (glibc's vectorised scan
// is the fastest plain read loop available: 19 GB/s vs 15 GB/s for a scalar XOR reduction on
// the development VM at 2 GiB, 43 vs 15 GB/s at 82 MiB), read again and again like a decoder
// re-reads its weights and cache every step; best pass of at least 3 and at least 0.5 s. A
// working set that fits in the last-level cache is read at cache speed, one larger than it at
// DRAM speed, so the bound for each model and depth uses a buffer of the bytes that step reads.
inline double ReadBandwidth(int threads, int64_t bytes) {
  const size_t n = static_cast<size_t>(std::max<int64_t>(bytes, 1 << 20));
  std::vector<unsigned char> buf(n, 0x5a);
  double best = 0;
  std::atomic<uintptr_t> sink{0};
  const auto start = Clock::now();
  for (int rep = 0; rep < 3 || (Since(start) < 0.5 && rep < 1000); ++rep) {
    auto t0 = Clock::now();
    std::vector<std::thread> ts;
    for (int t = 0; t < threads; ++t)
      ts.emplace_back([&, t] {
        const size_t lo = n * t / threads, hi = n * (t + 1) / threads;
        sink.fetch_xor(reinterpret_cast<uintptr_t>(std::memchr(buf.data() + lo, 0x17, hi - lo)));
      });
    for (auto& t : ts) t.join();
    best = std::max(best, n / Since(t0) / 1e9);
  }
  if (sink.load() == 42) std::printf(" ");
  return best;
}

// Last-level cache size in bytes (0 when the system does not say).
inline int64_t LastLevelCacheBytes() {
  for (int index = 4; index >= 0; --index) {
    FILE* f = std::fopen(("/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(index) + "/size").c_str(), "r");
    if (!f) continue;
    long long v = 0;
    char unit = 0;
    const int got = std::fscanf(f, "%lld%c", &v, &unit);
    std::fclose(f);
    if (got >= 1) return v * (unit == 'K' ? 1024LL : unit == 'M' ? 1048576LL : 1LL);
  }
  return 0;
}

inline double PeakRssMiB() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

inline int64_t FileSize(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return 0;
  std::fseek(f, 0, SEEK_END);
  const long s = std::ftell(f);
  std::fclose(f);
  return s;
}

// Bytes of a decoder graph as stored: the .onnx file (that of the KV variant `kv` when the model
// has one) plus the external data files model.json lists for the decoder ("decoder.onnx.data"
// beside "decoder.onnx", which a variant shares; a silk-form variant of such a decoder no longer
// reads the float32 logits head there, so this counts it once too often).
inline double DecoderFileBytes(const silk::ModelConfig& c, silk::DecoderPrecision p,
                               silk::KvPrecision kv = silk::KvPrecision::kFp32) {
  const std::string& file = c.DecoderFile(p);
  const std::string& variant = c.DecoderFile(p, kv).empty() ? file : c.DecoderFile(p, kv);
  double bytes = static_cast<double>(FileSize(c.dir + "/" + variant));
  for (const std::string& data : c.external_data)
    if (data.rfind(file + ".", 0) == 0) bytes += static_cast<double>(FileSize(c.dir + "/" + data));
  return bytes;
}

}  // namespace silk::bench
