// SPDX-License-Identifier: MIT
// OFF reader: header forms, polygons, comments, plausibility of header counts.
#include "io/off/off_reader.h"

#include <gtest/gtest.h>

namespace silk {
namespace {

TEST(OffReader, ReadsQuadsAndComments) {
  const char* text =
      "OFF\n# a comment\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0  # trailing\n\n2 2 2\n"
      "4 0 1 2 3\n3 0 2 4 255 0 0\n";
  auto m = ReadOff(text, "q.off");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->positions.size(), 5u);
  ASSERT_EQ(m->triangles.size(), 3u);
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m->triangles[2], (std::array<int32_t, 3>{0, 2, 4}));
  EXPECT_EQ(m->polygons_triangulated, 1);
}

TEST(OffReader, CountsOnHeaderLine) {
  auto m = ReadOff("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "h.off");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->triangles.size(), 1u);
}

TEST(OffReader, LyingHeaderFailsBeforeAllocating) {
  auto m = ReadOff("OFF\n353535235358 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "big.off");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("big.off:2: header says 353535235358 vertices"), std::string::npos)
      << m.status().message();
}

TEST(OffReader, Errors) {
  struct Case {
    const char* text;
    const char* expect;
  } cases[] = {
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "e.off:6: face 0: vertex index 3 out of range (3 vertices)"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "e.off:6: face 0 declares 3 corners but has 2 indices"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "e.off:6: face 0 has 2 corner(s)"},
      {"OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "e.off:4: vertex 1: non-finite"},
      {"OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "e.off: no faces"},
      {"PLY\n", "e.off:1: not an OFF file"},
  };
  for (const auto& c : cases) {
    auto m = ReadOff(c.text, "e.off");
    ASSERT_FALSE(m.ok());
    EXPECT_NE(m.status().message().find(c.expect), std::string::npos)
        << "message: " << m.status().message() << "\nexpected: " << c.expect;
  }
}

}  // namespace
}  // namespace silk
