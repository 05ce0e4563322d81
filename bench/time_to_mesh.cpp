// SPDX-License-Identifier: MIT
// time_to_mesh: what a mesh of N model calls costs from depth 0 with a release-size network, for
// each decoder precision x KV cache precision: wall time (load, encoder, the N calls), peak RSS,
// ms per call at the end, beside the memory-bandwidth bound for the same bytes (read bandwidth
// measured in the same run) and the official PyTorch loop (bench/official_loop.py, run in the
// same run at a few depths and extrapolated to N calls by its measured cost per depth).
//
//   time_to_mesh --model DIR [--calls 1000,4000] [--decoders int4,int8,fp32] [--kv fp32,fp16,int8]
//                [--threads 2] [--official-depths 0,1024] [--official-steps 24] [--no-official]
//
// A --kv item PRECISION@FOLDER takes that precision's variant from another model folder (e.g. one
// whose fp16 variants are `silk-export kv16 --attention ort`), printed as PRECISION@<folder name>.
//
// One pass of max(calls) calls per config; the figures for a smaller N are that pass's first N
// calls (the same thing: N calls from depth 0). Each config runs in a forked child (its own peak
// RSS); the KV precisions of one decoder are loaded side by side and fed in turns of 100 calls,
// so load from other processes hits them alike (decoders run one after the other: memory).
// Random ids: the decoder's cost does not depend on which ids it is fed.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_memory.h"
#include "runtime/decoder_runner.h"
#include "runtime/model/model.h"

namespace {

using silk::DecoderPrecision;
using silk::KvPrecision;
using silk::bench::Clock;
using silk::bench::Since;

// One KV configuration: a precision, from --model or from another folder.
struct KvConfig {
  KvPrecision precision = KvPrecision::kFp32;
  std::string folder;  // "" = --model
  std::string label;
};

struct Args {
  std::string model;
  std::vector<int> calls = {1000, 4000};
  std::vector<DecoderPrecision> decoders = {DecoderPrecision::kInt4};
  std::vector<KvConfig> kvs = {{KvPrecision::kFp32, "", "fp32"}, {KvPrecision::kFp16, "", "fp16"}};
  int threads = 2;
  std::vector<int> official_depths = {0, 1024};
  int official_steps = 24;
  bool official = true;
};

// One config's pass, written by the child to a pipe as plain doubles.
struct Pass {
  double load_s = 0, encoder_s = 0, rss_mib = 0;
  double cross_bytes = 0;    // of the cross K/V each call reads (float32 or float16, as loaded)
  double seconds[8] = {};    // decoder seconds for the first calls[i] calls
  double ms_at_end[8] = {};  // ms per call over the last 50 calls before calls[i]
  double ok = 0;
};

// A loaded model with its encoder output and cache, fed `block` calls at a time when its parent
// says so, so that the KV precisions of one decoder share the machine's load equally.
struct Worker {
  std::unique_ptr<silk::Model> model;
  Ort::Value cross{nullptr};
  silk::KvCache cache;
  std::unique_ptr<silk::DecoderRunner> runner;
  std::mt19937 rng{1};
  std::vector<double> at{0.0};  // decoder seconds after call i
};

bool OpenWorker(const Args& a, DecoderPrecision p, const KvConfig& kv, Worker* w, Pass* r) {
  silk::ModelLoadOptions lo;
  lo.threads = a.threads;
  lo.decoder = p;
  lo.kv = kv.precision;
  auto t0 = Clock::now();
  auto model = silk::Model::Load(kv.folder.empty() ? a.model : kv.folder, lo);
  if (!model.ok()) {
    std::fprintf(stderr, "  %s\n", model.status().ToString().c_str());
    return false;
  }
  r->load_s = Since(t0);
  w->model = std::move(*model);
  const silk::ModelConfig& c = w->model->config();
  std::uniform_real_distribution<float> u(-0.9f, 0.9f);
  std::vector<float> pts(static_cast<size_t>(c.dims.n_points) * 6);
  for (float& v : pts) v = u(w->rng);
  t0 = Clock::now();
  auto cross = silk::RunEncoder(w->model->impl(), pts.data(), c.dims.n_points);
  if (!cross.ok()) return false;
  r->encoder_s = Since(t0);
  w->cross = std::move(*cross);
  const auto info = w->cross.GetTensorTypeAndShapeInfo();
  r->cross_bytes = static_cast<double>(info.GetElementCount()) *
                   (info.GetElementType() == ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16 ? 2 : 4);
  if (!w->cache.Reserve(a.calls.back() + 1, silk::ModelKvShape(w->model->impl())).ok()) return false;
  w->runner = std::make_unique<silk::DecoderRunner>(w->model->impl(), &w->cache, w->cross.GetTensorMutableData<void>());
  return true;
}

// `n` more calls (the first feeds BOS at depth 0, the others random ids).
bool Feed(Worker& w, int n) {
  const silk::ModelConfig& c = w.model->config();
  std::uniform_int_distribution<int32_t> tok(0, c.eos_id - 1);
  for (int i = 0; i < n; ++i) {
    const int32_t id = w.cache.length() == 0 ? c.bos_id : tok(w.rng);
    const auto t0 = Clock::now();
    if (!w.runner->Feed(&id, 1).ok()) return false;
    w.at.push_back(w.at.back() + Since(t0));
  }
  return true;
}

void Summarise(const Args& a, const Worker& w, Pass* r) {
  for (size_t k = 0; k < a.calls.size() && k < 8; ++k) {
    const int m = a.calls[k], win = std::min(50, m);
    r->seconds[k] = w.at[m];
    r->ms_at_end[k] = (w.at[m] - w.at[m - win]) / win * 1e3;
  }
  r->rss_mib = silk::bench::PeakRssMiB();
  r->ok = 1;
}

// A forked worker: loads, then reads block sizes from `cmd` (0 = done) and answers each with one
// byte on `out` (1 = fed, 0 = failed), and finally the Pass.
[[noreturn]] void WorkerMain(const Args& a, DecoderPrecision p, const KvConfig& kv, int cmd, int out) {
  Worker w;
  Pass r;
  char ok = OpenWorker(a, p, kv, &w, &r) ? 1 : 0;
  if (write(out, &ok, 1) != 1 || !ok) _exit(1);
  for (int n = 0; read(cmd, &n, sizeof n) == static_cast<ssize_t>(sizeof n) && n > 0;) {
    ok = Feed(w, n) ? 1 : 0;
    if (write(out, &ok, 1) != 1 || !ok) _exit(1);
  }
  Summarise(a, w, &r);
  _exit(write(out, &r, sizeof r) == static_cast<ssize_t>(sizeof r) ? 0 : 1);
}

struct Child {
  pid_t pid = -1;
  int cmd = -1, out = -1;
  bool alive = false;
};

Child Spawn(const Args& a, DecoderPrecision p, const KvConfig& kv) {
  int c[2], o[2];
  Child ch;
  if (pipe(c) != 0 || pipe(o) != 0) return ch;
  ch.pid = fork();
  if (ch.pid == 0) {
    close(c[1]);
    close(o[0]);
    WorkerMain(a, p, kv, c[0], o[1]);
  }
  close(c[0]);
  close(o[1]);
  ch.cmd = c[1];
  ch.out = o[0];
  char ok = 0;
  ch.alive = read(ch.out, &ok, 1) == 1 && ok == 1;
  return ch;
}

// All KV precisions of one decoder, loaded side by side and fed in turns of `kBlock` calls, so a
// change of the machine's load during the run hits each of them alike.
constexpr int kBlock = 100;

std::vector<Pass> RunInterleaved(const Args& a, DecoderPrecision p, const std::vector<KvConfig>& kvs) {
  std::vector<Child> kids;
  for (const KvConfig& kv : kvs) kids.push_back(Spawn(a, p, kv));
  for (int done = 0; done < a.calls.back(); done += kBlock) {
    const int n = std::min(kBlock, a.calls.back() - done);
    for (Child& ch : kids) {
      char ok = 0;
      if (ch.alive)
        ch.alive =
            write(ch.cmd, &n, sizeof n) == static_cast<ssize_t>(sizeof n) && read(ch.out, &ok, 1) == 1 && ok == 1;
    }
  }
  std::vector<Pass> passes(kids.size());
  for (size_t i = 0; i < kids.size(); ++i) {
    const int zero = 0;
    if (kids[i].alive && write(kids[i].cmd, &zero, sizeof zero) == static_cast<ssize_t>(sizeof zero) &&
        read(kids[i].out, &passes[i], sizeof(Pass)) != static_cast<ssize_t>(sizeof(Pass)))
      passes[i] = Pass{};
    if (kids[i].cmd >= 0) close(kids[i].cmd);
    if (kids[i].out >= 0) close(kids[i].out);
    if (kids[i].pid > 0) waitpid(kids[i].pid, nullptr, 0);
  }
  return passes;
}

// Bytes the N calls from depth 0 read: per call the weights as stored in the KV variant's file
// (less the two fp32 tables, of which one row each is read) and the cross K/V as loaded (float32,
// or float16 in the silk form of the cache variants), plus the self K/V of the prefix
// (call i reads i positions): N (W + X) + R N (N - 1) / 2.
struct Bytes {
  double weights = 0, cross = 0, row = 0;
  double Total(int n) const { return n * (weights + cross) + row * n * (n - 1) / 2.0; }
  double AtDepth(int depth) const { return weights + cross + row * depth; }
};

Bytes CallBytes(const silk::ModelConfig& c, DecoderPrecision p, KvPrecision kv, double cross_bytes) {
  const silk::ModelDims& d = c.dims;
  Bytes b;
  b.weights = silk::bench::DecoderFileBytes(c, p, kv) - double(c.embedding_rows + d.max_seq_len) * d.d_model * 4;
  b.cross = cross_bytes;
  b.row = static_cast<double>(silk::KvShapeOf(d, kv).position_bytes());
  return b;
}

// bench/official_loop.py's JSON (ms per call at each depth), or null when it failed.
nlohmann::json RunOfficial(const Args& a) {
  std::ostringstream cmd;
  cmd << "python3 " << SILK_BENCH_DIR << "/official_loop.py --threads " << a.threads << " --steps " << a.official_steps
      << " --depths";
  for (int d : a.official_depths) cmd << " " << d;
  FILE* f = popen(cmd.str().c_str(), "r");
  if (!f) return nullptr;
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, f)) out.append(buf, n);
  if (pclose(f) != 0) return nullptr;
  const nlohmann::json j = nlohmann::json::parse(out, nullptr, false);
  return j.is_discarded() ? nlohmann::json(nullptr) : j;
}

// Least-squares line ms(depth) = a + b * depth through the official figures; seconds for N calls
// from depth 0 = sum over i < N of (a + b i).
double OfficialSeconds(const nlohmann::json& off, int n, double* a_ms, double* b_ms) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, k = 0;
  for (auto& [depth, ms] : off["ms_per_call"].items()) {
    const double x = std::atof(depth.c_str()), y = ms.get<double>();
    sx += x, sy += y, sxx += x * x, sxy += x * y, k += 1;
  }
  const double den = k * sxx - sx * sx;
  *b_ms = den > 0 ? (k * sxy - sx * sy) / den : 0;
  *a_ms = (sy - *b_ms * sx) / std::max(1.0, k);
  return (n * *a_ms + *b_ms * n * (n - 1) / 2.0) / 1e3;
}

std::vector<int> Ints(const std::string& s) {
  std::vector<int> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) v.push_back(std::atoi(x.c_str()));
  return v;
}

bool ParseArgs(int argc, char** argv, Args* a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (k == "--model")
      a->model = next();
    else if (k == "--calls")
      a->calls = Ints(next());
    else if (k == "--threads")
      a->threads = std::atoi(next().c_str());
    else if (k == "--official-depths")
      a->official_depths = Ints(next());
    else if (k == "--official-steps")
      a->official_steps = std::atoi(next().c_str());
    else if (k == "--no-official")
      a->official = false;
    else if (k == "--decoders") {
      a->decoders.clear();
      std::stringstream ss(next());
      for (std::string x; std::getline(ss, x, ',');)
        a->decoders.push_back(x == "int8"   ? DecoderPrecision::kInt8
                              : x == "fp32" ? DecoderPrecision::kFp32
                                            : DecoderPrecision::kInt4);
    } else if (k == "--kv") {
      a->kvs.clear();
      std::stringstream ss(next());
      for (std::string x; std::getline(ss, x, ',');) {
        KvConfig c;
        const size_t at = x.find('@');
        if (at != std::string::npos) c.folder = x.substr(at + 1);
        if (!silk::ParseKvPrecision(x.substr(0, at), &c.precision)) return false;
        c.label = silk::KvPrecisionName(c.precision);
        if (!c.folder.empty()) c.label += "@" + c.folder.substr(c.folder.find_last_of('/') + 1);
        a->kvs.push_back(c);
      }
    } else
      return false;
  }
  std::sort(a->calls.begin(), a->calls.end());
  return !a->model.empty() && !a->calls.empty() && a->calls.front() > 0 && a->calls.size() <= 8;
}

std::string LoadAverage() {
  double l[3] = {0, 0, 0};
  if (getloadavg(l, 3) < 0) return "?";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f %.2f %.2f", l[0], l[1], l[2]);
  return buf;
}

void PrintConfig(const Args& a, const silk::ModelConfig& c, DecoderPrecision p, const KvConfig& kv, const Pass& r,
                 const nlohmann::json& official) {
  const Bytes b = CallBytes(c, p, kv.precision, r.cross_bytes);
  for (size_t k = 0; k < a.calls.size(); ++k) {
    const int n = a.calls[k];
    const double avg_bytes = b.AtDepth(n / 2);
    const double gbps = silk::bench::ReadBandwidth(a.threads, static_cast<int64_t>(std::min(avg_bytes, 4e9)));
    const double bound_s = b.Total(n) / (gbps * 1e9);
    std::printf("%-5s %-5s %6d | %7.1f %6.1f %8.1f %8.1f | %7.1f %7.1f | %8.1f %4.0f%% %5.1f | %8.0f |",
                silk::DecoderPrecisionName(p), kv.label.c_str(), n, r.load_s, r.encoder_s, r.seconds[k],
                r.load_s + r.encoder_s + r.seconds[k], r.seconds[k] / n * 1e3, r.ms_at_end[k], bound_s,
                100 * bound_s / r.seconds[k], gbps, r.rss_mib);
    if (official.is_object()) {
      double oa = 0, ob = 0;
      const double os = OfficialSeconds(official, n, &oa, &ob);
      std::printf(" %8.0f %6.1fx", os, os / r.seconds[k]);
    }
    std::printf("   [load %s]\n", LoadAverage().c_str());
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (!ParseArgs(argc, argv, &a)) {
    std::fprintf(
        stderr,
        "usage: time_to_mesh --model DIR [--calls 1000,4000] [--decoders int4,int8,fp32] [--kv fp32,fp16,int8]\n"
        "                    [--threads 2] [--official-depths 0,1024] [--official-steps 24] [--no-official]\n"
        "  (DIR: a release-size model folder, e.g. python3 bench/export_bench_models.py --configs official\n"
        "   --out OUT, then python3 -m silk_export kv16 OUT/official; a --kv item PRECISION@FOLDER takes\n"
        "   that variant from another folder)\n");
    return 2;
  }
  auto cfg = silk::LoadModelConfig(a.model);
  if (!cfg.ok()) {
    std::fprintf(stderr, "%s\n", cfg.status().ToString().c_str());
    return 1;
  }
  std::printf("time_to_mesh: %s (%s, %d layers, d_model %d), %d threads, load average at start %s\n", a.model.c_str(),
              cfg->config_name.c_str(), cfg->dims.n_layers, cfg->dims.d_model, a.threads, LoadAverage().c_str());
  nlohmann::json official = nullptr;
  if (a.official) {
    const auto t0 = Clock::now();
    official = RunOfficial(a);
    if (official.is_object()) {
      double oa = 0, ob = 0;
      OfficialSeconds(official, 1, &oa, &ob);
      std::printf(
          "official loop (bench/official_loop.py: %s; %.0f s incl. building the model): ms per call %s "
          "-> %.1f ms + %.4f ms x depth   [load %s]\n",
          official["what"].get<std::string>().c_str(), Since(t0), official["ms_per_call"].dump().c_str(), oa, ob,
          LoadAverage().c_str());
    } else {
      std::printf("official loop: bench/official_loop.py failed (no official column)\n");
    }
  }
  std::printf(
      "\ndec   kv      N  | load s  enc s  calls s  total s | ms/call ms@end | bound s  %%bnd  GB/s | peak MiB |"
      " official s  speed-up\n");
  for (DecoderPrecision p : a.decoders) {
    std::vector<KvConfig> kvs;
    for (const KvConfig& kv : a.kvs) {
      auto other = kv.folder.empty() ? cfg : silk::LoadModelConfig(kv.folder);
      if (other.ok() && !other->DecoderFile(p, kv.precision).empty())
        kvs.push_back(kv);
      else
        std::printf("%-5s %-5s: not in that model folder (skipped)\n", silk::DecoderPrecisionName(p), kv.label.c_str());
    }
    std::fflush(stdout);
    const std::vector<Pass> passes = RunInterleaved(a, p, kvs);
    for (size_t i = 0; i < kvs.size(); ++i) {
      if (!passes[i].ok)
        std::printf("%-5s %-5s: failed\n", silk::DecoderPrecisionName(p), kvs[i].label.c_str());
      else
        PrintConfig(a, *cfg, p, kvs[i], passes[i], official);
      std::fflush(stdout);
    }
  }
  std::printf(
      "\n(calls s: decoder time of the first N calls from depth 0; ms@end: per call over calls N-50..N; "
      "bound: bytes of those N calls / read bandwidth of a working set of one call at depth N/2; "
      "official: its fitted cost summed over the same N calls)\n");
  return 0;
}
