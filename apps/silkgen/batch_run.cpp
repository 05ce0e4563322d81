// SPDX-License-Identifier: MIT
// The --batch loop (batch_run.h): shard and list first, then the model once, then each input
// (one after another here; --parallel: batch_parallel.cpp); an input's steps (batch_steps.h).
#include "../common/app_errors.h"
#include "../common/app_files.h"
#include "../common/file_roles.h"
#include "../common/interrupt.h"
#include "batch_run.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <system_error>

#include "batch_inputs.h"
#include "batch_parallel.h"
#include "batch_report.h"
#include "batch_steps.h"
#include "exit_codes.h"
#include "progress_bar.h"
#include "silk/silk.hpp"

namespace fs = std::filesystem;

namespace silkgen {

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

void SaveResult(const silk_generate_stats& st, const silk_cpp::Mesh& result, const BatchSettings& s,
                const std::string& format, BatchResult* r) {
  Fill(st, result, r);
  silk_save_params sp = s.save;
  sp.format = silk_cpp::EnumValue(silk_mesh_format_from_name, format);
  result.Save(r->output, sp);
}

std::string OutputOf(const BatchSettings& s, const BatchArgs& args, const BatchInput& in) {
  if (!in.problem.empty()) return "";
  return silkapp::Utf8(silkapp::FsPath(s.output_dir) / silkapp::FsPath(in.stem + "." + args.format));
}

bool Precheck(const BatchSettings& s, const BatchArgs& args, const BatchInput& in, BatchResult* r) {
  r->output = OutputOf(s, args, in);
  std::error_code ec;
  if (!in.problem.empty()) {  // a refused list line: nothing is opened
    r->status = "failed";
    r->error = silkapp::ErrorText(SILK_ERR_INVALID_ARGUMENT, in.problem);
    return false;
  }
  if (!args.overwrite && fs::exists(silkapp::FsPath(r->output), ec)) {
    r->status = "skipped";
    return false;
  }
  return true;
}

void NoteError(const std::exception& e, BatchResult* r) {
  const auto* silk_error = dynamic_cast<const silk_cpp::Error*>(&e);  // else std::bad_alloc, filesystem errors
  const bool cancelled = silk_error && silk_error->status() == SILK_ERR_CANCELLED && silkapp::InterruptSignal();
  r->status = cancelled ? "cancelled" : "failed";
  r->error = e.what();
}

void Settle(std::chrono::steady_clock::time_point t0, BatchResult* r) {
  if (r->status != "ok") {  // no figures without an output
    BatchResult bare;
    bare.status = r->status;
    bare.output = r->output;
    bare.error = r->error;
    *r = bare;
  }
  r->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void PrintLine(const BatchSettings& s, size_t k, size_t n, const BatchInput& in, const BatchResult& r) {
  if (r.status == "ok" && !s.quiet)
    std::fprintf(stderr,
                 "silkgen: [%zu/%zu] %s: ok -> %s (%d faces, %d part(s), %lld ids, %s, candidate %d of %d, %.2f s)\n",
                 k, n, in.entry.c_str(), r.output.c_str(), r.faces, r.parts, static_cast<long long>(r.tokens),
                 r.stop_reason.c_str(), r.chosen_candidate + 1, r.candidates, r.seconds);
  else if (r.status == "skipped" && !s.quiet)
    std::fprintf(stderr, "silkgen: [%zu/%zu] %s: skipped, %s exists (--overwrite redoes it)\n", k, n, in.entry.c_str(),
                 r.output.c_str());
  else if (r.status != "ok" && r.status != "skipped")  // failures are printed even with -q, in the error form
    std::fprintf(stderr, "silkgen: %s (input %zu of %zu, %s: %s)\n", r.error.c_str(), k, n, in.entry.c_str(),
                 r.status.c_str());
}

namespace {

struct Callbacks {
  ProgressBar* bar;
};

// First SIGINT/SIGTERM: the mesh in progress is abandoned (polled before every id) and the run
// stops; a second one ends the process at once, its temporaries removed (common/interrupt.h).
int32_t PollCancel(void*) { return silkapp::InterruptSignal() != 0 ? 1 : 0; }

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
  if (args.shard_given) return ParseShard(args.shard, shard, error);  // "" included: refused
  return ShardFromEnvironment(shard, error);
}

std::string DefaultReport(const std::string& outdir, const Shard& s) {
  const std::string name =
      s.count == 1 ? "silkgen_batch.jsonl"
                   : "silkgen_batch.shard-" + std::to_string(s.index) + "-of-" + std::to_string(s.count) + ".jsonl";
  return silkapp::Utf8(silkapp::FsPath(outdir) / name);
}

// The output folder exists (made if needed) and is not the input folder (outputs would become
// inputs on the next run).
bool PrepareOutputDir(const BatchArgs& args, const std::string& outdir, std::string* error) {
  std::error_code ec;
  fs::create_directories(silkapp::FsPath(outdir), ec);
  if (!fs::is_directory(silkapp::FsPath(outdir))) {
    *error = silkapp::ErrorText(SILK_ERR_IO,
                                outdir + ": cannot create the output folder" + (ec ? " (" + ec.message() + ")" : ""));
    return false;
  }
  if (fs::is_directory(silkapp::FsPath(args.source), ec) &&
      fs::equivalent(silkapp::FsPath(args.source), silkapp::FsPath(outdir), ec)) {
    *error = "invalid argument: " + outdir +
             ": the output folder is the input folder (its outputs would be inputs next time); use another -o";
    return false;
  }
  return true;
}

// Generation and the save (libsilk's writers are atomic: a temporary beside the output, renamed
// into place, so a failed or killed run never leaves a partial output).
void Generate(silk_cpp::Generator& generator, const BatchSettings& s, const BatchInput& in, const std::string& format,
              BatchResult* r) {
  silk_cpp::Mesh input = silk_cpp::Mesh::Load(in.path);
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  silk_cpp::Mesh result = generator.Generate(input, s.generate, &st);
  SaveResult(st, result, s, format, r);
}

BatchResult OneInput(silk_cpp::Generator& generator, const BatchSettings& s, const BatchArgs& args,
                     const BatchInput& in) {
  const auto t0 = std::chrono::steady_clock::now();
  BatchResult r;
  if (!Precheck(s, args, in, &r)) return r;
  try {
    silk_cpp::CheckOutputPath(r.output);  // a name the file system cannot hold: refused before generating
    Generate(generator, s, in, args.format, &r);
    r.status = "ok";
  } catch (const std::exception& e) {
    NoteError(e, &r);
  }
  Settle(t0, &r);
  return r;
}

// Every input of the shard in turn; stops after the one a signal interrupted, or when the report
// cannot be written (*error names it: a run that cannot record what it did does not go on).
Tally RunInputs(const BatchArgs& args, const BatchSettings& settings, const std::vector<BatchInput>& mine,
                const BatchRunInfo& run, BatchReport& report, std::string* error) {
  silk_cpp::Model model = silk_cpp::Model::Load(settings.model_dir, settings.model);
  if (args.parallel > 1) return RunInputsParallel(args, settings, mine, model, run, report, error);
  silk_cpp::Generator generator(model);
  ProgressBar bar(!settings.quiet);
  Callbacks callbacks{&bar};
  BatchSettings s = settings;
  s.generate.progress = OnProgress;
  s.generate.cancel = PollCancel;
  s.generate.user_data = &callbacks;
  Tally tally;
  for (size_t k = 0; k < mine.size() && !silkapp::InterruptSignal(); ++k) {
    const BatchResult r = OneInput(generator, s, args, mine[k]);
    bar.Finish();
    PrintLine(s, k + 1, mine.size(), mine[k], r);
    tally.Add(r.status);
    if (!report.Write(run, mine[k], r, error)) break;
  }
  return tally;
}

// The rule of common/file_roles.h over the whole list (so every shard decides alike): no output
// and not the report may be an input or the list, nor two of them one file.
bool CheckFileRoles(const BatchArgs& args, const BatchSettings& s, const std::vector<BatchInput>& all,
                    const std::string& report_path, std::string* error) {
  silkapp::FileRoles roles;
  if (!silkapp::IsDirectory(args.source)) roles.Reads(args.source, "the list");
  for (const BatchInput& in : all)
    if (in.problem.empty()) roles.Reads(in.path, "the input");
  roles.Writes(report_path, "the report");
  for (const BatchInput& in : all)
    if (in.problem.empty()) roles.Writes(OutputOf(s, args, in), "the output of " + in.entry);
  *error = roles.Check();
  if (!error->empty()) *error = silkapp::ErrorText(SILK_ERR_INVALID_ARGUMENT, *error);
  return error->empty();
}

// Shard, list, output folder, the file-role rule and the report, before the model is loaded.
int Prepare(const BatchArgs& args, const BatchSettings& settings, BatchRunInfo* run, std::vector<BatchInput>* all,
            std::string* report_path, BatchReport* report) {
  std::string error;
  if (!ChooseShard(args, &run->shard, &error)) {
    silkapp::PrintError("silkgen", SILK_ERR_INVALID_ARGUMENT, error);
    return kExitUsage;
  }
  if (args.report_given && args.report.empty()) {
    silkapp::PrintError("silkgen", SILK_ERR_INVALID_ARGUMENT, "--report: an empty path");
    return kExitUsage;
  }
  *report_path = args.report_given ? args.report : DefaultReport(settings.output_dir, run->shard);
  if (!ListInputs(args.source, all, &error) || !PrepareOutputDir(args, settings.output_dir, &error) ||
      !CheckFileRoles(args, settings, *all, *report_path, &error) || !report->Open(*report_path, &error)) {
    std::fprintf(stderr, "silkgen: %s\n", error.c_str());
    return kExitFail;
  }
  return kExitOk;
}

}  // namespace

int RunBatch(const BatchArgs& args, const BatchSettings& settings) {
  silkapp::HandleInterrupts(silkapp::OnInterrupt::kCancel);
  BatchRunInfo run;
  std::vector<BatchInput> all;
  std::string report_path, error;
  BatchReport report;
  if (int rc = Prepare(args, settings, &run, &all, &report_path, &report); rc != kExitOk) return rc;
  const std::vector<BatchInput> mine = ShardInputs(all, run.shard);
  run.run = RunId();
  run.seed = settings.seed;
  run.total = all.size();
  if (!settings.quiet)
    std::fprintf(stderr, "silkgen --batch: %zu of %zu inputs (shard %d/%d from %s), seed %llu, report %s\n",
                 mine.size(), all.size(), run.shard.index, run.shard.count, run.shard.source.c_str(),
                 static_cast<unsigned long long>(run.seed), report_path.c_str());
  const auto t0 = std::chrono::steady_clock::now();
  Tally t;
  if (!silkapp::InterruptSignal())  // throws only when the model fails to load
    t = RunInputs(args, settings, mine, run, report, &error);
  if (error.empty()) report.Close(&error);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int sig = silkapp::InterruptSignal();
  if (!settings.quiet || t.failed || sig || !error.empty())
    std::fprintf(stderr, "silkgen --batch: %zu ok, %zu skipped, %zu failed%s of %zu inputs in %.1f s%s\n", t.ok,
                 t.skipped, t.failed, t.cancelled ? (", " + std::to_string(t.cancelled) + " cancelled").c_str() : "",
                 mine.size(), wall,
                 sig              ? " (interrupted: the rest not started)"
                 : !error.empty() ? " (stopped: the report failed)"
                                  : "");
  if (!error.empty()) {
    silkapp::PrintError("silkgen", SILK_ERR_IO, error);
    return kExitFail;
  }
  if (sig) return 128 + sig;
  return t.failed ? kExitFail : kExitOk;
}

}  // namespace silkgen
