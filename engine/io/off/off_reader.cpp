// SPDX-License-Identifier: MIT
// OFF parsing: header keyword, counts line (may share the keyword's line), vertex lines,
// face lines "n i0 i1 ... [color]".
#include "io/off/off_reader.h"

#include <cmath>
#include <vector>

#include "io/files/number_parse.h"
#include "io/polygon_fan.h"
#include "io/read_error.h"
#include "io/files/text_lines.h"

namespace silk {

namespace {

// Next line that has something besides spaces and a comment; the comment is stripped.
bool NextDataLine(TextLines* lines, std::string_view* line) {
  while (lines->Next(line)) {
    size_t hash = line->find('#');
    if (hash != std::string_view::npos) *line = line->substr(0, hash);
    if (!LineTokens(*line).AtEnd()) return true;
  }
  return false;
}

bool IsOffKeyword(std::string_view kw) {
  return kw == "OFF" || kw == "COFF" || kw == "NOFF" || kw == "CNOFF" || kw == "STOFF" || kw == "STCOFF" ||
         kw == "STNOFF" || kw == "STCNOFF";
}

// The header's counts and the line they are on.
struct OffCounts {
  uint64_t vertices = 0;
  uint64_t faces = 0;
  int64_t line = 0;
};

// Header phase: the OFF keyword, then "<vertices> <faces> [<edges>]" on the same line or the
// next data line.
StatusOr<OffCounts> ReadOffHeader(TextLines* lines, const std::string& name) {
  std::string_view line;
  if (!NextDataLine(lines, &line)) return ParseErrorIn(name, "empty file");
  LineTokens head(line);
  std::string_view kw;
  head.Next(&kw);
  if (!IsOffKeyword(kw)) return ParseErrorAt(name, lines->line_number(), "not an OFF file (no 'OFF' header)");
  if (head.AtEnd()) {
    if (!NextDataLine(lines, &line)) return ParseErrorIn(name, "missing vertex/face counts");
    head = LineTokens(line);
  }
  OffCounts c;
  c.line = lines->line_number();
  int64_t counts[3] = {0, 0, 0};
  int ncounts = 0;
  std::string_view tok;
  while (head.Next(&tok)) {
    if (ncounts == 3 || !ParseInt64Token(tok, &counts[ncounts]) || counts[ncounts] < 0)
      return ParseErrorAt(name, c.line, "bad counts line (expected '<vertices> <faces> [<edges>]')");
    ++ncounts;
  }
  if (ncounts < 2) return ParseErrorAt(name, c.line, "bad counts line (expected '<vertices> <faces> [<edges>]')");
  c.vertices = static_cast<uint64_t>(counts[0]);
  c.faces = static_cast<uint64_t>(counts[1]);
  return c;
}

// Data lines after the header, counted up to `enough` (the lines are not consumed).
uint64_t CountDataLines(TextLines lines, uint64_t enough) {
  uint64_t data_lines = 0;
  std::string_view l;
  while (data_lines < enough && NextDataLine(&lines, &l)) ++data_lines;
  return data_lines;
}

// Vertex block: one "x y z [extra values]" line per vertex.
Status ReadOffVertices(TextLines* lines, uint64_t nv, const Status& too_few, const std::string& name, IoMesh* mesh) {
  std::string_view line, tok;
  for (uint64_t i = 0; i < nv; ++i) {
    if (!NextDataLine(lines, &line)) return too_few;
    const int64_t ln = lines->line_number();
    LineTokens toks(line);
    std::array<double, 3> p;
    for (int k = 0; k < 3; ++k) {
      if (!toks.Next(&tok))
        return ParseErrorAt(name, ln, "vertex " + std::to_string(i) + " has fewer than 3 coordinates");
      if (!ParseDoubleToken(tok, &p[k]))
        return ParseErrorAt(
            name, ln, "vertex " + std::to_string(i) + ": bad coordinate '" + std::string(tok.substr(0, 32)) + "'");
      if (!std::isfinite(p[k]))
        return ParseErrorAt(name, ln, "vertex " + std::to_string(i) + ": non-finite coordinate");
    }
    mesh->positions.push_back(p);
  }
  return Status::Ok();
}

// One face line "n i0 i1 ... [color]" (face number f, on line ln) into `corners`.
Status ParseOffFace(std::string_view line, uint64_t f, int64_t ln, uint64_t nv, const std::string& name,
                    std::vector<int32_t>* corners) {
  LineTokens toks(line);
  std::string_view tok;
  int64_t n = 0;
  toks.Next(&tok);
  if (!ParseInt64Token(tok, &n) || n < 0)
    return ParseErrorAt(name, ln,
                        "face " + std::to_string(f) + ": bad corner count '" + std::string(tok.substr(0, 32)) + "'");
  if (n < 3)
    return ParseErrorAt(name, ln,
                        "face " + std::to_string(f) + " has " + std::to_string(n) + " corner(s), at least 3 needed");
  corners->clear();
  for (int64_t k = 0; k < n; ++k) {
    int64_t idx;
    if (!toks.Next(&tok))
      return ParseErrorAt(name, ln,
                          "face " + std::to_string(f) + " declares " + std::to_string(n) + " corners but has " +
                              std::to_string(k) + " indices");
    if (!ParseInt64Token(tok, &idx))
      return ParseErrorAt(name, ln,
                          "face " + std::to_string(f) + ": bad vertex index '" + std::string(tok.substr(0, 32)) + "'");
    if (idx < 0 || static_cast<uint64_t>(idx) >= nv)
      return ParseErrorAt(name, ln, "face " + std::to_string(f) + ": " + VertexIndexOutOfRange(idx, nv));
    corners->push_back(static_cast<int32_t>(idx));
  }
  // Anything after the indices is an optional color; it must be numeric.
  while (toks.Next(&tok)) {
    double ignored;
    if (!ParseDoubleToken(tok, &ignored))
      return ParseErrorAt(
          name, ln,
          "face " + std::to_string(f) + ": unexpected '" + std::string(tok.substr(0, 32)) + "' after the indices");
  }
  return Status::Ok();
}

// Face block: one face line per face, fan-triangulated into the mesh.
Status ReadOffFaces(TextLines* lines, const OffCounts& c, const Status& too_few, const std::string& name,
                    const ReadOptions& opts, IoMesh* mesh) {
  std::string_view line;
  std::vector<int32_t> corners;
  for (uint64_t f = 0; f < c.faces; ++f) {
    if (!NextDataLine(lines, &line)) return too_few;
    SILK_RETURN_IF_ERROR(ParseOffFace(line, f, lines->line_number(), c.vertices, name, &corners));
    SILK_RETURN_IF_ERROR(AppendFanWithinLimit(corners, name, opts, mesh));
  }
  return Status::Ok();
}

}  // namespace

StatusOr<IoMesh> ReadOff(std::string_view text, const std::string& name, const ReadOptions& opts) {
  if (size_t bad = FindBinaryByte(text); bad != std::string_view::npos)
    return ParseErrorIn(name, "binary byte at offset " + std::to_string(bad) + " (binary OFF is not supported)");
  TextLines lines(text);
  SILK_ASSIGN_OR_RETURN(const OffCounts c, ReadOffHeader(&lines, name));
  const uint64_t nv = c.vertices, nf = c.faces;

  // Plausibility before allocating: each record needs its own non-empty line. An
  // implausible header is still read record by record (no reservation), so that a broken
  // record is reported as such; running out of lines reports the header counts.
  const uint64_t data_lines = CountDataLines(lines, nv + nf);
  const bool plausible = data_lines >= nv + nf;
  const Status too_few = ParseErrorAt(name, c.line,
                                      "header says " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                          " faces but only " + std::to_string(data_lines) + " data lines follow");
  const uint64_t max_vertices = VertexLimit(opts);
  if (plausible && nv > max_vertices)
    return LimitErrorIn(name, std::to_string(nv) + " vertices exceed the limit " + std::to_string(max_vertices));
  if (plausible && nf > opts.max_triangles)
    return LimitErrorIn(name, std::to_string(nf) + " faces exceed the limit " + std::to_string(opts.max_triangles));

  IoMesh mesh;
  if (plausible) {
    mesh.positions.reserve(nv);
    mesh.triangles.reserve(nf);
  }
  SILK_RETURN_IF_ERROR(ReadOffVertices(&lines, nv, too_few, name, &mesh));
  SILK_RETURN_IF_ERROR(ReadOffFaces(&lines, c, too_few, name, opts, &mesh));
  if (mesh.triangles.empty()) return ParseErrorIn(name, "no faces");
  return mesh;
}

}  // namespace silk
