// SPDX-License-Identifier: MIT
// The dev corpus against the official outputs (shared/spec/golden-dev): identical tokens for
// the 140 meshes the reference encodes, the same refusal for the other 20, and the same
// processed / unencodable face sets (with windings).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "mesh/normalize.h"
#include "support/golden_files.h"
#include "support/test_paths.h"
#include "tokenizer/refusal.h"
#include "tokenizer/tokenizer.h"

namespace silk {
namespace {

std::vector<testing::GridFace> ToGrid(const std::vector<std::array<QVec, 3>>& faces) {
  std::vector<testing::GridFace> out;
  for (const auto& f : faces) {
    std::array<std::array<int32_t, 3>, 3> c{};
    for (int k = 0; k < 3; ++k) c[k] = {f[k].x, f[k].y, f[k].z};
    out.push_back(testing::CanonicalFace(c));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Maps the reference's exception (INDEX.tsv status + message) to our named refusal.
bool ExpectedRefusal(const std::string& status, const std::string& message, Refusal* r) {
  if (status == "ZeroDivisionError") return *r = Refusal::kAllComponentsDropped, true;
  if (message.find("mobius") != std::string::npos) return *r = Refusal::kMobius, true;
  if (message.find("NM_verts exceed limit") != std::string::npos) return *r = Refusal::kTooManyNonManifoldVerts, true;
  if (message.find("edge graph edges exceed limit") != std::string::npos) return *r = Refusal::kEdgeGraphLimit, true;
  return false;
}

TEST(GoldenDevEncodeSlow, AllMeshesMatchOfficial) {
  const auto rows = testing::ReadTsvRows(testing::SharedPath("spec/golden-dev/INDEX.tsv"));
  ASSERT_EQ(rows.size(), 160u);
  int ok_match = 0, ok_total = 0, refused_match = 0, refused_total = 0;
  int64_t tokens_total = 0, processed_total = 0, encodable_total = 0;
  for (const auto& row : rows) {
    const std::string name = row.at("name");
    SCOPED_TRACE(name);
    IoMesh raw;
    ASSERT_TRUE(testing::ReadPlainObj(testing::SharedPath("corpus/dev/" + name + ".obj"), &raw));
    auto norm = NormalizeMesh(raw);
    ASSERT_TRUE(norm.ok()) << norm.status().ToString();
    auto enc = EncodeMesh(*norm);
    if (row.at("status") != "ok") {
      ++refused_total;
      Refusal want{}, got{};
      ASSERT_TRUE(ExpectedRefusal(row.at("status"), row.at("message"), &want)) << row.at("message");
      EXPECT_FALSE(enc.ok()) << "reference refused: " << row.at("message");
      if (!enc.ok()) {
        EXPECT_TRUE(RefusalFromStatus(enc.status(), &got)) << enc.status().ToString();
        EXPECT_EQ(RefusalName(got), std::string(RefusalName(want))) << enc.status().ToString();
        if (got == want) ++refused_match;
      }
      continue;
    }
    ++ok_total;
    EXPECT_TRUE(enc.ok()) << enc.status().ToString();
    if (!enc.ok()) continue;
    std::vector<int32_t> expected;
    ASSERT_TRUE(testing::ReadTokenFile(testing::SharedPath("spec/golden-dev/" + name + ".tokens.txt"), &expected));
    const bool same = enc->tokens == expected;
    EXPECT_TRUE(same) << "token mismatch (" << enc->tokens.size() << " vs " << expected.size() << ")";
    std::vector<testing::GridFace> processed, unencodable;
    testing::ReadProcessedFile(testing::SharedPath("spec/golden-dev/" + name + ".processed.txt"), &processed);
    testing::ReadProcessedFile(testing::SharedPath("spec/golden-dev/" + name + ".unencodable.txt"), &unencodable);
    std::sort(processed.begin(), processed.end());
    std::sort(unencodable.begin(), unencodable.end());
    EXPECT_EQ(ToGrid(enc->processed_faces), processed) << "processed faces/windings differ";
    EXPECT_EQ(ToGrid(enc->unencodable_faces), unencodable) << "unencodable faces differ";
    EXPECT_EQ(std::to_string(enc->stats.emitted_vertices), row.at("emitted_v"));
    EXPECT_EQ(std::to_string(enc->stats.processed_vertices), row.at("processed_v"));
    EXPECT_EQ(std::to_string(enc->stats.encodable_faces), row.at("encodable_f"));
    EXPECT_EQ(std::to_string(enc->stats.components_encoded), row.at("components"));
    if (same) ++ok_match;
    tokens_total += static_cast<int64_t>(enc->tokens.size());
    processed_total += enc->stats.processed_faces;
    encodable_total += enc->stats.encodable_faces;
  }
  std::printf(
      "golden-dev encode: %d/%d ok meshes token-identical, %d/%d refusals identical; "
      "%lld tokens, %lld processed faces, %lld encodable faces\n",
      ok_match, ok_total, refused_match, refused_total, static_cast<long long>(tokens_total),
      static_cast<long long>(processed_total), static_cast<long long>(encodable_total));
  EXPECT_EQ(ok_match, 140);
  EXPECT_EQ(refused_match, 20);
}

}  // namespace
}  // namespace silk
