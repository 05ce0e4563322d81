// SPDX-License-Identifier: MIT
// Protobuf wire-format walk of an ONNX ModelProto down to TensorProto.external_data entries.
// Only the messages that can hold tensors are entered; every other field is skipped by length.
#include "runtime/model/onnx_external_data.h"

#include <algorithm>
#include <fstream>
#include <vector>

#include "io/files/file_bytes.h"
#include "io/files/native_path.h"

namespace silk {

namespace {

constexpr int kMaxDepth = 100;           // protobuf's own default recursion limit
constexpr uint64_t kMaxLocation = 4096;  // bytes of one location string

enum class Kind { kModel, kGraph, kNode, kAttribute, kFunction, kTrainingInfo, kSparseTensor, kTensor, kEntry, kSkip };

// The message kind of a length-delimited field (onnx.proto field numbers); kSkip: not entered.
Kind ChildKind(Kind parent, uint64_t field) {
  switch (parent) {
    case Kind::kModel:
      return field == 7    ? Kind::kGraph
             : field == 25 ? Kind::kFunction
             : field == 20 ? Kind::kTrainingInfo
                           : Kind::kSkip;
    case Kind::kGraph:
      return field == 1 ? Kind::kNode : field == 5 ? Kind::kTensor : field == 15 ? Kind::kSparseTensor : Kind::kSkip;
    case Kind::kNode:
      return field == 5 ? Kind::kAttribute : Kind::kSkip;
    case Kind::kAttribute:
      if (field == 5 || field == 10) return Kind::kTensor;
      if (field == 6 || field == 11) return Kind::kGraph;
      return field == 22 || field == 23 ? Kind::kSparseTensor : Kind::kSkip;
    case Kind::kFunction:
      return field == 7 ? Kind::kNode : Kind::kSkip;
    case Kind::kTrainingInfo:
      return field == 1 || field == 2 ? Kind::kGraph : Kind::kSkip;
    case Kind::kSparseTensor:
      return field == 1 || field == 2 ? Kind::kTensor : Kind::kSkip;
    case Kind::kTensor:
      return field == 13 ? Kind::kEntry : Kind::kSkip;
    default:
      return Kind::kSkip;
  }
}

class Walker {
 public:
  Walker(OnnxByteSource& src, const std::string& name, const ExternalDataVisitor& visit)
      : src_(src), name_(name), visit_(visit) {}

  // Walks the fields of one message of `kind` in [pos, end), entering those that hold tensors.
  Status Message(Kind kind, uint64_t pos, uint64_t end, int depth) {
    if (depth > kMaxDepth) return Bad(pos, "messages nested deeper than " + std::to_string(kMaxDepth));
    while (pos < end) {
      uint64_t field = 0, len = 0;
      bool delimited = false;
      SILK_RETURN_IF_ERROR(NextField(&pos, end, &field, &delimited, &len));
      if (!delimited) continue;
      const Kind child = ChildKind(kind, field);
      if (child == Kind::kEntry)
        SILK_RETURN_IF_ERROR(Entry(pos, pos + len));
      else if (child != Kind::kSkip)
        SILK_RETURN_IF_ERROR(Message(child, pos, pos + len, depth + 1));
      pos += len;
    }
    return Status::Ok();
  }

 private:
  Status Bad(uint64_t at, const std::string& what) const {
    return ParseError(name_ + ": not a valid ONNX model (" + what + " at byte " + std::to_string(at) + ")");
  }

  // Reads one field's tag at *pos. A length-delimited field: *delimited, *len checked against
  // `end`, *pos left at its first byte. Any other: skipped whole.
  Status NextField(uint64_t* pos, uint64_t end, uint64_t* field, bool* delimited, uint64_t* len) {
    const uint64_t at = *pos;
    uint64_t tag = 0;
    SILK_RETURN_IF_ERROR(Varint(pos, end, &tag));
    if (tag >> 3 == 0 || tag > UINT32_MAX) return Bad(at, "invalid field number");
    *field = tag >> 3;
    *delimited = (tag & 7) == 2;
    uint64_t skip = 0;
    switch (tag & 7) {
      case 0:
        return Varint(pos, end, len);
      case 1:
        skip = 8;
        break;
      case 5:
        skip = 4;
        break;
      case 2:
        SILK_RETURN_IF_ERROR(Varint(pos, end, len));
        skip = *len;
        break;
      default:
        return Bad(at, "unsupported wire type " + std::to_string(tag & 7));
    }
    if (skip > end - *pos) return Bad(at, "field runs past its message");
    if (!*delimited) *pos += skip;
    return Status::Ok();
  }

  Status Varint(uint64_t* pos, uint64_t end, uint64_t* value) {
    const uint64_t at = *pos;
    *value = 0;
    for (int shift = 0; shift < 70; shift += 7) {
      char c = 0;
      if (*pos >= end) return Bad(at, "truncated varint");
      if (!src_.Read((*pos)++, 1, &c)) return IoError(name_ + ": read error");
      const auto b = static_cast<uint8_t>(c);
      if (shift == 63 && b > 1) return Bad(at, "varint over 64 bits");
      *value |= uint64_t{b & 0x7fu} << shift;
      if (!(b & 0x80)) return Status::Ok();
    }
    return Bad(at, "varint over 10 bytes");
  }

  Status ReadString(uint64_t pos, uint64_t len, std::string* out) {
    out->assign(static_cast<size_t>(len), '\0');
    if (len && !src_.Read(pos, out->size(), &(*out)[0])) return IoError(name_ + ": read error");
    return Status::Ok();
  }

  // A StringStringEntryProto: the last key and the last value win, as in protobuf.
  Status Entry(uint64_t pos, uint64_t end) {
    std::string key, value;
    bool value_too_long = false;
    while (pos < end) {
      uint64_t field = 0, len = 0;
      bool delimited = false;
      SILK_RETURN_IF_ERROR(NextField(&pos, end, &field, &delimited, &len));
      if (!delimited) continue;
      if (field == 1) {
        key = "(other)";  // only an 8-byte key can be "location"
        if (len == 8) SILK_RETURN_IF_ERROR(ReadString(pos, len, &key));
      } else if (field == 2) {
        value_too_long = len > kMaxLocation;
        value.clear();
        if (!value_too_long) SILK_RETURN_IF_ERROR(ReadString(pos, len, &value));
      }
      pos += len;
    }
    if (key != "location") return Status::Ok();
    if (value_too_long)
      return Bad(pos, "external data location longer than " + std::to_string(kMaxLocation) + " bytes");
    return visit_(value);
  }

  OnnxByteSource& src_;
  const std::string& name_;
  const ExternalDataVisitor& visit_;
};

class MemorySource : public OnnxByteSource {
 public:
  explicit MemorySource(std::string_view b) : b_(b) {}
  uint64_t size() const override { return b_.size(); }
  bool Read(uint64_t offset, size_t n, char* out) override {
    if (offset > b_.size() || n > b_.size() - offset) return false;
    std::copy_n(b_.data() + offset, n, out);
    return true;
  }

 private:
  std::string_view b_;
};

// A file read through one 64 KiB window: the walk reads tags and short strings, and skips the
// tensor bytes, so a large self-contained model costs a few reads per tensor.
class FileSource : public OnnxByteSource {
 public:
  FileSource(std::ifstream& f, uint64_t size) : f_(f), size_(size) {}
  uint64_t size() const override { return size_; }
  bool Read(uint64_t offset, size_t n, char* out) override {
    if (offset > size_ || n > size_ - offset) return false;
    if (n > kWindow) return Fill(offset, n, out);
    if (window_.empty() || offset < window_at_ || offset + n > window_at_ + window_.size()) {
      window_.resize(static_cast<size_t>(std::min<uint64_t>(kWindow, size_ - offset)));
      if (!Fill(offset, window_.size(), window_.data())) return false;
      window_at_ = offset;
    }
    std::copy_n(window_.data() + (offset - window_at_), n, out);
    return true;
  }

 private:
  static constexpr size_t kWindow = size_t{1} << 16;
  bool Fill(uint64_t offset, size_t n, char* out) {
    f_.clear();
    f_.seekg(static_cast<std::streamoff>(offset));
    f_.read(out, static_cast<std::streamsize>(n));
    if (f_.gcount() == static_cast<std::streamsize>(n)) return true;
    window_.clear();
    return false;
  }
  std::ifstream& f_;
  uint64_t size_;
  std::vector<char> window_;
  uint64_t window_at_ = 0;
};

}  // namespace

Status ForEachExternalDataLocation(OnnxByteSource& src, const std::string& name, const ExternalDataVisitor& visit) {
  return Walker(src, name, visit).Message(Kind::kModel, 0, src.size(), 0);
}

Status ForEachExternalDataLocation(std::string_view bytes, const std::string& name, const ExternalDataVisitor& visit) {
  MemorySource src(bytes);
  return ForEachExternalDataLocation(src, name, visit);
}

Status ForEachExternalDataLocationInFile(const std::string& path, const ExternalDataVisitor& visit) {
  SILK_RETURN_IF_ERROR(CheckRegularFile(path));
  std::ifstream f(NativePath(path), std::ios::binary | std::ios::ate);
  if (!f) return IoError(path + ": cannot open");
  const std::streamoff size = f.tellg();
  if (size < 0) return IoError(path + ": cannot read its size");
  FileSource src(f, static_cast<uint64_t>(size));
  return ForEachExternalDataLocation(src, path, visit);
}

}  // namespace silk
