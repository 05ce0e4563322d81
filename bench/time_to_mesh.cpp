// SPDX-License-Identifier: MIT
// time_to_mesh: what a mesh of N model calls costs from depth 0 with a release-size network, for
// each decoder precision x KV cache precision: wall time (load, encoder, the N calls), peak RSS,
// ms per call at the end, beside the memory-bandwidth bound for the same bytes (read bandwidth
// measured in the same run) and the official PyTorch loop (bench/official_loop.py, run in the
// same run at a few depths and extrapolated to N calls by its measured cost per depth).
//
//   time_to_mesh --model DIR [--calls 1000,4000] [--decoders int4,int8,fp32] [--kv fp32,fp16,int8]
//                [--threads 2] [--official-depths 0,1024] [--official-steps 24] [--no-official]
//                [--rows 1,2,4,8 [--baseline DIR]] [--block 100]
//
// A --kv item PRECISION@FOLDER takes that precision's variant from another model folder (e.g. one
// whose fp16 variants are `silk-export kv16 --attention ort`), printed as PRECISION@<folder name>.
//
// One pass of max(calls) calls per config; the figures for a smaller N are that pass's first N
// calls (the same thing: N calls from depth 0). Each config runs in a forked child (its own peak
// RSS); the KV precisions of one decoder are loaded side by side and fed in turns of --block calls (100),
// so load from other processes hits them alike (decoders run one after the other: memory).
// Random ids: the decoder's cost does not depend on which ids it is fed.
//
// --rows R1,R2,..: many sequences per call (decoder contract v4, issue 34). For each decoder x KV
// config, one child per R feeds R rows together from depth 0 through RowsDecoder over a
// RowsKvCache (one id per row per call, BOS first, all rows attending to one encoder output),
// beside a child feeding one sequence through DecoderRunner (today's path), all interleaved in
// turns of --block calls as above. Per R: ms per call, rows x calls per second and its ratio to R = 1
// of the same run, bytes per call and the bound counting the weights and cross K/V once and each
// row's cache, peak RSS; and R = 1 through RowsDecoder against DecoderRunner. --baseline DIR adds a
// DecoderRunner child on DIR's variant of the same precision (the same weights as a contract v3
// folder: today's graph).
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
#include "runtime/rows_decoder.h"
#include "runtime/rows_kv_cache.h"

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
  std::vector<int> rows;  // --rows: R values (empty: the table of KV precisions)
  std::string baseline;   // --baseline DIR: a second DecoderRunner child on DIR's variant (e.g. contract v3)
  int block = 100;        // --block: calls per child per turn
};

// One child's work: a KV configuration, fed as one sequence through DecoderRunner (rows 0) or as
// `rows` sequences together through RowsDecoder.
struct Job {
  KvConfig kv;
  int rows = 0;
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
  silk::RowsKvCache rows_cache;  // --rows: R sequences together
  std::unique_ptr<silk::RowsDecoder> rows;
  std::vector<int32_t> ids;  // this call's id of each row
  std::vector<silk::RowFeed> feeds;
  std::mt19937 rng{1};
  std::vector<double> at{0.0};  // decoder seconds after call i
};

// The decoder of a Worker: DecoderRunner over a KvCache of max(calls) + 1 positions, or (rows > 0)
// RowsDecoder over a RowsKvCache of `rows` slots that grows by doubling from 512 positions.
bool OpenDecoder(const Args& a, int rows, Worker* w) {
  const silk::Model::Impl& m = w->model->impl();
  if (rows == 0) {
    if (!w->cache.Reserve(a.calls.back() + 1, silk::ModelKvShape(m)).ok()) return false;
    w->runner = std::make_unique<silk::DecoderRunner>(m, &w->cache, w->cross.GetTensorMutableData<void>());
    return true;
  }
  const silk::Status st = w->rows_cache.Reserve(rows, a.calls.back() + 1, silk::ModelKvShape(m));
  if (!st.ok()) {
    std::fprintf(stderr, "  %s\n", st.ToString().c_str());
    return false;
  }
  w->rows = std::make_unique<silk::RowsDecoder>(m, &w->rows_cache);
  w->rows->SetSources(1);
  w->rows->SetSource(0, w->cross.GetTensorMutableData<void>());
  w->ids.assign(static_cast<size_t>(rows), 0);
  for (int32_t r = 0; r < rows; ++r) w->feeds.push_back({r, &w->ids[static_cast<size_t>(r)], 1, 0});
  return true;
}

bool OpenWorker(const Args& a, const Job& job, DecoderPrecision p, Worker* w, Pass* r) {
  const KvConfig& kv = job.kv;
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
  return OpenDecoder(a, job.rows, w);
}

// `n` more calls (the first feeds BOS at depth 0, the others random ids; with rows, one id per row
// per call).
bool Feed(Worker& w, int n) {
  const silk::ModelConfig& c = w.model->config();
  std::uniform_int_distribution<int32_t> tok(0, c.eos_id - 1);
  for (int i = 0; i < n; ++i) {
    const bool first = w.at.size() == 1;
    const int32_t id = first ? c.bos_id : tok(w.rng);
    for (int32_t& row_id : w.ids) row_id = first ? c.bos_id : tok(w.rng);
    const auto t0 = Clock::now();
    const silk::Status st = w.rows ? w.rows->Feed(w.feeds) : w.runner->Feed(&id, 1);
    if (!st.ok()) {
      std::fprintf(stderr, "  %s\n", st.ToString().c_str());
      return false;
    }
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
[[noreturn]] void WorkerMain(const Args& a, DecoderPrecision p, const Job& job, int cmd, int out) {
  Worker w;
  Pass r;
  char ok = OpenWorker(a, job, p, &w, &r) ? 1 : 0;
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

Child Spawn(const Args& a, DecoderPrecision p, const Job& job) {
  int c[2], o[2];
  Child ch;
  if (pipe(c) != 0 || pipe(o) != 0) return ch;
  ch.pid = fork();
  if (ch.pid == 0) {
    close(c[1]);
    close(o[0]);
    WorkerMain(a, p, job, c[0], o[1]);
  }
  close(c[0]);
  close(o[1]);
  ch.cmd = c[1];
  ch.out = o[0];
  char ok = 0;
  ch.alive = read(ch.out, &ok, 1) == 1 && ok == 1;
  return ch;
}

// The jobs of one decoder (its KV precisions, or one KV precision's R values), loaded side by side
// and fed in turns of --block calls (100), so a change of the machine's load during the run hits
// each of them alike (a smaller block: alike at a finer grain, for close comparisons).
std::vector<Pass> RunInterleaved(const Args& a, DecoderPrecision p, const std::vector<Job>& jobs) {
  std::vector<Child> kids;
  for (const Job& job : jobs) kids.push_back(Spawn(a, p, job));
  for (int done = 0; done < a.calls.back(); done += a.block) {
    const int n = std::min(a.block, a.calls.back() - done);
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
// or float16 in the silk form of the cache variants), once for all rows, plus each row's self K/V
// of its prefix (call i reads i positions of each of the R rows): N (W + X) + R P N (N - 1) / 2,
// P the bytes of one position.
struct Bytes {
  double weights = 0, cross = 0, row = 0, rows = 1;
  double Total(int n) const { return n * (weights + cross) + rows * row * n * (n - 1) / 2.0; }
  double AtDepth(int depth) const { return weights + cross + rows * row * depth; }
};

Bytes CallBytes(const silk::ModelConfig& c, DecoderPrecision p, KvPrecision kv, double cross_bytes, int rows = 1) {
  const silk::ModelDims& d = c.dims;
  Bytes b;
  b.rows = rows;
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
    else if (k == "--rows")
      a->rows = Ints(next());
    else if (k == "--baseline")
      a->baseline = next();
    else if (k == "--block")
      a->block = std::atoi(next().c_str());
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
  for (int r : a->rows)
    if (r < 1 || r > 64) return false;
  if (a->block < 1) return false;
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

// One --rows pass at N calls: rows x calls per second, and the bound for its bytes.
struct RowsLine {
  double seconds = 0, rate = 0, mb_per_call = 0, bound_s = 0, gbps = 0;
};

RowsLine RowsFigures(const Args& a, const silk::ModelConfig& c, DecoderPrecision p, const Job& job, const Pass& r,
                     size_t k) {
  const int n = a.calls[k], rows = std::max(job.rows, 1);
  const Bytes b = CallBytes(c, p, job.kv.precision, r.cross_bytes, rows);
  RowsLine l;
  l.seconds = r.seconds[k];
  l.rate = rows * n / r.seconds[k];
  l.mb_per_call = b.Total(n) / n / 1e6;
  l.gbps = silk::bench::ReadBandwidth(a.threads, static_cast<int64_t>(std::min(b.AtDepth(n / 2), 4e9)));
  l.bound_s = b.Total(n) / (l.gbps * 1e9);
  return l;
}

// The --rows table of one decoder x KV config: per N, the DecoderRunner baseline (jobs[0]) and each
// R, then R = 1 through RowsDecoder against DecoderRunner (the cost of the rows path for one row).
void PrintRows(const Args& a, const silk::ModelConfig& c, DecoderPrecision p, const std::vector<Job>& jobs,
               const std::vector<Pass>& passes) {
  for (size_t k = 0; k < a.calls.size(); ++k) {
    const int n = a.calls[k];
    std::vector<RowsLine> lines(jobs.size());
    double one_rate = 0;  // rows x calls / s of R = 1 through RowsDecoder (else DecoderRunner)
    for (size_t i = 0; i < jobs.size(); ++i) {
      if (!passes[i].ok) continue;
      lines[i] = RowsFigures(a, c, p, jobs[i], passes[i], k);
      if (jobs[i].rows <= 1 && (jobs[i].rows == 1 || one_rate == 0)) one_rate = lines[i].rate;
    }
    for (size_t i = 0; i < jobs.size(); ++i) {
      const char* path = jobs[i].rows == 0 ? "runner" : "rows";  // the label says a --baseline runner's folder
      if (!passes[i].ok) {
        std::printf("%-5s %-8s %-6s %2d %6d: failed\n", silk::DecoderPrecisionName(p), jobs[i].kv.label.c_str(), path,
                    std::max(jobs[i].rows, 1), n);
        continue;
      }
      const RowsLine& l = lines[i];
      std::printf("%-5s %-8s %-6s %2d %6d | %8.1f %7.1f %7.1f | %8.1f %6.2fx | %8.1f %8.1f %4.0f%% %5.1f | %8.0f |",
                  silk::DecoderPrecisionName(p), jobs[i].kv.label.c_str(), path, std::max(jobs[i].rows, 1), n,
                  l.seconds, l.seconds / n * 1e3, passes[i].ms_at_end[k], l.rate, one_rate > 0 ? l.rate / one_rate : 0,
                  l.mb_per_call, l.bound_s, 100 * l.bound_s / l.seconds, l.gbps, passes[i].rss_mib);
      std::printf("   [load %s]\n", LoadAverage().c_str());
    }
    for (size_t i = 0; i < jobs.size(); ++i)
      for (size_t j = 0; j < jobs.size(); ++j)
        if (jobs[i].rows == 1 && jobs[j].rows == 0 && passes[i].ok && passes[j].ok)
          std::printf("  batch of one, %d calls: RowsDecoder %.2f ms per call, DecoderRunner (%s) %.2f ms: %+.1f %%\n",
                      n, passes[i].seconds[k] / n * 1e3, jobs[j].kv.label.c_str(), passes[j].seconds[k] / n * 1e3,
                      100 * (passes[i].seconds[k] / passes[j].seconds[k] - 1));
    std::fflush(stdout);
  }
}

// --rows: for each decoder x KV config, DecoderRunner and each R interleaved (RunInterleaved).
void RunRows(const Args& a, const silk::ModelConfig& c, DecoderPrecision p, const std::vector<KvConfig>& kvs) {
  for (const KvConfig& kv : kvs) {
    std::vector<Job> jobs = {{kv, 0}};
    if (!a.baseline.empty()) {
      const std::string name = a.baseline.substr(a.baseline.find_last_of('/') + 1);
      jobs.push_back({{kv.precision, a.baseline, std::string(silk::KvPrecisionName(kv.precision)) + "@" + name}, 0});
    }
    for (int r : a.rows) jobs.push_back({kv, r});
    PrintRows(a, c, p, jobs, RunInterleaved(a, p, jobs));
  }
}

// The official loop at the start of the run, printed with its fitted line (null when not run).
nlohmann::json MeasureOfficial(const Args& a) {
  if (!a.official) return nullptr;
  const auto t0 = Clock::now();
  nlohmann::json official = RunOfficial(a);
  if (!official.is_object()) {
    std::printf("official loop: bench/official_loop.py failed (no official column)\n");
    return official;
  }
  double oa = 0, ob = 0;
  OfficialSeconds(official, 1, &oa, &ob);
  std::printf(
      "official loop (bench/official_loop.py: %s; %.0f s incl. building the model): ms per call %s "
      "-> %.1f ms + %.4f ms x depth   [load %s]\n",
      official["what"].get<std::string>().c_str(), Since(t0), official["ms_per_call"].dump().c_str(), oa, ob,
      LoadAverage().c_str());
  return official;
}

// The --kv configs whose variant of decoder `p` the model folder (or the item's folder) has.
std::vector<KvConfig> KvsOf(const Args& a, const silk::StatusOr<silk::ModelConfig>& cfg, DecoderPrecision p) {
  std::vector<KvConfig> kvs;
  for (const KvConfig& kv : a.kvs) {
    auto other = kv.folder.empty() ? cfg : silk::LoadModelConfig(kv.folder);
    if (other.ok() && !other->DecoderFile(p, kv.precision).empty())
      kvs.push_back(kv);
    else
      std::printf("%-5s %-5s: not in that model folder (skipped)\n", silk::DecoderPrecisionName(p), kv.label.c_str());
  }
  std::fflush(stdout);
  return kvs;
}

int Usage() {
  std::fprintf(stderr,
               "usage: time_to_mesh --model DIR [--calls 1000,4000] [--decoders int4,int8,fp32] [--kv fp32,fp16,int8]\n"
               "                    [--threads 2] [--official-depths 0,1024] [--official-steps 24] [--no-official]\n"
               "                    [--rows 1,2,4,8 [--baseline DIR]] [--block 100]\n"
               "  (DIR: a release-size model folder, e.g. python3 bench/export_bench_models.py --configs official\n"
               "   --out OUT, then python3 -m silk_export kv16 OUT/official; a --kv item PRECISION@FOLDER takes\n"
               "   that variant from another folder; --rows: R sequences per call, 1 to 64 each, beside\n"
               "   DecoderRunner, instead of the table of KV precisions: no official loop; --baseline DIR: a second\n"
               "   DecoderRunner on DIR's variant, e.g. the same weights in decoder contract v3; --block: calls each\n"
               "   child makes per turn)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (!ParseArgs(argc, argv, &a)) return Usage();
  auto cfg = silk::LoadModelConfig(a.model);
  if (!cfg.ok()) {
    std::fprintf(stderr, "%s\n", cfg.status().ToString().c_str());
    return 1;
  }
  std::printf("time_to_mesh: %s (%s, %d layers, d_model %d, model_version %d), %d threads, load average at start %s\n",
              a.model.c_str(), cfg->config_name.c_str(), cfg->dims.n_layers, cfg->dims.d_model, cfg->model_version,
              a.threads, LoadAverage().c_str());
  if (!a.rows.empty()) {
    std::printf(
        "\ndec   kv       path    R      N |  calls s ms/call  ms@end | rows*calls/s  x R=1 |  MB/call  bound s  %%bnd "
        " "
        "GB/s | peak MiB\n");
    for (DecoderPrecision p : a.decoders) RunRows(a, *cfg, p, KvsOf(a, cfg, p));
    std::printf(
        "\n(runner: one sequence through DecoderRunner; rows R: R sequences through RowsDecoder, one id each per "
        "call; calls s: decoder time of the first N calls from depth 0; x R=1: rows*calls/s against rows R=1 of the "
        "same run; MB/call: weights and cross K/V once + each row's cache, averaged over the N calls; bound: those "
        "bytes / read bandwidth of a working set of one call at depth N/2)\n");
    return 0;
  }
  const nlohmann::json official = MeasureOfficial(a);
  std::printf(
      "\ndec   kv      N  | load s  enc s  calls s  total s | ms/call ms@end | bound s  %%bnd  GB/s | peak MiB |"
      " official s  speed-up\n");
  for (DecoderPrecision p : a.decoders) {
    const std::vector<KvConfig> kvs = KvsOf(a, cfg, p);
    std::vector<Job> jobs;
    for (const KvConfig& kv : kvs) jobs.push_back({kv, 0});
    const std::vector<Pass> passes = RunInterleaved(a, p, jobs);
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
