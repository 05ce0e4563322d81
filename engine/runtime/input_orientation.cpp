// SPDX-License-Identifier: MIT
// Model-frame glue between generated grid meshes and the part-orientation vote.
#include "runtime/input_orientation.h"

#include "mesh/point_preprocessing.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {

StatusOr<std::shared_ptr<const OrientedPointSet>> MakeInputOrientation(const std::vector<float>& points,
                                                                       const CancelCheck& cancel) {
  auto set = std::make_shared<const OrientedPointSet>(PointRowPositions(points), PointRowNormals(points), cancel);
  if (set->cancelled()) return CancelledStatus("the orientation index");
  return std::shared_ptr<const OrientedPointSet>(std::move(set));
}

StatusOr<PartOrientationReport> OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference,
                                              const CancelCheck& cancel) {
  return OrientPartsToPoints(DequantizePositions(mesh->positions), &mesh->faces, mesh->face_component, mesh->components,
                             reference, cancel);
}

PartOrientationReport OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference) {
  return OrientPartsToPoints(DequantizePositions(mesh->positions), &mesh->faces, mesh->face_component, mesh->components,
                             reference);
}

}  // namespace silk
