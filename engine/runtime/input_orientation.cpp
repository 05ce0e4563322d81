// SPDX-License-Identifier: MIT
// Model-frame glue between generated grid meshes and the orientation vote, over surface patches.
#include "runtime/input_orientation.h"

#include <algorithm>
#include <utility>

#include "mesh/point_preprocessing.h"
#include "tokenizer/cleanup/quantize.h"
#include "tokenizer/manifold/union_find.h"

namespace silk {

StatusOr<std::shared_ptr<const OrientedPointSet>> MakeInputOrientation(const std::vector<float>& points,
                                                                       const CancelCheck& cancel) {
  auto set = std::make_shared<const OrientedPointSet>(PointRowPositions(points), PointRowNormals(points), cancel);
  if (set->cancelled()) return CancelledStatus("the orientation index");
  return std::shared_ptr<const OrientedPointSet>(std::move(set));
}

std::vector<int32_t> SurfacePatches(const TokenizerDecodedMesh& mesh, int32_t* count) {
  const size_t n = mesh.faces.size();
  std::vector<std::pair<uint64_t, int32_t>> edges;  // (undirected edge key, face)
  edges.reserve(3 * n);
  for (size_t f = 0; f < n; ++f)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<uint32_t>(mesh.faces[f][k]), b = static_cast<uint32_t>(mesh.faces[f][(k + 1) % 3]);
      edges.push_back({(static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b), static_cast<int32_t>(f)});
    }
  std::sort(edges.begin(), edges.end());
  UnionFind sets(static_cast<int32_t>(n));
  for (size_t i = 1; i < edges.size(); ++i)
    if (edges[i].first == edges[i - 1].first) sets.Union(edges[i].second, edges[i - 1].second);
  std::vector<int32_t> patch(n, -1), number(n, -1);
  *count = 0;
  for (size_t f = 0; f < n; ++f) {
    int32_t& id = number[static_cast<size_t>(sets.Find(static_cast<int32_t>(f)))];
    if (id < 0) id = (*count)++;
    patch[f] = id;
  }
  return patch;
}

StatusOr<PartOrientationReport> OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference,
                                              const CancelCheck& cancel) {
  int32_t patches = 0;
  const std::vector<int32_t> patch = SurfacePatches(*mesh, &patches);
  return OrientPartsToPoints(DequantizePositions(mesh->positions), &mesh->faces, patch, patches, reference, cancel);
}

PartOrientationReport OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference) {
  return OrientToInput(mesh, reference, CancelCheck{}).value();
}

}  // namespace silk
