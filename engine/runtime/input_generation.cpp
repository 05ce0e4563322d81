// SPDX-License-Identifier: MIT
// An input's preparation and its chosen candidate's conclusion (input_generation.h).
#include "runtime/input_generation.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>

#include "runtime/generation_output.h"
#include "runtime/model/model_impl.h"

namespace silk {

StatusOr<PreparedInput> PrepareInput(const Model& model, const GenerationRequest& request, const GenerationInput& input,
                                     const CancelCheck& cancel, const CancelCheck& flag) {
  PreparedInput out;
  SILK_ASSIGN_OR_RETURN(out.plan, ResolveRequest(request, model.config()));
  const std::string context = (input.name.empty() ? std::string("input") : input.name) + ": ";
  if (Status s = ValidateGenerationInput(input, flag); !s.ok()) return s.WithContext(context);
  const auto t0 = std::chrono::steady_clock::now();
  StatusOr<PreparedPoints> pts = out.plan.raw_points
                                     ? RawModelPoints(input, model.config().dims.n_points)
                                     : PrepareModelPoints(input, out.plan.preprocessing, request.seed, cancel);
  if (!pts.ok()) return pts.status().WithContext(context);
  out.points = std::move(pts->rows);
  out.transform = pts->transform;
  out.prepare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

SessionResult ConcludeChoice(CandidateChoice* choice, const PreparedInput& input, bool complete, const RowsRun* rows) {
  SessionResult out;
  out.generation = choice->Take();
  GenerationStats& st = out.generation.stats;
  if (!complete) st.stop_reason = StopReason::kCancelled;
  if (rows) {  // the candidates overlapped: wall time, and the feeds' time once
    st.rows = rows->rows;
    st.kv_cache_bytes = rows->cache_bytes;
    st.seconds.decoder = rows->decoder_seconds;
    st.generation_seconds = std::max(0.0, rows->wall_seconds - st.seconds.build_mesh - st.seconds.scoring);
  }
  out.output = FinishOutput(&out.generation, input.transform);  // verdicts into the stats
  st.seconds.load_input += input.prepare_seconds;
  st.seconds.total = st.seconds.load_input + st.generation_seconds + st.seconds.build_mesh + st.seconds.scoring;
  return out;
}

bool CandidatesAsRows(const GenerateOptions& options, const Model& model) {
  return options.rows > 1 && options.candidates > 1 && model.impl().rows_together;
}

}  // namespace silk
