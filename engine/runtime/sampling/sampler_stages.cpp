// SPDX-License-Identifier: MIT
// The numeric stages. Order and arithmetic are part of the golden test's contract with the
// Python reference loop: candidates in ascending id order; scores logit/temperature in double;
// stable sort by score descending (ties: lower id first); top-k cut; softmax in double
// (max-subtracted, std::exp); top-p cut at the smallest prefix whose mass reaches top_p;
// u = Uniform() * kept mass; first index whose running sum exceeds u. The official chain
// (top_p_temperature > 0) replaces the top-p cut: probabilities exp((logit - top) / top_p_temperature)
// in double over the top-k survivors, normalised; an id is kept while the mass before it is
// <= top_p (official_network.md §4: the cumulative mass shifted right by one), then the draw is at
// `temperature`.
#include "runtime/sampling/sampler_stages.h"

#include <algorithm>
#include <cmath>

#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

// The mask's ids (null: every id but PAD). No candidate: no choice; one: chosen without a draw.
class CandidatesStage : public SamplerStage {
 public:
  void Apply(SamplerCandidates* c) override {
    c->ids.clear();
    if (c->mask) {
      for (int32_t id = c->mask->Next(0); id >= 0; id = c->mask->Next(id + 1)) c->ids.push_back(id);
    } else {
      for (int32_t id = 0; id < vocab::k_model_vocab_size; ++id)
        if (id != vocab::k_pad_id) c->ids.push_back(id);
    }
    if (c->ids.size() > 1) return;
    c->id = c->ids.empty() ? -1 : c->ids[0];
    c->done = true;
  }
};

// temperature <= 0: the largest logit (lowest id on ties), no draw.
class GreedyStage : public SamplerStage {
 public:
  void Apply(SamplerCandidates* c) override {
    int32_t best = c->ids[0];
    for (int32_t id : c->ids)
      if (c->logits[id] > c->logits[best]) best = id;
    c->id = best;
    c->done = true;
  }
};

class TemperatureStage : public SamplerStage {
 public:
  explicit TemperatureStage(double temperature) : temperature_(temperature) {}
  void Apply(SamplerCandidates* c) override {
    c->scored.clear();
    for (int32_t id : c->ids) c->scored.push_back({static_cast<double>(c->logits[id]) / temperature_, id});
    c->keep = c->scored.size();
  }

 private:
  double temperature_;
};

// Ranks the candidates best first (ties: lower id first); keeps the first k (0: all).
class TopKStage : public SamplerStage {
 public:
  explicit TopKStage(int32_t k) : k_(k) {}
  void Apply(SamplerCandidates* c) override {
    auto better = [](const std::pair<double, int32_t>& a, const std::pair<double, int32_t>& b) {
      return a.first > b.first || (a.first == b.first && a.second < b.second);
    };
    c->keep = c->scored.size();
    if (k_ > 0 && static_cast<size_t>(k_) < c->keep) {
      c->keep = static_cast<size_t>(k_);
      std::partial_sort(c->scored.begin(), c->scored.begin() + c->keep, c->scored.end(), better);
    } else {
      std::sort(c->scored.begin(), c->scored.end(), better);
    }
  }

 private:
  int32_t k_;
};

// The official top-p cut, on the ranked survivors' logits at its own temperature.
class OfficialTopPStage : public SamplerStage {
 public:
  OfficialTopPStage(double top_p, double temperature) : top_p_(top_p), temperature_(temperature) {}
  void Apply(SamplerCandidates* c) override {
    std::vector<double>& p = c->probs;
    p.resize(c->keep);
    const double top = c->logits[c->scored[0].second];
    double mass = 0;
    for (size_t i = 0; i < c->keep; ++i)
      mass += (p[i] = std::exp((c->logits[c->scored[i].second] - top) / temperature_));
    double before = 0;  // normalised mass of the ids ahead of i
    for (size_t i = 0; i < c->keep; ++i) {
      if (before > top_p_) {
        c->keep = i;
        return;
      }
      before += p[i] / mass;
    }
  }

 private:
  double top_p_, temperature_;
};

// Unnormalised softmax of the survivors' scores (max-subtracted) and their mass.
class SoftmaxStage : public SamplerStage {
 public:
  void Apply(SamplerCandidates* c) override {
    c->probs.resize(c->keep);
    const double top = c->scored[0].first;
    c->mass = 0;
    for (size_t i = 0; i < c->keep; ++i) c->mass += (c->probs[i] = std::exp(c->scored[i].first - top));
  }
};

// The smallest ranked prefix whose mass reaches top_p.
class TopPStage : public SamplerStage {
 public:
  explicit TopPStage(double top_p) : top_p_(top_p) {}
  void Apply(SamplerCandidates* c) override {
    double run = 0;
    size_t n = 0;
    while (n < c->keep) {
      run += c->probs[n++];
      if (run >= top_p_ * c->mass) break;
    }
    c->keep = n;
    c->mass = run;
  }

 private:
  double top_p_;
};

// One uniform draw over the survivors' weights.
class DrawStage : public SamplerStage {
 public:
  explicit DrawStage(SplitMix64* rng) : rng_(rng) {}
  void Apply(SamplerCandidates* c) override {
    const double u = rng_->Uniform() * c->mass;
    double run = 0;
    c->done = true;
    for (size_t i = 0; i < c->keep; ++i) {
      run += c->probs[i];
      if (run > u) {
        c->id = c->scored[i].second;
        return;
      }
    }
    c->id = c->scored[c->keep - 1].second;
  }

 private:
  SplitMix64* rng_;
};

}  // namespace

void AddSamplingStages(SamplerChain* chain, const SamplingParams& p) {
  chain->Add(std::make_unique<CandidatesStage>());
  if (p.temperature <= 0) {
    chain->Add(std::make_unique<GreedyStage>());
    return;
  }
  const bool official = p.top_p_temperature > 0, top_p = p.top_p < 1.0;
  chain->Add(std::make_unique<TemperatureStage>(p.temperature));
  chain->Add(std::make_unique<TopKStage>(p.top_k));
  if (official && top_p) chain->Add(std::make_unique<OfficialTopPStage>(p.top_p, p.top_p_temperature));
  chain->Add(std::make_unique<SoftmaxStage>());
  if (!official && top_p) chain->Add(std::make_unique<TopPStage>(p.top_p));
  chain->Add(std::make_unique<DrawStage>(chain->rng()));
}

}  // namespace silk
