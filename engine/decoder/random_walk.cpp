// Random legal walks over the grammar (see random_walk.h): uniform within the legal ids of the
// chosen token class, the class picked to reach a per-layer target size and then close.
#include "decoder/random_walk.h"

#include <algorithm>

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

}  // namespace

std::vector<int32_t> RandomLegalWalk(Grammar* g, std::mt19937_64* rng, const RandomWalkOptions& o) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int32_t components = 0, target = 2, last_layers = 1;
  std::vector<int32_t> out;
  auto take = [&](int32_t id) {
    Rejection r = g->Accept(id);
    if (!r.ok()) return false;
    out.push_back(id);
    return true;
  };
  auto new_target = [&](int32_t layer) {
    const int32_t lo = layer == 1 ? 2 : 1;
    target = std::uniform_int_distribution<int32_t>(lo, std::max(lo, o.max_layer_size))(*rng);
  };
  for (int32_t step = 0; step < 1 << 20; ++step) {
    const TokenMask& m = g->LegalMask();
    if (m.Empty()) break;
    const GrammarPhase ph = g->phase();
    const auto& layers = g->stream().components.empty() ? std::vector<StreamLayer>{} : g->stream().components.back().layers;
    const int32_t layer = static_cast<int32_t>(layers.size()) - 1;
    const int32_t n = layers.empty() ? 0 : static_cast<int32_t>(layers.back().vertices.size());
    if (ph == GrammarPhase::kEnded) break;
    if (ph == GrammarPhase::kStart || ph == GrammarPhase::kAfterE) {
      const bool more = m.Test(vocab::kCBegin) && (ph == GrammarPhase::kStart || (components < o.max_components && unit(*rng) < 0.3));
      if (!take(more ? vocab::kCBegin : vocab::k_eos_id)) break;
      if (more) {
        ++components;
        last_layers = std::uniform_int_distribution<int32_t>(1, std::max(1, o.max_layers))(*rng);
      }
      if (ph == GrammarPhase::kStart || more) new_target(1);
      continue;
    }
    if (ph == GrammarPhase::kWantS || ph == GrammarPhase::kAfterS) {
      // Prefer tokens that keep the target size reachable.
      std::vector<int32_t> cands;
      if (ph == GrammarPhase::kWantS) {
        cands = Members(m, vocab::kSBegin, vocab::kSEnd);
        std::vector<int32_t> fit;
        const int32_t aim = std::max(target, n);
        for (int32_t id : cands)
          if (g->WindowFits(aim, id - vocab::kSBegin)) fit.push_back(id);
        if (!fit.empty()) cands.swap(fit);
        if (unit(*rng) < o.sparse) {
          std::vector<int32_t> sparse;
          for (int32_t id : cands)
            if (__builtin_popcount(static_cast<unsigned>(id - vocab::kSBegin)) <= 2) sparse.push_back(id);
          if (!sparse.empty()) cands.swap(sparse);
        }
        if (!take(Pick(cands, rng))) break;
        continue;
      } else {
        auto xs = Members(m, vocab::kXBegin, vocab::kXEnd);
        auto bs = Members(m, vocab::kBBegin, vocab::kBEnd);
        std::shuffle(xs.begin(), xs.end(), *rng);
        std::shuffle(bs.begin(), bs.end(), *rng);
        if (unit(*rng) < o.sparse) {
          std::vector<int32_t> few;
          for (int32_t id : bs)
            if (__builtin_popcount(static_cast<unsigned>(BetweenCasePattern((id - vocab::kBBegin) % kBetweenCases))) <= 1) few.push_back(id);
          if (!few.empty()) bs.swap(few);
        }
        const bool prefer_b = !bs.empty() && (xs.empty() || unit(*rng) >= o.extra_x);
        cands = prefer_b ? bs : xs;
        const auto& other = prefer_b ? xs : bs;
        cands.insert(cands.end(), other.begin(), other.end());
      }
      int32_t chosen = -1;
      const int32_t aim = std::max(target, n);
      bool b_failed = false;  // all B ids end the X list alike: one failed trial rules them out
      for (size_t i = 0, tried = 0; i < cands.size() && tried < 256 && chosen < 0; ++i) {
        const bool is_b = cands[i] >= vocab::kBBegin && cands[i] < vocab::kBEnd;
        if (is_b && b_failed) continue;
        ++tried;
        Grammar trial = g->Clone();
        if (trial.Accept(cands[i]).ok() && trial.NextClosableSize(aim) == aim) chosen = cands[i];
        else if (is_b) b_failed = true;
      }
      if (chosen < 0) chosen = cands.empty() ? m.Next(0) : cands[0];
      if (!take(chosen)) break;
      continue;
    }
    if (ph == GrammarPhase::kAfterB) {
      if (g->NextClosableSize(n) != n && g->NextClosableSize(target) != target) target = std::max(n, g->NextClosableSize(n));
      const bool can_close = m.Test(vocab::kEBegin);
      auto bs = Members(m, vocab::kBBegin, vocab::kBEnd);
      if (!bs.empty() && unit(*rng) < o.extra_b) {
        if (!take(Pick(bs, rng))) break;
        continue;
      }
      if (can_close && (n >= target || !m.Test(vocab::kKBegin))) {
        const bool up = m.Test(vocab::kUBegin) && layer < last_layers;
        if (!take(up ? vocab::kUBegin : vocab::kEBegin)) break;
        if (up) new_target(layer + 1);
        continue;
      }
      if (m.Test(vocab::kKBegin)) {  // K ids are legal all together
        if (!take(std::uniform_int_distribution<int32_t>(vocab::kKBegin, vocab::kKEnd - 1)(*rng))) break;
        continue;
      }
      if (!bs.empty()) {
        if (!take(Pick(bs, rng))) break;
        continue;
      }
      if (!take(m.Next(0))) break;
      continue;
    }
    // K, O, U after the root: uniform over the legal ids (rejection sampling inside the class).
    const int32_t lo = m.Next(0);
    int32_t hi = lo;
    for (int32_t id = lo; id >= 0; id = m.Next(id + 1)) hi = id;
    int32_t id = -1;
    for (int32_t t = 0; t < 64 && id < 0; ++t) {
      const int32_t c = std::uniform_int_distribution<int32_t>(lo, hi)(*rng);
      if (m.Test(c)) id = c;
    }
    if (id < 0) id = Pick(Members(m, 0, TokenMask::kBits), rng);
    if (!take(id)) break;
  }
  return out;
}

}  // namespace silk
