// Structural verdicts on an output mesh (silkgen --stats): edge-manifold, watertight,
// consistently oriented. Counted on vertex indices, independent of how the mesh was made.
#pragma once
#include <cstdint>

#include "io/raw_mesh.h"

namespace silk {

struct MeshVerdicts {
  bool edge_manifold = true;          // no edge has more than two faces
  bool watertight = true;             // every edge has exactly two faces (and there are faces)
  bool consistently_oriented = true;  // no directed edge is used twice
  int64_t boundary_edges = 0;         // edges with one face
  int64_t nonmanifold_edges = 0;      // edges with three or more faces
};

MeshVerdicts CheckMesh(const RawMesh& mesh);

}  // namespace silk
