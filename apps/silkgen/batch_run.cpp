// SPDX-License-Identifier: MIT
// The --batch loop (batch_run.h): shard and list first, then the model once, then each input.
#include "../common/app_files.h"
#include "batch_run.h"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <system_error>

#include "batch_inputs.h"
#include "batch_report.h"
#include "exit_codes.h"
#include "progress_bar.h"
#include "silk/silk.hpp"

namespace fs = std::filesystem;

namespace silkgen {
namespace {

// First SIGINT/SIGTERM: abandon the mesh in progress (polled before every id) and stop; the
// second one kills at once (default action).
volatile std::sig_atomic_t g_signal = 0;

extern "C" void OnSignal(int sig) {
  g_signal = sig;
  std::signal(sig, SIG_DFL);
}

struct Callbacks {
  ProgressBar* bar;
};

int32_t PollCancel(void*) { return g_signal != 0 ? 1 : 0; }

void OnProgress(const silk_generate_progress* g, void* user) { static_cast<Callbacks*>(user)->bar->Update(*g); }

std::string RunId() {
  const char* host = std::getenv("SLURMD_NODENAME");
  if (!host) host = std::getenv("COMPUTERNAME");
#ifndef _WIN32
  static char name[256] = "";
  if (!host && gethostname(name, sizeof name - 1) == 0 && name[0]) host = name;
#endif
  const std::time_t t = std::time(nullptr);
  char when[32];
  std::strftime(when, sizeof when, "%Y%m%dT%H%M%SZ", std::gmtime(&t));
  return std::string(host ? host : "host") + ":" + std::to_string(getpid()) + ":" + when;
}

// --shard, else Slurm's variables, else 0/1.
bool ChooseShard(const BatchArgs& args, Shard* shard, std::string* error) {
  if (!args.shard.empty()) return ParseShard(args.shard, shard, error);
  return ShardFromEnvironment(shard, error);
}

std::string DefaultReport(const std::string& outdir, const Shard& s) {
  const std::string name = s.count == 1 ? "silkgen_batch.jsonl"
                                        : "silkgen_batch.shard-" + std::to_string(s.index) + "-of-" +
                                              std::to_string(s.count) + ".jsonl";
  return silkapp::Utf8(silkapp::FsPath(outdir) / name);
}

// The output folder exists (made if needed) and is not the input folder (outputs would become
// inputs on the next run).
bool PrepareOutputDir(const BatchArgs& args, const std::string& outdir, std::string* error) {
  std::error_code ec;
  fs::create_directories(silkapp::FsPath(outdir), ec);
  if (!fs::is_directory(silkapp::FsPath(outdir))) {
    *error = outdir + ": cannot create the output folder" + (ec ? " (" + ec.message() + ")" : "");
    return false;
  }
  if (fs::is_directory(silkapp::FsPath(args.source), ec) &&
      fs::equivalent(silkapp::FsPath(args.source), silkapp::FsPath(outdir), ec)) {
    *error = outdir + ": the output folder is the input folder (its outputs would be inputs next time); use another -o";
    return false;
  }
  return true;
}

void Fill(const silk_generate_stats& st, const silk_cpp::Mesh& mesh, BatchResult* r) {
  r->faces = st.faces;
  r->vertices = static_cast<int>(mesh.vertex_count());
  r->parts = st.components;
  r->tokens = st.tokens;
  r->stop_reason = silk_stop_reason_name(st.stop_reason);
  r->candidates = st.candidates;
  r->chosen_candidate = st.chosen_candidate;
  r->score = st.score;
  r->watertight = st.watertight;
  r->edge_manifold = st.edge_manifold;
}

// Generation and the save (libsilk's writers are atomic: a temporary beside the output, renamed
// into place, so a failed or killed run never leaves a partial output).
void Generate(silk_cpp::Generator& generator, const BatchSettings& s, const BatchInput& in, const std::string& format,
              BatchResult* r) {
  silk_cpp::Mesh input = silk_cpp::Mesh::Load(in.path);
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  silk_cpp::Mesh result = generator.Generate(input, s.generate, &st);
  Fill(st, result, r);
  silk_save_params sp = s.save;
  sp.format = format == "obj" ? SILK_FORMAT_OBJ : format == "ply" ? SILK_FORMAT_PLY : SILK_FORMAT_GLB;
  result.Save(r->output, sp);
}

BatchResult OneInput(silk_cpp::Generator& generator, const BatchSettings& s, const BatchArgs& args,
                     const BatchInput& in) {
  const auto t0 = std::chrono::steady_clock::now();
  BatchResult r;
  r.output = silkapp::Utf8(silkapp::FsPath(s.output_dir) / silkapp::FsPath(in.stem + "." + args.format));
  std::error_code ec;
  if (!args.overwrite && fs::exists(silkapp::FsPath(r.output), ec)) {
    r.status = "skipped";
    return r;
  }
  try {
    Generate(generator, s, in, args.format, &r);
    r.status = "ok";
  } catch (const silk_cpp::Error& e) {
    r.status = e.status() == SILK_ERR_CANCELLED && g_signal ? "cancelled" : "failed";
    r.error = e.what();
  } catch (const std::exception& e) {  // std::bad_alloc, filesystem errors
    r.status = "failed";
    r.error = e.what();
  }
  if (r.status != "ok") {  // no figures without an output
    BatchResult bare;
    bare.status = r.status;
    bare.output = r.output;
    bare.error = r.error;
    r = bare;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void PrintLine(const BatchSettings& s, size_t k, size_t n, const BatchInput& in, const BatchResult& r) {
  if (r.status == "ok" && !s.quiet)
    std::fprintf(stderr, "silkgen: [%zu/%zu] %s: ok -> %s (%d faces, %d part(s), %lld ids, %s, candidate %d of %d, %.2f s)\n",
                 k, n, in.entry.c_str(), r.output.c_str(), r.faces, r.parts, static_cast<long long>(r.tokens),
                 r.stop_reason.c_str(), r.chosen_candidate + 1, r.candidates, r.seconds);
  else if (r.status == "skipped" && !s.quiet)
    std::fprintf(stderr, "silkgen: [%zu/%zu] %s: skipped, %s exists (--overwrite redoes it)\n", k, n, in.entry.c_str(),
                 r.output.c_str());
  else if (r.status != "ok" && r.status != "skipped")  // failures are printed even with -q
    std::fprintf(stderr, "silkgen: [%zu/%zu] %s: %s: %s\n", k, n, in.entry.c_str(), r.status.c_str(),
                 r.error.c_str());
}

struct Tally {
  size_t ok = 0, skipped = 0, failed = 0, cancelled = 0;
  void Add(const std::string& status) {
    (status == "ok" ? ok : status == "skipped" ? skipped : status == "failed" ? failed : cancelled) += 1;
  }
};

// Every input of the shard in turn; stops after the one a signal interrupted.
Tally RunInputs(const BatchArgs& args, const BatchSettings& settings, const std::vector<BatchInput>& mine,
                const BatchRunInfo& run, BatchReport& report) {
  silk_cpp::Model model = silk_cpp::Model::Load(settings.model_dir, settings.model);
  silk_cpp::Generator generator(model);
  ProgressBar bar(!settings.quiet);
  Callbacks callbacks{&bar};
  BatchSettings s = settings;
  s.generate.progress = OnProgress;
  s.generate.cancel = PollCancel;
  s.generate.user_data = &callbacks;
  Tally tally;
  for (size_t k = 0; k < mine.size() && !g_signal; ++k) {
    const BatchResult r = OneInput(generator, s, args, mine[k]);
    bar.Finish();
    report.Write(run, mine[k], r);
    PrintLine(s, k + 1, mine.size(), mine[k], r);
    tally.Add(r.status);
  }
  return tally;
}

}  // namespace

int RunBatch(const BatchArgs& args, const BatchSettings& settings) {
  BatchRunInfo run;
  std::string error;
  if (!ChooseShard(args, &run.shard, &error)) {
    std::fprintf(stderr, "silkgen: %s\n", error.c_str());
    return kExitUsage;
  }
  std::vector<BatchInput> all;
  BatchReport report;
  const std::string report_path = args.report.empty() ? DefaultReport(settings.output_dir, run.shard) : args.report;
  if (!ListInputs(args.source, &all, &error) || !PrepareOutputDir(args, settings.output_dir, &error) ||
      !report.Open(report_path, &error)) {
    std::fprintf(stderr, "silkgen: %s\n", error.c_str());
    return kExitFail;
  }
  const std::vector<BatchInput> mine = ShardInputs(all, run.shard);
  run.run = RunId();
  run.seed = settings.seed;
  run.total = all.size();
  if (!settings.quiet)
    std::fprintf(stderr, "silkgen --batch: %zu of %zu inputs (shard %d/%d from %s), seed %llu, report %s\n", mine.size(),
                 all.size(), run.shard.index, run.shard.count, run.shard.source.c_str(),
                 static_cast<unsigned long long>(run.seed), report_path.c_str());
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  const auto t0 = std::chrono::steady_clock::now();
  const Tally t = RunInputs(args, settings, mine, run, report);  // throws only when the model fails to load
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!settings.quiet || t.failed || g_signal)
    std::fprintf(stderr, "silkgen --batch: %zu ok, %zu skipped, %zu failed%s of %zu inputs in %.1f s%s\n", t.ok,
                 t.skipped, t.failed, t.cancelled ? ", 1 cancelled" : "", mine.size(), wall,
                 g_signal ? " (interrupted: the rest not started)" : "");
  if (g_signal) return 128 + g_signal;
  return t.failed ? kExitFail : kExitOk;
}

}  // namespace silkgen
