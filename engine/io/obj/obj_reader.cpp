// SPDX-License-Identifier: MIT
// OBJ parsing: one pass over lines, strict numbers, index validation with line numbers.
#include "io/obj/obj_reader.h"

#include <cctype>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <vector>

#include "io/files/number_parse.h"
#include "io/polygon_fan.h"
#include "io/read_error.h"
#include "io/files/text_lines.h"

namespace silk {

namespace {

constexpr size_t kMaxWarnings = 20;

bool IsIdentifier(std::string_view s) {
  if (s.empty()) return false;
  unsigned char c0 = static_cast<unsigned char>(s[0]);
  if (!std::isalpha(c0) && c0 != '_') return false;
  for (char ch : s) {
    unsigned char c = static_cast<unsigned char>(ch);
    if (!std::isalnum(c) && c != '_') return false;
  }
  return true;
}

// Checks the "/vt/vn" tail of a face corner: each part empty or an integer.
bool ValidCornerTail(std::string_view tail) {
  int parts = 0;
  while (!tail.empty()) {
    if (tail[0] != '/' || ++parts > 2) return false;
    tail.remove_prefix(1);
    size_t slash = tail.find('/');
    std::string_view part = tail.substr(0, slash);
    int64_t ignored;
    if (!part.empty() && !ParseInt64Token(part, &ignored)) return false;
    tail = slash == std::string_view::npos ? std::string_view() : tail.substr(slash);
  }
  return true;
}

// Line prologue: drops the '#' comment and refuses a binary byte (a binary file is not OBJ).
Status StripCommentAndCheckText(std::string_view* line, int64_t ln, const std::string& name) {
  size_t hash = line->find('#');
  if (hash != std::string_view::npos) *line = line->substr(0, hash);
  size_t bad = FindBinaryByte(*line);
  if (bad == std::string_view::npos) return Status::Ok();
  char hex[8];
  std::snprintf(hex, sizeof(hex), "0x%02x", static_cast<unsigned char>((*line)[bad]));
  return ParseErrorAt(name, ln, std::string("binary byte ") + hex + " (not a text OBJ file)");
}

// "v x y z [w | r g b]": appends the position; the optional values must still be numbers.
Status ReadObjVertex(LineTokens* toks, int64_t ln, const std::string& name, uint64_t max_vertices, IoMesh* mesh) {
  std::array<double, 3> p;
  std::string_view t;
  for (int k = 0; k < 3; ++k) {
    if (!toks->Next(&t)) return ParseErrorAt(name, ln, "vertex has fewer than 3 coordinates");
    if (!ParseDoubleToken(t, &p[k])) return ParseErrorAt(name, ln, "bad vertex coordinate '" + std::string(t) + "'");
    if (!std::isfinite(p[k]))
      return ParseErrorAt(name, ln,
                          "vertex " + std::to_string(mesh->positions.size() + 1) + " has a non-finite coordinate '" +
                              std::string(t) + "'");
  }
  while (toks->Next(&t)) {
    double ignored;
    if (!ParseDoubleToken(t, &ignored)) return ParseErrorAt(name, ln, "bad vertex value '" + std::string(t) + "'");
  }
  if (mesh->positions.size() >= max_vertices)
    return LimitErrorIn(name, "more than " + std::to_string(max_vertices) + " vertices");
  mesh->positions.push_back(p);
  return Status::Ok();
}

// One face corner "v[/vt][/vn]" as a 0-based vertex index; negative indices count back from
// the last vertex read so far (`nverts`).
StatusOr<int32_t> ObjCornerIndex(std::string_view t, int64_t nverts, int64_t ln, const std::string& name) {
  size_t slash = t.find('/');
  std::string_view head = t.substr(0, slash);
  int64_t idx;
  if (!ParseInt64Token(head, &idx) || (slash != std::string_view::npos && !ValidCornerTail(t.substr(slash))))
    return ParseErrorAt(name, ln, "bad face corner '" + std::string(t) + "'");
  if (idx == 0) return ParseErrorAt(name, ln, "face index 0 is invalid (OBJ indices start at 1)");
  const int64_t zero_based = idx < 0 ? nverts + idx : idx - 1;
  if (zero_based < 0 || zero_based >= nverts)
    return ParseErrorAt(
        name, ln, "face index " + std::to_string(idx) + " out of range (" + std::to_string(nverts) + " vertices)");
  return static_cast<int32_t>(zero_based);
}

// "f c0 c1 c2 ...": at least 3 corners, fan-triangulated into the mesh.
Status ReadObjFace(LineTokens* toks, int64_t ln, const std::string& name, const ReadOptions& opts,
                   std::vector<int32_t>* corners, IoMesh* mesh) {
  corners->clear();
  std::string_view t;
  const int64_t nverts = static_cast<int64_t>(mesh->positions.size());
  while (toks->Next(&t)) {
    SILK_ASSIGN_OR_RETURN(const int32_t corner, ObjCornerIndex(t, nverts, ln, name));
    corners->push_back(corner);
  }
  if (corners->size() < 3)
    return ParseErrorAt(name, ln, "face has " + std::to_string(corners->size()) + " corner(s), at least 3 needed");
  return AppendFanWithinLimit(*corners, name, opts, mesh);
}

// Other statements: vt, vn, vp, o, g, s, usemtl, mtllib are geometry we do not use; l, p and
// free-form statements are ignored with a warning (the first kMaxWarnings of them).
Status NoteOtherStatement(std::string_view kw, int64_t ln, const std::string& name, int64_t* ignored_statements,
                          IoMesh* mesh) {
  if (!IsIdentifier(kw)) return ParseErrorAt(name, ln, "not an OBJ statement: '" + std::string(kw.substr(0, 32)) + "'");
  if (kw == "vt" || kw == "vn" || kw == "vp" || kw == "o" || kw == "g" || kw == "s" || kw == "usemtl" || kw == "mtllib")
    return Status::Ok();
  if (++*ignored_statements <= static_cast<int64_t>(kMaxWarnings))
    mesh->warnings.push_back(name + ":" + std::to_string(ln) + ": ignored statement '" + std::string(kw) + "'");
  return Status::Ok();
}

}  // namespace

StatusOr<IoMesh> ReadObj(std::string_view text, const std::string& name, const ReadOptions& opts) {
  IoMesh mesh;
  if (text.empty()) return ParseErrorIn(name, "empty file (no vertices, no faces)");
  TextLines lines(text);
  std::string_view line;
  std::vector<int32_t> corners;
  int64_t ignored_statements = 0;
  const uint64_t max_vertices = VertexLimit(opts);

  while (lines.Next(&line)) {
    const int64_t ln = lines.line_number();
    SILK_RETURN_IF_ERROR(StripCommentAndCheckText(&line, ln, name));
    LineTokens toks(line);
    std::string_view kw;
    if (!toks.Next(&kw)) continue;
    if (kw == "v") {
      SILK_RETURN_IF_ERROR(ReadObjVertex(&toks, ln, name, max_vertices, &mesh));
    } else if (kw == "f") {
      SILK_RETURN_IF_ERROR(ReadObjFace(&toks, ln, name, opts, &corners, &mesh));
    } else {
      SILK_RETURN_IF_ERROR(NoteOtherStatement(kw, ln, name, &ignored_statements, &mesh));
    }
  }
  if (mesh.triangles.empty()) return ParseErrorIn(name, "no faces");
  return mesh;
}

}  // namespace silk
