// SPDX-License-Identifier: MIT
// Table-driven legal/illegal sequences: each row is a base stream, an edit, and the expected
// outcome (accepted, or the reason and position of the first refusal). A failing row writes
// its ids to $TMPDIR/silk_grammar_<name>.tokens.txt, which `silktok check` replays.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "io/tokens/token_text.h"
#include "support/test_paths.h"

namespace silk {
namespace {

std::vector<int32_t> Golden(const std::string& name) {
  auto ids = ReadTokenText(testing::SharedPath("spec/golden/" + name + ".tokens.txt"));
  return ids.ok() ? *ids : std::vector<int32_t>{};
}

struct Case {
  const char* name;
  const char* base;
  std::function<void(std::vector<int32_t>*)> edit;
  RejectReason expect;  // kNone = accepted
  int64_t position;     // expected refusal position (-1: don't care)
};

std::string DumpReplay(const std::string& name, const std::vector<int32_t>& ids) {
  const char* tmp = std::getenv("TMPDIR");
  const std::string path = std::string(tmp ? tmp : "/tmp") + "/silk_grammar_" + name + ".tokens.txt";
  std::ofstream(path) << FormatTokenText(ids);
  return path;
}

const Case kCases[] = {
    {"cube_ok", "cube", [](std::vector<int32_t>*) {}, RejectReason::kNone, -1},
    {"tetra_ok", "tetrahedron", [](std::vector<int32_t>*) {}, RejectReason::kNone, -1},
    {"two_components_ok", "two_components", [](std::vector<int32_t>*) {}, RejectReason::kNone, -1},
    {"empty_incomplete", "cube", [](std::vector<int32_t>* v) { v->clear(); }, RejectReason::kIncomplete, 0},
    {"first_not_c", "cube", [](std::vector<int32_t>* v) { (*v)[0] = 1; }, RejectReason::kWrongClass, 0},
    {"offset_before_block", "cube", [](std::vector<int32_t>* v) { std::swap((*v)[1], (*v)[2]); },
     RejectReason::kWrongClass, 1},
    {"e_after_root", "cube", [](std::vector<int32_t>* v) { (*v)[3] = 2; }, RejectReason::kLayerZeroSize, 3},
    {"two_roots", "cube", [](std::vector<int32_t>* v) { (*v)[3] = 5659; }, RejectReason::kWrongClass, 3},
    {"pad_inside", "cube", [](std::vector<int32_t>* v) { (*v)[5] = 10268; }, RejectReason::kPadToken, 5},
    {"eos_inside", "cube", [](std::vector<int32_t>* v) { (*v)[28] = 10267; }, RejectReason::kEosNotAfterE, 28},
    {"out_of_vocab", "cube", [](std::vector<int32_t>* v) { (*v)[6] = 10269; }, RejectReason::kOutOfVocabulary, 6},
    {"eos_at_end_ok", "cube", [](std::vector<int32_t>* v) { v->push_back(10267); }, RejectReason::kNone, -1},
    {"token_after_eos", "cube",
     [](std::vector<int32_t>* v) {
       v->push_back(10267);
       v->push_back(0);
     },
     RejectReason::kAfterEos, 35},
    {"truncated", "cube", [](std::vector<int32_t>* v) { v->resize(30); }, RejectReason::kIncomplete, 30},
    // Layer 1 allows only B id 460 (token_format.md §11.3).
    {"layer1_b459", "cube", [](std::vector<int32_t>* v) { (*v)[7] = 459; }, RejectReason::kBOutsidePrevLayer, 7},
    {"layer1_two_b", "cube", [](std::vector<int32_t>* v) { v->insert(v->begin() + 8, 460); },
     RejectReason::kBContinuation, 8},
    // Cube layer 2 row over 6 columns: s=0 case 0 (459). s=1 case 0 reaches column 6 -> outside.
    {"b_outside", "cube", [](std::vector<int32_t>* v) { (*v)[32] = 459 + 26; }, RejectReason::kBOutsidePrevLayer, 32},
    {"b_continuation", "cube", [](std::vector<int32_t>* v) { v->insert(v->begin() + 33, 459 + 26 * 5 + 1); },
     RejectReason::kBContinuation, 33},
    // S window of a 1-vertex layer must be 0 (bits at distance >= N; token_format.md §11.2).
    {"window_beyond", "cube", [](std::vector<int32_t>* v) { (*v)[31] = 204; }, RejectReason::kLayerNotClosable, 33},
    // Cube layer 1 row 0 drops its d=5 bit (w=1): the partner row 5 still states the pair.
    {"window_inconsistent", "cube", [](std::vector<int32_t>* v) { (*v)[6] = 204; }, RejectReason::kLayerNotClosable,
     28},
    // Layer-1 chain: row 0 without bit 0 forces N = 1, which layer 1 cannot have.
    {"layer1_chain", "cube", [](std::vector<int32_t>* v) { (*v)[6] = 203 + 16; }, RejectReason::kNotCanonical, 6},
    {"x_small_layer", "cube", [](std::vector<int32_t>* v) { v->insert(v->begin() + 7, 3 + 8); },
     RejectReason::kLayerNotClosable, 29},
    {"x_below_8", "cube", [](std::vector<int32_t>* v) { v->insert(v->begin() + 7, 3 + 7); }, RejectReason::kXOutOfRange,
     7},
    {"x_not_increasing", "cube",
     [](std::vector<int32_t>* v) {
       v->insert(v->begin() + 7, 3 + 20);
       v->insert(v->begin() + 8, 3 + 9);
     },
     RejectReason::kXNotIncreasing, 8},
    {"zero_length_edge", "cube",
     [](std::vector<int32_t>* v) {
       (*v)[8] = (*v)[4];
       (*v)[9] = (*v)[5];
     },
     RejectReason::kZeroLengthEdge, 9},
    {"u_at_layer_end_ok_as_e", "cube", [](std::vector<int32_t>* v) { (*v)[33] = 2; }, RejectReason::kNone, -1},
};

TEST(GrammarTable, LegalAndIllegalSequences) {
  for (const Case& c : kCases) {
    std::vector<int32_t> ids = Golden(c.base);
    ASSERT_FALSE(ids.empty()) << c.base;
    c.edit(&ids);
    size_t pos = 0;
    Rejection r = CheckTokens(ids, GrammarOptions{}, &pos);
    const bool ok = r.reason == c.expect && (c.position < 0 || static_cast<int64_t>(pos) == c.position);
    if (!ok) {
      const std::string replay = DumpReplay(c.name, ids);
      ADD_FAILURE() << c.name << ": got " << RejectReasonName(r.reason) << " at " << pos << " (" << r.message
                    << "), expected " << RejectReasonName(c.expect) << " at " << c.position
                    << "; replay: silktok check " << replay;
    }
  }
}

// The mask agrees with Accept on every id at every step of a golden stream (small streams:
// each step checks all 10269 ids on a clone).
TEST(GrammarTable, MaskMatchesAcceptOnCube) {
  for (const char* name : {"cube", "tetrahedron", "grid", "nonmanifold_book"}) {
    const auto ids = Golden(name);
    Grammar g;
    for (size_t i = 0; i < ids.size(); ++i) {
      const TokenMask mask = g.LegalMask();
      for (int32_t id = 0; id < TokenMask::kBits; id += (id < 460 ? 1 : 7)) {
        Grammar t = g.Clone();
        ASSERT_EQ(mask.Test(id), t.Accept(id).ok()) << name << " position " << i << " id " << id;
      }
      ASSERT_TRUE(g.Accept(ids[i]).ok());
    }
  }
}

TEST(GrammarTable, ForcedTokens) {
  Grammar g;
  EXPECT_EQ(g.Forced(), 0);  // C
  const auto ids = Golden("cube");
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(g.Accept(ids[i]).ok());
  EXPECT_EQ(g.Forced(), 1);  // U after the root
  for (int i = 3; i < 7; ++i) ASSERT_TRUE(g.Accept(ids[i]).ok());
  // Layer 1: the only legal B is 460 (X values stay legal: the layer may still grow to N >= 18).
  int32_t b_count = 0;
  for (int32_t id = 459; id < 5659; ++id) b_count += g.LegalMask().Test(id);
  EXPECT_EQ(b_count, 1);
  EXPECT_TRUE(g.LegalMask().Test(460));
  ASSERT_TRUE(g.Accept(460).ok());
  ASSERT_TRUE(g.Accept(ids[8]).ok());
  ASSERT_TRUE(g.Accept(ids[9]).ok());
  // Row 1 with bit 0 clear would end layer 1 at N = 2, where its bit 4 points past the layer.
  Grammar h = g.Clone();
  EXPECT_EQ(h.Accept(203 + 16).reason, RejectReason::kNotCanonical);
  EXPECT_TRUE(h.Accept(203 + 17).ok());
  EXPECT_EQ(h.NextClosableSize(0), 6);  // row 1's bit 4 (d=5): ring of 6 is the smallest fit
}

TEST(GrammarTable, RewindAndClone) {
  const auto ids = Golden("torus_12x8");
  Grammar g;
  for (int32_t id : ids) ASSERT_TRUE(g.Accept(id).ok());
  for (size_t prefix : {size_t{0}, size_t{1}, size_t{5}, size_t{152}, size_t{200}, ids.size() - 1}) {
    Grammar h = g.Clone();
    ASSERT_TRUE(h.Rewind(prefix).ok());
    Grammar fresh;
    for (size_t i = 0; i < prefix; ++i) ASSERT_TRUE(fresh.Accept(ids[i]).ok());
    EXPECT_EQ(h.size(), prefix);
    EXPECT_EQ(h.LegalMask().words(), fresh.LegalMask().words()) << prefix;
    for (size_t i = prefix; i < ids.size(); ++i) ASSERT_TRUE(h.Accept(ids[i]).ok()) << i;
    EXPECT_TRUE(h.CanEnd());
  }
  EXPECT_FALSE(g.Rewind(ids.size() + 1).ok());
}

}  // namespace
}  // namespace silk
