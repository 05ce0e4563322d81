// SPDX-License-Identifier: MIT
// One GenerationSession run as the runtime tests drive it: Start, Advance(max_ids, until) until
// done, Finish; every step is expected to succeed (an empty result when one does not).
#pragma once
#include <cstdint>
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

}  // namespace silk::testing
