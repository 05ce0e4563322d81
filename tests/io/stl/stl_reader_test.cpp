// SPDX-License-Identifier: MIT
// STL reader: ascii, binary, binary whose header starts with "solid", raw vertices.
#include "io/stl/stl_reader.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"

namespace silk {
namespace {

std::string BinaryStl(const std::string& header80, int ntri) {
  std::string s = header80;
  s.resize(80, ' ');
  testing::AppendLE(&s, static_cast<uint32_t>(ntri));
  for (int t = 0; t < ntri; ++t) {
    for (float v : {0.f, 0.f, 1.f}) testing::AppendLE(&s, v);  // normal
    const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, static_cast<float>(t)};
    for (float v : corners) testing::AppendLE(&s, v);
    testing::AppendLE(&s, uint16_t{0});
  }
  return s;
}

TEST(StlReader, Ascii) {
  const char* text =
      "solid cube\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
      "    endloop\n  endfacet\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 1 0 0\n      vertex 1 1 0\n      vertex 0.5 1 1e-3\n"
      "    endloop\n  endfacet\n"
      "endsolid cube\n";
  auto m = ReadStl(text, "a.stl");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->positions.size(), 6u);  // 3 new vertices per triangle, not welded
  ASSERT_EQ(m->triangles.size(), 2u);
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{3, 4, 5}));
  EXPECT_EQ(m->positions[5][2], 1e-3);
}

TEST(StlReader, Binary) {
  auto m = ReadStl(BinaryStl("binary header", 3), "b.stl");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->positions.size(), 9u);
  EXPECT_EQ(m->triangles.size(), 3u);
  EXPECT_EQ(m->positions[8][2], 2.0);
}

TEST(StlReader, BinaryStartingWithSolidIsDetectedBySize) {
  auto m = ReadStl(BinaryStl("solid exported by a tool that writes solid in binary headers", 2), "s.stl");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->triangles.size(), 2u);
}

TEST(StlReader, Errors) {
  std::string wrong_count = BinaryStl("hdr", 2);
  wrong_count[80] = 5;
  struct Case {
    std::string text, expect;
  } cases[] = {
      {wrong_count, "w.stl: binary STL header says 5 triangles"},
      {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
       "w.stl:6: facet has 2 vertices"},
      {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 inf 0\nvertex 1 1 1\nendloop\nendfacet\n",
       "w.stl:5: non-finite"},
      {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "w.stl:4: unexpected end of file"},
      {"solid x\nendsolid x\n", "w.stl: no faces"},
      {"hello", "w.stl: not an STL file"},
  };
  for (const auto& c : cases) {
    auto m = ReadStl(c.text, "w.stl");
    ASSERT_FALSE(m.ok());
    EXPECT_NE(m.status().message().find(c.expect), std::string::npos)
        << "message: " << m.status().message() << "\nexpected: " << c.expect;
  }
}

}  // namespace
}  // namespace silk
