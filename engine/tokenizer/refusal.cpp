// Names and reference messages of tokenizer refusals (token_format.md §14.A).
#include "tokenizer/refusal.h"

#include <cstring>

namespace silk {
namespace {
struct Entry {
  Refusal r;
  const char* name;
  const char* ref;
};
constexpr Entry kEntries[] = {
    {Refusal::kNotTriangles, "not-triangles", "only support triangles now"},
    {Refusal::kEdgeGraphLimit, "nm-edge-graph-limit", "[NM] edge graph edges exceed limit"},
    {Refusal::kStillDisconnectedFan, "nm-disconnected-fan", "[NM] still meet 1v2cc situation"},
    {Refusal::kTooManyNonManifoldVerts, "nm-vertex-limit", "[NM] NM_verts exceed limit"},
    {Refusal::kNonManifoldWrong, "nm-partition-failed", "non-manifold wrong"},
    {Refusal::kPostNotManifold, "nm-post-not-manifold", "[NM] post not manifold"},
    {Refusal::kMeetNonManifold, "non-manifold-edge", "meet non-manifold"},
    {Refusal::kMobius, "mobius", "mobius cycle topology"},
    {Refusal::kVertexSharedByComponents, "vertex-shared-by-components", "pre process non-manifold wrong"},
    {Refusal::kTooManyFaces, "face-limit", "too many faces_p"},
    {Refusal::kBoundaryVertex, "bad-boundary-vertex", "nonmanifold, pls checking preprocess"},
    {Refusal::kLayerCountLimit, "layer-count-limit", "reach layer limit"},
    {Refusal::kNoFaces, "no-faces", "max() arg is an empty sequence"},
    {Refusal::kLayerSizeLimit, "layer-size-limit", "[Encoder] max lv"},
    {Refusal::kAllComponentsDropped, "all-components-dropped", "ZeroDivisionError"},
};
}  // namespace

const char* RefusalName(Refusal r) {
  for (const auto& e : kEntries) if (e.r == r) return e.name;
  return "unknown";
}
const char* RefusalReferenceMessage(Refusal r) {
  for (const auto& e : kEntries) if (e.r == r) return e.ref;
  return "";
}
Status Refuse(Refusal r, const std::string& detail) {
  std::string m = RefusalName(r);
  if (!detail.empty()) m += ": " + detail;
  return Status(StatusCode::kRefused, m);
}
bool RefusalFromStatus(const Status& s, Refusal* out) {
  if (s.code() != StatusCode::kRefused) return false;
  for (const auto& e : kEntries) {
    const size_t n = std::strlen(e.name);
    if (s.message().compare(0, n, e.name) == 0 && (s.message().size() == n || s.message()[n] == ':')) {
      if (out) *out = e.r;
      return true;
    }
  }
  return false;
}

}  // namespace silk
