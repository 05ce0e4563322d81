// SPDX-License-Identifier: MIT
// PLY body reading for the three encodings, driven by the parsed header.
#include "io/ply/ply_reader.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "io/files/number_parse.h"
#include "io/ply/ply_header.h"
#include "io/polygon_fan.h"
#include "io/read_error.h"
#include "io/files/text_lines.h"

namespace silk {

namespace {

// What the reader does with each property of the element being read.
enum class Role : uint8_t { kSkip, kX, kY, kZ, kNx, kNy, kNz, kFaceList };

struct ElementPlan {
  const PlyElement* element;
  std::vector<Role> roles;
  bool is_vertex = false;
  bool is_face = false;
};

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
constexpr bool kHostBigEndian = true;
#else
constexpr bool kHostBigEndian = false;
#endif

template <typename T>
T LoadRaw(const uint8_t* p, bool swap) {
  uint8_t b[sizeof(T)];
  if (swap) {
    for (size_t i = 0; i < sizeof(T); ++i) b[i] = p[sizeof(T) - 1 - i];
  } else {
    std::memcpy(b, p, sizeof(T));
  }
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

int64_t LoadInt(const uint8_t* p, PlyType t, bool swap) {  // integer types only
  switch (t) {
    case PlyType::kInt8:
      return LoadRaw<int8_t>(p, swap);
    case PlyType::kUInt8:
      return LoadRaw<uint8_t>(p, swap);
    case PlyType::kInt16:
      return LoadRaw<int16_t>(p, swap);
    case PlyType::kUInt16:
      return LoadRaw<uint16_t>(p, swap);
    case PlyType::kInt32:
      return LoadRaw<int32_t>(p, swap);
    case PlyType::kUInt32:
      return LoadRaw<uint32_t>(p, swap);
    default:
      return 0;
  }
}

double LoadDouble(const uint8_t* p, PlyType t, bool swap) {
  if (t == PlyType::kFloat32) return LoadRaw<float>(p, swap);
  if (t == PlyType::kFloat64) return LoadRaw<double>(p, swap);
  return static_cast<double>(LoadInt(p, t, swap));  // every PLY integer type is exact in a double
}

// Parses an ascii value of type t; float32 values are rounded to float.
bool ParseAsciiValue(std::string_view tok, PlyType t, double* out) {
  if (PlyTypeIsInteger(t)) {
    int64_t v;
    if (!ParseInt64Token(tok, &v)) return false;
    *out = static_cast<double>(v);
    return true;
  }
  if (!ParseDoubleToken(tok, out)) return false;
  if (t == PlyType::kFloat32 && std::isfinite(*out)) *out = static_cast<double>(static_cast<float>(*out));
  return true;
}

std::string Item(const PlyElement& e, uint64_t i) { return e.name + " " + std::to_string(i); }

class PlyBodyReader {
 public:
  PlyBodyReader(std::string_view data, const PlyHeader& h, const std::string& name, const ReadOptions& opts,
                IoMesh* mesh, std::vector<std::array<double, 3>>* normals)
      : data_(data), h_(h), name_(name), opts_(opts), mesh_(mesh), normals_(normals) {}

  Status Read(const std::vector<ElementPlan>& plans, uint64_t vertex_count) {
    vertex_count_ = vertex_count;
    if (h_.format == PlyFormat::kAscii) {
      TextLines lines(data_, h_.body_offset, h_.body_line);
      for (const ElementPlan& plan : plans) SILK_RETURN_IF_ERROR(ReadAscii(plan, &lines));
    } else {
      const uint8_t* p = reinterpret_cast<const uint8_t*>(data_.data()) + h_.body_offset;
      const uint8_t* end = reinterpret_cast<const uint8_t*>(data_.data()) + data_.size();
      const bool swap = (h_.format == PlyFormat::kBinaryBigEndian) != kHostBigEndian;
      for (const ElementPlan& plan : plans) SILK_RETURN_IF_ERROR(ReadBinary(plan, swap, &p, end));
    }
    return Status::Ok();
  }

 private:
  Status Truncated(const PlyElement& e, uint64_t i) {
    return ParseErrorIn(
        name_, "truncated body: " + Item(e, i) + " of " + std::to_string(e.count) + " ends past the end of the file");
  }

  Status AddPosition(const PlyElement& e, uint64_t i, const std::array<double, 3>& p, const std::array<double, 3>& n) {
    for (double c : p)
      if (!std::isfinite(c)) return ParseErrorIn(name_, Item(e, i) + ": non-finite coordinate");
    if (normals_) {
      for (double c : n)
        if (!std::isfinite(c)) return ParseErrorIn(name_, Item(e, i) + ": non-finite normal");
      normals_->push_back(n);
    }
    if (mesh_->positions.size() >= VertexLimit(opts_))
      return LimitErrorIn(name_, "more than " + std::to_string(opts_.max_vertices) + " vertices");
    mesh_->positions.push_back(p);
    return Status::Ok();
  }

  Status AddFace(const PlyElement& e, uint64_t i) {
    if (corners_.size() < 3)
      return ParseErrorIn(name_, Item(e, i) + ": " + std::to_string(corners_.size()) + " corner(s), at least 3 needed");
    return AppendFanWithinLimit(corners_, name_, opts_, mesh_);
  }

  Status CheckIndex(const PlyElement& e, uint64_t i, int64_t v) {
    if (v < 0 || static_cast<uint64_t>(v) >= vertex_count_)
      return ParseErrorIn(name_, Item(e, i) + ": " + VertexIndexOutOfRange(v, vertex_count_));
    corners_.push_back(static_cast<int32_t>(v));
    return Status::Ok();
  }

  Status ReadBinary(const ElementPlan& plan, bool swap, const uint8_t** pp, const uint8_t* end) {
    const PlyElement& e = *plan.element;
    if (e.properties.empty()) return Status::Ok();
    const uint8_t* p = *pp;
    std::array<double, 3> pos{0, 0, 0}, nrm{0, 0, 0};
    for (uint64_t i = 0; i < e.count; ++i) {
      corners_.clear();
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& prop = e.properties[k];
        const Role role = plan.roles[k];
        const size_t vs = PlyTypeSize(prop.value_type);
        if (!prop.is_list) {
          if (static_cast<size_t>(end - p) < vs) return Truncated(e, i);
          if (role == Role::kX || role == Role::kY || role == Role::kZ)
            pos[static_cast<int>(role) - static_cast<int>(Role::kX)] = LoadDouble(p, prop.value_type, swap);
          if (role == Role::kNx || role == Role::kNy || role == Role::kNz)
            nrm[static_cast<int>(role) - static_cast<int>(Role::kNx)] = LoadDouble(p, prop.value_type, swap);
          p += vs;
          continue;
        }
        const size_t cs = PlyTypeSize(prop.count_type);
        if (static_cast<size_t>(end - p) < cs) return Truncated(e, i);
        const int64_t n = LoadInt(p, prop.count_type, swap);
        p += cs;
        if (n < 0) return ParseErrorIn(name_, Item(e, i) + ": negative list length " + std::to_string(n));
        if (static_cast<uint64_t>(n) > static_cast<uint64_t>(end - p) / vs) return Truncated(e, i);
        if (role == Role::kFaceList) {
          for (int64_t j = 0; j < n; ++j, p += vs)
            SILK_RETURN_IF_ERROR(CheckIndex(e, i, LoadInt(p, prop.value_type, swap)));
        } else {
          p += static_cast<size_t>(n) * vs;
        }
      }
      if (plan.is_vertex) SILK_RETURN_IF_ERROR(AddPosition(e, i, pos, nrm));
      if (plan.is_face) SILK_RETURN_IF_ERROR(AddFace(e, i));
    }
    *pp = p;
    return Status::Ok();
  }

  Status ReadAscii(const ElementPlan& plan, TextLines* lines) {
    const PlyElement& e = *plan.element;
    if (e.properties.empty()) return Status::Ok();
    std::array<double, 3> pos{0, 0, 0}, nrm{0, 0, 0};
    std::string_view line;
    for (uint64_t i = 0; i < e.count; ++i) {
      do {
        if (!lines->Next(&line)) return Truncated(e, i);
      } while (LineTokens(line).AtEnd());
      const int64_t ln = lines->line_number();
      LineTokens toks(line);
      std::string_view tok;
      corners_.clear();
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& prop = e.properties[k];
        const Role role = plan.roles[k];
        if (!toks.Next(&tok))
          return ParseErrorAt(name_, ln, Item(e, i) + ": missing value for property '" + prop.name + "'");
        if (!prop.is_list) {
          double v;
          if (!ParseAsciiValue(tok, prop.value_type, &v))
            return ParseErrorAt(
                name_, ln,
                Item(e, i) + ": bad value '" + std::string(tok.substr(0, 32)) + "' for property '" + prop.name + "'");
          if (role == Role::kX || role == Role::kY || role == Role::kZ)
            pos[static_cast<int>(role) - static_cast<int>(Role::kX)] = v;
          if (role == Role::kNx || role == Role::kNy || role == Role::kNz)
            nrm[static_cast<int>(role) - static_cast<int>(Role::kNx)] = v;
          continue;
        }
        int64_t n;
        if (!ParseInt64Token(tok, &n) || n < 0)
          return ParseErrorAt(name_, ln,
                              Item(e, i) + ": bad list length '" + std::string(tok.substr(0, 32)) + "' for property '" +
                                  prop.name + "'");
        for (int64_t j = 0; j < n; ++j) {
          if (!toks.Next(&tok))
            return ParseErrorAt(
                name_, ln, Item(e, i) + ": list '" + prop.name + "' has fewer than " + std::to_string(n) + " values");
          if (role == Role::kFaceList) {
            int64_t idx;
            if (!ParseInt64Token(tok, &idx))
              return ParseErrorAt(name_, ln,
                                  Item(e, i) + ": bad vertex index '" + std::string(tok.substr(0, 32)) + "'");
            Status s = CheckIndex(e, i, idx);
            if (!s.ok()) return ParseErrorAt(name_, ln, s.message().substr(name_.size() + 2));
          } else {
            double v;
            if (!ParseAsciiValue(tok, prop.value_type, &v))
              return ParseErrorAt(
                  name_, ln,
                  Item(e, i) + ": bad value '" + std::string(tok.substr(0, 32)) + "' in list '" + prop.name + "'");
          }
        }
      }
      if (!toks.AtEnd()) return ParseErrorAt(name_, ln, Item(e, i) + ": extra values at end of line");
      if (plan.is_vertex) {
        Status s = AddPosition(e, i, pos, nrm);
        if (!s.ok()) return ParseErrorAt(name_, ln, s.message().substr(name_.size() + 2));
      }
      if (plan.is_face) SILK_RETURN_IF_ERROR(AddFace(e, i));
    }
    return Status::Ok();
  }

  std::string_view data_;
  const PlyHeader& h_;
  const std::string& name_;
  const ReadOptions& opts_;
  IoMesh* mesh_;
  std::vector<std::array<double, 3>>* normals_;  // null: normals not read
  uint64_t vertex_count_ = 0;
  std::vector<int32_t> corners_;
};

}  // namespace

namespace {

// What the body reader does with the header's elements: one ElementPlan per element, and
// which elements hold the vertices and the faces.
struct ReadPlan {
  std::vector<ElementPlan> elements;
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  bool normals = false;  // normals were asked for and the vertex element has nx, ny and nz
};

// Plan of the vertex element: x, y and z are required scalars; nx, ny and nz are read when
// asked for and all three are scalars (otherwise the normals are left out).
Status PlanVertexElement(const PlyElement& e, const std::string& name, bool want_normals, ElementPlan* plan,
                         bool* normals) {
  plan->is_vertex = true;
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    bool found = false;
    for (size_t k = 0; k < e.properties.size(); ++k) {
      if (e.properties[k].name != axes[a]) continue;
      if (e.properties[k].is_list)
        return ParseErrorAt(name, e.line, std::string("vertex property '") + axes[a] + "' is a list");
      plan->roles[k] = static_cast<Role>(static_cast<int>(Role::kX) + a);
      found = true;
    }
    if (!found) return ParseErrorAt(name, e.line, std::string("vertex element has no property '") + axes[a] + "'");
  }
  if (!want_normals) return Status::Ok();
  const char* naxes[3] = {"nx", "ny", "nz"};
  int n_found = 0;
  for (int a = 0; a < 3; ++a)
    for (size_t k = 0; k < e.properties.size(); ++k)
      if (e.properties[k].name == naxes[a] && !e.properties[k].is_list) ++n_found;
  *normals = n_found == 3;
  if (!*normals) return Status::Ok();  // no (complete) normals: positions only
  for (int a = 0; a < 3; ++a)
    for (size_t k = 0; k < e.properties.size(); ++k)
      if (e.properties[k].name == naxes[a] && !e.properties[k].is_list)
        plan->roles[k] = static_cast<Role>(static_cast<int>(Role::kNx) + a);
  return Status::Ok();
}

// Plan of the face element: exactly one integer list named vertex_indices or vertex_index.
Status PlanFaceElement(const PlyElement& e, const std::string& name, ElementPlan* plan) {
  for (size_t k = 0; k < e.properties.size(); ++k) {
    const PlyProperty& p = e.properties[k];
    if (!p.is_list || (p.name != "vertex_indices" && p.name != "vertex_index")) continue;
    if (plan->is_face) return ParseErrorAt(name, e.line, "face element has both vertex_indices and vertex_index");
    if (!PlyTypeIsInteger(p.value_type))
      return ParseErrorAt(name, e.line, "face list '" + p.name + "' has a non-integer index type");
    plan->roles[k] = Role::kFaceList;
    plan->is_face = true;
  }
  if (!plan->is_face) return ParseErrorAt(name, e.line, "face element has no vertex_indices list");
  return Status::Ok();
}

// Plan phase: which element is the vertex / face element and what each property is used for.
StatusOr<ReadPlan> PlanElements(const PlyHeader& h, const std::string& name, bool want_normals) {
  ReadPlan r;
  for (const PlyElement& e : h.elements) {
    for (const ElementPlan& q : r.elements)
      if (q.element->name == e.name) return ParseErrorAt(name, e.line, "duplicate element '" + e.name + "'");
    ElementPlan plan;
    plan.element = &e;
    plan.roles.assign(e.properties.size(), Role::kSkip);
    if (e.name == "vertex") {
      SILK_RETURN_IF_ERROR(PlanVertexElement(e, name, want_normals, &plan, &r.normals));
      r.vertex = &e;
    } else if (e.name == "face") {
      SILK_RETURN_IF_ERROR(PlanFaceElement(e, name, &plan));
      r.face = &e;
    }
    r.elements.push_back(std::move(plan));
  }
  if (!r.vertex) return ParseErrorIn(name, "no 'vertex' element");
  return r;
}

// Fewest bytes one item of the element can take (a face list counted with 3 indices).
uint64_t MinItemBytes(const ElementPlan& plan, bool ascii) {
  const PlyElement& e = *plan.element;
  uint64_t min_item = 0;
  for (size_t k = 0; k < e.properties.size(); ++k) {
    const PlyProperty& p = e.properties[k];
    const uint64_t values = plan.roles[k] == Role::kFaceList ? 3 : 0;
    if (ascii)
      min_item += 2 * (1 + (p.is_list ? values : 0));
    else
      min_item +=
          p.is_list ? PlyTypeSize(p.count_type) + values * PlyTypeSize(p.value_type) : PlyTypeSize(p.value_type);
  }
  return min_item;
}

// Plausibility: every element's declared count must fit in the `remaining` bytes after the
// header. Only a plausible header is trusted for allocation; an implausible one is still read
// (growing with the data actually present) so the error names the first missing item.
bool CountsFitBody(const PlyHeader& h, const std::vector<ElementPlan>& plans, uint64_t remaining) {
  const bool ascii = h.format == PlyFormat::kAscii;
  const uint64_t slack = ascii ? 1 : 0;  // the last ascii line may lack its newline
  uint64_t needed = 0;
  for (const ElementPlan& plan : plans) {
    const PlyElement& e = *plan.element;
    if (e.count == 0 || e.properties.empty()) continue;
    const uint64_t min_item = MinItemBytes(plan, ascii);
    if (e.count > (remaining + slack) / min_item || needed + e.count * min_item > remaining + slack) return false;
    needed += e.count * min_item;
  }
  return true;
}

// Limits on the declared (and plausible) vertex and face counts, before anything is reserved.
Status CheckDeclaredCounts(const ReadPlan& plan, const std::string& name, const ReadOptions& opts) {
  const uint64_t max_vertices = VertexLimit(opts);
  if (plan.vertex->count > max_vertices)
    return LimitErrorIn(name, "header declares " + std::to_string(plan.vertex->count) + " vertices (limit " +
                                  std::to_string(max_vertices) + ")");
  if (plan.face && plan.face->count > opts.max_triangles)
    return LimitErrorIn(name, "header declares " + std::to_string(plan.face->count) + " faces (limit " +
                                  std::to_string(opts.max_triangles) + ")");
  return Status::Ok();
}

// Shared body of ReadPly and ReadPlyPointCloud: `normals` non-null reads nx/ny/nz when the
// vertex element has all three (left empty otherwise) and allows a file without faces.
StatusOr<IoMesh> ReadPlyImpl(std::string_view data, const std::string& name, const ReadOptions& opts,
                             std::vector<std::array<double, 3>>* normals) {
  const bool normals_requested = normals != nullptr;
  SILK_ASSIGN_OR_RETURN(PlyHeader h, ParsePlyHeader(data, name));
  SILK_ASSIGN_OR_RETURN(ReadPlan plan, PlanElements(h, name, normals_requested));
  const uint64_t remaining = data.size() - h.body_offset;
  const bool plausible = CountsFitBody(h, plan.elements, remaining);
  if (plausible) SILK_RETURN_IF_ERROR(CheckDeclaredCounts(plan, name, opts));

  IoMesh mesh;
  if (plausible) {
    mesh.positions.reserve(plan.vertex->count);
    if (plan.face) mesh.triangles.reserve(plan.face->count);
  }
  PlyBodyReader reader(data, h, name, opts, &mesh, plan.normals ? normals : nullptr);
  SILK_RETURN_IF_ERROR(reader.Read(plan.elements, plan.vertex->count));
  if (!plausible)  // cannot happen: the body reader runs out of data first
    return ParseErrorIn(name,
                        "header counts do not fit in the " + std::to_string(remaining) + " bytes after the header");
  if (mesh.triangles.empty() && !normals_requested)
    return ParseErrorIn(name, plan.face ? "no faces" : "no faces (no 'face' element)");
  return mesh;
}

}  // namespace

StatusOr<IoMesh> ReadPly(std::string_view data, const std::string& name, const ReadOptions& opts) {
  return ReadPlyImpl(data, name, opts, nullptr);
}

StatusOr<PlyPointCloud> ReadPlyPointCloud(std::string_view data, const std::string& name, const ReadOptions& opts) {
  PlyPointCloud pc;
  SILK_ASSIGN_OR_RETURN(pc.mesh, ReadPlyImpl(data, name, opts, &pc.normals));
  if (pc.mesh.positions.empty()) return ParseErrorIn(name, "no vertices");
  return pc;
}

}  // namespace silk
