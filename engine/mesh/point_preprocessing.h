// SPDX-License-Identifier: MIT
// The encoder's input: the one implementation of the pre-processing a model was trained with,
// described by model.json "preprocessing" (docs/runtime.md) and shared by silkgen, the C API
// and the Python training code (through silk_points_prepare), so no second copy can drift.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "io/io_mesh.h"
#include "mesh/normalize.h"

namespace silk {

enum class PreprocessingKind {
  kSilk,      // normalise all vertices to +-bound, n_points area-weighted samples (or a subset)
  kOfficial,  // Mesh Silksong's inference pre-processing (official_network.md §4)
};

struct PreprocessingParams {
  PreprocessingKind kind = PreprocessingKind::kSilk;
  double normalize_bound = kDefaultNormalizeBound;
  double merge_distance_fraction = 0;  // of the bounding-box diagonal; 0 = no merging
  int32_t surface_samples = 0;         // > n_points: sample this many, then draw n_points; 0: n_points
  bool round_float16 = false;          // points and normals rounded to float16 before the draw
  int32_t n_points = 4096;
};

// The most encoder points a pre-processing draws (PreprocessingParams::n_points).
inline constexpr int32_t kMaxPreprocessingPoints = 1 << 20;

// Silk's own (what PrepareModelPoints always did) and the official one, with `n_points`.
PreprocessingParams SilkPreprocessing(double normalize_bound, int32_t n_points);
PreprocessingParams OfficialPreprocessing(int32_t n_points);
const char* PreprocessingKindName(PreprocessingKind kind);
// Every value in range; messages name the field ("preprocessing.<field>").
Status ValidatePreprocessing(const PreprocessingParams& params);

struct PreparedPoints {
  std::vector<float> rows;       // n * 6: normalised xyz, normal
  NormalizeTransform transform;  // input frame -> model frame
};

// `normals` null: `mesh` is a triangle mesh; else a point cloud with one normal per position
// (rescaled to unit length). Steps, all from one seed:
//  1. official kind, or merge_distance_fraction > 0: MergeCloseVertices at that fraction of
//     the referenced bounding-box diagonal (meshes only; unreferenced vertices go too);
//  2. normalisation: per-axis centre, largest extent to 2 * normalize_bound;
//  3. a mesh: max(surface_samples, n_points) area-weighted samples with face normals
//     (SampleSurface); a point cloud: all its points;
//  4. round_float16: every coordinate of points and normals rounded to float16;
//  5. n_points drawn without replacement when there are more (a cloud with fewer keeps all).
// Silk's kind draws its n_points samples with `seed` directly, so its output is unchanged from
// before model.json described pre-processing; the official kind derives its draw's seed.
// `cancel` is polled between the steps and every kCancelPollInterval surface samples.
// Columns of PreparedPoints::rows (n * 6 floats; a trailing partial row is ignored): positions
// (xyz) or normals.
std::vector<std::array<double, 3>> PointRowPositions(const std::vector<float>& rows);
std::vector<std::array<double, 3>> PointRowNormals(const std::vector<float>& rows);

StatusOr<PreparedPoints> PreparePoints(const IoMesh& mesh, const std::vector<std::array<double, 3>>* normals,
                                       const PreprocessingParams& params, uint64_t seed,
                                       const CancelCheck& cancel = {});

}  // namespace silk
