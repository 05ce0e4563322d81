// SPDX-License-Identifier: MIT
// generation_bench: decoder throughput of exported models (bench/export_bench_models.py makes
// random-weight tiny/small/paper models and "official", the released Mesh Silksong network at the
// release size) through the runtime's KV cache, at depth 0-512 and around 4,096 (prefill, then
// decode steps), fp32, INT8 and INT4, with peak RSS and each variant's fidelity to fp32 (from
// model.json "import.fidelity") — printed beside the official implementation's figures and beside
// the memory-bandwidth bound measured in the same run (bytes read per token / read bandwidth of a
// streaming loop over a buffer of that many bytes). (Its former comparisons of the copying KV cache,
// sample-then-check and running the model for forced ids went with those modes: docs/benchmarks.md.)
//
//   generation_bench --models DIR [--configs tiny,small,paper,official] [--precisions fp32,int8,int4]
//                    [--threads 2] [--steps 64] [--budget 20] [--no-int8]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <time.h>

#include <nlohmann/json.hpp>

#include "io/files/file_system.h"
#include "runtime/decoder_runner.h"
#include "runtime/generator.h"
#include "runtime/model/model.h"
#include "runtime/model/model_config.h"
#include "bench_memory.h"

namespace {

using silk::DecoderPrecision;
using silk::bench::Clock;
using silk::bench::DecoderFileBytes;
using silk::bench::LastLevelCacheBytes;
using silk::bench::PeakRssMiB;
using silk::bench::ReadBandwidth;
using silk::bench::Since;

struct Args {
  std::string models;
  std::vector<std::string> configs = {"tiny", "small", "paper"};
  // Each is run where the model has that decoder (model.json "files").
  std::vector<DecoderPrecision> precisions = {DecoderPrecision::kFp32, DecoderPrecision::kInt8,
                                              DecoderPrecision::kInt4};
  int threads = 2;
  int steps = 64;
  double budget = 20;  // seconds for the depth 0-512 window before it stops early
};

// Official implementation's figures (tok/s, depth 0-512 and ~4,096, 2-core CPU) for tiny / small /
// paper; "official" is the released network, the paper's size.
const std::map<std::string, std::pair<double, double>> kOfficial = {
    {"tiny", {32.7, 20.4}}, {"small", {5.7, 3.3}}, {"paper", {2.4, 1.5}}, {"official", {2.4, 1.5}}};

struct Result {
  double load_s = 0, encoder_s = 0;
  double tps_shallow = 0;
  int shallow_steps = 0, shallow_target = 0;  // steps done / asked in the depth 0-512 window
  double prefill_tps = 0, tps_deep = 0;
  double bound_shallow = 0, bound_deep = 0;
  double rss_mib = 0;
};

// Depth of the deep window: 4,096, or less where the model's positions end sooner.
int64_t DeepDepth(const silk::ModelDims& d) { return std::min<int64_t>(4096, d.max_seq_len - 16); }
constexpr double kShallowDepth = 256;  // mid-window depth for the depth 0-512 bound

// Bytes one generated token reads at `depth`: the decoder's weights as stored for that precision
// (INT8: int8 MatMul weights + scales; INT4: 4-bit blocks + scales, logits head fp32), less the
// token and position tables (Gather, fp32 in every variant: one row each is read), plus the cross
// K/V (n_latents rows per layer: 261 for the official network, its 4 memory slots + 257 context
// rows) and the self K/V of the prefix.
double StepBytes(const silk::ModelConfig& c, DecoderPrecision p, double depth) {
  const silk::ModelDims& d = c.dims;
  const double tables = double(c.embedding_rows + d.max_seq_len) * d.d_model * 4;
  return DecoderFileBytes(c, p) - tables + d.cross_kv_floats() * 4.0 + depth * d.kv_row_floats() * 4.0;
}

// The exporter's fidelity of a variant to the fp32 decoder (model.json "import.fidelity": top-1
// agreement and mean KL(fp32 || variant), teacher-forced on the fp32 model's greedy sequences).
struct Fidelity {
  double top1 = -1, kl = -1;  // < 0: not recorded
  int positions = 0;
};

Fidelity ReadFidelity(const std::string& dir, DecoderPrecision p) {
  std::ifstream in(dir + "/model.json");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  const std::string key = p == DecoderPrecision::kInt8   ? "decoder_int8"
                          : p == DecoderPrecision::kInt4 ? "decoder_int4"
                                                         : "decoder";
  const nlohmann::json::json_pointer at("/import/fidelity/" + key);
  Fidelity f;
  if (j.is_discarded() || !j.contains(at) || !j.at(at).is_object()) return f;
  const nlohmann::json& fig = j.at(at);
  f.top1 = fig.value("top1_agreement", -1.0);
  f.kl = fig.value("kl_mean", -1.0);
  f.positions = fig.value("positions", 0);
  return f;
}

// A loaded model, its cross K/V for random points, a cache and random mesh tokens.
struct Session {
  std::unique_ptr<silk::Model> model;
  const silk::ModelConfig* c = nullptr;
  Ort::Value cross_value{nullptr};  // the encoder's output, [L, 2, H, M, D]
  float* cross = nullptr;
  silk::KvCache cache;
  std::mt19937 rng{1};
  std::uniform_int_distribution<int32_t> tok;
  int32_t Token() { return tok(rng); }
};

bool OpenSession(const Args& a, const std::string& name, DecoderPrecision p, Session* s, Result* r) {
  silk::ModelLoadOptions lo;
  lo.threads = a.threads;
  lo.decoder = p;
  auto t0 = Clock::now();
  auto model = silk::Model::Load(a.models + "/" + name, lo);
  if (!model.ok()) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), model.status().ToString().c_str());
    return false;
  }
  r->load_s = Since(t0);
  s->model = std::move(*model);
  s->c = &s->model->config();
  const silk::ModelDims& d = s->c->dims;
  std::uniform_real_distribution<float> u(-0.9f, 0.9f);
  std::vector<float> pts(static_cast<size_t>(d.n_points) * 6);
  for (auto& v : pts) v = u(s->rng);
  t0 = Clock::now();
  auto cross = silk::RunEncoder(s->model->impl(), pts.data(), d.n_points);
  if (!cross.ok()) return false;
  r->encoder_s = Since(t0);
  s->cross_value = std::move(*cross);
  s->cross = s->cross_value.GetTensorMutableData<float>();
  s->tok = std::uniform_int_distribution<int32_t>(0, s->c->eos_id - 1);
  return s->cache.Reserve(DeepDepth(d) + a.steps + 1, silk::ModelKvShape(s->model->impl())).ok();
}

// Single random-token steps until n are done, the cache reaches stop_depth or budget_s (> 0)
// passes; returns (steps, seconds).
std::pair<int, double> FeedSteps(Session& s, silk::DecoderRunner& runner, int n, double budget_s, int64_t stop_depth) {
  int done = 0;
  const auto ts = Clock::now();
  while (done < n && s.cache.length() < stop_depth) {
    const int32_t id = s.Token();
    if (!runner.Feed(&id, 1).ok()) break;
    ++done;
    if (budget_s > 0 && Since(ts) > budget_s) break;
  }
  return {done, Since(ts)};
}

// Everything for one model + precision; runs in a child process (separate peak RSS).
// bandwidth[0] / [1]: GB/s measured for the step's working set at depth 256 / DeepDepth.
bool Measure(const Args& a, const std::string& name, DecoderPrecision p, const double bandwidth[2], Result* r) {
  Session s;
  if (!OpenSession(a, name, p, &s, r)) return false;
  const silk::ModelConfig& c = *s.c;
  auto bound = [&](double depth, double gbps) { return gbps * 1e9 / StepBytes(c, p, depth); };
  const int64_t deep = DeepDepth(c.dims), shallow = std::min<int64_t>(512, deep);
  {  // depth 0-512: BOS, then single steps until depth 512 (or the time budget).
    silk::DecoderRunner runner(s.model->impl(), &s.cache, s.cross);
    const int32_t bos = c.bos_id;
    if (!runner.Feed(&bos, 1).ok()) return false;
    auto [n, sec] = FeedSteps(s, runner, static_cast<int>(shallow - 1), a.budget, shallow);
    r->shallow_steps = n;
    r->shallow_target = static_cast<int>(shallow - 1);
    r->tps_shallow = n / sec;
    r->bound_shallow = bound(n / 2.0, bandwidth[0]);
  }
  // ~4,096: prefill deep - steps known tokens in chunks, then `steps` single steps.
  s.cache.Clear();
  silk::DecoderRunner runner(s.model->impl(), &s.cache, s.cross);
  std::vector<int32_t> ids(static_cast<size_t>(deep - a.steps));
  ids[0] = c.bos_id;
  for (size_t i = 1; i < ids.size(); ++i) ids[i] = s.Token();
  auto tp = Clock::now();
  if (!runner.Feed(ids.data(), static_cast<int64_t>(ids.size())).ok()) return false;
  r->prefill_tps = ids.size() / Since(tp);
  auto [n, sec] = FeedSteps(s, runner, a.steps, 0, deep);
  r->tps_deep = n / sec;
  r->bound_deep = bound(static_cast<double>(deep), bandwidth[1]);
  r->rss_mib = PeakRssMiB();
  return true;
}

bool ParsePrecisions(const std::string& list, std::vector<DecoderPrecision>* out) {
  out->clear();
  std::stringstream ss(list);
  for (std::string p; std::getline(ss, p, ',');) {
    if (p == "fp32")
      out->push_back(DecoderPrecision::kFp32);
    else if (p == "int8")
      out->push_back(DecoderPrecision::kInt8);
    else if (p == "int4")
      out->push_back(DecoderPrecision::kInt4);
    else
      return false;
  }
  return !out->empty();
}

bool ParseArgs(int argc, char** argv, Args* a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (k == "--models")
      a->models = next();
    else if (k == "--threads")
      a->threads = std::atoi(next().c_str());
    else if (k == "--steps")
      a->steps = std::atoi(next().c_str());
    else if (k == "--budget")
      a->budget = std::atof(next().c_str());
    else if (k == "--no-int8")
      a->precisions.erase(std::remove(a->precisions.begin(), a->precisions.end(), DecoderPrecision::kInt8),
                          a->precisions.end());
    else if (k == "--precisions") {
      if (!ParsePrecisions(next(), &a->precisions)) return false;
    } else if (k == "--configs") {
      a->configs.clear();
      std::stringstream ss(next());
      for (std::string c; std::getline(ss, c, ',');) a->configs.push_back(c);
    } else {
      return false;
    }
  }
  return !a->models.empty() && a->threads > 0 && a->steps > 0;
}

// Measure() in a forked child (its own peak RSS); false when it failed.
bool MeasureInChild(const Args& a, const std::string& name, DecoderPrecision p, const double bw[2], Result* r) {
  int fd[2];
  if (pipe(fd) != 0) return false;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    Result child;
    const bool ok = Measure(a, name, p, bw, &child);
    if (write(fd[1], &child, sizeof(child)) != static_cast<ssize_t>(sizeof(child))) _exit(3);
    _exit(ok ? 0 : 1);
  }
  close(fd[1]);
  const bool got = read(fd[0], r, sizeof(*r)) == static_cast<ssize_t>(sizeof(*r));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return got && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

void PrintHeader() {
  std::printf("%-8s %-4s %6s %6s | %-32s | %-40s | %8s | %s\n", "config", "prec", "load s", "enc s",
              "0-512: tok/s (bound, %, x off.)", "~4096: prefill, tok/s (bound, %, x off.)", "peak RSS",
              "vs fp32: top-1, KL");
}

void PrintRow(const std::string& name, DecoderPrecision p, const Result& r, const Fidelity& f) {
  const auto off = kOfficial.count(name) ? kOfficial.at(name) : std::make_pair(0.0, 0.0);
  auto times = [](double tps, double official) { return official > 0 ? tps / official : 0.0; };
  std::printf(
      "%-8s %-4s %6.1f %6.2f | %7.1f (%7.1f, %3.0f%%, %5.1fx)%s | %7.0f, %7.1f (%7.1f, %3.0f%%, %5.1fx) | "
      "%4.0f MiB |",
      name.c_str(), silk::DecoderPrecisionName(p), r.load_s, r.encoder_s, r.tps_shallow, r.bound_shallow,
      100 * r.tps_shallow / r.bound_shallow, times(r.tps_shallow, off.first),
      r.shallow_steps < r.shallow_target ? "*" : " ", r.prefill_tps, r.tps_deep, r.bound_deep,
      100 * r.tps_deep / r.bound_deep, times(r.tps_deep, off.second), r.rss_mib);
  if (f.top1 >= 0) std::printf(" %5.1f%%, %.2g (%d pos.)", 100 * f.top1, f.kl, f.positions);
  std::printf("\n");
  if (p == DecoderPrecision::kFp32 && off.first > 0) {
    char shallow[40], deep[40];
    std::snprintf(shallow, sizeof(shallow), "official %.1f", off.first);
    std::snprintf(deep, sizeof(deep), "official %.1f", off.second);
    std::printf("%27s | %-32s | %-40s |\n", "", shallow, deep);
  }
}

// Every requested precision the model in <models>/<name> has; the bandwidth notes go to `notes`.
void BenchConfig(const Args& a, const std::string& name, std::string* notes) {
  if (!silk::IsRegularFile(a.models + "/" + name + "/model.json")) {
    std::printf("%-8s skipped (no model in %s/%s)\n", name.c_str(), a.models.c_str(), name.c_str());
    return;
  }
  auto cfg = silk::LoadModelConfig(a.models + "/" + name);
  if (!cfg.ok()) {
    std::printf("%-8s skipped: %s\n", name.c_str(), cfg.status().ToString().c_str());
    return;
  }
  for (DecoderPrecision p : a.precisions) {
    if (cfg->DecoderFile(p).empty()) continue;
    const char* prec = silk::DecoderPrecisionName(p);
    // Bandwidth for this step's working set, measured here (not in the child: its buffer would
    // count in the child's peak RSS).
    double bw[2];
    for (int k = 0; k < 2; ++k) {
      const double depth = k ? static_cast<double>(DeepDepth(cfg->dims)) : kShallowDepth;
      const double bytes = StepBytes(*cfg, p, depth);
      bw[k] = ReadBandwidth(a.threads, static_cast<int64_t>(bytes));
      char line[200];
      std::snprintf(line, sizeof(line),
                    "  %-8s %-4s depth %4.0f: %7.1f MiB read per token (cross K/V: %d rows), "
                    "bandwidth %5.1f GB/s\n",
                    name.c_str(), prec, depth, bytes / 1048576.0, cfg->dims.n_latents, bw[k]);
      *notes += line;
    }
    Result r;
    if (!MeasureInChild(a, name, p, bw, &r)) {
      std::printf("%-8s %-4s failed (see stderr)\n", name.c_str(), prec);
      continue;
    }
    PrintRow(name, p, r, ReadFidelity(cfg->dir, p));
  }
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (!ParseArgs(argc, argv, &a)) {
    std::fprintf(stderr,
                 "usage: generation_bench --models DIR [--configs tiny,small,paper,official] "
                 "[--precisions fp32,int8,int4] [--threads 2] [--steps 64] [--budget 20] [--no-int8]\n"
                 "  (make DIR with: python3 bench/export_bench_models.py --out DIR [--configs ... official])\n");
    return 2;
  }
  const int64_t llc = LastLevelCacheBytes();
  const int64_t dram_bytes = std::max<int64_t>(4 * llc, int64_t{1} << 30);
  const double dram = ReadBandwidth(a.threads, dram_bytes);
  std::printf(
      "generation_bench: %d threads; last-level cache %.0f MiB; DRAM read bandwidth %.1f GB/s "
      "(%d-thread memchr scan over %.0f MiB)\n",
      a.threads, llc / 1048576.0, dram, a.threads, dram_bytes / 1048576.0);
  PrintHeader();
  std::string notes;
  for (const std::string& name : a.configs) BenchConfig(a, name, &notes);
  std::printf(
      "(* = depth 0-512 window stopped early by the --budget; %% = share of the bound; x off. = times "
      "the official implementation's tok/s; bound = read bandwidth for a working set of that size / "
      "(decoder weights as stored for the precision + cross K/V + self K/V at that depth); top-1, KL = "
      "the exporter's fidelity to fp32, model.json \"import.fidelity\"), per model:)\n%s",
      notes.c_str());
  return 0;
}
