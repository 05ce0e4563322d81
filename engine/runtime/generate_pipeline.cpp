// Input loading/preparation and output conversion for generation.
#include "runtime/generate_pipeline.h"

#include <chrono>
#include <cmath>

#include "mesh/input_file.h"
#include "mesh/mesh_checks.h"
#include "mesh/surface_sampling.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {

StatusOr<GenerationInput> LoadGenerationInput(const std::string& path) {
  GenerationInput in;
  SILK_ASSIGN_OR_RETURN(IoPointCloud file, ReadGenerationInputFile(path));
  in.point_cloud = file.mesh.triangles.empty();
  in.mesh = std::move(file.mesh);
  if (in.point_cloud) in.normals = std::move(file.normals);
  Status s = ValidateGenerationInput(in);
  if (!s.ok()) return s.WithContext(path + ": ");
  return in;
}

Status ValidateGenerationInput(const GenerationInput& in, const CancelCheck& cancel) {
  if (in.mesh.positions.empty()) return InvalidArgument("input has no vertices");
  if (in.point_cloud) {
    if (in.normals.size() != in.mesh.positions.size())
      return InvalidArgument("point cloud: " + std::to_string(in.normals.size()) + " normals for " +
                             std::to_string(in.mesh.positions.size()) + " points");
    for (size_t i = 0; i < in.normals.size(); ++i) {
      if (i % kCancelPollInterval == 0 && CancelRequested(cancel)) return CancelledStatus("the input check");
      const auto& n = in.normals[i];
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!std::isfinite(len) || len == 0) return InvalidArgument("point " + std::to_string(i) + " has a zero or non-finite normal");
    }
  } else if (in.mesh.triangles.empty()) {
    return InvalidArgument("input mesh has no faces");
  }
  return Status::Ok();
}

StatusOr<PreparedPoints> PrepareModelPoints(const GenerationInput& in, const PreprocessingParams& params,
                                            uint64_t seed, const CancelCheck& cancel) {
  SILK_RETURN_IF_ERROR(ValidateGenerationInput(in));
  return PreparePoints(in.mesh, in.point_cloud ? &in.normals : nullptr, params, seed, cancel);
}

PreprocessingParams ModelPreprocessing(const ModelConfig& config, int32_t n_points) {
  PreprocessingParams p = config.preprocessing;
  if (n_points > 0) p.n_points = n_points;
  return p;
}

StatusOr<PreparedPoints> RawModelPoints(const GenerationInput& in, int32_t n_points) {
  if (!in.point_cloud) return InvalidArgument("raw points need a point-cloud PLY (x y z nx ny nz, no faces)");
  if (in.mesh.positions.size() != static_cast<size_t>(n_points))
    return InvalidArgument("raw points: the file has " + std::to_string(in.mesh.positions.size()) +
                           " points, the model takes " + std::to_string(n_points));
  PreparedPoints out;
  out.rows.reserve(in.mesh.positions.size() * 6);
  for (size_t i = 0; i < in.mesh.positions.size(); ++i)
    for (const auto* v : {&in.mesh.positions[i], &in.normals[i]})
      for (double x : *v) {
        if (!std::isfinite(x)) return InvalidArgument("raw points: point " + std::to_string(i) + " is not finite");
        out.rows.push_back(static_cast<float>(x));
      }
  return out;
}

IoMesh ToInputFrame(const TokenizerDecodedMesh& decoded, const NormalizeTransform& t) {
  IoMesh g;
  g.positions.reserve(decoded.positions.size());
  for (const QVec& q : decoded.positions)
    g.positions.push_back(UndoNormalization(DequantizePosition(q), t));
  g.triangles = decoded.faces;
  return g;
}

StatusOr<PipelineResult> GenerateFromInput(Generator* generator, const ModelConfig& config,
                                           const GenerationInput& input, const GenerateOptions& options,
                                           const GenerateCallbacks& callbacks,
                                           const PreprocessingParams* preprocessing) {
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(options));
  if (callbacks.cancel && callbacks.cancel()) return Status(StatusCode::kCancelled, "generation cancelled");
  const auto t0 = std::chrono::steady_clock::now();
  SILK_ASSIGN_OR_RETURN(PreparedPoints pts, preprocessing
                                                ? PrepareModelPoints(input, *preprocessing, options.sampling.seed, callbacks.cancel)
                                                : RawModelPoints(input, config.dims.n_points));
  const double prep = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  PipelineResult r;
  SILK_ASSIGN_OR_RETURN(r.generation, generator->Run(pts.rows, options, callbacks));
  r.generation.stats.seconds.load_input += prep;
  r.output = FinishOutput(&r.generation, pts.transform);
  return r;
}

IoMesh FinishOutput(GenerateResult* generation, const NormalizeTransform& transform) {
  IoMesh out = ToInputFrame(generation->mesh, transform);
  FillVerdicts(out, &generation->stats);
  return out;
}

void FillVerdicts(const IoMesh& mesh, GenerationStats* st) {
  const MeshVerdicts v = CheckMesh(mesh);
  st->edge_manifold = v.edge_manifold;
  st->watertight = v.watertight;
  st->consistently_oriented = v.consistently_oriented;
  st->vertex_manifold = v.vertex_manifold;
  st->nonmanifold_vertices = static_cast<int32_t>(v.nonmanifold_vertices);
  st->open_edges = static_cast<int32_t>(v.boundary_edges);
}

}  // namespace silk
