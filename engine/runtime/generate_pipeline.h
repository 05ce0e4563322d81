// The file/mesh side of generation around Generator: reading the input (point-cloud PLY with
// normals, or any mesh), normalising it and sampling the encoder's points, and putting the
// generated mesh back into the input's frame with its verdicts. Shared by silkgen and the C API.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/raw_mesh.h"
#include "mesh/normalize.h"
#include "runtime/generator.h"

namespace silk {

struct GenerationInput {
  RawMesh mesh;                                  // triangles empty for a point cloud
  std::vector<std::array<double, 3>> normals;    // point cloud: one per position
  bool point_cloud = false;
};

// A PLY without faces is a point cloud and must carry nx/ny/nz; everything else is read as a
// mesh (OBJ, PLY, STL, OFF, glTF/GLB, optionally gzipped).
StatusOr<GenerationInput> LoadGenerationInput(const std::string& path);
// Checks a caller-built input (sizes, finite values, index ranges).
Status ValidateGenerationInput(const GenerationInput& input);

struct ModelPoints {
  std::vector<float> rows;  // n * 6: normalised xyz, unit normal
  NormalizeTransform transform;
};

// Normalises (bounding box to +-bound) and takes n_points: area-weighted surface samples of a
// mesh, or a seeded subset of a point cloud (all points if it has fewer).
StatusOr<ModelPoints> PrepareModelPoints(const GenerationInput& input, int32_t n_points, uint64_t seed,
                                         double bound);

struct GeneratedMesh {
  RawMesh mesh;                             // input frame
  std::vector<int32_t> triangle_component;  // part index per triangle
  int32_t components = 0;
};

// Grid positions -> [-1, 1] (tokenizer dequantisation) -> input frame (UndoNormalization).
GeneratedMesh ToInputFrame(const DecodedMesh& decoded, const NormalizeTransform& transform);

// Edge-manifold / watertight / orientation verdicts and open edges of the output, into stats.
void FillVerdicts(const GeneratedMesh& mesh, GenerationStats* stats);

// ToInputFrame + FillVerdicts into generation->stats.
GeneratedMesh FinishOutput(GenerateResult* generation, const NormalizeTransform& transform);

struct PipelineResult {
  GenerateResult generation;  // tokens, grid mesh, report, stats (verdicts filled in)
  GeneratedMesh output;
};

// PrepareModelPoints (n_points 0 = the model's n_points) + Generator::Run + ToInputFrame +
// verdicts; stats.seconds.load_input covers the point preparation.
StatusOr<PipelineResult> GenerateFromInput(Generator* generator, const ModelConfig& config,
                                           const GenerationInput& input, const GenerateOptions& options,
                                           const GenerateCallbacks& callbacks = {}, int32_t n_points = 0);

}  // namespace silk
