// SPDX-License-Identifier: MIT
// Bounding-box normalisation into [-bound, bound] (token_format.md §2.1), done by the caller before
// tokenizing; kept exact (one IEEE operation per step, no FMA) so tokens match the reference.
#pragma once
#include <array>

#include "core/status.h"
#include "io/io_mesh.h"

namespace silk {

struct NormalizeTransform {
  std::array<double, 3> center{0, 0, 0};
  double scale = 1.0;  // v' = (v - center) * scale
};

inline constexpr double kDefaultNormalizeBound = 0.95;

// Per-axis min/max over ALL vertices (unreferenced ones included). Fails on an empty or
// non-finite vertex array, or when all vertices coincide (zero extent).
StatusOr<NormalizeTransform> ComputeNormalization(const IoMesh& mesh, double bound = kDefaultNormalizeBound);
IoMesh ApplyNormalization(const IoMesh& mesh, const NormalizeTransform& t);
// Inverse, to put generated geometry back into the input's frame.
std::array<double, 3> UndoNormalization(const std::array<double, 3>& p, const NormalizeTransform& t);
// Convenience: compute + apply.
StatusOr<IoMesh> NormalizeMesh(const IoMesh& mesh, double bound = kDefaultNormalizeBound);

}  // namespace silk
