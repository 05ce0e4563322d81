// SPDX-License-Identifier: MIT
// EncodeMesh: the encoder pipeline of token_format.md §2-§8, stage by stage, with per-phase timing.
// Mirror of token_decoder.
#include <algorithm>
#include <chrono>
#include <string>

#include "tokenizer/adjacency/between_layer_encoder.h"
#include "tokenizer/layering/components.h"
#include "tokenizer/cleanup/face_cleanup.h"
#include "tokenizer/layering/layering.h"
#include "tokenizer/manifold/nonmanifold_split.h"
#include "tokenizer/manifold/orientation_repair.h"
#include "tokenizer/processed_encoder.h"
#include "tokenizer/refusal.h"
#include "tokenizer/layering/rotation_lists.h"
#include "tokenizer/adjacency/self_layer_encoder.h"
#include "tokenizer/packing/token_writer.h"
#include "tokenizer/tokenizer.h"

namespace silk {
namespace {

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// Fills the S/X/B parts of every vertex of one component's layers.
StreamComponent EncodeComponent(const TokenizerProcessedMesh& mesh, const ComponentVertexLayers& cl,
                                const Layering& lay, const RotationLists& rot) {
  StreamComponent sc;
  sc.layers.resize(cl.layers.size());
  std::vector<int32_t> dists, cols;
  for (size_t L = 0; L < cl.layers.size(); ++L) {
    const auto& layer = cl.layers[L];
    const int32_t n = static_cast<int32_t>(layer.size());
    const int32_t prev_n = L > 0 ? static_cast<int32_t>(cl.layers[L - 1].size()) : 0;
    auto& out = sc.layers[L].vertices;
    out.resize(layer.size());
    for (int32_t i = 0; i < n; ++i) {
      const VertexId v = layer[static_cast<size_t>(i)];
      StreamVertex& sv = out[static_cast<size_t>(i)];
      sv.pos = mesh.pos(v);
      if (L == 0) continue;
      dists.clear();
      cols.clear();
      const VertexId* R = rot.first(v);
      for (int32_t k = 0; k < rot.size(v); ++k) {
        const size_t x = static_cast<size_t>(R[k].get());
        const int32_t lx = lay.layer_of[x];
        if (lx == static_cast<int32_t>(L)) {
          dists.push_back(((lay.index_in_layer[x] - i) % n + n) % n);
        } else if (lx == static_cast<int32_t>(L) - 1) {
          cols.push_back(lay.index_in_layer[x]);
        }
      }
      EncodeSelfLayerRow(n, dists, &sv.window, &sv.extras);
      std::sort(cols.begin(), cols.end());
      cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
      EncodeBetweenLayerRow(prev_n, cols, &sv.between);
    }
  }
  return sc;
}

// The processed faces of the kept components and those of them the layering cannot carry (a
// corner left unlayered or an edge spanning more than one layer, §5.4), with the vertex and face counts.
void RecordFaceLists(const TokenizerProcessedMesh& mesh, const ComponentSplit& split, const Layering& lay,
                     EncodeResult* res) {
  EncodeStats& st = res->stats;
  std::vector<char> used(static_cast<size_t>(mesh.vertex_count()), 0);
  for (const Component& c : split.kept) {
    for (FaceId f : c.faces) {
      const Tri& t = mesh.face(f);
      std::array<QVec, 3> q{mesh.pos(t[0]), mesh.pos(t[1]), mesh.pos(t[2])};
      res->processed_faces.push_back(q);
      bool carried = true;
      for (int k = 0; k < 3; ++k) {
        used[static_cast<size_t>(t[k].get())] = 1;
        const int32_t la = lay.layer_of[static_cast<size_t>(t[k].get())];
        const int32_t lb = lay.layer_of[static_cast<size_t>(t[(k + 1) % 3].get())];
        if (la < 0 || lb < 0 || la - lb > 1 || lb - la > 1) carried = false;
      }
      if (!carried) res->unencodable_faces.push_back(q);
    }
  }
  for (char u : used) st.processed_vertices += u;
  st.processed_faces = static_cast<int32_t>(res->processed_faces.size());
  st.encodable_faces = st.processed_faces - static_cast<int32_t>(res->unencodable_faces.size());
}

// Layer counts and sizes over every component.
void RecordLayerStats(const Layering& lay, EncodeStats* st) {
  for (const ComponentVertexLayers& cl : lay.components) {
    st->layers += static_cast<int32_t>(cl.layers.size());
    if (static_cast<int32_t>(cl.layers.size()) > st->max_layer_count)
      st->max_layer_count = static_cast<int32_t>(cl.layers.size());
    for (const auto& l : cl.layers) {
      st->emitted_vertices += static_cast<int32_t>(l.size());
      if (static_cast<int32_t>(l.size()) > st->max_layer_size) st->max_layer_size = static_cast<int32_t>(l.size());
    }
  }
}

}  // namespace

StatusOr<LayeredStream> EncodeProcessedMesh(TokenizerProcessedMesh mesh) {
  NonManifoldStats nms;
  SILK_RETURN_IF_ERROR(SplitNonManifoldVertices(mesh, &nms));
  SILK_ASSIGN_OR_RETURN(FaceAdjacency adj, BuildFaceAdjacency(mesh));
  int32_t flipped = 0;
  SILK_RETURN_IF_ERROR(RepairOrientation(mesh, adj, &flipped));
  SILK_ASSIGN_OR_RETURN(ComponentSplit split, FindComponents(mesh, adj));
  SILK_ASSIGN_OR_RETURN(RotationLists rot, BuildRotationLists(mesh, split.kept));
  SILK_ASSIGN_OR_RETURN(Layering lay, BuildLayers(mesh, split.kept, rot));
  LayeredStream stream;
  for (const ComponentVertexLayers& cl : lay.components)
    stream.components.push_back(EncodeComponent(mesh, cl, lay, rot));
  return stream;
}

StatusOr<EncodeResult> EncodeMesh(const IoMesh& normalized, const EncodeOptions& options) {
  EncodeResult res;
  EncodeStats& st = res.stats;
  st.input_vertices = static_cast<int32_t>(normalized.positions.size());
  st.input_faces = static_cast<int32_t>(normalized.triangles.size());

  auto t0 = Clock::now();
  CleanupStats cs;
  SILK_ASSIGN_OR_RETURN(TokenizerProcessedMesh mesh, QuantizeAndClean(normalized, &cs));
  st.merged_vertices = cs.merged_vertices;
  st.dropped_degenerate_faces = cs.degenerate_faces;
  st.dropped_duplicate_faces = cs.duplicate_faces;
  auto t1 = Clock::now();
  st.times.quantize_cleanup = Seconds(t0, t1);

  if (options.nonmanifold_processing) {
    NonManifoldStats nms;
    SILK_RETURN_IF_ERROR(SplitNonManifoldVertices(mesh, &nms));
    st.nonmanifold_copies = nms.copies;
  }
  auto t2 = Clock::now();
  st.times.nonmanifold = Seconds(t1, t2);

  SILK_ASSIGN_OR_RETURN(FaceAdjacency adj, BuildFaceAdjacency(mesh));
  SILK_RETURN_IF_ERROR(RepairOrientation(mesh, adj, &st.flipped_faces));
  auto t3 = Clock::now();
  st.times.orientation = Seconds(t2, t3);

  SILK_ASSIGN_OR_RETURN(ComponentSplit split, FindComponents(mesh, adj));
  st.components_found = split.found;
  st.components_dropped_small = split.dropped_small;
  auto t4 = Clock::now();
  st.times.components = Seconds(t3, t4);

  SILK_ASSIGN_OR_RETURN(RotationLists rot, BuildRotationLists(mesh, split.kept));
  SILK_ASSIGN_OR_RETURN(Layering lay, BuildLayers(mesh, split.kept, rot));
  auto t5 = Clock::now();
  st.times.layering = Seconds(t4, t5);
  if (split.kept.empty())
    return Refuse(Refusal::kAllComponentsDropped,
                  "every component has fewer than 3 faces after cleanup (" + std::to_string(split.found) + " found)");

  res.stream.components.reserve(split.kept.size());
  for (const ComponentVertexLayers& cl : lay.components)
    res.stream.components.push_back(EncodeComponent(mesh, cl, lay, rot));
  auto t6 = Clock::now();
  st.times.codecs = Seconds(t5, t6);

  res.tokens = WriteTokenStream(res.stream);
  auto t7 = Clock::now();
  st.times.packing = Seconds(t6, t7);

  // Statistics and the processed / unencodable face lists (token_format.md §5.4).
  st.components_encoded = static_cast<int32_t>(split.kept.size());
  RecordFaceLists(mesh, split, lay, &res);
  RecordLayerStats(lay, &st);
  st.tokens = static_cast<int64_t>(res.tokens.size());
  return res;
}

}  // namespace silk
