// SPDX-License-Identifier: MIT
// The grammar's rule table: each phase described once, as the classes of ids it may take and
// the predicates an id of each class must pass. Accept/Check (Grammar::Step) and the legal mask
// (Grammar::ComputeMask) both walk this table, so they cannot disagree by construction.
//
// How a row is read (grammar_rules.cpp holds the table, grammar_predicates.cpp the predicates):
//  * Step(id): the first class whose id range holds `id`; none -> kWrongClass (kEosNotAfterE for
//    EOS). Then the class's `test` (the id-dependent predicate) and its `gates` (predicates that
//    do not depend on the id) in order; the first refusal is the answer. Then `apply`.
//  * Mask: for each class whose gates pass, `bulk` adds exactly the ids its `test` admits (each
//    pair is written over one shared description, see grammar_predicates.cpp), or the whole range
//    when the class has no test.
#pragma once
#include <array>
#include <climits>
#include <cstdint>

#include "decoder/grammar_limits.h"
#include "decoder/grammar_rejection.h"
#include "decoder/layer_size_set.h"
#include "decoder/token_mask.h"

namespace silk {

class Grammar;

// A predicate that does not depend on the id within its class (room left, layer closable...):
// the refusal, or ok. `id` only names the token in the refusal's message.
using GrammarGate = Rejection (Grammar::*)(int32_t id) const;
// The id-dependent predicate of a class, and the same predicate over the whole class: `bulk`
// adds to the mask every id of the class that `test` admits.
using GrammarIdTest = Rejection (Grammar::*)(int32_t id) const;
using GrammarIdBulk = void (Grammar::*)(TokenMask* mask) const;
// Applies an admitted id to the state (Accept only; runs after the id joined the history).
using GrammarApply = void (Grammar::*)(int32_t id);

inline constexpr int32_t kGrammarMaxGates = 3;

struct GrammarClassRule {
  int32_t begin = 0, end = 0;                         // candidate ids [begin, end), from the vocabulary layout
  GrammarIdTest test = nullptr;                       // nullptr: every id of the range passes
  GrammarIdBulk bulk = nullptr;                       // set exactly when `test` is
  std::array<GrammarGate, kGrammarMaxGates> gates{};  // in order; a nullptr ends the list
  GrammarApply apply = nullptr;
  bool Holds(int32_t id) const { return id >= begin && id < end; }
};

struct GrammarPhaseRule {
  const char* expects = "";                   // the classes in words, for kWrongClass refusals
  std::array<GrammarClassRule, 4> classes{};  // disjoint id ranges; `count` are used
  int32_t count = 0;
  const GrammarClassRule* Find(int32_t id) const {
    for (int32_t i = 0; i < count; ++i)
      if (classes[i].Holds(id)) return &classes[i];
    return nullptr;
  }
};

// The X values one row may carry if its layer closes with a given size (token_format.md §6, §11.2), as
// three disjoint intervals, one per kind of statement, each with its length-budget verdict.
// An X value e is admitted at that size iff some interval holding e fits; the test reads this
// per value, the mask adds the fitting intervals.
struct XRowRule {
  enum Kind { kForward, kWrap, kEcho, kKinds };
  int32_t hi = -1;                                                   // largest X value at this size: min(N - 10, 190)
  std::array<int32_t, kKinds> first{{0, 0, 0}}, last{{-1, -1, -1}};  // [first, last], empty if last < first
  std::array<bool, kKinds> fits{};  // the cheapest completion after such a value fits the cap
  bool Covers(int32_t e) const {
    for (int k = 0; k < kKinds; ++k)
      if (e >= first[k] && e <= last[k]) return true;
    return false;
  }
  bool Admits(int32_t e) const {
    for (int k = 0; k < kKinds; ++k)
      if (fits[k] && e >= first[k] && e <= last[k]) return true;
    return false;
  }
};

// The layer sizes an S token can keep open, split by what the window w decides (token_format.md §11.2):
// `far` sizes (>= b+9) see no wrap-around bit, only the layer-1 chain rule (w's bit 0) applies;
// each `near` size is judged by Grammar::WindowOk. Both within the length budget.
struct WindowSizeRule {
  LayerSizeSet far;
  std::array<int32_t, grammar_limits::kSelfWindow> near{};
  int32_t near_count = 0;
  int32_t budget_max = 0;  // largest size whose completion fits the cap
};

}  // namespace silk
