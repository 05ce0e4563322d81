// SPDX-License-Identifier: MIT
// GenerationStats: what one generation did and how long each phase took (silkgen --stats,
// silk_generate_stats). Plain data, filled by Generator and GenerationSession.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/stop_reason.h"

namespace silk {

struct PhaseSeconds {
  double load_input = 0;     // input check + normalising + surface sampling (session)
  double encoder = 0;        // encoder.onnx
  double decoder = 0;        // decoder.onnx calls (all chunks)
  double grammar = 0;        // legal masks + Accept
  double sampling = 0;       // the sampling chain
  double build_mesh = 0;     // tokens -> faces (+ hole handling)
  double guidance = 0;       // surface guidance: distance field + K/O mask restriction
  double face_guidance = 0;  // face guidance: the faces of the legal B ids scored (hard: masked)
  double scoring = 0;        // candidates' Chamfer scores
  double total = 0;
};

// One best-of-N candidate: its sampling seed and its score (symmetric Chamfer distance to the
// encoder's points in the model frame; +infinity without a face of positive area).
struct CandidateScore {
  uint64_t seed = 0;
  double score = 0;
  int32_t faces = 0;
  int64_t tokens = 0;
  double seconds = 0;  // its generation (encoder + token loop)
};

struct GenerationStats {
  int64_t tokens = 0;         // generated ids, EOS included when reached
  int64_t forced_tokens = 0;  // ids the grammar forced (no sampling; model step skipped)
  int64_t sampled_tokens = 0;
  int64_t model_calls = 0;                     // decoder.onnx runs
  int64_t fed_positions = 0;                   // positions written to the KV cache (BOS included)
  StopReason stop_reason = StopReason::kNone;  // kNone while running
  std::string dead_end;                        // grammar_dead_end: where (a grammar bug; reported, not fatal)
  int32_t faces = 0, vertices = 0, components = 0;
  int32_t holes_found = 0, holes_repaired = 0, faces_added = 0, window_findings = 0;
  int32_t open_edges = 0;
  bool edge_manifold = false, watertight = false, consistently_oriented = false;
  // Vertex fans (docs/grammar.md): verdict and count on the written mesh; the rule's actions.
  bool vertex_manifold = false;
  int32_t nonmanifold_vertices = 0;
  int32_t fan_gaps_closed = 0, vertices_split = 0;
  // Parts reversed to face the input's normals (orient_to_input; runtime/input_orientation.h).
  int32_t parts_flipped = 0;
  int64_t illegal_at = -1;  // unconstrained mode: index of the first id the grammar rejects
  std::string illegal_reason;
  int64_t kv_cache_bytes = 0;
  int32_t threads = 0;
  bool int8 = false;
  std::string decoder = "fp32";       // decoder precision in use: fp32, int8, int4
  std::string kv_precision = "fp32";  // self-K/V cache element type: fp32, fp16
  int32_t model_version = 0;          // model.json model_version of the folder
  int32_t decoder_contract = 3;       // the decoder graph in use: 3 (one row), 4 (R rows per call)
  // Surface guidance: vertex ids sampled under it, and vertex ids (sampled or forced) taken
  // outside the tolerance because no legal id was within it.
  int64_t guided_tokens = 0, guidance_fallbacks = 0;
  // Face guidance: B ids sampled under it, and of those the steps where no legal B id's faces
  // passed (hard: the best-scoring ones kept; soft: all penalised).
  int64_t face_guided_tokens = 0, face_fallbacks = 0;
  // Best of N: every candidate in order (one entry for a single generation), the chosen one.
  std::vector<CandidateScore> candidates;
  int32_t chosen_candidate = 0;
  int32_t rows = 1;  // rows used (min(rows, N)): candidates decoded together (GenerationSession)
  PhaseSeconds seconds;
  double generation_seconds = 0;  // encoder + token loop
  double tokens_per_second = 0;   // tokens / token-loop seconds
  double forced_share() const { return tokens ? static_cast<double>(forced_tokens) / tokens : 0; }
};

}  // namespace silk
