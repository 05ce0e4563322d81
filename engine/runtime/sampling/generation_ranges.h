// SPDX-License-Identifier: MIT
// The one table of the valid range of every generation setting (sampling, caps, guidance, best of
// N, encoder points, threads), so the C API, model.json's "sampling", the generator and model
// loading refuse a value by the same rule, with one message naming the setting, the value and the
// range. Clients (silkgen, silk_mesh, the Blender add-on) keep no copy: they pass values on and
// report libsilk's message.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/status.h"
#include "mesh/point_preprocessing.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

// The fewest ids a complete mesh takes (one triangle with its layer ends and EOS); a smaller
// max_tokens or max_seq_len - 1 can only end in an empty mesh and is refused up front.
inline constexpr int32_t kMinMeshTokens = 14;

// One setting's valid values: lo..hi inclusive (hi of INT32_MAX: no upper bound), or 0 as well
// where 0 means "off" / "the model's" below lo. NaN is never valid.
struct SettingRange {
  const char* name;     // the field's name in silk_generate_params / silk_model_params
  double lo, hi;        // inclusive
  bool integer;         // an integer setting (its bounds printed as integers)
  bool zero_is_off;     // 0 is valid too, below lo
  const char* meaning;  // what the special values mean, for the message ("" if none)
};

// Best of N's rows (ranges::kRows) when neither the caller nor model.json ("sampling.rows") names
// them: how many of the candidates are decoded together, at most. Rows of one decoder call read
// every weight once and each candidate's ids are exactly those it gets alone (same seeds), so the
// result does not depend on rows, only the time does; with N candidates min(rows, N) rows are used.
inline constexpr int32_t kDefaultRows = 8;

namespace ranges {
inline constexpr SettingRange kTemperature{"temperature", 0, 100, false, false, "0 = greedy"};
inline constexpr SettingRange kTopK{"top_k", 0, vocab::k_model_vocab_size, true, false, "0 = off"};
inline constexpr SettingRange kTopP{"top_p", 0, 1, false, false, "1 = off"};
inline constexpr SettingRange kTopPTemperature{"top_p_temperature", 0, 100, false, false, "0 = at the temperature"};
inline constexpr SettingRange kMaxTokens{
    "max_tokens", kMinMeshTokens, INT32_MAX, true, true, "0 = the model's limit; 14 ids make the smallest mesh"};
inline constexpr SettingRange kMaxFaces{"max_faces", 0, INT32_MAX, true, false, "0 = off"};
inline constexpr SettingRange kSurfaceTolerance{"surface_tolerance", 0, 127, true, false, "cells of 128; 0 = off"};
inline constexpr SettingRange kFaceTolerance{"face_tolerance", 0.5, 64, false, false, "cells of 128"};
inline constexpr SettingRange kCandidates{"candidates", 1, 64, true, false, ""};
// Best of N: how many of the candidates are decoded together, at most (GenerationSession).
inline constexpr SettingRange kRows{"rows", 1, 64, true, false, ""};
// A batch of inputs (MeshRows): how many meshes are decoded together, at most.
inline constexpr SettingRange kParallel{"parallel", 1, 16, true, false, "1 = one after another"};
inline constexpr SettingRange kPointCount{"point_count", 1, kMaxPreprocessingPoints, true, true, "0 = the model's"};
// onnxruntime's intra-op threads: 0 (the physical cores) up to the larger of 64 and the
// hardware's threads.
SettingRange Threads();
}  // namespace ranges

// The setting of that name (every entry above, threads included), or nullopt: how the C API's
// silk_param_range / silk_param_check reach the table.
std::optional<SettingRange> FindSetting(std::string_view name);

// Ok when `value` is valid for `range`; otherwise InvalidArgument "temperature 150 is not in
// [0, 100] (0 = greedy)".
Status CheckSetting(const SettingRange& range, double value);

}  // namespace silk
