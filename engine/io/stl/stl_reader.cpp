// SPDX-License-Identifier: MIT
// STL parsing: binary by exact size, otherwise strict ascii "solid/facet/outer loop/vertex".
#include "io/stl/stl_reader.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <vector>

#include "io/files/number_parse.h"
#include "io/polygon_fan.h"
#include "io/read_error.h"
#include "io/files/text_lines.h"

namespace silk {

namespace {

float LoadFloatLE(const uint8_t* p) {
  uint32_t u = uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

StatusOr<IoMesh> ReadBinaryStl(std::string_view data, const std::string& name, const ReadOptions& opts) {
  const uint8_t* b = reinterpret_cast<const uint8_t*>(data.data());
  const uint64_t n = uint64_t{b[80]} | uint64_t{b[81]} << 8 | uint64_t{b[82]} << 16 | uint64_t{b[83]} << 24;
  if (84 + 50 * n != data.size())
    return ParseErrorIn(name, "binary STL header says " + std::to_string(n) + " triangles (" +
                                  std::to_string(84 + 50 * n) + " bytes) but the file has " +
                                  std::to_string(data.size()) + " bytes");
  if (n == 0) return ParseErrorIn(name, "no faces (binary STL with 0 triangles)");
  if (3 * n > VertexLimit(opts) || n > opts.max_triangles)
    return LimitErrorIn(name, std::to_string(n) + " triangles exceed the vertex/triangle limit");
  IoMesh mesh;
  mesh.positions.resize(3 * n);
  mesh.triangles.resize(n);
  for (uint64_t t = 0; t < n; ++t) {
    const uint8_t* rec = b + 84 + 50 * t + 12;  // skip the normal
    for (int c = 0; c < 3; ++c) {
      std::array<double, 3>& p = mesh.positions[3 * t + c];
      for (int k = 0; k < 3; ++k) {
        p[k] = LoadFloatLE(rec + 12 * c + 4 * k);
        if (!std::isfinite(p[k]))
          return ParseErrorIn(name, "triangle " + std::to_string(t) + ": non-finite vertex coordinate");
      }
    }
    const int32_t base = static_cast<int32_t>(3 * t);
    mesh.triangles[t] = {base, base + 1, base + 2};
  }
  return mesh;
}

// Token stream over the ascii file with line numbers.
class StlTokens {
 public:
  explicit StlTokens(std::string_view text) : lines_(text), toks_(std::string_view()) {}
  bool Next(std::string_view* tok) {
    while (!toks_.Next(tok)) {
      std::string_view line;
      if (!lines_.Next(&line)) return false;
      toks_ = LineTokens(line);
    }
    return true;
  }
  void SkipRestOfLine() { toks_ = LineTokens(std::string_view()); }
  int64_t line() const { return lines_.line_number(); }

 private:
  TextLines lines_;
  LineTokens toks_;
};

StatusOr<IoMesh> ReadAsciiStl(std::string_view text, const std::string& name, const ReadOptions& opts) {
  if (size_t bad = FindBinaryByte(text); bad != std::string_view::npos)
    return ParseErrorIn(name, "binary byte at offset " + std::to_string(bad) +
                                  " in an ascii STL (and the size does not fit a binary STL)");
  IoMesh mesh;
  StlTokens in(text);
  std::string_view tok;
  auto expect = [&](const char* word) -> Status {
    if (!in.Next(&tok))
      return ParseErrorAt(name, in.line(), std::string("unexpected end of file, expected '") + word + "'");
    if (tok != word)
      return ParseErrorAt(name, in.line(),
                          std::string("expected '") + word + "', found '" + std::string(tok.substr(0, 32)) + "'");
    return Status::Ok();
  };
  auto number = [&](double* v) -> Status {
    if (!in.Next(&tok)) return ParseErrorAt(name, in.line(), "unexpected end of file, expected a number");
    if (!ParseDoubleToken(tok, v))
      return ParseErrorAt(name, in.line(), "bad number '" + std::string(tok.substr(0, 32)) + "'");
    return Status::Ok();
  };
  const uint64_t max_vertices = VertexLimit(opts);
  std::vector<int32_t> corners;
  bool any_solid = false;
  while (in.Next(&tok)) {
    if (tok != "solid")
      return ParseErrorAt(name, in.line(), "expected 'solid', found '" + std::string(tok.substr(0, 32)) + "'");
    any_solid = true;
    in.SkipRestOfLine();  // solid name
    while (true) {
      if (!in.Next(&tok)) return ParseErrorAt(name, in.line(), "unexpected end of file, expected 'endsolid'");
      if (tok == "endsolid") {
        in.SkipRestOfLine();
        break;
      }
      if (tok != "facet")
        return ParseErrorAt(name, in.line(),
                            "expected 'facet' or 'endsolid', found '" + std::string(tok.substr(0, 32)) + "'");
      SILK_RETURN_IF_ERROR(expect("normal"));
      double ignored;
      for (int k = 0; k < 3; ++k) SILK_RETURN_IF_ERROR(number(&ignored));
      SILK_RETURN_IF_ERROR(expect("outer"));
      SILK_RETURN_IF_ERROR(expect("loop"));
      corners.clear();
      while (true) {
        if (!in.Next(&tok)) return ParseErrorAt(name, in.line(), "unexpected end of file in a facet");
        if (tok == "endloop") break;
        if (tok != "vertex")
          return ParseErrorAt(name, in.line(),
                              "expected 'vertex' or 'endloop', found '" + std::string(tok.substr(0, 32)) + "'");
        std::array<double, 3> p;
        for (int k = 0; k < 3; ++k) {
          SILK_RETURN_IF_ERROR(number(&p[k]));
          if (!std::isfinite(p[k])) return ParseErrorAt(name, in.line(), "non-finite vertex coordinate");
        }
        if (mesh.positions.size() >= max_vertices)
          return LimitErrorIn(name, "more than " + std::to_string(max_vertices) + " vertices");
        corners.push_back(static_cast<int32_t>(mesh.positions.size()));
        mesh.positions.push_back(p);
      }
      if (corners.size() < 3)
        return ParseErrorAt(name, in.line(),
                            "facet has " + std::to_string(corners.size()) + " vertices, at least 3 needed");
      SILK_RETURN_IF_ERROR(AppendFanWithinLimit(corners, name, opts, &mesh));
      SILK_RETURN_IF_ERROR(expect("endfacet"));
    }
  }
  if (!any_solid) return ParseErrorIn(name, "empty STL file");
  if (mesh.triangles.empty()) return ParseErrorIn(name, "no faces");
  return mesh;
}

}  // namespace

StatusOr<IoMesh> ReadStl(std::string_view data, const std::string& name, const ReadOptions& opts) {
  if (data.size() >= 84) {
    const uint8_t* b = reinterpret_cast<const uint8_t*>(data.data());
    const uint64_t n = uint64_t{b[80]} | uint64_t{b[81]} << 8 | uint64_t{b[82]} << 16 | uint64_t{b[83]} << 24;
    if (84 + 50 * n == data.size()) return ReadBinaryStl(data, name, opts);
  }
  size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (data.substr(i, 5) == "solid") return ReadAsciiStl(data, name, opts);
  if (data.size() >= 84) return ReadBinaryStl(data, name, opts);  // reports the size mismatch
  return ParseErrorIn(name, "not an STL file (no 'solid' and shorter than a binary STL header)");
}

}  // namespace silk
