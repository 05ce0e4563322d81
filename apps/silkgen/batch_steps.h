// SPDX-License-Identifier: MIT
// One --batch input's steps, shared by the loop one after another (batch_run.cpp) and the
// --parallel loop (batch_parallel.cpp), so both decide, save, print and count an input alike.
#pragma once
#include <chrono>
#include <cstddef>
#include <exception>
#include <string>

#include "batch_inputs.h"
#include "batch_options.h"
#include "batch_report.h"
#include "batch_run.h"
#include "silk/silk.hpp"

namespace silkgen {

struct Tally {
  size_t ok = 0, skipped = 0, failed = 0, cancelled = 0;
  void Add(const std::string& status) {
    (status == "ok" ? ok : status == "skipped" ? skipped : status == "failed" ? failed : cancelled) += 1;
  }
};

// OUTDIR/<stem>.<format> ("" for a refused list line).
std::string OutputOf(const BatchSettings& s, const BatchArgs& args, const BatchInput& in);
// r->output set; false when the input is decided without generating (a refused list line:
// failed; an existing output without --overwrite: skipped).
bool Precheck(const BatchSettings& s, const BatchArgs& args, const BatchInput& in, BatchResult* r);
// The figures into *r and the mesh saved to r->output (atomically: libsilk's writers).
void SaveResult(const silk_generate_stats& st, const silk_cpp::Mesh& result, const BatchSettings& s,
                const std::string& format, BatchResult* r);
// An exception's status ("cancelled" after a signal's cancel, else "failed") and message into *r.
void NoteError(const std::exception& e, BatchResult* r);
// A result that is not ok keeps no figures; the seconds since t0.
void Settle(std::chrono::steady_clock::time_point t0, BatchResult* r);
// The input's line on stderr ([k/n], ok / skipped, failures in the error form even with -q).
void PrintLine(const BatchSettings& s, size_t k, size_t n, const BatchInput& in, const BatchResult& r);

}  // namespace silkgen
