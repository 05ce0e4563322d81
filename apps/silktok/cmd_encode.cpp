// SPDX-License-Identifier: MIT
// `silktok encode`: mesh -> token file; one input to a file, or many inputs to a folder in
// parallel (dataset form), where a failing input is reported and the rest go on.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "../common/app_files.h"
#include "commands.h"
#include "mesh_input.h"
#include "output_checks.h"

namespace silktok {
namespace {

struct EncodeArgs {
  std::vector<std::string> inputs;
  std::string output;
  int jobs = 0;
  bool no_nonmanifold = false;
  bool quiet = false;
};

std::string StemOf(const std::string& path) {
  std::string base = silkapp::FileName(path);
  for (const char* ext : {".gz"}) {
    const std::string e = ext;
    if (base.size() > e.size() && base.compare(base.size() - e.size(), e.size(), e) == 0)
      base.resize(base.size() - e.size());
  }
  const size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

// One input to one token file (written atomically); throws silk_cpp::Error.
void EncodeOne(const std::string& in, const std::string& out, const silk_encode_params& params) {
  LoadAndEncode(in, params).Save(out);
}

// mkdir -p; fine if it exists as a folder.
void MakeDirectories(const std::string& path) {
  const std::string why = silkapp::MakeDirectories(path);
  if (!why.empty()) throw AppError(SILK_ERR_IO, path + ": cannot create folder: " + why);
}

int Run(const EncodeArgs& a) {
  silk_encode_params params = silk_encode_default_params();
  params.nonmanifold_processing = a.no_nonmanifold ? 0 : 1;
  try {
    if (a.inputs.size() == 1 && !silkapp::IsDirectory(a.output)) {
      if (int rc = CheckOutputs(a.inputs, {a.output}); rc != kExitOk) return rc;
      EncodeOne(a.inputs[0], a.output, params);
      return kExitOk;
    }
    MakeDirectories(a.output);  // batch form: -o is a folder, one <stem>.tokens.txt per input
  } catch (const silk_cpp::Error& e) {
    ReportError(e);
    return kExitFailure;
  }
  std::vector<std::string> outputs;
  for (const std::string& in : a.inputs) outputs.push_back(a.output + "/" + StemOf(in) + ".tokens.txt");
  if (int rc = CheckOutputs(a.inputs, outputs); rc != kExitOk) return rc;
  unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const size_t jobs = std::min(a.inputs.size(), static_cast<size_t>(a.jobs > 0 ? a.jobs : static_cast<int>(hw)));
  std::atomic<size_t> next{0};
  std::atomic<int> failed{0};
  std::mutex io_mu;
  auto worker = [&] {
    for (size_t i; (i = next.fetch_add(1)) < a.inputs.size();) {
      try {
        EncodeOne(a.inputs[i], outputs[i], params);
      } catch (const silk_cpp::Error& e) {
        ++failed;
        std::lock_guard<std::mutex> lock(io_mu);
        ReportError(e);
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 0; t < jobs; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (!a.quiet)
    std::fprintf(stderr, "silktok encode: %zu inputs, %zu encoded, %d failed\n", a.inputs.size(),
                 a.inputs.size() - static_cast<size_t>(failed.load()), failed.load());
  return failed.load() ? kExitFailure : kExitOk;
}

}  // namespace

void RegisterEncodeCommand(CLI::App& app) {
  auto args = std::make_shared<EncodeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "encode",
      "Tokenize meshes (OBJ/PLY/STL/OFF/glTF/GLB, optionally .gz): one token id per line, no BOS/EOS/PAD.\n"
      "  silktok encode IN -o OUT.txt\n"
      "  silktok encode IN1 IN2 ... -o DIR [-j N]   (writes DIR/<stem>.tokens.txt per input)\n"
      "Each mesh is normalised to [-0.95, 0.95] (bounding box) and quantised to 128 bins.");
  cmd->add_option("inputs", args->inputs, "Input mesh files")->required()->check(silkapp::ExistingFile());
  cmd->add_option("-o,--output", args->output, "Output token file, or folder when several inputs are given")
      ->required();
  cmd->add_option("-j,--jobs", args->jobs, "Parallel encodes in batch form (default: hardware threads)")
      ->check(CLI::Range(0, 1024));
  cmd->add_flag(
      "--no-nonmanifold", args->no_nonmanifold,
      "Skip non-manifold processing (token_format.md §3); non-manifold meshes are then refused (default: off)");
  cmd->add_flag("-q,--quiet", args->quiet, "No batch summary on stderr (default: off)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
