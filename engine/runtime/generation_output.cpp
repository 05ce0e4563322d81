// SPDX-License-Identifier: MIT
// The generated mesh into the input's frame, with its verdicts.
#include "runtime/generation_output.h"

#include "mesh/mesh_checks.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {

IoMesh ToInputFrame(const TokenizerDecodedMesh& decoded, const NormalizeTransform& t) {
  IoMesh g;
  g.positions.reserve(decoded.positions.size());
  for (const QVec& q : decoded.positions) g.positions.push_back(UndoNormalization(DequantizePosition(q), t));
  g.triangles = decoded.faces;
  return g;
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
