// SPDX-License-Identifier: MIT
// Area-weighted random surface samples with normals: the point cloud the encoder reads when
// the input is a mesh (4,096 samples by default). Seeded and platform-independent.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "io/io_mesh.h"

namespace silk {

struct OrientedPoint {
  std::array<double, 3> position;
  std::array<double, 3> normal;  // unit normal of the sampled face (its winding's side)
};

// Each sample: a face drawn with probability proportional to its area (zero-area faces never),
// then a uniform point in it (sqrt barycentric trick). Fails when no face has area. `cancel` is
// polled every kCancelPollInterval samples (kCancelled when it asks to stop).
StatusOr<std::vector<OrientedPoint>> SampleSurface(const IoMesh& mesh, int32_t count, uint64_t seed,
                                                   const CancelCheck& cancel = {});

// `count` of `points` chosen without replacement (seeded partial shuffle, order kept random);
// all of them, unchanged, when there are not more than `count`.
std::vector<OrientedPoint> SubsamplePoints(const std::vector<OrientedPoint>& points, int32_t count, uint64_t seed);

}  // namespace silk
