// SPDX-License-Identifier: MIT
// PLY header parsing: "ply", "format", "element", "property [list]", "comment", "obj_info",
// "end_header". Type names include the int8/uint8/.../float64 aliases.
#include "io/ply/ply_header.h"

#include <optional>

#include "io/files/number_parse.h"
#include "io/read_error.h"
#include "io/files/text_lines.h"

namespace silk {

size_t PlyTypeSize(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUInt8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUInt16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUInt32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

bool PlyTypeIsInteger(PlyType t) { return t != PlyType::kFloat32 && t != PlyType::kFloat64; }

namespace {

std::optional<PlyType> TypeFromName(std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::kInt8;
  if (s == "uchar" || s == "uint8") return PlyType::kUInt8;
  if (s == "short" || s == "int16") return PlyType::kInt16;
  if (s == "ushort" || s == "uint16") return PlyType::kUInt16;
  if (s == "int" || s == "int32") return PlyType::kInt32;
  if (s == "uint" || s == "uint32") return PlyType::kUInt32;
  if (s == "float" || s == "float32") return PlyType::kFloat32;
  if (s == "double" || s == "float64") return PlyType::kFloat64;
  return std::nullopt;
}

// "format <ascii|binary_little_endian|binary_big_endian> 1.0".
Status ParseFormatLine(LineTokens* toks, const std::string& name, int64_t ln, PlyHeader* h) {
  std::string_view f, ver;
  if (!toks->Next(&f) || !toks->Next(&ver) || !toks->AtEnd()) return ParseErrorAt(name, ln, "bad format line");
  if (f == "ascii")
    h->format = PlyFormat::kAscii;
  else if (f == "binary_little_endian")
    h->format = PlyFormat::kBinaryLittleEndian;
  else if (f == "binary_big_endian")
    h->format = PlyFormat::kBinaryBigEndian;
  else
    return ParseErrorAt(name, ln, "unknown PLY format '" + std::string(f) + "'");
  if (ver != "1.0") return ParseErrorAt(name, ln, "unsupported PLY version '" + std::string(ver) + "'");
  return Status::Ok();
}

// "element <name> <count>": opens a new element for the property lines that follow.
Status ParseElementLine(LineTokens* toks, const std::string& name, int64_t ln, PlyHeader* h) {
  std::string_view en, cnt;
  int64_t count = 0;
  if (!toks->Next(&en) || !toks->Next(&cnt) || !toks->AtEnd() || !ParseInt64Token(cnt, &count) || count < 0)
    return ParseErrorAt(name, ln, "bad element line (expected 'element <name> <count>')");
  PlyElement e;
  e.name = std::string(en);
  e.count = static_cast<uint64_t>(count);
  e.line = ln;
  h->elements.push_back(std::move(e));
  return Status::Ok();
}

// The rest of "property list <count type> <value type> <name>" after "list".
Status ParseListProperty(LineTokens* toks, const std::string& name, int64_t ln, PlyProperty* p) {
  std::string_view ct, vt, pn;
  if (!toks->Next(&ct) || !toks->Next(&vt) || !toks->Next(&pn) || !toks->AtEnd())
    return ParseErrorAt(name, ln, "bad list property line");
  auto c = TypeFromName(ct);
  auto v = TypeFromName(vt);
  if (!c || !v) return ParseErrorAt(name, ln, "unknown property type in list");
  if (!PlyTypeIsInteger(*c)) return ParseErrorAt(name, ln, "list count type must be an integer type");
  p->is_list = true;
  p->count_type = *c;
  p->value_type = *v;
  p->name = std::string(pn);
  return Status::Ok();
}

// "property <type> <name>" or "property list ...": adds a property to the last element.
Status ParsePropertyLine(LineTokens* toks, const std::string& name, int64_t ln, PlyHeader* h) {
  if (h->elements.empty()) return ParseErrorAt(name, ln, "property before any element");
  PlyProperty p;
  std::string_view t1;
  if (!toks->Next(&t1)) return ParseErrorAt(name, ln, "bad property line");
  if (t1 == "list") {
    SILK_RETURN_IF_ERROR(ParseListProperty(toks, name, ln, &p));
  } else {
    std::string_view pn;
    auto v = TypeFromName(t1);
    if (!v) return ParseErrorAt(name, ln, "unknown property type '" + std::string(t1) + "'");
    if (!toks->Next(&pn) || !toks->AtEnd()) return ParseErrorAt(name, ln, "bad property line");
    p.value_type = *v;
    p.name = std::string(pn);
  }
  for (const PlyProperty& q : h->elements.back().properties)
    if (q.name == p.name) return ParseErrorAt(name, ln, "duplicate property '" + p.name + "'");
  h->elements.back().properties.push_back(std::move(p));
  return Status::Ok();
}

}  // namespace

StatusOr<PlyHeader> ParsePlyHeader(std::string_view data, const std::string& name) {
  PlyHeader h;
  TextLines lines(data);
  std::string_view line;
  if (!lines.Next(&line) || line != "ply") return ParseErrorIn(name, "not a PLY file (first line is not 'ply')");
  bool have_format = false;
  constexpr size_t kMaxHeaderBytes = 1 << 20;
  while (true) {
    if (lines.position() > kMaxHeaderBytes) return ParseErrorIn(name, "PLY header longer than 1 MiB (no end_header?)");
    if (!lines.Next(&line)) return ParseErrorIn(name, "PLY header has no end_header line");
    const int64_t ln = lines.line_number();
    if (FindBinaryByte(line) != std::string_view::npos)
      return ParseErrorAt(name, ln, "binary byte in PLY header (no end_header line?)");
    LineTokens toks(line);
    std::string_view kw;
    if (!toks.Next(&kw)) continue;
    if (kw == "comment" || kw == "obj_info") continue;
    if (kw == "end_header") {
      if (!toks.AtEnd()) return ParseErrorAt(name, ln, "text after end_header");
      if (!have_format) return ParseErrorIn(name, "PLY header has no format line");
      h.body_offset = lines.position();
      h.body_line = ln + 1;
      return h;
    }
    if (kw == "format") {
      SILK_RETURN_IF_ERROR(ParseFormatLine(&toks, name, ln, &h));
      have_format = true;
    } else if (kw == "element") {
      SILK_RETURN_IF_ERROR(ParseElementLine(&toks, name, ln, &h));
    } else if (kw == "property") {
      SILK_RETURN_IF_ERROR(ParsePropertyLine(&toks, name, ln, &h));
    } else {
      return ParseErrorAt(name, ln, "unknown PLY header keyword '" + std::string(kw.substr(0, 32)) + "'");
    }
  }
}

}  // namespace silk
