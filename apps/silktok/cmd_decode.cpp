// SPDX-License-Identifier: MIT
// `silktok decode`: token file -> OBJ mesh, every face the tokens carry, oriented.
#include <cstdio>
#include <string>

#include "../common/app_files.h"
#include "commands.h"
#include "cli_errors.h"
#include "output_checks.h"

namespace silktok {
namespace {

struct DecodeArgs {
  std::string input;
  std::string output;
  bool grid = false;
  bool split_nonmanifold = false;
};

std::string HeaderComment(const DecodeArgs& a, const silk_decode_stats& s) {
  return "decoded by silktok from " + a.input + ": " + std::to_string(s.vertices) + " vertices, " +
         std::to_string(s.faces) + " faces, " + std::to_string(s.components) + " components" +
         (a.grid ? " (grid coordinates 0..127)" : "") +
         (a.split_nonmanifold ? ", " + std::to_string(s.vertices_split) + " non-manifold vertices split" : "");
}

int Run(const DecodeArgs& a) {
  if (int rc = CheckOutputs({a.input}, {a.output}); rc != kExitOk) return rc;
  try {
    const silk_cpp::Tokens tokens = silk_cpp::Tokens::Load(a.input);
    silk_decode_params p = silk_decode_default_params();
    p.grid_coordinates = a.grid ? 1 : 0;
    // Faithful by default: the official streams contain a few vertices with two fans.
    p.split_nonmanifold_vertices = a.split_nonmanifold ? 1 : 0;
    silk_decode_stats stats = silk_cpp::Sized<silk_decode_stats>();
    silk_cpp::Mesh mesh = [&] {
      try {
        return silk_cpp::Mesh::Decode(tokens, p, &stats);
      } catch (const silk_cpp::Error& e) {
        throw WithContext(e, a.input + ": ");
      }
    }();
    const std::string comment = HeaderComment(a, stats);
    silk_save_params save = silk_save_default_params();
    save.format = SILK_FORMAT_OBJ;
    save.obj_comment = comment.c_str();
    mesh.Save(a.output, save);
  } catch (const silk_cpp::Error& e) {
    ReportError(e);
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void RegisterDecodeCommand(CLI::App& app) {
  auto args = std::make_shared<DecodeArgs>();
  CLI::App* cmd =
      app.add_subcommand("decode",
                         "Decode a token file (one id per line) into an OBJ mesh with every face the tokens carry,\n"
                         "consistently oriented. Vertices are in token reading order.");
  cmd->add_option("input", args->input, "Token file")->required()->check(silkapp::ExistingFile());
  cmd->add_option("-o,--output", args->output, "Output OBJ file (written atomically)")->required();
  cmd->add_flag("--grid", args->grid,
                "Write integer grid coordinates 0..127 instead of dequantised [-1, 1] bin centres (default: off)");
  cmd->add_flag("--split-nonmanifold-vertices", args->split_nonmanifold,
                "Split every vertex whose faces form two or more fans (one copy per extra fan, same position),\n"
                "so the OBJ is vertex-manifold (default: off, the mesh the tokens encode)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
