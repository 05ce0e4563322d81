// SPDX-License-Identifier: MIT
// An independent check of mesh/mesh_checks (the verdicts silkgen --stats and the C API report):
// OpenMesh's half-edge mesh is built from the same faces and its answers are compared with
// CheckFaces / CheckMesh. OpenMesh is linked into this test only, never into libsilk.
//
// What OpenMesh says: add_face refuses a face whose directed edge already has a face (an edge
// with a third face, or two faces with the same winding) or which would attach a fan to a vertex
// whose fan is already closed. On a face set it took whole, every directed edge is used once, so
// mesh_checks must find it edge-manifold and consistently oriented, count the same open edges
// (OpenMesh's boundary edges) and the same bowtie vertices (OpenMesh: more than one outgoing
// boundary halfedge, !is_manifold). When it refused faces, mesh_checks must report a fault, and
// the faces it took are compared again in full.
//
// Meshes: the dev corpus as read (faces that repeat a corner left out on both sides: neither
// check is defined for them), the official golden-dev token streams decoded (DecodeTokens, and
// the grammar's mesh builder with the default and the faithful vertex-fan rules), random legal
// walks, and, with onnxruntime, the tiny model's generations in the input frame.
#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "decoder/random_walk.h"
#include "io/mesh_reader.h"
#include "io/tokens/token_text.h"
#include "mesh/mesh_checks.h"
#include "support/test_paths.h"
#include "tokenizer/tokenizer.h"
#include "tokenizer/vocabulary_layout.h"
#ifdef SILK_HAVE_RUNTIME
#include "runtime/runtime_test_util.h"
#include "runtime/generation_output.h"
#endif

namespace silk {
namespace {

using Faces = std::vector<std::array<int32_t, 3>>;

struct OpenMeshView {
  std::vector<char> taken;           // per face: add_face succeeded
  int64_t refused = 0;               // faces add_face refused
  int64_t boundary_edges = 0;        // edges with a face on one side only
  int64_t nonmanifold_vertices = 0;  // vertices with faces and more than one outgoing boundary halfedge
};

OpenMeshView BuildWithOpenMesh(const Faces& faces, int32_t num_vertices) {
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  Mesh m;
  std::vector<Mesh::VertexHandle> vh(static_cast<size_t>(num_vertices));
  for (auto& h : vh) h = m.add_vertex(Mesh::Point(0, 0, 0));  // connectivity only
  OpenMeshView out;
  out.taken.resize(faces.size(), 0);
  for (size_t f = 0; f < faces.size(); ++f) {
    const auto& t = faces[f];
    out.taken[f] = m.add_face(vh[t[0]], vh[t[1]], vh[t[2]]).is_valid();
    out.refused += !out.taken[f];
  }
  for (auto e : m.edges()) out.boundary_edges += m.is_boundary(e);
  for (auto v : m.vertices()) out.nonmanifold_vertices += !m.is_isolated(v) && !m.is_manifold(v);
  return out;
}

// "" when the verdicts agree with OpenMesh's on a face set it took whole, else the first difference.
std::string CompareWhole(const MeshVerdicts& v, const OpenMeshView& om, bool has_faces) {
  if (om.refused != 0) return "OpenMesh refused " + std::to_string(om.refused) + " face(s) of a whole set";
  if (!v.consistently_oriented) return "mesh_checks: a directed edge twice; OpenMesh took every face";
  if (!v.edge_manifold) return "mesh_checks: an edge with 3+ faces; OpenMesh took every face";
  if (v.boundary_edges != om.boundary_edges)
    return "open edges: mesh_checks " + std::to_string(v.boundary_edges) + ", OpenMesh " +
           std::to_string(om.boundary_edges);
  if (v.nonmanifold_vertices != om.nonmanifold_vertices)
    return "bowtie vertices: mesh_checks " + std::to_string(v.nonmanifold_vertices) + ", OpenMesh " +
           std::to_string(om.nonmanifold_vertices);
  if (v.vertex_manifold != (om.nonmanifold_vertices == 0)) return "vertex_manifold disagrees with the bowtie count";
  if (v.watertight != (has_faces && om.boundary_edges == 0))
    return "watertight: mesh_checks " + std::to_string(v.watertight) + ", OpenMesh " +
           std::to_string(has_faces && om.boundary_edges == 0);
  return "";
}

struct Tally {
  int64_t meshes = 0, faces = 0, with_refusals = 0, with_bowties = 0, watertight = 0, open = 0;
};

// Checks `verdicts` (what Silk reports for `faces`) against OpenMesh; counts into `tally`.
void ExpectAgreement(const Faces& faces, int32_t num_vertices, const MeshVerdicts& verdicts, Tally* tally) {
  const OpenMeshView om = BuildWithOpenMesh(faces, num_vertices);
  ++tally->meshes;
  tally->faces += static_cast<int64_t>(faces.size());
  if (om.refused == 0) {
    EXPECT_EQ(CompareWhole(verdicts, om, !faces.empty()), "");
    tally->with_bowties += om.nonmanifold_vertices > 0;
    tally->watertight += verdicts.watertight;
    tally->open += om.boundary_edges > 0;
    return;
  }
  ++tally->with_refusals;
  EXPECT_FALSE(verdicts.consistently_oriented && verdicts.edge_manifold && verdicts.vertex_manifold)
      << "OpenMesh refused " << om.refused << " face(s); mesh_checks finds the mesh sound";
  Faces taken;
  for (size_t f = 0; f < faces.size(); ++f)
    if (om.taken[f]) taken.push_back(faces[f]);
  EXPECT_EQ(CompareWhole(CheckFaces(taken, num_vertices), BuildWithOpenMesh(taken, num_vertices), !taken.empty()), "")
      << "on the " << taken.size() << " face(s) OpenMesh took";
}

std::vector<std::string> FilesEndingWith(const std::string& dir, const std::string& suffix) {
  std::vector<std::string> out;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string p = e.path().string();
    if (p.size() > suffix.size() && p.compare(p.size() - suffix.size(), suffix.size(), suffix) == 0) out.push_back(p);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void PrintTally(const char* what, const Tally& t) {
  std::printf("%s: %lld meshes, %lld faces; %lld with refused faces, %lld with bowties, %lld watertight, %lld open\n",
              what, static_cast<long long>(t.meshes), static_cast<long long>(t.faces),
              static_cast<long long>(t.with_refusals), static_cast<long long>(t.with_bowties),
              static_cast<long long>(t.watertight), static_cast<long long>(t.open));
}

class OpenMeshOracle : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { ::omerr().disable(); }  // refusals are expected, not news
};

// The comparison can fail: each verdict falsified on small meshes is caught.
TEST_F(OpenMeshOracle, CatchesWrongVerdicts) {
  const Faces tetra = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const Faces open(tetra.begin(), tetra.end() - 1);
  const Faces bowtie = {{0, 1, 2}, {0, 3, 4}};
  Faces flipped = tetra;
  std::swap(flipped[0][1], flipped[0][2]);
  const Faces fin = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {1, 2, 4}};
  struct Case {
    const Faces* faces;
    int32_t vertices;
    bool refused;
  };
  for (const Case& c : {Case{&tetra, 4, false}, Case{&open, 4, false}, Case{&bowtie, 5, false}, Case{&flipped, 4, true},
                        Case{&fin, 5, true}}) {
    const OpenMeshView om = BuildWithOpenMesh(*c.faces, c.vertices);
    const MeshVerdicts v = CheckFaces(*c.faces, c.vertices);
    ASSERT_EQ(om.refused > 0, c.refused) << c.faces->size() << " faces";
    Tally t;
    ExpectAgreement(*c.faces, c.vertices, v, &t);
    if (c.refused) continue;
    ASSERT_EQ(CompareWhole(v, om, true), "");
    for (int k = 0; k < 6; ++k) {
      MeshVerdicts wrong = v;
      switch (k) {
        case 0:
          wrong.consistently_oriented = !wrong.consistently_oriented;
          break;
        case 1:
          wrong.edge_manifold = !wrong.edge_manifold;
          break;
        case 2:
          wrong.boundary_edges += 1;
          break;
        case 3:
          wrong.nonmanifold_vertices += 1;
          break;
        case 4:
          wrong.vertex_manifold = !wrong.vertex_manifold;
          break;
        default:
          wrong.watertight = !wrong.watertight;
          break;
      }
      EXPECT_NE(CompareWhole(wrong, om, true), "") << "falsified verdict " << k << " not caught";
    }
  }
  EXPECT_EQ(BuildWithOpenMesh(bowtie, 5).nonmanifold_vertices, 1);
  EXPECT_EQ(BuildWithOpenMesh(open, 4).boundary_edges, 3);
}

TEST_F(OpenMeshOracle, DevCorpusAsRead) {
  const auto files = FilesEndingWith(testing::SharedPath("corpus/dev"), ".obj");
  ASSERT_GE(files.size(), 100u) << testing::SharedPath("corpus/dev");
  Tally tally;
  int64_t repeated_corner = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f);
    auto mesh = ReadMeshFile(f);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    IoMesh m = std::move(*mesh);
    Faces kept;
    for (const auto& t : m.triangles)
      if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) kept.push_back(t);
    repeated_corner += static_cast<int64_t>(m.triangles.size() - kept.size());
    m.triangles = kept;
    ExpectAgreement(m.triangles, static_cast<int32_t>(m.positions.size()), CheckMesh(m), &tally);
  }
  PrintTally("dev corpus", tally);
  std::printf("dev corpus: %lld faces repeating a corner left out\n", static_cast<long long>(repeated_corner));
  // The corpus exercises both branches (no mesh of it is watertight as read, unwelded: the
  // decoded streams and the walks cover that verdict).
  EXPECT_GT(tally.with_refusals, 0);
  EXPECT_GT(tally.with_bowties, 0);
  EXPECT_GT(tally.open, 0);
}

TEST_F(OpenMeshOracle, DecodedGoldenDevStreams) {
  const auto files = FilesEndingWith(testing::SharedPath("spec/golden-dev"), ".tokens.txt");
  ASSERT_GE(files.size(), 100u) << testing::SharedPath("spec/golden-dev");
  Tally decoded, built, faithful;
  for (const auto& f : files) {
    SCOPED_TRACE(f);
    auto ids = ReadTokenText(f);
    ASSERT_TRUE(ids.ok()) << ids.status().ToString();
    auto mesh = DecodeTokens(*ids);  // silktok decode, silk_tokens_decode
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    const auto n = static_cast<int32_t>(mesh->positions.size());
    ExpectAgreement(mesh->faces, n, CheckFaces(mesh->faces, n), &decoded);
    GrammarOptions go;
    go.max_length = 0;  // some dev streams exceed the model's length limit
    Grammar g(go);
    for (int32_t id : *ids) ASSERT_TRUE(g.Accept(id).ok());
    for (VertexFanPolicy fans : {VertexFanPolicy::kResolve, VertexFanPolicy::kKeep}) {
      MeshBuildOptions mo;  // the generator's mesh (silkgen, silk_repair)
      mo.holes = HolePolicy::kRepair;
      mo.vertex_fans = fans;
      MeshBuildReport rep;
      auto b = BuildMeshSoFar(g, mo, &rep);
      ASSERT_TRUE(b.ok()) << b.status().ToString();
      const auto bn = static_cast<int32_t>(b->positions.size());
      ExpectAgreement(b->faces, bn, CheckFaces(b->faces, bn), fans == VertexFanPolicy::kKeep ? &faithful : &built);
    }
  }
  PrintTally("decoded", decoded);
  PrintTally("built (repair, fans resolved)", built);
  PrintTally("built (repair, fans kept)", faithful);
  EXPECT_GT(decoded.with_bowties, 0);
  EXPECT_GT(built.watertight, 0);
  EXPECT_EQ(built.with_bowties, 0);  // the vertex-fan rule's guarantee, seen by OpenMesh too
  EXPECT_EQ(built.with_refusals, 0);
}

TEST_F(OpenMeshOracle, RandomLegalWalks) {
  Tally tally, resolved;
  for (uint64_t seed = 0; seed < 300; ++seed) {
    std::mt19937_64 rng(seed);
    Grammar g;
    RandomLegalWalk(&g, &rng);
    MeshBuildOptions mo;
    mo.holes = seed % 2 ? HolePolicy::kRepair : HolePolicy::kOff;
    mo.vertex_fans = seed % 3 == 0 ? VertexFanPolicy::kKeep : VertexFanPolicy::kResolve;
    auto b = BuildMeshSoFar(g, mo, nullptr);
    ASSERT_TRUE(b.ok()) << "seed " << seed << ": " << b.status().ToString();
    const auto n = static_cast<int32_t>(b->positions.size());
    SCOPED_TRACE("seed " + std::to_string(seed));
    const bool keep = mo.vertex_fans == VertexFanPolicy::kKeep;
    ExpectAgreement(b->faces, n, CheckFaces(b->faces, n), keep ? &tally : &resolved);
  }
  PrintTally("random walks (fans kept)", tally);
  PrintTally("random walks (fans resolved)", resolved);
  EXPECT_EQ(resolved.with_refusals + resolved.with_bowties, 0);  // the grammar's guarantee (grammar.h)
  EXPECT_GT(tally.with_refusals, 0);                             // kKeep walks: bowties next to closed fans
  EXPECT_GT(tally.with_bowties, 0);
  EXPECT_GT(tally.watertight, 0);
}

#ifdef SILK_HAVE_RUNTIME
// What silkgen writes: the tiny model's generations, in the input frame, with the verdicts the
// generation stats report (FinishOutput).
TEST_F(OpenMeshOracle, TinyModelGenerations) {
  auto model = testing::LoadTinyModel(1);
  ASSERT_TRUE(model);
  auto pts = PrepareModelPoints(testing::SampleMeshInput(), ModelPreprocessing(model->config()), 1);
  ASSERT_TRUE(pts.ok()) << pts.status().ToString();
  Generator gen(*model);
  Tally tally;
  for (uint64_t seed = 0; seed < 6; ++seed) {
    GenerateOptions o;
    o.sampling.seed = seed;
    o.max_tokens = 1500;
    o.holes = seed % 2 ? HolePolicy::kRepair : HolePolicy::kOff;
    auto r = gen.Run(pts->rows, o);
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    const IoMesh out = FinishOutput(&*r, pts->transform);
    const GenerationStats& st = r->stats;
    MeshVerdicts reported;
    reported.edge_manifold = st.edge_manifold;
    reported.watertight = st.watertight;
    reported.consistently_oriented = st.consistently_oriented;
    reported.vertex_manifold = st.vertex_manifold;
    reported.nonmanifold_vertices = st.nonmanifold_vertices;
    reported.boundary_edges = st.open_edges;
    SCOPED_TRACE("seed " + std::to_string(seed));
    ExpectAgreement(out.triangles, static_cast<int32_t>(out.positions.size()), reported, &tally);
  }
  PrintTally("tiny-model generations", tally);
  EXPECT_GT(tally.faces, 0);
}
#endif

}  // namespace
}  // namespace silk
