// SPDX-License-Identifier: MIT
// The legal-token mask: the rule table (grammar_rules.cpp) read in bulk. For the current phase's
// row, every class whose gates pass adds the ids its test admits (its bulk form), so the mask
// holds exactly the ids Grammar::Step would accept.
#include "decoder/grammar.h"

namespace silk {

void Grammar::ComputeMask() {
  mask_.Clear();
  messages_ = false;  // the gates' verdicts only; no refusal texts
  // The checks of Step that hold in every phase and do not depend on the id (the others, a model
  // id and not PAD, hold for every id of every class: grammar_rules.cpp checks the ranges).
  if (NotEnded(vocab::k_eos_id).ok() && RoomForToken(vocab::k_eos_id).ok()) {
    const GrammarPhaseRule& row = RuleRow(phase_);
    for (int32_t i = 0; i < row.count; ++i) {
      const GrammarClassRule& cls = row.classes[i];
      bool open = true;
      for (GrammarGate gate : cls.gates) {
        if (!gate || !open) break;
        open = (this->*gate)(cls.begin).ok();
      }
      if (!open) continue;
      if (cls.bulk)
        (this->*cls.bulk)(&mask_);
      else
        mask_.SetRange(cls.begin, cls.end);
    }
  }
  messages_ = true;
}

const TokenMask& Grammar::LegalMask() {
  if (!mask_valid_) {
    ComputeMask();
    mask_valid_ = true;
  }
  return mask_;
}

int32_t Grammar::NextClosableSize(int32_t from) const {
  // Inside a vertex's X list every size of the row set is still reachable (more X may follow).
  if (phase_ == GrammarPhase::kAfterS) return row_sizes_.Next(from);
  return sizes_.Next(from);
}

int32_t Grammar::Forced() { return LegalMask().Single(); }

}  // namespace silk
