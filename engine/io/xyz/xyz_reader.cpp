// SPDX-License-Identifier: MIT
// XYZ/PTS parsing: comment stripping, value splitting (spaces, tabs, commas), the optional PTS
// count line, and the per-line checks (same column count throughout, unit normals).
#include "io/xyz/xyz_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/files/number_parse.h"
#include "io/files/text_lines.h"
#include "io/read_error.h"

namespace silk {

namespace {

constexpr double kUnitTolerance = 0.1;  // |normal| within 1 +- this (a float-rounded unit vector passes)
const char* const kLineForms = "a point line is 'x y z' or 'x y z nx ny nz'";

bool IsSeparator(char c) { return IsSpaceByte(c) || c == ','; }

// The values of one line (comment stripped): all counted, the first 6 kept.
struct XyzValues {
  std::string_view token[6];
  int count = 0;
};

XyzValues SplitValues(std::string_view line) {
  XyzValues v;
  size_t i = 0;
  while (true) {
    while (i < line.size() && IsSeparator(line[i])) ++i;
    if (i >= line.size()) return v;
    const size_t b = i;
    while (i < line.size() && !IsSeparator(line[i])) ++i;
    if (v.count < 6) v.token[v.count] = line.substr(b, i - b);
    ++v.count;
  }
}

// Next line with at least one value ('#' comments stripped), split.
bool NextDataLine(TextLines* lines, XyzValues* values) {
  std::string_view line;
  while (lines->Next(&line)) {
    if (size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    *values = SplitValues(line);
    if (values->count > 0) return true;
  }
  return false;
}

std::string Values(int n) { return std::to_string(n) + (n == 1 ? " value" : " values"); }

std::string Shown(std::string_view tok) { return "'" + std::string(tok.substr(0, 32)) + "'"; }

std::string LengthText(double len) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", len);
  return buf;
}

// One point line of `columns` values (3 or 6) into the cloud; errors name the line.
Status AppendPoint(const XyzValues& v, int columns, int64_t ln, const std::string& name, IoPointCloud* pc) {
  double x[6];
  for (int k = 0; k < columns; ++k) {
    if (!ParseDoubleToken(v.token[k], &x[k])) return ParseErrorAt(name, ln, "bad number " + Shown(v.token[k]));
    if (!std::isfinite(x[k])) return ParseErrorAt(name, ln, "non-finite value " + Shown(v.token[k]));
  }
  pc->mesh.positions.push_back({x[0], x[1], x[2]});
  if (columns == 6) {
    const double len = std::sqrt(x[3] * x[3] + x[4] * x[4] + x[5] * x[5]);
    if (!(std::fabs(len - 1) <= kUnitTolerance))
      return ParseErrorAt(name, ln,
                          "values 4-6 are not a unit normal (length " + LengthText(len) + "); " + kLineForms +
                              " (colours are not read)");
    pc->normals.push_back({x[3], x[4], x[5]});
  }
  return Status::Ok();
}

// The column count every point line must have, from the first point line.
Status CheckColumns(const XyzValues& v, int64_t ln, int64_t first_line, int columns, const std::string& name) {
  if (columns == 0) {
    if (v.count == 3 || v.count == 6) return Status::Ok();
    return ParseErrorAt(name, ln, Values(v.count) + "; " + kLineForms + " (drop colour or intensity columns first)");
  }
  if (v.count == columns) return Status::Ok();
  return ParseErrorAt(name, ln,
                      Values(v.count) + ", but line " + std::to_string(first_line) + " has " + std::to_string(columns) +
                          " (every point line has the same columns)");
}

// A PTS count line: a single whole number as the first data line (-1 when there is none).
StatusOr<int64_t> CountLine(const XyzValues& v, int64_t ln, const std::string& name) {
  if (v.count != 1) return int64_t{-1};
  int64_t count = 0;
  if (!ParseInt64Token(v.token[0], &count) || count < 0)
    return ParseErrorAt(name, ln,
                        "1 value " + Shown(v.token[0]) + "; " + kLineForms +
                            " (a single value is only allowed as the first line's point count)");
  return count;
}

// The point lines after the optional count line.
Status ReadPointLines(TextLines* lines, XyzValues v, bool have_line, const std::string& name, const ReadOptions& opts,
                      IoPointCloud* pc) {
  const uint64_t limit = VertexLimit(opts);
  int columns = 0;
  int64_t first_line = 0;
  for (; have_line; have_line = NextDataLine(lines, &v)) {
    const int64_t ln = lines->line_number();
    SILK_RETURN_IF_ERROR(CheckColumns(v, ln, first_line, columns, name));
    if (columns == 0) columns = v.count, first_line = ln;
    if (pc->mesh.positions.size() >= limit)
      return LimitErrorIn(name, "more than " + std::to_string(limit) + " points (the limit)");
    SILK_RETURN_IF_ERROR(AppendPoint(v, columns, ln, name, pc));
  }
  return Status::Ok();
}

}  // namespace

StatusOr<IoPointCloud> ReadXyz(std::string_view text, const std::string& name, const ReadOptions& opts) {
  if (size_t bad = FindBinaryByte(text); bad != std::string_view::npos)
    return ParseErrorIn(name, "binary byte at offset " + std::to_string(bad) + " (not a text point cloud)");
  IoPointCloud pc;
  // Every point needs its own line, so the line count bounds the reservation.
  const uint64_t lines_in_text = static_cast<uint64_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  pc.mesh.positions.reserve(std::min(lines_in_text, VertexLimit(opts)));
  TextLines lines(text);
  XyzValues v;
  bool have_line = NextDataLine(&lines, &v);
  if (!have_line) return ParseErrorIn(name, "no points");
  const int64_t count_line_no = lines.line_number();
  SILK_ASSIGN_OR_RETURN(const int64_t declared, CountLine(v, count_line_no, name));
  if (declared >= 0) have_line = NextDataLine(&lines, &v);
  SILK_RETURN_IF_ERROR(ReadPointLines(&lines, v, have_line, name, opts, &pc));
  const uint64_t n = pc.mesh.positions.size();
  if (declared >= 0 && static_cast<uint64_t>(declared) != n)
    return ParseErrorAt(
        name, count_line_no,
        "the count line says " + std::to_string(declared) + " points, the file has " + std::to_string(n));
  if (n == 0) return ParseErrorIn(name, "no points");
  return pc;
}

}  // namespace silk
