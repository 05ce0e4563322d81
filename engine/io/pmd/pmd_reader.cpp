// SPDX-License-Identifier: MIT
// PMD parsing: a bounds-checked little-endian cursor walks the file section by section; every
// count is compared with the bytes left before use, so arbitrary input fails with a message.
#include "io/pmd/pmd_reader.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "io/read_error.h"

namespace silk {

namespace {

// Sizes of the fixed records (bytes).
constexpr uint64_t kHeaderBytes = 12;             // magic, version, data size
constexpr uint64_t kVec3Bytes = 12;               // float x, y, z
constexpr uint64_t kUvBytes = 8;                  // float u, v
constexpr uint64_t kBlendBytes = 4 + 16;          // u8 bones[4], float weights[4]
constexpr uint64_t kFaceBytes = 6;                // u16 vertices[3]
constexpr uint64_t kBoneBytes = 12 + 16;          // translation, quaternion
constexpr uint64_t kPropTailBytes = 12 + 16 + 1;  // translation, quaternion, u8 bone

class Cursor {
 public:
  Cursor(std::string_view data, const std::string& name) : data_(data), name_(name) {}

  uint64_t offset() const { return pos_; }
  uint64_t left() const { return data_.size() - pos_; }

  // Error unless `n` more bytes are available for `field`.
  Status Need(uint64_t n, const std::string& field) const {
    if (n <= left()) return Status::Ok();
    return ParseErrorIn(name_, "truncated at byte " + std::to_string(pos_) + " reading " + field + " (needs " +
                                   std::to_string(n) + " bytes, " + std::to_string(left()) + " left)");
  }
  Status U32(const std::string& field, uint32_t* v) {
    SILK_RETURN_IF_ERROR(Need(4, field));
    const uint8_t* p = bytes() + pos_;
    *v = uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
    pos_ += 4;
    return Status::Ok();
  }
  // Callers check the room first (Need) for whole arrays; these do not.
  uint16_t U16Unchecked() {
    const uint8_t* p = bytes() + pos_;
    pos_ += 2;
    return static_cast<uint16_t>(p[0] | p[1] << 8);
  }
  float F32Unchecked() {
    const uint8_t* p = bytes() + pos_;
    const uint32_t u = uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
    pos_ += 4;
    float f;
    std::memcpy(&f, &u, 4);
    return f;
  }
  void Skip(uint64_t n) { pos_ += n; }

  // Reads a u32 count of records of `record_bytes` each and checks they fit in the rest.
  Status Count(const std::string& field, uint64_t record_bytes, uint32_t* n) {
    const uint64_t at = pos_;
    SILK_RETURN_IF_ERROR(U32(field, n));
    if (record_bytes > 0 && *n > left() / record_bytes)
      return ParseErrorIn(name_, field + " = " + std::to_string(*n) + " at byte " + std::to_string(at) + " needs " +
                                     std::to_string(*n * record_bytes) + " bytes, only " + std::to_string(left()) +
                                     " left");
    return Status::Ok();
  }

 private:
  const uint8_t* bytes() const { return reinterpret_cast<const uint8_t*>(data_.data()); }
  std::string_view data_;
  const std::string& name_;
  uint64_t pos_ = 0;
};

// Header: "PSMD" magic, version 1 to 4, and a data size that matches the file; returns the version.
StatusOr<uint32_t> ReadPmdHeader(std::string_view data, const std::string& name, Cursor* in) {
  if (data.size() < 4 || std::memcmp(data.data(), "PSMD", 4) != 0)
    return ParseErrorIn(name, "not a PMD file (no 'PSMD' magic)");
  in->Skip(4);
  uint32_t version = 0, data_size = 0;
  SILK_RETURN_IF_ERROR(in->U32("version", &version));
  if (version < 1 || version > 4)
    return Unsupported(name + ": PMD version " + std::to_string(version) + " not supported (1 to 4)");
  SILK_RETURN_IF_ERROR(in->U32("data size", &data_size));
  if (uint64_t{data_size} != data.size() - kHeaderBytes)
    return ParseErrorIn(name, "header data size " + std::to_string(data_size) + " but the file has " +
                                  std::to_string(data.size() - kHeaderBytes) + " bytes after the header");
  return version;
}

// Vertex block: position, normal, UV sets (one before version 4), bone blend; only the
// positions are kept.
Status ReadPmdVertices(uint32_t version, const std::string& name, const ReadOptions& opts, Cursor* in, IoMesh* mesh) {
  uint32_t num_vertices = 0, num_uv_sets = 1;
  SILK_RETURN_IF_ERROR(in->U32("vertex count", &num_vertices));
  if (version >= 4) {
    SILK_RETURN_IF_ERROR(in->U32("UV set count", &num_uv_sets));
    if (num_uv_sets > in->left() / kUvBytes)
      return ParseErrorIn(name, "UV set count " + std::to_string(num_uv_sets) + " does not fit in the file");
  }
  const uint64_t vertex_bytes = 2 * kVec3Bytes + kUvBytes * num_uv_sets + kBlendBytes;
  if (num_vertices > in->left() / vertex_bytes)
    return ParseErrorIn(name, "vertex count " + std::to_string(num_vertices) + " needs " +
                                  std::to_string(num_vertices * vertex_bytes) + " bytes, only " +
                                  std::to_string(in->left()) + " left");
  if (num_vertices == 0) return ParseErrorIn(name, "no vertices");
  if (num_vertices > VertexLimit(opts))
    return LimitErrorIn(name, std::to_string(num_vertices) + " vertices exceed the vertex limit");
  mesh->positions.resize(num_vertices);
  for (uint32_t v = 0; v < num_vertices; ++v) {
    std::array<double, 3>& p = mesh->positions[v];
    for (int k = 0; k < 3; ++k) {
      p[k] = in->F32Unchecked();
      if (!std::isfinite(p[k]))
        return ParseErrorIn(name, "vertex " + std::to_string(v) + ": non-finite position coordinate");
    }
    in->Skip(vertex_bytes - kVec3Bytes);
  }
  return Status::Ok();
}

// Face block: three u16 vertex indices each.
Status ReadPmdFaces(const std::string& name, const ReadOptions& opts, Cursor* in, IoMesh* mesh) {
  const uint64_t num_vertices = mesh->positions.size();
  uint32_t num_faces = 0;
  SILK_RETURN_IF_ERROR(in->Count("face count", kFaceBytes, &num_faces));
  if (num_faces == 0) return ParseErrorIn(name, "no faces");
  if (num_faces > opts.max_triangles)
    return LimitErrorIn(name, std::to_string(num_faces) + " faces exceed the triangle limit");
  mesh->triangles.resize(num_faces);
  for (uint32_t f = 0; f < num_faces; ++f) {
    for (int c = 0; c < 3; ++c) {
      const uint16_t idx = in->U16Unchecked();
      if (idx >= num_vertices)
        return ParseErrorIn(name, "face " + std::to_string(f) + ": " + VertexIndexOutOfRange(idx, num_vertices));
      mesh->triangles[f][c] = idx;
    }
  }
  return Status::Ok();
}

// Rest-pose bones, then (version 2 on) prop points: both dropped, but their sizes checked.
Status SkipPmdBonesAndProps(uint32_t version, Cursor* in) {
  uint32_t num_bones = 0;
  SILK_RETURN_IF_ERROR(in->Count("bone count", kBoneBytes, &num_bones));
  in->Skip(uint64_t{num_bones} * kBoneBytes);
  if (version < 2) return Status::Ok();
  uint32_t num_props = 0;
  // Smallest prop point: empty name.
  SILK_RETURN_IF_ERROR(in->Count("prop point count", 4 + kPropTailBytes, &num_props));
  for (uint32_t i = 0; i < num_props; ++i) {
    const std::string field = "prop point " + std::to_string(i);
    uint32_t name_length = 0;
    SILK_RETURN_IF_ERROR(in->U32(field + " name length", &name_length));
    SILK_RETURN_IF_ERROR(in->Need(uint64_t{name_length} + kPropTailBytes, field));
    in->Skip(uint64_t{name_length} + kPropTailBytes);
  }
  return Status::Ok();
}

}  // namespace

StatusOr<IoMesh> ReadPmd(std::string_view data, const std::string& name, const ReadOptions& opts) {
  Cursor in(data, name);
  SILK_ASSIGN_OR_RETURN(const uint32_t version, ReadPmdHeader(data, name, &in));
  IoMesh mesh;
  SILK_RETURN_IF_ERROR(ReadPmdVertices(version, name, opts, &in, &mesh));
  SILK_RETURN_IF_ERROR(ReadPmdFaces(name, opts, &in, &mesh));
  SILK_RETURN_IF_ERROR(SkipPmdBonesAndProps(version, &in));
  if (in.left() != 0)
    return ParseErrorIn(name, std::to_string(in.left()) + " unexpected bytes after the " +
                                  (version >= 2 ? "prop points" : "bones") + " at byte " + std::to_string(in.offset()));
  return mesh;
}

}  // namespace silk
