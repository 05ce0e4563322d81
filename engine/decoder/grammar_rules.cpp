// SPDX-License-Identifier: MIT
// The rule table itself: for each phase of the grammar (token_format.md §11.1 packing order), the classes
// of ids it may take (ranges of the vocabulary layout), each class's id-dependent test with its
// bulk form, its gates and what accepting it does. Read by Grammar::Step and Grammar::ComputeMask.
#include "decoder/grammar.h"

#include <cstdlib>

#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

constexpr GrammarClassRule Class(int32_t begin, int32_t end, GrammarApply apply, GrammarIdTest test = nullptr,
                                 GrammarIdBulk bulk = nullptr, std::array<GrammarGate, kGrammarMaxGates> gates = {}) {
  GrammarClassRule c;
  c.begin = begin;
  c.end = end;
  c.apply = apply;
  c.test = test;
  c.bulk = bulk;
  c.gates = gates;
  return c;
}

constexpr GrammarPhaseRule Row(const char* expects, std::array<GrammarClassRule, 4> classes, int32_t count) {
  GrammarPhaseRule r;
  r.expects = expects;
  r.classes = classes;
  r.count = count;
  return r;
}

// Every class lies inside the model ids short of PAD (so Step's id and PAD checks hold for every
// id the mask adds) and the ranges of a row are disjoint: checked at compile time.
constexpr bool WellFormed(const GrammarPhaseRule& row) {
  for (int32_t i = 0; i < row.count; ++i) {
    const GrammarClassRule& c = row.classes[i];
    if (c.begin < 0 || c.begin >= c.end || c.end > vocab::k_pad_id) return false;
    for (int32_t j = 0; j < i; ++j)
      if (c.begin < row.classes[j].end && row.classes[j].begin < c.end) return false;
  }
  return true;
}

// A test comes with its bulk form. Comparing member-function pointers is not a constant
// expression for GCC under -fsanitize=undefined, so this is checked once, at the table's first
// use; every grammar test reaches it, and a malformed table aborts them all.
bool TestsHaveBulkForms(const GrammarPhaseRule* rows, size_t n) {
  for (size_t r = 0; r < n; ++r)
    for (int32_t i = 0; i < rows[r].count; ++i)
      if ((rows[r].classes[i].test == nullptr) != (rows[r].classes[i].bulk == nullptr)) return false;
  return true;
}

}  // namespace

const GrammarPhaseRule& Grammar::RuleRow(GrammarPhase p) {
  using G = Grammar;
  using namespace vocab;
  constexpr GrammarClassRule kC =
      Class(kCBegin, kCEnd, &G::ApplyComponentStart, nullptr, nullptr, {&G::RoomForComponent});
  constexpr GrammarClassRule kK = Class(kKBegin, kKEnd, &G::ApplyBlock);
  static constexpr GrammarPhaseRule kRows[] = {
      // kStart
      Row("C", {kC}, 1),
      // kWantK: a vertex's block, after C or U
      Row("K (block)", {kK}, 1),
      // kWantO: its offset
      Row("O (offset)", {Class(kOBegin, kOEnd, &G::ApplyOffset, &G::TestPosition, &G::AddPositions)}, 1),
      // kWantU0: layer 0 is the root alone
      Row("U (layer 0 holds only the root)",
          {Class(kUBegin, kUEnd, &G::ApplyRootLayerEnd),
           Class(kEBegin, kEEnd, nullptr, nullptr, nullptr, {&G::RefuseEndAfterRoot})},
          2),
      // kWantS: the row's self-layer window
      Row("S (window)", {Class(kSBegin, kSEnd, &G::ApplyWindow, &G::TestWindow, &G::AddWindows)}, 1),
      // kAfterS: X values, then the row's first B
      Row("X or B",
          {Class(kXBegin, kXEnd, &G::ApplyX, &G::TestX, &G::AddX),
           Class(kBBegin, kBEnd, &G::ApplyFirstB, &G::TestB, &G::AddB, {&G::RowCanFinish})},
          2),
      // kAfterB: more B, the next vertex, or the layer's end
      Row("B, K, U or E",
          {Class(kBBegin, kBEnd, &G::ApplyNextB, &G::TestB, &G::AddB, {&G::RoomToCloseAfterB}),
           Class(kKBegin, kKEnd, &G::ApplyBlock, nullptr, nullptr, {&G::BelowLayerSizeLimit, &G::RoomForVertex}),
           Class(kUBegin, kUEnd, &G::ApplyLayerEnd, nullptr, nullptr,
                 {&G::LayerClosable, &G::BelowLayerIndexLimit, &G::RoomForLayer}),
           Class(kEBegin, kEEnd, &G::ApplyLayerEnd, nullptr, nullptr, {&G::LayerClosable, &G::RoomForEos})},
          4),
      // kAfterE: the next component or the end
      Row("C or EOS", {kC, Class(k_eos_id, k_eos_id + 1, &G::ApplyEos)}, 2),
      // kEnded
      Row("nothing (after EOS)", {}, 0),
  };
  static_assert(sizeof(kRows) / sizeof(kRows[0]) == static_cast<size_t>(GrammarPhase::kEnded) + 1, "one row per phase");
  static_assert(WellFormed(kRows[0]) && WellFormed(kRows[1]) && WellFormed(kRows[2]) && WellFormed(kRows[3]) &&
                    WellFormed(kRows[4]) && WellFormed(kRows[5]) && WellFormed(kRows[6]) && WellFormed(kRows[7]) &&
                    WellFormed(kRows[8]),
                "rule table rows must be well formed");
  static const bool paired = TestsHaveBulkForms(kRows, sizeof(kRows) / sizeof(kRows[0]));
  if (!paired) std::abort();
  return kRows[static_cast<size_t>(p)];
}

}  // namespace silk
