// Model-frame glue between generated grid meshes and the part-orientation vote.
#include "runtime/input_orientation.h"

#include "tokenizer/quantize.h"

namespace silk {

std::shared_ptr<const OrientedPointSet> MakeInputOrientation(const std::vector<float>& points) {
  std::vector<Point3> pos, nrm;
  pos.reserve(points.size() / 6);
  nrm.reserve(points.size() / 6);
  for (size_t i = 0; i + 6 <= points.size(); i += 6) {
    pos.push_back({points[i], points[i + 1], points[i + 2]});
    nrm.push_back({points[i + 3], points[i + 4], points[i + 5]});
  }
  return std::make_shared<const OrientedPointSet>(std::move(pos), std::move(nrm));
}

PartOrientationReport OrientToInput(DecodedMesh* mesh, const OrientedPointSet& reference) {
  std::vector<Point3> pos;
  pos.reserve(mesh->positions.size());
  for (const QVec& q : mesh->positions) pos.push_back({DequantizeCoord(q.x), DequantizeCoord(q.y), DequantizeCoord(q.z)});
  return OrientPartsToPoints(pos, &mesh->faces, mesh->face_component, mesh->components, reference);
}

}  // namespace silk
