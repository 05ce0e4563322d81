// SPDX-License-Identifier: MIT
// Random legal walks over the grammar (see random_walk.h): uniform within the legal ids of the
// chosen token class, the class picked to reach a per-layer target size and then close.
#include "decoder/random_walk.h"

#include <algorithm>
#include <utility>

#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

std::vector<int32_t> Members(const TokenMask& m, int32_t begin, int32_t end) {
  std::vector<int32_t> out;
  for (int32_t id = m.Next(begin); id >= 0 && id < end; id = m.Next(id + 1)) out.push_back(id);
  return out;
}

int32_t Pick(const std::vector<int32_t>& v, std::mt19937_64* rng) {
  return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(*rng)];
}

// Keeps only the ids that pass `keep`, unless none does (then all stay), in their order.
template <class Keep>
void NarrowTo(std::vector<int32_t>* ids, Keep keep) {
  std::vector<int32_t> kept;
  for (int32_t id : *ids)
    if (keep(id)) kept.push_back(id);
  if (!kept.empty()) ids->swap(kept);
}

// One walk: each step looks at the grammar's phase and picks the next id by the rule for that
// phase (component boundary, vertex set S, the ids after S, after B, anything else). Every
// Step* returns false to end the walk (an id the grammar refused).
class Walker {
 public:
  Walker(Grammar* g, std::mt19937_64* rng, const RandomWalkOptions& o) : g_(g), rng_(rng), o_(o) {}

  std::vector<int32_t> Run() {
    for (int32_t step = 0; step < 1 << 20; ++step) {
      const TokenMask& m = g_->LegalMask();
      if (m.Empty()) break;
      const GrammarPhase ph = g_->phase();
      int32_t layer = -1, n = 0;
      CurrentLayer(&layer, &n);
      if (ph == GrammarPhase::kEnded) break;
      if (!Step(m, ph, layer, n)) break;
    }
    return std::move(out_);
  }

 private:
  bool Step(const TokenMask& m, GrammarPhase ph, int32_t layer, int32_t n) {
    if (ph == GrammarPhase::kStart || ph == GrammarPhase::kAfterE) return StepBoundary(m, ph);
    if (ph == GrammarPhase::kWantS) return Take(PickVertexSet(m, n));
    if (ph == GrammarPhase::kAfterS) return Take(TrialClose(AfterSCandidates(m), m, n));
    if (ph == GrammarPhase::kAfterB) return StepAfterB(m, layer, n);
    return Take(UniformLegal(m));
  }

  // The current component's last layer index (-1 before any) and its vertex count so far.
  void CurrentLayer(int32_t* layer, int32_t* n) const {
    const auto& components = g_->stream().components;
    if (components.empty()) return;
    const auto& layers = components.back().layers;
    *layer = static_cast<int32_t>(layers.size()) - 1;
    *n = layers.empty() ? 0 : static_cast<int32_t>(layers.back().vertices.size());
  }

  bool Take(int32_t id) {
    Rejection r = g_->Accept(id);
    if (!r.ok()) return false;
    out_.push_back(id);
    return true;
  }

  void NewTarget(int32_t layer) {
    const int32_t lo = layer == 1 ? 2 : 1;
    target_ = std::uniform_int_distribution<int32_t>(lo, std::max(lo, o_.max_layer_size))(*rng_);
  }

  // Start or after E: a new component (always first; later with chance 0.3 up to the cap) or EOS.
  bool StepBoundary(const TokenMask& m, GrammarPhase ph) {
    const bool more = m.Test(vocab::kCBegin) &&
                      (ph == GrammarPhase::kStart || (components_ < o_.max_components && unit_(*rng_) < 0.3));
    if (!Take(more ? vocab::kCBegin : vocab::k_eos_id)) return false;
    if (more) {
      ++components_;
      last_layers_ = std::uniform_int_distribution<int32_t>(1, std::max(1, o_.max_layers))(*rng_);
    }
    if (ph == GrammarPhase::kStart || more) NewTarget(1);
    return true;
  }

  // S: prefer ids that keep the target size reachable, then (mostly) sparse ones.
  int32_t PickVertexSet(const TokenMask& m, int32_t n) {
    std::vector<int32_t> cands = Members(m, vocab::kSBegin, vocab::kSEnd);
    const int32_t aim = std::max(target_, n);
    NarrowTo(&cands, [&](int32_t id) { return g_->WindowFits(aim, id - vocab::kSBegin); });
    if (unit_(*rng_) < o_.sparse)
      NarrowTo(&cands, [](int32_t id) { return __builtin_popcount(static_cast<unsigned>(id - vocab::kSBegin)) <= 2; });
    return Pick(cands, rng_);
  }

  // After S: the legal X and B ids shuffled, B first unless a free X is drawn (or no B is legal).
  std::vector<int32_t> AfterSCandidates(const TokenMask& m) {
    auto xs = Members(m, vocab::kXBegin, vocab::kXEnd);
    auto bs = Members(m, vocab::kBBegin, vocab::kBEnd);
    std::shuffle(xs.begin(), xs.end(), *rng_);
    std::shuffle(bs.begin(), bs.end(), *rng_);
    if (unit_(*rng_) < o_.sparse)
      NarrowTo(&bs, [](int32_t id) {
        return __builtin_popcount(static_cast<unsigned>(BetweenCasePattern((id - vocab::kBBegin) % kBetweenCases))) <=
               1;
      });
    const bool prefer_b = !bs.empty() && (xs.empty() || unit_(*rng_) >= o_.extra_x);
    std::vector<int32_t> cands = prefer_b ? bs : xs;
    const auto& other = prefer_b ? xs : bs;
    cands.insert(cands.end(), other.begin(), other.end());
    return cands;
  }

  // The first candidate (of up to 256 tried on a clone) after which the layer can still close at
  // the target size; else the first candidate, or the first legal id.
  int32_t TrialClose(const std::vector<int32_t>& cands, const TokenMask& m, int32_t n) {
    int32_t chosen = -1;
    const int32_t aim = std::max(target_, n);
    bool b_failed = false;  // all B ids end the X list alike: one failed trial rules them out
    for (size_t i = 0, tried = 0; i < cands.size() && tried < 256 && chosen < 0; ++i) {
      const bool is_b = cands[i] >= vocab::kBBegin && cands[i] < vocab::kBEnd;
      if (is_b && b_failed) continue;
      ++tried;
      Grammar trial = g_->Clone();
      if (trial.Accept(cands[i]).ok() && trial.NextClosableSize(aim) == aim)
        chosen = cands[i];
      else if (is_b)
        b_failed = true;
    }
    if (chosen < 0) chosen = cands.empty() ? m.Next(0) : cands[0];
    return chosen;
  }

  // After B: sometimes another B; close the layer (U up to the component's layer count, else E)
  // once it reaches the target; else a vertex K, a B, or the first legal id.
  bool StepAfterB(const TokenMask& m, int32_t layer, int32_t n) {
    if (g_->NextClosableSize(n) != n && g_->NextClosableSize(target_) != target_)
      target_ = std::max(n, g_->NextClosableSize(n));
    const bool can_close = m.Test(vocab::kEBegin);
    auto bs = Members(m, vocab::kBBegin, vocab::kBEnd);
    if (!bs.empty() && unit_(*rng_) < o_.extra_b) return Take(Pick(bs, rng_));
    if (can_close && (n >= target_ || !m.Test(vocab::kKBegin))) {
      const bool up = m.Test(vocab::kUBegin) && layer < last_layers_;
      if (!Take(up ? vocab::kUBegin : vocab::kEBegin)) return false;
      if (up) NewTarget(layer + 1);
      return true;
    }
    if (m.Test(vocab::kKBegin))  // K ids are legal all together
      return Take(std::uniform_int_distribution<int32_t>(vocab::kKBegin, vocab::kKEnd - 1)(*rng_));
    if (!bs.empty()) return Take(Pick(bs, rng_));
    return Take(m.Next(0));
  }

  // K, O, U after the root: uniform over the legal ids (rejection sampling inside the class).
  int32_t UniformLegal(const TokenMask& m) {
    const int32_t lo = m.Next(0);
    int32_t hi = lo;
    for (int32_t id = lo; id >= 0; id = m.Next(id + 1)) hi = id;
    int32_t id = -1;
    for (int32_t t = 0; t < 64 && id < 0; ++t) {
      const int32_t c = std::uniform_int_distribution<int32_t>(lo, hi)(*rng_);
      if (m.Test(c)) id = c;
    }
    if (id < 0) id = Pick(Members(m, 0, TokenMask::kBits), rng_);
    return id;
  }

  Grammar* g_;
  std::mt19937_64* rng_;
  const RandomWalkOptions& o_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  int32_t components_ = 0, target_ = 2, last_layers_ = 1;
  std::vector<int32_t> out_;
};

}  // namespace

std::vector<int32_t> RandomLegalWalk(Grammar* g, std::mt19937_64* rng, const RandomWalkOptions& o) {
  return Walker(g, rng, o).Run();
}

}  // namespace silk
