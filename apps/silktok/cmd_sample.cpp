// `silktok sample --random N`: N random legal sequences drawn from the grammar's masks (biased
// toward closing layers), each written as DIR/NNNN.tokens.txt and its mesh DIR/NNNN.obj.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "commands.h"
#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "decoder/random_walk.h"
#include "io/obj_writer.h"
#include "io/token_text.h"
#include "mesh_input.h"
#include "tokenizer/quantize.h"

namespace silktok {
namespace {

struct SampleArgs {
  int32_t count = 10;
  uint64_t seed = 1;
  std::string dir;
  int32_t max_layers = 6, max_layer_size = 12;
};

int Run(const SampleArgs& a) {
  std::error_code ec;
  std::filesystem::create_directories(a.dir, ec);
  if (ec) {
    ReportError(silk::IoError(a.dir + ": cannot create directory: " + ec.message()));
    return kExitFailure;
  }
  silk::RandomWalkOptions wo;
  wo.max_layers = a.max_layers;
  wo.max_layer_size = a.max_layer_size;
  for (int32_t k = 0; k < a.count; ++k) {
    std::mt19937_64 rng(a.seed + static_cast<uint64_t>(k));
    silk::Grammar g;
    std::vector<int32_t> ids = silk::RandomLegalWalk(&g, &rng, wo);
    char name[32];
    std::snprintf(name, sizeof name, "%04d", k);
    const std::string base = a.dir + "/" + name;
    std::ofstream(base + ".tokens.txt") << silk::FormatTokenText(ids);
    auto mesh = silk::BuildMeshSoFar(g, silk::MeshBuildOptions{}, nullptr);
    if (!mesh.ok()) {
      ReportError(mesh.status().WithContext(base + ".tokens.txt: "));
      return kExitFailure;
    }
    silk::OutputMesh out;
    for (const silk::QVec& q : mesh->positions)
      out.positions.push_back({silk::DequantizeCoord(q.x), silk::DequantizeCoord(q.y), silk::DequantizeCoord(q.z)});
    out.triangles = mesh->faces;
    silk::Status st = silk::WriteObjFile(base + ".obj", out);
    if (!st.ok()) {
      ReportError(st);
      return kExitFailure;
    }
    std::printf("%s: %zu tokens, %zu vertices, %zu faces\n", base.c_str(), ids.size(), mesh->positions.size(),
                mesh->faces.size());
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
