// The file/mesh side of generation around Generator: reading the input (a point cloud, or any
// mesh), normalising it and sampling the encoder's points, and putting the
// generated mesh back into the input's frame with its verdicts. Shared by silkgen and the C API.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/io_mesh.h"
#include "mesh/normalize.h"
#include "mesh/point_preprocessing.h"
#include "runtime/generator.h"

namespace silk {

struct GenerationInput {
  IoMesh mesh;                                  // triangles empty for a point cloud
  std::vector<std::array<double, 3>> normals;    // point cloud: one per position
  bool point_cloud = false;
};

// A PLY without faces or an XYZ/PTS file is a point cloud, with its own normals or estimated
// ones (ReadGenerationInputFile); everything else is read as a mesh (OBJ, PLY, STL, OFF,
// glTF/GLB, PMD, optionally gzipped).
StatusOr<GenerationInput> LoadGenerationInput(const std::string& path);
// Checks a caller-built input (sizes, finite values, index ranges); polls `cancel` every
// kCancelPollInterval points (kCancelled).
Status ValidateGenerationInput(const GenerationInput& input, const CancelCheck& cancel = {});

// The model's pre-processing (model.json "preprocessing", mesh/point_preprocessing.h) on a
// validated input: normalised points and the transform back to the input frame.
StatusOr<PreparedPoints> PrepareModelPoints(const GenerationInput& input, const PreprocessingParams& params,
                                            uint64_t seed, const CancelCheck& cancel = {});
// The model's pre-processing with n_points (0: the model's own).
PreprocessingParams ModelPreprocessing(const ModelConfig& config, int32_t n_points = 0);

// A point cloud used exactly as given (silkgen --raw-points): no normalisation, resampling or
// rounding, identity transform (the output stays in the model's frame). Its point count must
// be `n_points`; every value must be finite.
StatusOr<PreparedPoints> RawModelPoints(const GenerationInput& input, int32_t n_points);

// The one step from the generated mesh to the output (docs/mesh_types.md): grid positions ->
// [-1, 1] (tokenizer dequantisation) -> input frame (UndoNormalization); faces as decoded. The
// part index per triangle stays in decoded.face_component.
IoMesh ToInputFrame(const TokenizerDecodedMesh& decoded, const NormalizeTransform& transform);

// Edge-manifold / watertight / orientation verdicts and open edges of the output, into stats.
void FillVerdicts(const IoMesh& mesh, GenerationStats* stats);

// ToInputFrame + FillVerdicts into generation->stats.
IoMesh FinishOutput(GenerateResult* generation, const NormalizeTransform& transform);

struct PipelineResult {
  GenerateResult generation;  // tokens, grid mesh (parts: generation.mesh.face_component), report, stats
  IoMesh output;              // input frame
};

// PrepareModelPoints with `preprocessing` (null: RawModelPoints with the model's n_points) +
// Generator::Run + ToInputFrame + verdicts; stats.seconds.load_input covers the preparation.
StatusOr<PipelineResult> GenerateFromInput(Generator* generator, const ModelConfig& config,
                                           const GenerationInput& input, const GenerateOptions& options,
                                           const GenerateCallbacks& callbacks,
                                           const PreprocessingParams* preprocessing);

}  // namespace silk
