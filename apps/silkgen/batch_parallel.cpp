// SPDX-License-Identifier: MIT
// The --parallel loop (batch_parallel.h): inputs are added to one silk_batch while fewer than R
// are in flight, each pulled as it ends (its output written then), and the finished inputs are
// printed and reported in input order as soon as every earlier one is.
#include "batch_parallel.h"

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "../common/interrupt.h"
#include "progress_bar.h"

namespace silkgen {
namespace {

using Clock = std::chrono::steady_clock;

// The progress line: how many meshes are in flight, how many inputs are done, the ids in flight.
struct Progress {
  ProgressBar* bar;
  std::map<int32_t, int64_t> ids;  // by batch index: the latest report's ids of each in flight
  size_t done = 0, total = 0;
  void Draw() {
    int64_t sum = 0;
    for (const auto& [index, n] : ids) sum += n;
    bar->Draw(std::to_string(ids.size()) + " mesh(es) in flight, " + std::to_string(done) + " of " +
              std::to_string(total) + " inputs done, " + std::to_string(sum) + " ids in flight");
  }
};

void OnProgress(int32_t input, const silk_generate_progress* p, void* user) {
  auto* progress = static_cast<Progress*>(user);
  progress->ids[input] = p->tokens;
  progress->Draw();
}

// First SIGINT/SIGTERM: the meshes in flight are cancelled and no other input starts (common/interrupt.h).
int32_t PollCancel(void*) { return silkapp::InterruptSignal() != 0 ? 1 : 0; }

struct Flight {
  size_t k = 0;  // its place in `mine`
  Clock::time_point t0;
};

// Input `in` added to the batch (*index); false when it is decided without generating (*r final
// but for Settle): a refused line, an existing output, an output name refused, a mesh that fails to load.
bool StartInput(silk_batch* batch, const BatchSettings& s, const BatchArgs& args, const BatchInput& in, BatchResult* r,
                int32_t* index) {
  if (!Precheck(s, args, in, r)) return false;
  try {
    silk_cpp::CheckOutputPath(r->output);  // a name the file system cannot hold: refused before generating
    const silk_cpp::Mesh mesh = silk_cpp::Mesh::Load(in.path);
    const silk_generate_input input{sizeof(silk_generate_input), mesh.get(), nullptr, 0};  // copied by the batch
    silk_cpp::Check(silk_batch_add(batch, &input, &s.generate, index));
    return true;
  } catch (const std::exception& e) {
    NoteError(e, r);
    return false;
  }
}

// The next input to end, saved: (batch index, its result).
std::pair<int32_t, BatchResult> EndInput(silk_batch* batch, const BatchSettings& s, const BatchArgs& args,
                                         const std::map<int32_t, Flight>& flights,
                                         const std::vector<BatchInput>& mine) {
  int32_t index = -1;
  silk_mesh* mesh = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  const silk_status status = silk_batch_next(batch, &index, &mesh, nullptr, &st);
  silk_cpp::Mesh result(mesh);
  BatchResult r;
  if (index < 0) silk_cpp::Check(status);  // nothing in flight: a bug of this loop, thrown as such
  const Flight& f = flights.at(index);
  r.output = OutputOf(s, args, mine[f.k]);
  try {
    silk_cpp::Check(status);
    SaveResult(st, result, s, args.format, &r);
    r.status = "ok";
  } catch (const std::exception& e) {
    NoteError(e, &r);
  }
  Settle(f.t0, &r);
  return {index, r};
}

std::unique_ptr<silk_batch, void (*)(silk_batch*)> MakeBatch(const silk_cpp::Model& model, int32_t parallel,
                                                             int32_t rows, Progress* progress) {
  silk_batch_params bp = silk_batch_default_params();
  bp.parallel = parallel;
  bp.rows = rows;
  bp.progress = OnProgress;
  bp.cancel = PollCancel;
  bp.user_data = progress;
  silk_batch* b = nullptr;
  silk_cpp::Check(silk_batch_create(model.get(), &bp, &b));
  return {b, silk_batch_destroy};
}

}  // namespace

Tally RunInputsParallel(const BatchArgs& args, const BatchSettings& settings, const std::vector<BatchInput>& mine,
                        const silk_cpp::Model& model, const BatchRunInfo& run, BatchReport& report,
                        std::string* error) {
  ProgressBar bar(!settings.quiet);
  Progress progress{&bar, {}, 0, mine.size()};
  auto batch = MakeBatch(model, args.parallel, settings.generate.rows, &progress);
  std::vector<std::optional<BatchResult>> done(mine.size());
  std::map<int32_t, Flight> flights;  // by batch index
  Tally tally;
  for (size_t next = 0, shown = 0;;) {
    while (flights.size() < static_cast<size_t>(args.parallel) && next < mine.size() && !silkapp::InterruptSignal()) {
      const size_t k = next++;
      const Flight f{k, Clock::now()};
      BatchResult r;
      int32_t index = -1;
      if (StartInput(batch.get(), settings, args, mine[k], &r, &index)) {
        flights.emplace(index, f);
        continue;
      }
      Settle(f.t0, &r);
      done[k] = r;
    }
    for (; shown < next && done[shown]; ++shown) {  // in input order
      bar.Finish();
      PrintLine(settings, shown + 1, mine.size(), mine[shown], *done[shown]);
      tally.Add(done[shown]->status);
      if (!report.Write(run, mine[shown], *done[shown], error)) return tally;
    }
    if (flights.empty()) {
      if (next >= mine.size() || silkapp::InterruptSignal()) break;
      continue;
    }
    auto [index, r] = EndInput(batch.get(), settings, args, flights, mine);
    done[flights.at(index).k] = std::move(r);
    flights.erase(index);
    progress.ids.erase(index);
    ++progress.done;
  }
  return tally;
}

}  // namespace silkgen
