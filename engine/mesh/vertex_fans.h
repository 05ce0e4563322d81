// SPDX-License-Identifier: MIT
// Vertex fans: the faces around a vertex grouped by edge-connectivity at that vertex. A vertex
// is manifold (a disk or half-disk, what Blender's "Select Non-Manifold" and slicers expect)
// when its faces form exactly one fan; a "bowtie" vertex has two or more fans touching only at
// it. One implementation for the verdicts (mesh_checks) and the decoder's split/close rules.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace silk {

// Per corner (face f, corner k -> f*3+k) the index of its vertex's fan (0..fans-1, fans
// numbered in order of each fan's first face), and per vertex the number of fans (0 when the
// vertex has no face). Faces must not repeat a corner. Two faces at v are in one fan when they
// share an edge at v (a second corner besides v).
struct VertexFans {
  std::vector<int32_t> corner_fan;
  std::vector<int32_t> fans_per_vertex;
  int64_t nonmanifold_vertices = 0;  // vertices with two or more fans
};

VertexFans ComputeVertexFans(const std::vector<std::array<int32_t, 3>>& faces, int32_t num_vertices);

// Splits every vertex with two or more fans: fan 0 keeps the vertex, each further fan gets a new
// vertex appended after the existing ones (corners rewritten in place). `copy_of` receives, per
// new vertex, the vertex it copies (so callers can duplicate positions and attributes).
// Returns the number of vertices split. Splitting never changes an edge's face count or
// orientation, so an edge-manifold, oriented mesh stays so, and becomes vertex-manifold.
int32_t SplitNonManifoldFans(std::vector<std::array<int32_t, 3>>* faces, int32_t num_vertices,
                             std::vector<int32_t>* copy_of);

}  // namespace silk
