// SPDX-License-Identifier: MIT
// TextLines / LineTokens: line-by-line, whitespace-token scanning of an in-memory text file,
// shared by the OBJ, OFF, PLY-ascii and STL-ascii readers. Tracks 1-based line numbers.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace silk {

inline bool IsSpaceByte(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

class TextLines {
 public:
  explicit TextLines(std::string_view text, size_t start = 0, int64_t first_line = 1)
      : text_(text), pos_(start), line_no_(first_line - 1) {}
  // Next line without its terminator ("\n" or "\r\n"); false at end of text.
  bool Next(std::string_view* line) {
    if (pos_ >= text_.size()) return false;
    size_t nl = text_.find('\n', pos_);
    size_t end = nl == std::string_view::npos ? text_.size() : nl;
    *line = text_.substr(pos_, end - pos_);
    if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
    pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
    ++line_no_;
    return true;
  }
  int64_t line_number() const { return line_no_; }
  size_t position() const { return pos_; }  // offset of the next unread byte

 private:
  std::string_view text_;
  size_t pos_;
  int64_t line_no_;
};

class LineTokens {
 public:
  explicit LineTokens(std::string_view line) : line_(line) {}
  bool Next(std::string_view* tok) {
    while (pos_ < line_.size() && IsSpaceByte(line_[pos_])) ++pos_;
    if (pos_ >= line_.size()) return false;
    size_t b = pos_;
    while (pos_ < line_.size() && !IsSpaceByte(line_[pos_])) ++pos_;
    *tok = line_.substr(b, pos_ - b);
    return true;
  }
  bool AtEnd() {
    while (pos_ < line_.size() && IsSpaceByte(line_[pos_])) ++pos_;
    return pos_ >= line_.size();
  }
  std::string_view Rest() {  // remaining text, leading spaces skipped
    AtEnd();
    return line_.substr(pos_);
  }

 private:
  std::string_view line_;
  size_t pos_ = 0;
};

// First control byte that cannot appear in a text mesh file (NUL, other C0 controls except
// tab/CR/LF/FF/VT, DEL); returns the offset or npos.
inline size_t FindBinaryByte(std::string_view s) {
  for (size_t i = 0; i < s.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v') || c == 0x7f) return i;
  }
  return std::string_view::npos;
}

}  // namespace silk
