// SPDX-License-Identifier: MIT
// PMD reader: synthetic v1/v3/v4 files built here, every truncation and lying count refused
// with a message, random bytes never crash; and (when the 0 A.D. meshes are extracted) the
// 160 dev OBJ meshes equal their PMD sources.
#include "io/pmd/pmd_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "io/mesh_reader.h"
#include "io/io_test_util.h"
#include "support/golden_files.h"
#include "support/test_paths.h"

namespace silk {
namespace {

using testing::AppendLE;

struct PmdSpec {
  uint32_t version = 4;
  uint32_t uv_sets = 1;  // written as a field from version 4 on; always 1 before
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<uint16_t, 3>> faces;
  uint32_t bones = 0;
  std::vector<std::string> props;  // prop point names (version >= 2)
};

// Lays the file out as the format says; normals/UVs/weights get recognisable filler values.
std::string BuildPmd(const PmdSpec& s) {
  std::string body;
  AppendLE(&body, static_cast<uint32_t>(s.positions.size()));
  if (s.version >= 4) AppendLE(&body, s.uv_sets);
  for (const auto& p : s.positions) {
    for (float c : p) AppendLE(&body, c);
    for (float c : {0.f, 1.f, 0.f}) AppendLE(&body, c);  // normal
    for (uint32_t u = 0; u < (s.version >= 4 ? s.uv_sets : 1u); ++u) {
      AppendLE(&body, 0.25f);
      AppendLE(&body, 0.75f);
    }
    for (uint8_t b : {uint8_t{0}, uint8_t{0xFF}, uint8_t{0xFF}, uint8_t{0xFF}}) AppendLE(&body, b);
    for (float w : {1.f, 0.f, 0.f, 0.f}) AppendLE(&body, w);
  }
  AppendLE(&body, static_cast<uint32_t>(s.faces.size()));
  for (const auto& f : s.faces)
    for (uint16_t i : f) AppendLE(&body, i);
  AppendLE(&body, s.bones);
  for (uint32_t b = 0; b < s.bones; ++b)
    for (float c : {1.f, 2.f, 3.f, 0.f, 0.f, 0.f, 1.f}) AppendLE(&body, c);
  if (s.version >= 2) {
    AppendLE(&body, static_cast<uint32_t>(s.props.size()));
    for (const std::string& name : s.props) {
      AppendLE(&body, static_cast<uint32_t>(name.size()));
      body += name;
      for (float c : {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 1.f}) AppendLE(&body, c);
      AppendLE(&body, uint8_t{0xFF});
    }
  }
  std::string out = "PSMD";
  AppendLE(&out, s.version);
  AppendLE(&out, static_cast<uint32_t>(body.size()));
  return out + body;
}

PmdSpec Quad(uint32_t version) {
  PmdSpec s;
  s.version = version;
  s.positions = {{0.f, 0.f, 0.f}, {1.5f, 0.f, 0.f}, {1.5f, 2.f, -0.125f}, {0.f, 2.f, 1e-7f}};
  s.faces = {{0, 1, 2}, {0, 2, 3}};
  return s;
}

void PatchU32(std::string* s, size_t at, uint32_t v) {
  std::string b;
  AppendLE(&b, v);
  s->replace(at, 4, b);
}

// The data-size field made consistent with a (shortened or grown) file.
std::string FixDataSize(std::string s) {
  if (s.size() >= 12) PatchU32(&s, 8, static_cast<uint32_t>(s.size() - 12));
  return s;
}

void ExpectQuad(const StatusOr<IoMesh>& m) {
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ASSERT_EQ(m->positions.size(), 4u);
  EXPECT_EQ(m->positions[2], (std::array<double, 3>{1.5, 2.0, -0.125}));
  EXPECT_EQ(m->positions[3][2], static_cast<double>(1e-7f));
  ASSERT_EQ(m->triangles.size(), 2u);
  EXPECT_EQ(m->triangles[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{0, 2, 3}));
}

TEST(PmdReader, Version4WithTwoUvSetsBonesAndProps) {
  PmdSpec s = Quad(4);
  s.uv_sets = 2;
  s.bones = 2;
  s.props = {"root", "", "prop-with-a-longer-name"};
  ExpectQuad(ReadPmd(BuildPmd(s), "q4.pmd"));
}

TEST(PmdReader, Version3HasOneUvSetAndNoUvCountField) {
  PmdSpec s = Quad(3);
  s.props = {"garrison"};
  const std::string bytes = BuildPmd(s);
  ExpectQuad(ReadPmd(bytes, "q3.pmd"));
  // The same bytes labelled version 4 are misread (first normal taken as a UV count) and refused.
  std::string as_v4 = bytes;
  PatchU32(&as_v4, 4, 4);
  EXPECT_FALSE(ReadPmd(as_v4, "q3as4.pmd").ok());
}

TEST(PmdReader, Versions1And2) {
  PmdSpec v1 = Quad(1);  // no prop point section at all
  v1.bones = 1;
  ExpectQuad(ReadPmd(BuildPmd(v1), "q1.pmd"));
  PmdSpec v2 = Quad(2);
  v2.props = {"a"};
  ExpectQuad(ReadPmd(BuildPmd(v2), "q2.pmd"));
}

TEST(PmdReader, VerticesAreNotWelded) {
  PmdSpec s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.faces = {{0, 1, 2}, {3, 5, 4}};
  auto m = ReadPmd(BuildPmd(s), "dup.pmd");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->positions.size(), 6u);
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{3, 5, 4}));
}

TEST(PmdReader, DispatchByExtensionMagicAndMemory) {
  const std::string bytes = BuildPmd(Quad(4));
  testing::TempDir dir;
  ExpectQuad(ReadMeshFile(dir.Write("quad.PMD", bytes)));
  ExpectQuad(ReadMeshFile(dir.Write("quad.model", bytes)));  // unknown extension: "PSMD" magic
  ExpectQuad(
      ReadMeshFromMemory(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), MeshFormat::kPmd, "mem.pmd"));
  EXPECT_EQ(MeshFormatFromPath("a/b/house.dae.cached.pmd"), MeshFormat::kPmd);
  EXPECT_STREQ(MeshFormatName(MeshFormat::kPmd), "PMD");
}

TEST(PmdReader, ErrorsNameFileAndField) {
  const std::string good = BuildPmd(Quad(4));
  struct Case {
    std::string bytes, expect;
  } cases[] = {
      {"", "e.pmd: not a PMD file (no 'PSMD' magic)"},
      {"PSMX" + good.substr(4), "e.pmd: not a PMD file"},
      {"PSMD", "e.pmd: truncated at byte 4 reading version (needs 4 bytes, 0 left)"},
      {[&] {
         std::string b = good;
         PatchU32(&b, 4, 5);
         return b;
       }(),
       "e.pmd: PMD version 5 not supported"},
      {[&] {
         std::string b = good;
         PatchU32(&b, 4, 0);
         return b;
       }(),
       "e.pmd: PMD version 0 not supported"},
      {good + "x", "e.pmd: header data size"},
      {FixDataSize(good + "xyz"), "e.pmd: 3 unexpected bytes after the prop points"},
      {[&] {
         std::string b = good;
         PatchU32(&b, 12, 0xFFFFFFFFu);
         return b;
       }(),
       "e.pmd: vertex count 4294967295 needs"},
      {[&] {
         std::string b = good;
         PatchU32(&b, 12, 0);
         return b;
       }(),
       "e.pmd: "},
      {[&] {
         std::string b = good;
         PatchU32(&b, 16, 0x7FFFFFFFu);
         return b;
       }(),
       "e.pmd: UV set count 2147483647 does not fit"},
  };
  for (const Case& c : cases) {
    auto m = ReadPmd(c.bytes, "e.pmd");
    ASSERT_FALSE(m.ok()) << c.expect;
    EXPECT_EQ(m.status().message().rfind(c.expect, 0), 0u) << m.status().message() << "\nexpected: " << c.expect;
  }
  EXPECT_EQ(ReadPmd(good + "x", "e.pmd").status().code(), StatusCode::kParseError);
  std::string v5 = good;
  PatchU32(&v5, 4, 5);
  EXPECT_EQ(ReadPmd(v5, "e.pmd").status().code(), StatusCode::kUnsupported);
}

TEST(PmdReader, BadContentRefused) {
  PmdSpec bad_index = Quad(4);
  bad_index.faces[1] = {0, 2, 4};
  auto m = ReadPmd(BuildPmd(bad_index), "i.pmd");
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().message(), "i.pmd: face 1: vertex index 4 out of range (4 vertices)");

  PmdSpec nan = Quad(4);
  nan.positions[3][1] = std::numeric_limits<float>::quiet_NaN();
  m = ReadPmd(BuildPmd(nan), "n.pmd");
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().message(), "n.pmd: vertex 3: non-finite position coordinate");

  PmdSpec no_faces = Quad(4);
  no_faces.faces.clear();
  m = ReadPmd(BuildPmd(no_faces), "f.pmd");
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().message(), "f.pmd: no faces");

  PmdSpec no_vertices;
  m = ReadPmd(BuildPmd(no_vertices), "v.pmd");
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().message(), "v.pmd: no vertices");

  // A prop point whose name length runs past the end of the file.
  PmdSpec prop = Quad(4);
  prop.props = {"abc"};
  std::string b = BuildPmd(prop);
  PatchU32(&b, b.size() - (4 + 3 + 29), 1000);
  m = ReadPmd(b, "p.pmd");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("p.pmd: truncated at byte"), std::string::npos) << m.status().message();
  EXPECT_NE(m.status().message().find("reading prop point 0"), std::string::npos) << m.status().message();

  ReadOptions small;
  small.max_vertices = 3;
  m = ReadPmd(BuildPmd(Quad(4)), "l.pmd", small);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kLimitExceeded);
  small = ReadOptions();
  small.max_triangles = 1;
  EXPECT_EQ(ReadPmd(BuildPmd(Quad(4)), "l.pmd", small).status().code(), StatusCode::kLimitExceeded);
}

TEST(PmdReader, EveryTruncationIsRefused) {
  for (uint32_t version : {1u, 3u, 4u}) {
    PmdSpec s = Quad(version);
    s.bones = 1;
    if (version >= 2) s.props = {"p"};
    const std::string full = BuildPmd(s);
    ASSERT_TRUE(ReadPmd(full, "t.pmd").ok());
    for (size_t n = 0; n < full.size(); ++n) {
      auto m = ReadPmd(FixDataSize(full.substr(0, n)), "t.pmd");
      ASSERT_FALSE(m.ok()) << "version " << version << ", " << n << " bytes";
      EXPECT_EQ(m.status().message().rfind("t.pmd: ", 0), 0u) << m.status().message();
    }
  }
}

TEST(PmdReader, RandomBytesAndFlipsNeverCrash) {
  const std::string good = BuildPmd(Quad(4));
  uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<uint32_t>(state >> 33);
  };
  int accepted = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    std::string b = good;
    const int flips = 1 + next() % 4;
    for (int k = 0; k < flips; ++k) b[next() % b.size()] = static_cast<char>(next());
    if (iter % 2) b = FixDataSize(b.substr(0, next() % (b.size() + 1)));
    auto m = ReadPmd(b, "r.pmd");
    if (m.ok()) {
      ++accepted;
      for (const auto& t : m->triangles)
        for (int32_t i : t) ASSERT_LT(static_cast<size_t>(i), m->positions.size());
    } else {
      EXPECT_EQ(m.status().message().rfind("r.pmd", 0), 0u) << m.status().message();
    }
  }
  EXPECT_GT(accepted, 0);  // flips inside normals/UVs/weights are harmless
}

// The dev OBJ files were converted from these PMDs keeping positions (6 decimals) and
// triangles: same counts, same triangles, positions within the rounding of 6 decimals.
TEST(PmdDevCorpus, MatchesObjSourcesSkippedUnlessSILK_0AD_MESHESIsSet) {
  const char* meshes = std::getenv("SILK_0AD_MESHES");
  if (!meshes || !*meshes)
    GTEST_SKIP() << "SILK_0AD_MESHES not set: run scripts/fetch_0ad.sh and point it at the "
                    "extracted art/meshes folder to compare the 160 dev meshes with their PMD sources";
  const auto rows = testing::ReadTsvRows(testing::SharedPath("corpus/dev/MANIFEST.tsv"));
  ASSERT_FALSE(rows.empty()) << "MANIFEST.tsv not found or empty";
  const std::string prefix = "0ad-data:art/meshes/";
  int compared = 0;
  double max_diff = 0;
  for (const auto& row : rows) {
    ASSERT_TRUE(row.count("file") && row.count("source")) << "MANIFEST.tsv columns";
    const std::string& file = row.at("file");
    const std::string& source = row.at("source");
    ASSERT_EQ(source.rfind(prefix, 0), 0u) << source;
    auto obj = ReadMeshFile(testing::SharedPath("corpus/dev/" + file));
    auto pmd = ReadMeshFile(std::string(meshes) + "/" + source.substr(prefix.size()));
    ASSERT_TRUE(obj.ok()) << obj.status().ToString();
    ASSERT_TRUE(pmd.ok()) << pmd.status().ToString();
    ASSERT_EQ(pmd->positions.size(), obj->positions.size()) << file;
    ASSERT_EQ(pmd->triangles.size(), obj->triangles.size()) << file;
    EXPECT_TRUE(pmd->triangles == obj->triangles) << file;
    for (size_t v = 0; v < obj->positions.size(); ++v)
      for (int k = 0; k < 3; ++k) {
        const double d = std::fabs(pmd->positions[v][k] - obj->positions[v][k]);
        max_diff = std::max(max_diff, d);
        ASSERT_LE(d, 5e-7 + 1e-12) << file << " vertex " << v;
      }
    ++compared;
  }
  EXPECT_EQ(compared, 160);
  std::printf("compared %d dev meshes with their PMD sources, max |position difference| %.3g\n", compared, max_diff);
}

}  // namespace
}  // namespace silk
