// SPDX-License-Identifier: MIT
// One GenerationSession run as the runtime tests drive it: Start, Advance(max_ids, until) until
// done, Finish; every step is expected to succeed (an empty result when one does not); and the
// comparison of two runs' choices.
#pragma once
#include <cstdint>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "runtime/generation_session.h"

namespace silk::testing {

inline SessionResult RunSession(GenerationSession* s, const GenerationRequest& r, const GenerationInput& input,
                                int32_t max_ids = 1 << 30, AdvanceUntil until = AdvanceUntil::kIds,
                                const GenerateCallbacks& cb = {}) {
  const Status started = s->Start(r, input, cb);
  EXPECT_TRUE(started.ok()) << started.ToString();
  while (started.ok() && !s->done()) {
    const Status st = s->Advance(max_ids, until);
    EXPECT_TRUE(st.ok()) << st.ToString();
    if (!st.ok()) break;
  }
  auto out = s->Finish();
  EXPECT_TRUE(out.ok()) << out.status().ToString();
  return out.ok() ? std::move(*out) : SessionResult{};
}

// The same choice: ids, triangles, chosen index and every candidate's seed, score, ids and faces.
inline void ExpectSameChoice(const SessionResult& a, const SessionResult& b, const std::string& what) {
  EXPECT_EQ(a.generation.tokens, b.generation.tokens) << what;
  EXPECT_EQ(a.output.triangles, b.output.triangles) << what;
  EXPECT_EQ(a.generation.stats.chosen_candidate, b.generation.stats.chosen_candidate) << what;
  ASSERT_EQ(a.generation.stats.candidates.size(), b.generation.stats.candidates.size()) << what;
  for (size_t i = 0; i < a.generation.stats.candidates.size(); ++i) {
    const CandidateScore &x = a.generation.stats.candidates[i], &y = b.generation.stats.candidates[i];
    EXPECT_EQ(x.seed, y.seed) << what << " candidate " << i;
    EXPECT_EQ(x.score, y.score) << what << " candidate " << i;
    EXPECT_EQ(x.tokens, y.tokens) << what << " candidate " << i;
    EXPECT_EQ(x.faces, y.faces) << what << " candidate " << i;
  }
}

}  // namespace silk::testing
