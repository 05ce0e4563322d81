# SPDX-License-Identifier: MIT
# Turns engine/tokenizer/vocabulary_layout.json (the single source of truth for token ids)
# into a C++ header of constexpr constants at configure time.
function(silk_generate_vocabulary json_in header_out)
  file(READ "${json_in}" J)
  set(out "// Generated from tokenizer/vocabulary_layout.json by cmake/SilkVocabulary.cmake. Do not edit.\n#pragma once\n#include <cstdint>\nnamespace silk::vocab {\n")
  foreach(key token_format_version quant_bins blocks_per_axis offsets_per_axis self_window between_window
              between_cases layer_vertex_limit layer_count_limit max_faces max_seq_length
              format_vocab_size eos_id pad_id pad_in_data model_vocab_size)
    string(JSON v GET "${J}" ${key})
    string(APPEND out "inline constexpr int32_t k_${key} = ${v};\n")
  endforeach()
  string(JSON fmt GET "${J}" token_format)
  string(APPEND out "inline constexpr const char* k_token_format = \"${fmt}\";\n")
  foreach(cls C U E X S B K O)
    string(JSON b GET "${J}" ranges ${cls} 0)
    string(JSON e GET "${J}" ranges ${cls} 1)
    string(APPEND out "inline constexpr int32_t k${cls}Begin = ${b};\ninline constexpr int32_t k${cls}End = ${e};\n")
  endforeach()
  string(APPEND out "}  // namespace silk::vocab\n")
  file(WRITE "${header_out}.tmp" "${out}")
  configure_file("${header_out}.tmp" "${header_out}" COPYONLY)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${json_in}")
endfunction()
