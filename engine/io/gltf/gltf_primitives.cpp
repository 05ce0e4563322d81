// SPDX-License-Identifier: MIT
// glTF accessor validation (bounds, types, strides) and primitive-to-triangle conversion.
#include "io/gltf/gltf_primitives.h"

#include <cmath>
#include <cstring>
#include <vector>

#include "io/read_error.h"

namespace silk {

namespace {

struct AccessorView {
  const uint8_t* base = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int component_type = 0;
};

StatusOr<AccessorView> ViewAccessor(const tinygltf::Model& model, int index, const std::string& what,
                                    const std::string& name) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    return ParseErrorIn(name, what + ": accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = model.accessors[index];
  const std::string who = what + " (accessor " + std::to_string(index) + ")";
  if (a.sparse.isSparse) return Unsupported(name + ": " + who + ": sparse accessors are not supported");
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
    return ParseErrorIn(name, who + ": missing or invalid bufferView");
  const tinygltf::BufferView& bv = model.bufferViews[a.bufferView];
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
    return ParseErrorIn(name, who + ": bufferView " + std::to_string(a.bufferView) + " has an invalid buffer");
  const tinygltf::Buffer& buf = model.buffers[bv.buffer];
  const int comp_size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  const int ncomp = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  if (comp_size <= 0 || ncomp <= 0) return ParseErrorIn(name, who + ": invalid type or componentType");
  const uint64_t elem = static_cast<uint64_t>(comp_size) * static_cast<uint64_t>(ncomp);
  const uint64_t stride = bv.byteStride ? bv.byteStride : elem;
  if (stride < elem)
    return ParseErrorIn(name, who + ": byteStride " + std::to_string(stride) + " is smaller than an element");
  const uint64_t bv_off = bv.byteOffset, bv_len = bv.byteLength, acc_off = a.byteOffset;
  if (bv_off > buf.data.size() || bv_len > buf.data.size() - bv_off)
    return ParseErrorIn(name, who + ": bufferView " + std::to_string(a.bufferView) + " runs past the end of buffer " +
                                  std::to_string(bv.buffer) + " (" + std::to_string(buf.data.size()) + " bytes)");
  const uint64_t count = a.count;
  if (count > 0) {
    if (acc_off > bv_len || count > bv_len / stride + 1 || acc_off + (count - 1) * stride + elem > bv_len)
      return ParseErrorIn(name, who + ": " + std::to_string(count) + " elements run past the end of bufferView " +
                                    std::to_string(a.bufferView));
  }
  AccessorView v;
  v.base = buf.data.data() + bv_off + acc_off;
  v.count = static_cast<size_t>(count);
  v.stride = static_cast<size_t>(stride);
  v.component_type = a.componentType;
  return v;
}

uint32_t LoadIndex(const AccessorView& v, size_t i) {
  const uint8_t* p = v.base + i * v.stride;
  switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t x;
      std::memcpy(&x, p, 2);
      return x;
    }
    default: {
      uint32_t x;
      std::memcpy(&x, p, 4);
      return x;
    }
  }
}

// The node transform of one mesh instance (column-major, as glTF stores it).
struct InstanceTransform {
  std::array<double, 16> m;
  bool identity;
  bool flip;  // negative determinant: the winding is reversed to keep faces outward
};

InstanceTransform TransformOf(const GltfMeshInstance& inst) {
  const auto& M = inst.matrix;
  const bool identity = M == std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const double det =
      M[0] * (M[5] * M[10] - M[9] * M[6]) - M[4] * (M[1] * M[10] - M[9] * M[2]) + M[8] * (M[1] * M[6] - M[5] * M[2]);
  return InstanceTransform{M, identity, det < 0};
}

// The POSITION accessor of a primitive: present, in bounds, VEC3 of FLOAT.
StatusOr<AccessorView> ViewPositions(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                     const std::string& what, const std::string& name) {
  auto pos_it = prim.attributes.find("POSITION");
  if (pos_it == prim.attributes.end()) return ParseErrorIn(name, what + ": no POSITION attribute");
  SILK_ASSIGN_OR_RETURN(AccessorView pos, ViewAccessor(model, pos_it->second, what + " POSITION", name));
  const tinygltf::Accessor& pa = model.accessors[pos_it->second];
  if (pa.type != TINYGLTF_TYPE_VEC3 || pa.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    return Unsupported(name + ": " + what + ": POSITION must be VEC3 of FLOAT");
  return pos;
}

// Corner list: the indices accessor (each index checked against the vertex count), or
// implicitly 0..count-1 when the primitive has none.
StatusOr<std::vector<uint32_t>> PrimitiveCorners(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                                 const AccessorView& pos, const std::string& what,
                                                 const std::string& name, uint64_t max_vertices) {
  std::vector<uint32_t> corners;
  if (prim.indices < 0) {
    if (pos.count > max_vertices) return LimitErrorIn(name, what + ": too many vertices");
    corners.resize(pos.count);
    for (size_t i = 0; i < pos.count; ++i) corners[i] = static_cast<uint32_t>(i);
    return corners;
  }
  SILK_ASSIGN_OR_RETURN(AccessorView idx, ViewAccessor(model, prim.indices, what + " indices", name));
  const tinygltf::Accessor& ia = model.accessors[prim.indices];
  if (ia.type != TINYGLTF_TYPE_SCALAR || (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                          ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                          ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    return ParseErrorIn(name, what + ": indices must be SCALAR unsigned byte/short/int");
  corners.resize(idx.count);
  for (size_t i = 0; i < idx.count; ++i) {
    corners[i] = LoadIndex(idx, i);
    if (corners[i] >= pos.count)
      return ParseErrorIn(name, what + ": index " + std::to_string(corners[i]) + " (at " + std::to_string(i) +
                                    ") out of range (" + std::to_string(pos.count) + " vertices)");
  }
  return corners;
}

// Triangles of one primitive in local vertex numbers, from its corners as the glTF spec
// defines TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN.
StatusOr<std::vector<std::array<uint32_t, 3>>> PrimitiveTriangles(int mode, const std::vector<uint32_t>& corners,
                                                                  const std::string& what, const std::string& name) {
  std::vector<std::array<uint32_t, 3>> tris;
  const size_t n = corners.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0) return ParseErrorIn(name, what + ": " + std::to_string(n) + " corners is not a multiple of 3");
    for (size_t i = 0; i + 2 < n; i += 3) tris.push_back({corners[i], corners[i + 1], corners[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < n; ++i) {
      if (i % 2 == 0)
        tris.push_back({corners[i], corners[i + 1], corners[i + 2]});
      else
        tris.push_back({corners[i + 1], corners[i], corners[i + 2]});
    }
  } else {
    for (size_t i = 1; i + 1 < n; ++i) tris.push_back({corners[i], corners[i + 1], corners[0]});
  }
  return tris;
}

// Appends every POSITION (unreferenced ones too), transformed; each must be finite before
// and after the transform.
Status AppendPositions(const AccessorView& pos, const InstanceTransform& xf, const GltfMeshInstance& inst,
                       const std::string& what, const std::string& name, IoMesh* mesh) {
  const auto& M = xf.m;
  mesh->positions.reserve(mesh->positions.size() + pos.count);
  for (size_t i = 0; i < pos.count; ++i) {
    float f[3];
    std::memcpy(f, pos.base + i * pos.stride, sizeof(f));
    std::array<double, 3> p{f[0], f[1], f[2]};
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return ParseErrorIn(name, what + ": POSITION " + std::to_string(i) + " is not finite");
    if (!xf.identity) {
      std::array<double, 3> q;
      for (int r = 0; r < 3; ++r) q[r] = M[r] * p[0] + M[4 + r] * p[1] + M[8 + r] * p[2] + M[12 + r];
      p = q;
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        return ParseErrorIn(name, what + ": POSITION " + std::to_string(i) + " is not finite after the node " +
                                      std::to_string(inst.node) + " transform");
    }
    mesh->positions.push_back(p);
  }
  return Status::Ok();
}

// One primitive: mode, accessor and limit checks, then its positions and its triangles
// (renumbered past the vertices already in the mesh) appended.
Status AppendPrimitive(const tinygltf::Model& model, const GltfMeshInstance& inst, size_t pi,
                       const InstanceTransform& xf, const std::string& name, const ReadOptions& opts, IoMesh* mesh) {
  const tinygltf::Primitive& prim = model.meshes[inst.mesh].primitives[pi];
  const std::string what = "mesh " + std::to_string(inst.mesh) + " primitive " + std::to_string(pi);
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
    if (mesh->warnings.size() < 20) mesh->warnings.push_back(name + ": " + what + ": points/lines skipped");
    return Status::Ok();
  }
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN) return ParseErrorIn(name, what + ": invalid mode " + std::to_string(mode));
  SILK_ASSIGN_OR_RETURN(const AccessorView pos, ViewPositions(model, prim, what, name));
  const uint64_t max_vertices = VertexLimit(opts);
  SILK_ASSIGN_OR_RETURN(const std::vector<uint32_t> corners,
                        PrimitiveCorners(model, prim, pos, what, name, max_vertices));
  SILK_ASSIGN_OR_RETURN(const auto tris, PrimitiveTriangles(mode, corners, what, name));

  if (mesh->positions.size() + pos.count > max_vertices)
    return LimitErrorIn(name, "more than " + std::to_string(max_vertices) + " vertices");
  if (mesh->triangles.size() + tris.size() > opts.max_triangles)
    return LimitErrorIn(name, "more than " + std::to_string(opts.max_triangles) + " triangles");
  const int32_t base = static_cast<int32_t>(mesh->positions.size());
  SILK_RETURN_IF_ERROR(AppendPositions(pos, xf, inst, what, name, mesh));
  for (const auto& t : tris) {
    const int32_t a = base + static_cast<int32_t>(t[0]);
    const int32_t b = base + static_cast<int32_t>(t[1]);
    const int32_t c = base + static_cast<int32_t>(t[2]);
    mesh->triangles.push_back(xf.flip ? std::array<int32_t, 3>{a, c, b} : std::array<int32_t, 3>{a, b, c});
  }
  return Status::Ok();
}

}  // namespace

Status AppendGltfMeshInstance(const tinygltf::Model& model, const GltfMeshInstance& inst, const std::string& name,
                              const ReadOptions& opts, IoMesh* mesh) {
  const InstanceTransform xf = TransformOf(inst);
  for (size_t pi = 0; pi < model.meshes[inst.mesh].primitives.size(); ++pi)
    SILK_RETURN_IF_ERROR(AppendPrimitive(model, inst, pi, xf, name, opts, mesh));
  return Status::Ok();
}

}  // namespace silk
