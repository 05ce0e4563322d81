// The one-call generation from a silk_mesh or from rows of points through silk_generator_run
// (C API 1.0 phase 2 has one entry point), so the capi tests that only need a generation read short.
#pragma once
#include <cstddef>

#include "silk/silk.h"
#include "silk/silk.hpp"

namespace silk::testing {

inline silk_status GenerateFromMesh(silk_generator* g, const silk_mesh* mesh, const silk_generate_params* p,
                                    silk_mesh** out, silk_tokens** tokens, silk_generate_stats* stats) {
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = mesh;
  return silk_generator_run(g, &in, p, out, tokens, stats);
}
inline silk_status GenerateFromPoints(silk_generator* g, const double* points, size_t rows, const silk_generate_params* p,
                                      silk_mesh** out, silk_tokens** tokens, silk_generate_stats* stats) {
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.points = points;
  in.point_rows = rows;
  return silk_generator_run(g, &in, p, out, tokens, stats);
}

}  // namespace silk::testing
