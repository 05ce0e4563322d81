// SPDX-License-Identifier: MIT
// `silktok sample --random N`: N random legal sequences drawn from the grammar's masks (biased
// toward closing layers), each written as DIR/NNNN.tokens.txt and its mesh DIR/NNNN.obj.
#include <cstdio>
#include <vector>

#include "../common/app_files.h"
#include "commands.h"
#include "cli_errors.h"

namespace silktok {
namespace {

struct SampleArgs {
  int32_t count = 10;
  uint64_t seed = 1;
  std::string dir;
  int32_t max_layers = 6, max_layer_size = 12;
};

// Sample k: DIR/kkkk.tokens.txt and DIR/kkkk.obj (both written atomically).
void WriteSample(const SampleArgs& a, int32_t k) {
  silk_random_walk_params p = silk_random_walk_default_params();
  p.seed = a.seed + static_cast<uint64_t>(k);
  p.max_layers = a.max_layers;
  p.max_layer_size = a.max_layer_size;
  char name[32];
  std::snprintf(name, sizeof name, "%04d", k);
  const std::string base = a.dir + "/" + name;
  std::vector<int32_t> ids;
  const silk_cpp::Mesh mesh = [&] {
    try {
      return silk_cpp::Mesh::RandomWalk(p, &ids);
    } catch (const silk_cpp::Error& e) {
      throw WithContext(e, base + ".tokens.txt: ");
    }
  }();
  silk_cpp::Tokens::FromIds(ids).Save(base + ".tokens.txt");
  silk_save_params save = silk_save_default_params();
  save.format = SILK_FORMAT_OBJ;
  mesh.Save(base + ".obj", save);
  std::printf("%s: %zu tokens, %zu vertices, %zu faces\n", base.c_str(), ids.size(), mesh.vertex_count(),
              mesh.triangle_count());
}

int Run(const SampleArgs& a) {
  const std::string why = silkapp::MakeDirectories(a.dir);
  try {
    if (!why.empty()) throw AppError(SILK_ERR_IO, a.dir + ": cannot create directory: " + why);
    for (int32_t k = 0; k < a.count; ++k) WriteSample(a, k);
  } catch (const silk_cpp::Error& e) {
    ReportError(e);
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void RegisterSampleCommand(CLI::App& app) {
  auto args = std::make_shared<SampleArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sample",
      "Write random legal token sequences: ids drawn uniformly from the grammar's legal masks, with a\n"
      "bias toward closing layers at a random target size so sequences end. Each sample k is written as\n"
      "DIR/kkkk.tokens.txt (EOS included) and its decoded mesh DIR/kkkk.obj. Sample k uses seed S+k.");
  cmd->add_option("--random", args->count, "Number of sequences (default: 10)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--seed", args->seed, "Seed of the first sequence (default: 1)");
  cmd->add_option("-o,--output", args->dir, "Output directory (created if missing)")->required();
  cmd->add_option("--max-layers", args->max_layers, "Most layers per component after the root (default: 6)");
  cmd->add_option("--max-layer-size", args->max_layer_size, "Largest target layer size (default: 12)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
