// SPDX-License-Identifier: MIT
// Issue 20, finding 2: a model folder may only make libsilk read files inside it. The tiny
// model's decoder is rewritten with its weights in an ONNX external-data file (a small protobuf
// rewrite below, no onnx package needed), whose location is legit, "../outside.bin", absolute, or
// a symlink leading out; and model.json's decoder itself is tried as a symlink leading out.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/files/file_bytes.h"
#include "io/io_test_util.h"
#include "runtime/generator.h"
#include "runtime/model/onnx_external_data.h"
#include "runtime_test_util.h"

namespace silk {
namespace {

namespace fs = std::filesystem;

void PutVarint(std::string* s, uint64_t v) {
  for (; v >= 0x80; v >>= 7) s->push_back(static_cast<char>((v & 0x7f) | 0x80));
  s->push_back(static_cast<char>(v));
}
uint64_t GetVarint(std::string_view b, size_t* pos) {
  uint64_t v = 0;
  for (int shift = 0;; shift += 7) {
    const auto c = static_cast<uint8_t>(b.at((*pos)++));
    v |= uint64_t{c & 0x7fu} << shift;
    if (!(c & 0x80)) return v;
  }
}
void PutBytes(std::string* s, uint64_t field, std::string_view payload) {
  PutVarint(s, field << 3 | 2);
  PutVarint(s, payload.size());
  s->append(payload);
}

// One field of a (trusted) protobuf message: its number, wire type, whole bytes and payload.
struct Field {
  uint64_t number;
  int wire;
  std::string_view whole, payload;
};
std::vector<Field> Fields(std::string_view m) {
  std::vector<Field> out;
  for (size_t pos = 0; pos < m.size();) {
    const size_t at = pos;
    const uint64_t tag = GetVarint(m, &pos);
    const int wire = static_cast<int>(tag & 7);
    size_t len = wire == 1 ? 8 : wire == 5 ? 4 : 0, start = pos;
    if (wire == 0) GetVarint(m, &pos);
    if (wire == 2) len = GetVarint(m, &pos), start = pos;
    pos = wire == 0 ? pos : start + len;
    out.push_back({tag >> 3, wire, m.substr(at, pos - at), m.substr(start, len)});
  }
  return out;
}

// A TensorProto with raw_data moved to `*data` (appended) and named by external-data entries.
std::string Externalize(std::string_view tensor, const std::string& location, std::string* data) {
  std::string out, raw;
  for (const Field& f : Fields(tensor))
    (f.number == 9 && f.wire == 2 ? raw : out).append(f.number == 9 ? f.payload : f.whole);
  const std::pair<std::string, std::string> entries[] = {
      {"location", location}, {"offset", std::to_string(data->size())}, {"length", std::to_string(raw.size())}};
  for (const auto& [k, v] : entries) {
    std::string e;
    PutBytes(&e, 1, k);
    PutBytes(&e, 2, v);
    PutBytes(&out, 13, e);
  }
  PutVarint(&out, 14 << 3);  // data_location = EXTERNAL
  PutVarint(&out, 1);
  data->append(raw);
  return out;
}

// The model with every initializer of its graph in external data at `location`.
std::string ExternalizeModel(std::string_view model, const std::string& location, std::string* data) {
  std::string out;
  for (const Field& m : Fields(model)) {
    if (m.number != 7 || m.wire != 2) {
      out.append(m.whole);
      continue;
    }
    std::string graph;
    for (const Field& g : Fields(m.payload)) {
      if (g.number == 5 && g.wire == 2)
        PutBytes(&graph, 5, Externalize(g.payload, location, data));
      else
        graph.append(g.whole);
    }
    PutBytes(&out, 7, graph);
  }
  return out;
}

// <tmp>/model: the tiny model with its decoder's weights at `location`, whose bytes are written
// to <tmp>/<data_file> (relative to <tmp>/model when data_file starts with "model/").
class ModelFolder {
 public:
  ModelFolder(const std::string& location, const std::string& data_file) {
    dir_ = tmp_.path() + "/model";
    fs::create_directory(dir_);
    for (const char* f : {"model.json", "encoder.onnx"})
      fs::copy_file(testing::TinyModelDir() + "/" + f, dir_ + "/" + f);
    auto onnx = ReadFileBytes(testing::TinyModelDir() + "/decoder.onnx", 1 << 30);
    EXPECT_TRUE(onnx.ok());
    std::string data;
    tmp_.Write("model/decoder.onnx", ExternalizeModel(*onnx, location, &data));
    tmp_.Write(data_file, data);
  }
  std::string tmp() const { return tmp_.path(); }
  std::string dir() const { return dir_; }

 private:
  testing::TempDir tmp_;
  std::string dir_;
};

std::vector<int32_t> Tokens(const Model& model) {
  GenerateOptions o;
  o.sampling.seed = 3;
  o.max_tokens = 200;
  Generator g(model);
  auto r = g.Run(testing::SamplePoints(model), o);
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  return r.ok() ? r->tokens : std::vector<int32_t>{};
}

void ExpectRefused(const std::string& dir, const std::string& needle) {
  auto m = Model::Load(dir);
  ASSERT_FALSE(m.ok()) << "loaded, but should be refused: " << needle;
  EXPECT_EQ(m.status().code(), StatusCode::kParseError) << m.status().ToString();
  EXPECT_NE(m.status().message().find(needle), std::string::npos) << m.status().message();
}

TEST(ModelFolderFiles, ExternalDataInsideTheFolderLoadsAndGeneratesTheSame) {
  ModelFolder f("decoder.onnx.data", "model/decoder.onnx.data");
  auto ext = Model::Load(f.dir());
  ASSERT_TRUE(ext.ok()) << ext.status().ToString();
  auto tiny = testing::LoadTinyModel(1);
  ASSERT_TRUE(tiny);
  EXPECT_EQ(Tokens(**ext), Tokens(*tiny));
  fs::create_directory(f.dir() + "/weights");  // a subfolder is inside too
  fs::rename(f.dir() + "/decoder.onnx.data", f.dir() + "/weights/d.bin");
  ModelFolder sub("weights/d.bin", "model/weights_unused.bin");
  fs::create_directory(sub.dir() + "/weights");
  fs::copy_file(f.dir() + "/weights/d.bin", sub.dir() + "/weights/d.bin");
  auto s = Model::Load(sub.dir());
  EXPECT_TRUE(s.ok()) << s.status().ToString();
}

TEST(ModelFolderFiles, ExternalDataClimbingOutIsRefused) {
  ModelFolder f("../outside.bin", "outside.bin");
  ExpectRefused(f.dir(), f.dir() + "/decoder.onnx: external data location '../outside.bin' climbs out with '..'");
}

TEST(ModelFolderFiles, ExternalDataAtAnAbsolutePathIsRefused) {
  testing::TempDir other;
  const std::string abs = other.path() + "/outside.bin";
  ModelFolder f(abs, "unused.bin");
  fs::copy_file(f.tmp() + "/unused.bin", abs);
  ExpectRefused(f.dir(), f.dir() + "/decoder.onnx: external data location '" + abs + "' is an absolute path");
}

TEST(ModelFolderFiles, ExternalDataSymlinkLeadingOutIsRefused) {
  ModelFolder f("link.bin", "outside.bin");
  fs::create_symlink(f.tmp() + "/outside.bin", f.dir() + "/link.bin");
  ExpectRefused(f.dir(), f.dir() + "/decoder.onnx: external data location 'link.bin' leads outside the model folder");
}

TEST(ModelFolderFiles, ModelJsonFileSymlinkLeadingOutIsRefused) {
  ModelFolder f("decoder.onnx.data", "model/decoder.onnx.data");
  fs::rename(f.dir() + "/encoder.onnx", f.tmp() + "/encoder.onnx");
  fs::create_symlink(f.tmp() + "/encoder.onnx", f.dir() + "/encoder.onnx");
  ExpectRefused(f.dir(), f.dir() + "/model.json: file 'encoder.onnx' leads outside the model folder");
}

// The walker finds a location in every place a tensor can be: initializer, Constant attribute,
// both If branches, sparse initializer, function (fuzz/make_onnx_seeds.py builds the seed).
TEST(OnnxExternalData, FindsEveryPlaceAndRefusesTruncation) {
  const std::string seeds = testing::SourcePath("fuzz/corpus/onnx_external_data_fuzzer/");
  std::vector<std::string> seen;
  Status s = ForEachExternalDataLocationInFile(seeds + "climbs_out.onnx", [&](const std::string& loc) {
    seen.push_back(loc);
    return Status::Ok();
  });
  ASSERT_TRUE(s.ok()) << s.ToString();
  EXPECT_EQ(seen, std::vector<std::string>(6, "../outside.bin"));
  Status t =
      ForEachExternalDataLocationInFile(seeds + "truncated.onnx", [](const std::string&) { return Status::Ok(); });
  EXPECT_EQ(t.code(), StatusCode::kParseError) << t.ToString();
  EXPECT_NE(t.message().find("truncated.onnx: not a valid ONNX model"), std::string::npos) << t.message();
}

}  // namespace
}  // namespace silk
