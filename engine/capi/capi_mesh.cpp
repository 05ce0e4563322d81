// SPDX-License-Identifier: MIT
// C API: mesh handles (create from arrays, load, save, query-then-copy).
#include <algorithm>
#include <cctype>
#include <cstring>
#include <memory>

#include "capi/capi_internal.h"
#include "io/mesh_reader.h"
#include "mesh/glb_parts.h"
#include "mesh/input_file.h"
#include "io/obj/obj_writer.h"
#include "io/ply/ply_writer.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

std::unique_ptr<silk_mesh> silk::capi::MeshHandle(std::vector<std::array<double, 3>> positions,
                                                  const silk::TokenizerDecodedMesh& decoded) {
  auto m = std::make_unique<silk_mesh>();
  m->mesh.positions = std::move(positions);
  m->mesh.triangles = decoded.faces;
  m->triangle_component = decoded.face_component;
  m->triangle_component.resize(m->mesh.triangles.size(), 0);
  return m;
}

namespace {
bool EndsWith(const std::string& s, const char* suf) {
  const size_t n = std::strlen(suf);
  if (s.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suf[i]) return false;
  return true;
}
}  // namespace

extern "C" {

silk_status silk_mesh_create(const double* positions, size_t n_vertices, const int32_t* triangles, size_t n_triangles,
                             silk_mesh** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_mesh_create: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(positions || n_vertices == 0, "silk_mesh_create: positions is NULL");
    SILK_CAPI_REQUIRE(triangles || n_triangles == 0, "silk_mesh_create: triangles is NULL");
    auto m = std::make_unique<silk_mesh>();
    m->mesh.positions.resize(n_vertices);
    for (size_t i = 0; i < n_vertices; ++i)
      for (int a = 0; a < 3; ++a) m->mesh.positions[i][a] = positions[3 * i + a];
    m->mesh.triangles.resize(n_triangles);
    for (size_t f = 0; f < n_triangles; ++f)
      for (int k = 0; k < 3; ++k) {
        const int32_t idx = triangles[3 * f + k];
        if (idx < 0 || static_cast<size_t>(idx) >= n_vertices)
          return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_mesh_create: triangle " + std::to_string(f) +
                                                         " references vertex " + std::to_string(idx) + " of " +
                                                         std::to_string(n_vertices));
        m->mesh.triangles[f][k] = idx;
      }
    m->triangle_component.assign(n_triangles, 0);
    *out = m.release();
    return Ok();
  });
}

silk_load_params silk_load_default_params(void) {
  silk_load_params p;
  p.struct_size = sizeof(p);
  p.point_clouds = 1;
  return p;
}

silk_status silk_mesh_load(const char* path, const silk_load_params* params, silk_mesh** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_mesh_load: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(path, "silk_mesh_load: path is NULL");
    SILK_CAPI_TRY(
        silk::capi::CheckParamsSize("silk_mesh_load", "silk_load_params", params, "silk_load_default_params()"));
    const silk_load_params lp = silk::capi::ReadParams(params, silk_load_default_params());
    SILK_CAPI_CHECK("silk_mesh_load", silk::capi::CheckFlag("point_clouds", lp.point_clouds));
    auto m = std::make_unique<silk_mesh>();
    if (lp.point_clouds) {
      // A PLY without faces or an XYZ/PTS file is a point cloud: its normals, or estimated ones.
      auto in = silk::ReadGenerationInputFile(path);
      if (!in.ok()) return SetError(in.status());
      m->mesh = std::move(in->mesh);
      m->normals = std::move(in->normals);
      m->triangle_component.assign(m->mesh.triangles.size(), 0);
      m->source = path;
      *out = m.release();
      return Ok();
    }
    auto r = silk::ReadMeshFile(path);
    if (!r.ok()) return SetError(r.status());
    m->mesh = std::move(*r);
    m->triangle_component.assign(m->mesh.triangles.size(), 0);
    m->source = path;
    *out = m.release();
    return Ok();
  });
}

silk_save_params silk_save_default_params(void) {
  silk_save_params p;
  p.struct_size = sizeof(p);
  p.part_colors = 0;
  p.obj_comment = nullptr;
  p.format = SILK_FORMAT_BY_EXTENSION;
  return p;
}

silk_status silk_mesh_save(const silk_mesh* mesh, const char* path, const silk_save_params* params) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(mesh && path, "silk_mesh_save: mesh or path is NULL");
    SILK_CAPI_TRY(
        silk::capi::CheckParamsSize("silk_mesh_save", "silk_save_params", params, "silk_save_default_params()"));
    const silk_save_params sp = silk::capi::ReadParams(params, silk_save_default_params());
    SILK_CAPI_CHECK("silk_mesh_save", silk::capi::CheckFlag("part_colors", sp.part_colors));
    SILK_CAPI_CHECK("silk_mesh_save", silk::capi::CheckEnum("format", sp.format, SILK_FORMAT_BY_EXTENSION,
                                                            SILK_FORMAT_GLB, "silk_mesh_format"));
    const std::string p = path;
    const auto is = [&](int32_t format, const char* ext) {
      return sp.format == format || (sp.format == SILK_FORMAT_BY_EXTENSION && EndsWith(p, ext));
    };
    silk::Status st;
    if (is(SILK_FORMAT_OBJ, ".obj")) {
      silk::ObjWriteOptions opt;
      if (sp.obj_comment) opt.header_comment = sp.obj_comment;
      st = silk::WriteObjFile(p, mesh->mesh, opt);
    } else if (is(SILK_FORMAT_PLY, ".ply"))
      st = silk::WritePlyFile(p, mesh->mesh);
    else if (is(SILK_FORMAT_GLB, ".glb"))
      st = silk::WriteGlbFile(p, silk::SplitGlbParts(mesh->mesh, mesh->triangle_component, sp.part_colors != 0),
                              "silk " SILK_VERSION_STRING);
    else
      return SetError(SILK_ERR_UNSUPPORTED, p + ": unsupported output extension (use .glb, .obj or .ply)");
    return SetError(st);
  });
}

void silk_mesh_destroy(silk_mesh* mesh) { delete mesh; }

silk_status silk_mesh_copy_positions(const silk_mesh* mesh, double* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE(mesh, "silk_mesh_copy_positions: mesh is NULL");
    const size_t n = mesh->mesh.positions.size() * 3;
    if (silk_status c; !silk::capi::BeginCopy("silk_mesh_copy_positions", out, capacity, n, out_count, &c)) return c;
    for (size_t i = 0; i < mesh->mesh.positions.size(); ++i)
      for (int a = 0; a < 3; ++a) out[3 * i + a] = mesh->mesh.positions[i][a];
    return Ok();
  });
}

silk_status silk_mesh_copy_triangles(const silk_mesh* mesh, int32_t* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE(mesh, "silk_mesh_copy_triangles: mesh is NULL");
    const size_t n = mesh->mesh.triangles.size() * 3;
    if (silk_status c; !silk::capi::BeginCopy("silk_mesh_copy_triangles", out, capacity, n, out_count, &c)) return c;
    for (size_t f = 0; f < mesh->mesh.triangles.size(); ++f)
      for (int k = 0; k < 3; ++k) out[3 * f + k] = mesh->mesh.triangles[f][k];
    return Ok();
  });
}

silk_status silk_mesh_copy_triangle_components(const silk_mesh* mesh, int32_t* out, size_t capacity,
                                               size_t* out_count) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE(mesh, "silk_mesh_copy_triangle_components: mesh is NULL");
    const size_t n = mesh->triangle_component.size();
    if (silk_status c; !silk::capi::BeginCopy("silk_mesh_copy_triangle_components", out, capacity, n, out_count, &c))
      return c;
    std::copy(mesh->triangle_component.begin(), mesh->triangle_component.end(), out);
    return Ok();
  });
}

int32_t silk_mesh_has_normals(const silk_mesh* mesh) { return mesh && !mesh->normals.empty() ? 1 : 0; }

silk_status silk_mesh_copy_normals(const silk_mesh* mesh, double* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE(mesh, "silk_mesh_copy_normals: mesh is NULL");
    const size_t n = mesh->normals.size() * 3;
    if (silk_status c; !silk::capi::BeginCopy("silk_mesh_copy_normals", out, capacity, n, out_count, &c)) return c;
    for (size_t i = 0; i < mesh->normals.size(); ++i)
      for (int a = 0; a < 3; ++a) out[3 * i + a] = mesh->normals[i][a];
    return Ok();
  });
}

}  // extern "C"
