// SPDX-License-Identifier: MIT
// One input's way into and out of a generation, shared by GenerationSession (one input, step by
// step) and MeshRows (many inputs as rows of one decoder): the request resolved and the input
// prepared into the encoder's points before; the chosen candidate in the input frame after.
#pragma once
#include <cstdint>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "io/io_mesh.h"
#include "mesh/normalize.h"
#include "runtime/candidates.h"
#include "runtime/generation_input.h"
#include "runtime/generation_request.h"
#include "runtime/generator.h"
#include "runtime/model/model.h"

namespace silk {

// A finished generation: the chosen candidate (ids, grid mesh with its parts, report, stats with
// every candidate's score) and its mesh in the input frame.
struct SessionResult {
  GenerateResult generation;
  IoMesh output;
};

// A resolved request with its input's encoder points.
struct PreparedInput {
  GenerationPlan plan;
  std::vector<float> points;
  NormalizeTransform transform;  // model frame -> input frame (identity for raw points)
  double prepare_seconds = 0;
};

// ResolveRequest (its messages name the field), then the input checked (polling `flag`) and its
// points prepared (raw as given, else the plan's pre-processing, polling `cancel`); the input's
// errors start with its name ("input: " when it has none).
StatusOr<PreparedInput> PrepareInput(const Model& model, const GenerationRequest& request, const GenerationInput& input,
                                     const CancelCheck& cancel, const CancelCheck& flag);

// How the candidates of an input ran when they ran as rows (their stats count the run's wall time
// and the shared feeds' time, not the sum of the candidates').
struct RowsRun {
  int32_t rows = 1;
  int64_t cache_bytes = 0;
  double decoder_seconds = 0, wall_seconds = 0;
};

// The chosen candidate of `choice` (emptied) in the input frame with its verdicts and the whole
// run's times; `complete` false marks it cancelled. `rows`: null when one after another.
SessionResult ConcludeChoice(CandidateChoice* choice, const PreparedInput& input, bool complete, const RowsRun* rows);

// The one rule for whether a generation's candidates run as rows (GenerationSession, MeshRows):
// more than one row and one candidate asked, and a decoder whose rows are each their own
// (Model::Impl::rows_together: contract v4, not INT8).
bool CandidatesAsRows(const GenerateOptions& options, const Model& model);

}  // namespace silk
