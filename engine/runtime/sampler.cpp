// The sampling chain. Order and arithmetic are part of the golden test's contract with the
// Python reference loop: candidates in ascending id order; scores logit/temperature in double;
// stable sort by score descending (ties: lower id first); top-k cut; softmax in double
// (max-subtracted, std::exp); top-p cut at the smallest prefix whose mass reaches top_p;
// u = Uniform() * kept mass; first index whose running sum exceeds u. The official chain
// (top_p_temperature > 0) replaces the top-p cut: probabilities exp((logit - top) / top_p_temperature)
// in double over the top-k survivors, normalised; an id is kept while the mass before it is
// <= top_p (official_network.md §4: the cumulative mass shifted right by one), then the draw is at
// `temperature`.
#include "runtime/sampler.h"

#include <algorithm>
#include <cmath>

#include "tokenizer/vocabulary_layout.h"

namespace silk {

int32_t Sampler::Sample(const float* logits, const TokenMask* legal) {
  ids_.clear();
  if (legal) {
    for (int32_t id = legal->Next(0); id >= 0; id = legal->Next(id + 1)) ids_.push_back(id);
  } else {
    for (int32_t id = 0; id < vocab::k_model_vocab_size; ++id)
      if (id != vocab::k_pad_id) ids_.push_back(id);
  }
  return SampleFrom(logits, ids_);
}

int32_t Sampler::SampleFrom(const float* logits, const std::vector<int32_t>& candidates) {
  if (candidates.empty()) return -1;
  if (candidates.size() == 1) return candidates[0];
  if (params_.temperature <= 0) {
    int32_t best = candidates[0];
    for (int32_t id : candidates)
      if (logits[id] > logits[best]) best = id;
    return best;
  }
  scored_.clear();
  for (int32_t id : candidates) scored_.push_back({static_cast<double>(logits[id]) / params_.temperature, id});
  auto better = [](const std::pair<double, int32_t>& a, const std::pair<double, int32_t>& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  };
  size_t keep = scored_.size();
  if (params_.top_k > 0 && static_cast<size_t>(params_.top_k) < keep) {
    keep = static_cast<size_t>(params_.top_k);
    std::partial_sort(scored_.begin(), scored_.begin() + keep, scored_.end(), better);
  } else {
    std::sort(scored_.begin(), scored_.end(), better);
  }
  const bool official = params_.top_p_temperature > 0;
  if (official && params_.top_p < 1.0) keep = OfficialTopP(logits, keep);
  probs_.resize(keep);
  const double top = scored_[0].first;
  double mass = 0;
  for (size_t i = 0; i < keep; ++i) mass += (probs_[i] = std::exp(scored_[i].first - top));
  if (!official && params_.top_p < 1.0) {
    double run = 0;
    size_t n = 0;
    while (n < keep) {
      run += probs_[n++];
      if (run >= params_.top_p * mass) break;
    }
    keep = n;
    mass = run;
  }
  const double u = rng_.Uniform() * mass;
  double run = 0;
  for (size_t i = 0; i < keep; ++i) {
    run += probs_[i];
    if (run > u) return scored_[i].second;
  }
  return scored_[keep - 1].second;
}

size_t Sampler::OfficialTopP(const float* logits, size_t keep) {
  probs_.resize(keep);
  const double t = params_.top_p_temperature, top = logits[scored_[0].second];
  double mass = 0;
  for (size_t i = 0; i < keep; ++i) mass += (probs_[i] = std::exp((logits[scored_[i].second] - top) / t));
  double before = 0;  // normalised mass of the ids ahead of i
  for (size_t i = 0; i < keep; ++i) {
    if (before > params_.top_p) return i;
    before += probs_[i] / mass;
  }
  return keep;
}

}  // namespace silk
