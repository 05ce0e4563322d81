// SPDX-License-Identifier: MIT
// Chamfer distance between a mesh's surface and a point set: the score that picks the best of
// several generated candidates (closest to the input), computed without Python.
#pragma once
#include <cstdint>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "io/io_mesh.h"
#include "mesh/nearest_points.h"

namespace silk {

struct ChamferDistance {
  double a_to_b = 0;  // mean over a of the distance to the nearest point of b
  double b_to_a = 0;
  double value() const { return 0.5 * (a_to_b + b_to_a); }  // the symmetric Chamfer distance
};

// Mean nearest-neighbour distances both ways (+infinity towards an empty set).
ChamferDistance PointSetChamfer(const std::vector<Point3>& a, const std::vector<Point3>& b);
// The same, polling `cancel` every kChamferPollInterval queries (a million points take seconds):
// kCancelled when it asks to stop.
StatusOr<ChamferDistance> PointSetChamfer(const std::vector<Point3>& a, const std::vector<Point3>& b,
                                          const CancelCheck& cancel);
inline constexpr int64_t kChamferPollInterval = 4096;  // nearest-point queries (~10 ms)

// `samples` area-weighted surface samples of `mesh` (seeded) against `points`. A mesh without
// a face of positive area scores +infinity both ways, so it never beats one with faces.
ChamferDistance MeshToPointsChamfer(const IoMesh& mesh, const std::vector<Point3>& points, int32_t samples,
                                    uint64_t seed);
// The same, polling `cancel` (as PointSetChamfer above).
StatusOr<ChamferDistance> MeshToPointsChamfer(const IoMesh& mesh, const std::vector<Point3>& points, int32_t samples,
                                              uint64_t seed, const CancelCheck& cancel);

}  // namespace silk
