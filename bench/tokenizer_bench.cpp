// SPDX-License-Identifier: MIT
// Tokenizer throughput on real mesh sets: read + normalise (the I/O baseline), encode and
// decode, each timed as its own parallel pass so every figure sits beside the baseline.
//
//   tokenizer_bench [-j N] [--top K] PATH...   (files or folders, searched recursively)
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "io/mesh_format.h"
#include "io/mesh_reader.h"
#include "mesh/normalize.h"
#include "tokenizer/refusal.h"
#include "tokenizer/tokenizer.h"

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Reference figure quoted in the project issue, not measured here.
constexpr double kPythonSecondsPerMesh = 0.43;

struct MeshRun {
  std::string path;
  int64_t faces = 0, vertices = 0;
  double read_s = 0, normalize_s = 0, encode_s = 0, decode_s = 0;
  std::string failure;  // empty when encoded; else "read: ...", "refused: <name>", ...
  silk::IoMesh normalized;
  std::vector<int32_t> tokens;
  silk::EncodeStats stats;
  bool decoded = false;
  int64_t decoded_faces = 0;
};

// Every supported mesh file (by extension) under the given files/folders, sorted.
std::vector<std::string> CollectMeshFiles(const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      for (auto it = fs::recursive_directory_iterator(in, ec); !ec && it != fs::recursive_directory_iterator();
           it.increment(ec))
        if (it->is_regular_file(ec) && silk::MeshFormatFromPath(it->path().string()))
          out.push_back(it->path().string());
    } else {
      out.push_back(in);  // explicit files are taken as given (sniffed if the extension is unknown)
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Process CPU time (user + system), seconds.
double CpuSeconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

struct PassTime {
  double wall = 0, cpu = 0;  // cpu: all threads together; below wall * threads when the machine is busy
};

// Runs fn(i) for i in [0, n) on `threads` workers.
PassTime ParallelFor(size_t n, int threads, const std::function<void(size_t)>& fn) {
  std::atomic<size_t> next{0};
  const double cpu0 = CpuSeconds();
  const auto t0 = Clock::now();
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (size_t i = next++; i < n; i = next++) fn(i);
    });
  for (auto& th : pool) th.join();
  return {Since(t0), CpuSeconds() - cpu0};
}

std::string LoadAverage() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return f ? a + " " + b + " " + c : std::string("unknown");
}

std::string FailureName(const silk::Status& s, const char* stage) {
  silk::Refusal r;
  if (silk::RefusalFromStatus(s, &r)) return std::string("refused: ") + silk::RefusalName(r);
  return std::string(stage) + " " + silk::StatusCodeName(s.code());
}

double PeakRssMiB() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;  // Linux: KiB
}

void PrintSlowest(const std::vector<MeshRun>& runs, double MeshRun::*field, const char* what, int top) {
  std::vector<const MeshRun*> order;
  for (const auto& r : runs) order.push_back(&r);
  std::sort(order.begin(), order.end(), [&](const MeshRun* a, const MeshRun* b) { return a->*field > b->*field; });
  std::printf("slowest %s:\n", what);
  for (int i = 0; i < top && i < static_cast<int>(order.size()); ++i)
    std::printf("  %8.3f s  %6lld faces  %s\n", order[i]->*field, static_cast<long long>(order[i]->faces),
                order[i]->path.c_str());
}

int Usage() {
  std::fprintf(stderr,
               "usage: tokenizer_bench [-j THREADS (default 2)] [--top K (default 5)] PATH...\n"
               "  PATH: mesh files or folders (searched recursively for .obj .ply .stl .off .gltf .glb .pmd)\n");
  return 2;
}

struct Options {
  int threads = 2, top = 5;
  std::vector<std::string> inputs;
};

// -j N, --top K and the paths; false on a bad argument.
bool ParseArgs(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "-j" || a == "--top") && i + 1 < argc) {
      const int v = std::atoi(argv[++i]);
      if (v < (a == "-j" ? 1 : 0)) return false;
      (a == "-j" ? o->threads : o->top) = v;
    } else if (a == "-h" || a == "--help" || (!a.empty() && a[0] == '-')) {
      return false;
    } else {
      o->inputs.push_back(a);
    }
  }
  return !o->inputs.empty();
}

// Pass 1 (the baseline) on one mesh: read + normalise.
void ReadAndNormalize(MeshRun& r) {
  auto t0 = Clock::now();
  auto raw = silk::ReadMeshFile(r.path);
  r.read_s = Since(t0);
  if (!raw.ok()) {
    r.failure = FailureName(raw.status(), "read");
    return;
  }
  r.faces = static_cast<int64_t>(raw->triangles.size());
  r.vertices = static_cast<int64_t>(raw->positions.size());
  t0 = Clock::now();
  auto norm = silk::NormalizeMesh(*raw);
  r.normalize_s = Since(t0);
  if (!norm.ok()) {
    r.failure = FailureName(norm.status(), "normalize");
    return;
  }
  r.normalized = std::move(*norm);
}

// Pass 2 on one mesh: encode (then drop the normalised mesh to keep memory flat for the decode pass).
void Encode(MeshRun& r) {
  if (!r.failure.empty()) return;
  const auto t0 = Clock::now();
  try {
    auto enc = silk::EncodeMesh(r.normalized);
    r.encode_s = Since(t0);
    if (!enc.ok()) {
      r.failure = FailureName(enc.status(), "encode");
    } else {
      r.tokens = std::move(enc->tokens);
      r.stats = enc->stats;
    }
  } catch (const std::exception& e) {
    r.encode_s = Since(t0);
    r.failure = "encode threw (bug)";
  }
  r.normalized = silk::IoMesh();
}

// Pass 3 on one mesh: decode its tokens.
void Decode(MeshRun& r) {
  if (!r.failure.empty()) return;
  const auto t0 = Clock::now();
  try {
    auto dec = silk::DecodeTokens(r.tokens);
    r.decode_s = Since(t0);
    if (!dec.ok()) {
      r.failure = FailureName(dec.status(), "decode");
    } else {
      r.decoded = true;
      r.decoded_faces = static_cast<int64_t>(dec->faces.size());
    }
  } catch (const std::exception& e) {
    r.decode_s = Since(t0);
    r.failure = "decode threw (bug)";
  }
}

struct Passes {
  PassTime read, encode, decode;
  double total_wall = 0;
};

// The page cache warmed (untimed), then the three passes, each over every mesh on `threads` workers.
Passes RunPasses(std::vector<MeshRun>& runs, int threads, Clock::time_point t_all) {
  const size_t n = runs.size();
  ParallelFor(n, threads, [&](size_t i) {
    std::ifstream f(runs[i].path, std::ios::binary);
    std::vector<char> buf(1 << 16);
    while (f.read(buf.data(), buf.size()) || f.gcount() > 0) {
    }
  });
  Passes p;
  p.read = ParallelFor(n, threads, [&](size_t i) { ReadAndNormalize(runs[i]); });
  p.encode = ParallelFor(n, threads, [&](size_t i) { Encode(runs[i]); });
  p.decode = ParallelFor(n, threads, [&](size_t i) { Decode(runs[i]); });
  p.total_wall = Since(t_all);
  return p;
}

struct Totals {
  int64_t read_ok = 0, faces_read = 0, encode_tried = 0, encoded = 0, faces_encoded = 0, decoded = 0, faces_decoded = 0,
          tokens = 0, encodable_faces = 0;
  double sum_read = 0, sum_norm = 0, sum_enc = 0, sum_dec = 0, sum_enc_ok = 0;
  silk::EncodePhaseTimes ph;
  std::map<std::string, std::pair<int, double>> failures;  // count, encode+decode thread time
};

void AddPhases(const silk::EncodePhaseTimes& t, silk::EncodePhaseTimes* ph) {
  ph->quantize_cleanup += t.quantize_cleanup;
  ph->nonmanifold += t.nonmanifold;
  ph->orientation += t.orientation;
  ph->components += t.components;
  ph->layering += t.layering;
  ph->codecs += t.codecs;
  ph->packing += t.packing;
}

Totals Summarize(const std::vector<MeshRun>& runs) {
  Totals s;
  for (const MeshRun& r : runs) {
    s.sum_read += r.read_s;
    s.sum_norm += r.normalize_s;
    s.sum_enc += r.encode_s;
    s.sum_dec += r.decode_s;
    if (r.failure.rfind("read", 0) != 0) {
      ++s.read_ok;
      s.faces_read += r.faces;
    }
    if (!r.failure.empty()) {
      s.failures[r.failure].first++;
      s.failures[r.failure].second += r.encode_s + r.decode_s;
    }
    if (r.encode_s > 0 || r.stats.tokens > 0) {
      ++s.encode_tried;
      s.faces_encoded += r.faces;
    }
    if (!r.tokens.empty() || r.decoded) {
      ++s.encoded;
      s.tokens += r.stats.tokens;
      s.sum_enc_ok += r.encode_s;
      s.encodable_faces += r.stats.encodable_faces;
      AddPhases(r.stats.times, &s.ph);
    }
    if (r.decoded) {
      ++s.decoded;
      s.faces_decoded += r.decoded_faces;
    }
  }
  return s;
}

void PrintPasses(const Passes& p, const Totals& s, size_t n, int threads) {
  std::printf("\n== passes (wall clock, %d threads) ==\n", threads);
  std::printf("%-26s %7s %9s %9s %10s %12s %13s %11s\n", "pass", "meshes", "wall s", "cpu s", "meshes/s", "faces/s",
              "thread-s/mesh", "cpu-s/mesh");
  auto row = [&](const char* name, int64_t m, PassTime t, int64_t faces, double thread_s) {
    std::printf("%-26s %7lld %9.3f %9.3f %10.1f %12.0f %13.5f %11.5f\n", name, static_cast<long long>(m), t.wall, t.cpu,
                t.wall > 0 ? m / t.wall : 0.0, t.wall > 0 ? faces / t.wall : 0.0, m ? thread_s / m : 0.0,
                m ? t.cpu / m : 0.0);
  };
  row("read+normalize (baseline)", static_cast<int64_t>(n), p.read, s.faces_read, s.sum_read + s.sum_norm);
  row("encode", s.encode_tried, p.encode, s.faces_encoded, s.sum_enc);
  row("decode", s.decoded, p.decode, s.faces_decoded, s.sum_dec);
  row("encode+decode", s.encode_tried, {p.encode.wall + p.decode.wall, p.encode.cpu + p.decode.cpu}, s.faces_encoded,
      s.sum_enc + s.sum_dec);
  std::printf(
      "(faces/s: input faces for read and encode, decoded faces for decode; thread-s: wall time inside\n"
      " each call summed over threads; cpu s: process CPU time of the pass)\n");
  std::printf("read alone: %.3f thread-s, normalize alone: %.3f thread-s\n", s.sum_read, s.sum_norm);
  std::printf(
      "encode+decode wall = %.2fx the read+normalize baseline; total wall (with file walk and "
      "cache warm-up) %.3f s\n",
      p.read.wall > 0 ? (p.encode.wall + p.decode.wall) / p.read.wall : 0.0, p.total_wall);
}

void PrintPhases(const Totals& s) {
  std::printf(
      "\n== encode phases (EncodeStats::times summed over %lld encoded meshes, %% of all encode thread time %.3f s) "
      "==\n",
      static_cast<long long>(s.encoded), s.sum_enc);
  const silk::EncodePhaseTimes& ph = s.ph;
  const std::pair<const char*, double> phases[] = {{"quantize+cleanup", ph.quantize_cleanup},
                                                   {"non-manifold", ph.nonmanifold},
                                                   {"orientation", ph.orientation},
                                                   {"components", ph.components},
                                                   {"layering", ph.layering},
                                                   {"codecs", ph.codecs},
                                                   {"packing", ph.packing}};
  const double sum_enc = s.sum_enc;
  double phase_sum = 0;
  for (const auto& p : phases) {
    phase_sum += p.second;
    std::printf("  %-18s %9.3f s %6.1f%%\n", p.first, p.second, sum_enc > 0 ? 100 * p.second / sum_enc : 0.0);
  }
  std::printf("  %-18s %9.3f s %6.1f%%  (encoded meshes, time outside the phases)\n", "other", s.sum_enc_ok - phase_sum,
              sum_enc > 0 ? 100 * (s.sum_enc_ok - phase_sum) / sum_enc : 0.0);
  std::printf("  %-18s %9.3f s %6.1f%%  (meshes refused by the encoder; no phase split returned)\n", "refused meshes",
              sum_enc - s.sum_enc_ok, sum_enc > 0 ? 100 * (sum_enc - s.sum_enc_ok) / sum_enc : 0.0);
}

void PrintOutcome(const Totals& s, const Passes& p, size_t n) {
  std::printf("\n== outcome ==\n");
  std::printf("encoded %lld / %zu meshes, decoded %lld; tokens %lld; faces: read %lld, encodable %lld, decoded %lld\n",
              static_cast<long long>(s.encoded), n, static_cast<long long>(s.decoded), static_cast<long long>(s.tokens),
              static_cast<long long>(s.faces_read), static_cast<long long>(s.encodable_faces),
              static_cast<long long>(s.faces_decoded));
  for (const auto& [why, f] : s.failures)
    std::printf("  %-34s %6d meshes  %8.3f thread-s spent before the refusal\n", why.c_str(), f.first, f.second);

  std::printf("\n== baseline and reference ==\n");
  std::printf("I/O baseline (read+normalize, same run): %.3f s wall for %zu meshes\n", p.read.wall, n);
  std::printf(
      "official Python tokenizer (reference from the issue, not measured): ~%.2f s/mesh -> ~%.0f s "
      "single-threaded for these %zu meshes; ours: %.4f s/mesh encode, %.4f s/mesh encode+decode "
      "(thread time)\n",
      kPythonSecondsPerMesh, kPythonSecondsPerMesh * n, n, s.encode_tried ? s.sum_enc / s.encode_tried : 0.0,
      s.encode_tried ? (s.sum_enc + s.sum_dec) / s.encode_tried : 0.0);
  std::printf("peak RSS: %.1f MiB (all normalized meshes are held between passes); load average at end %s\n\n",
              PeakRssMiB(), LoadAverage().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!ParseArgs(argc, argv, &o)) return Usage();
  const auto t_all = Clock::now();
  std::vector<MeshRun> runs;
  for (const std::string& p : CollectMeshFiles(o.inputs)) runs.emplace_back().path = p;
  if (runs.empty()) {
    std::fprintf(stderr, "tokenizer_bench: no mesh files found\n");
    return 1;
  }
  const size_t n = runs.size();
  std::printf("tokenizer_bench: %zu meshes, %d threads, %u hardware threads, load average at start %s\n", n, o.threads,
              std::thread::hardware_concurrency(), LoadAverage().c_str());
  const Passes passes = RunPasses(runs, o.threads, t_all);
  const Totals totals = Summarize(runs);
  PrintPasses(passes, totals, n, o.threads);
  PrintPhases(totals);
  PrintOutcome(totals, passes, n);
  if (o.top > 0) {
    PrintSlowest(runs, &MeshRun::encode_s, "encode", o.top);
    PrintSlowest(runs, &MeshRun::decode_s, "decode", o.top);
  }
  return 0;
}
