// `silktok decode`: token file -> OBJ mesh, every face the tokens carry, oriented.
#include <cstdio>
#include <vector>

#include "commands.h"
#include "io/obj_writer.h"
#include "io/token_text.h"
#include "mesh/vertex_fans.h"
#include "mesh_input.h"
#include "tokenizer/quantize.h"

namespace silktok {
namespace {

struct DecodeArgs {
  std::string input;
  std::string output;
  bool grid = false;
  bool split_nonmanifold = false;
};

int Run(const DecodeArgs& a) {
  auto ids = silk::ReadTokenText(a.input);
  if (!ids.ok()) {
    ReportError(ids.status());
    return kExitFailure;
  }
  auto dec = silk::DecodeTokens(*ids);
  if (!dec.ok()) {
    ReportError(dec.status().WithContext(a.input + ": "));
    return kExitFailure;
  }
  int32_t split = 0;
  if (a.split_nonmanifold) {
    // Faithful by default: the official streams contain a few vertices with two fans.
    std::vector<int32_t> copy_of;
    split = silk::SplitNonManifoldFans(&dec->faces, static_cast<int32_t>(dec->positions.size()), &copy_of);
    for (int32_t v : copy_of) dec->positions.push_back(dec->positions[v]);
  }
  silk::OutputMesh out;
  out.positions.reserve(dec->positions.size());
  for (const silk::QVec& q : dec->positions) {
    if (a.grid) out.positions.push_back({double(q.x), double(q.y), double(q.z)});
    else out.positions.push_back({silk::DequantizeCoord(q.x), silk::DequantizeCoord(q.y), silk::DequantizeCoord(q.z)});
  }
  out.triangles = dec->faces;
  silk::ObjWriteOptions opt;
  opt.integer_coordinates = a.grid;
  opt.header_comment = "decoded by silktok from " + a.input + ": " + std::to_string(dec->positions.size()) +
                       " vertices, " + std::to_string(dec->faces.size()) + " faces, " +
                       std::to_string(dec->components) + " components" + (a.grid ? " (grid coordinates 0..127)" : "") +
                       (a.split_nonmanifold ? ", " + std::to_string(split) + " non-manifold vertices split" : "");
  silk::Status st = silk::WriteObjFile(a.output, out, opt);
  if (!st.ok()) {
    ReportError(st);
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void RegisterDecodeCommand(CLI::App& app) {
  auto args = std::make_shared<DecodeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "decode",
      "Decode a token file (one id per line) into an OBJ mesh with every face the tokens carry,\n"
      "consistently oriented. Vertices are in token reading order.");
  cmd->add_option("input", args->input, "Token file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "Output OBJ file (written atomically)")->required();
  cmd->add_flag("--grid", args->grid,
                "Write integer grid coordinates 0..127 instead of dequantised [-1, 1] bin centres (default: off)");
  cmd->add_flag("--split-nonmanifold-vertices", args->split_nonmanifold,
                "Split every vertex whose faces form two or more fans (one copy per extra fan, same position),\n"
                "so the OBJ is vertex-manifold (default: off, the mesh the tokens encode)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
