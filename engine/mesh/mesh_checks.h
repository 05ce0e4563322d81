// SPDX-License-Identifier: MIT
// Structural verdicts on an output mesh (silkgen --stats): edge-manifold, vertex-manifold,
// watertight, consistently oriented. Counted on vertex indices, independent of how the mesh was made.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "io/io_mesh.h"

namespace silk {

struct MeshVerdicts {
  bool edge_manifold = true;          // no edge has more than two faces
  bool watertight = true;             // every edge has exactly two faces (and there are faces)
  bool consistently_oriented = true;  // no directed edge is used twice
  bool vertex_manifold = true;        // the faces around every vertex form one fan (vertex_fans.h)
  int64_t nonmanifold_vertices = 0;   // vertices whose faces form two or more fans ("bowties")
  int64_t boundary_edges = 0;         // edges with one face
  int64_t nonmanifold_edges = 0;      // edges with three or more faces
};

MeshVerdicts CheckMesh(const IoMesh& mesh);
// Same on bare faces over vertices 0..num_vertices-1 (decoded meshes).
MeshVerdicts CheckFaces(const std::vector<std::array<int32_t, 3>>& faces, int32_t num_vertices);

}  // namespace silk
