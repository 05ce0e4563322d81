// SPDX-License-Identifier: MIT
// Consistent orientation of unoriented normals (Hoppe et al. 1992, "Surface reconstruction from
// unorganized points"): a plane fit gives each point a normal line, not a side; the sign is
// propagated along a minimum spanning tree of the neighbour graph, so that it crosses between
// nearly parallel normals first, and each tree is seeded to face outward.
#pragma once
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "mesh/nearest_points.h"

namespace silk {

// Flips entries of `normals` (unit, one per point) in place. The graph: an edge between every
// point and each of its k nearest neighbours, weight 1 - |n_i . n_j|; its minimum spanning
// forest (unique: ties broken by the point indices, so the result is deterministic; found by
// Boruvka's rounds in O(n k log n) time and about 36 bytes per point beyond the graph). In each
// tree the point farthest from the tree's centroid (for a closed surface its normal line goes
// through the centroid, and outward is away from it) gets the normal facing away from the
// centroid; every other point takes the sign that agrees with its parent's (n_child . n_parent
// >= 0). Last, a tree whose normals sum to an inward flux (sum of n . (p - centroid) < 0) is reversed
// as a whole: the divergence theorem's vote, which corrects a seed at a thin tip.
// Returns the number of trees; kCancelled when `cancel` (polled every kCancelPollInterval points
// of each round) asks to stop.
StatusOr<int32_t> OrientNormals(const std::vector<Point3>& points, const KnnGraph& graph, std::vector<Point3>* normals,
                                const CancelCheck& cancel = {});

}  // namespace silk
