// SPDX-License-Identifier: MIT
// Registers --batch, --format, --shard, --report, --parallel and --overwrite (batch_options.h).
#include "batch_options.h"

#include <CLI/CLI.hpp>

#include "silk/silk.hpp"

namespace silkgen {

void AddBatchOptions(CLI::App& app, BatchArgs& b, const std::string& parallel_range) {
  const char* group = "Many meshes at once (docs/batch.md)";
  app.add_option("--batch", b.source,
                 "Generate for every input of LIST (a text file: one path a line, relative paths from the list's "
                 "folder, '#' comments) or DIR (its files the readers take, not its subfolders), loading the model "
                 "once; -o is then the output folder, OUTDIR/<stem>.<format>. An existing output is skipped "
                 "(--overwrite redoes it); exit 1 if any input failed")
      ->group(group)
      ->type_name("LIST_OR_DIR");
  app.add_option("--format", b.format, "--batch output format")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_mesh_format_name, SILK_FORMAT_OBJ)))  // not by_extension
      ->capture_default_str()
      ->group(group);
  app.add_option(
         "--shard", b.shard,
         "--batch: take every N-th input of the sorted list from the I-th (0 <= I < N), so N processes cover it "
         "once; default: SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT when set, else 0/1")
      ->group(group)
      ->type_name("I/N");
  app.add_option("--report", b.report,
                 "--batch: JSON Lines report, one object per input, appended (default: OUTDIR/silkgen_batch.jsonl, "
                 "or OUTDIR/silkgen_batch.shard-I-of-N.jsonl when sharded)")
      ->group(group)
      ->type_name("FILE");
  app.add_option("--parallel", b.parallel,
                 "--batch: decode up to R meshes together, one decoder call per step for all of them (a model folder "
                 "of decoder contract v4; an older one runs them one after another); every output, report row and "
                 "the exit status are those of --parallel 1, only the time differs; 1 = one after another" +
                     parallel_range)
      ->capture_default_str()
      ->group(group)
      ->type_name("R");
  app.add_flag("--overwrite", b.overwrite, "--batch: generate again for inputs whose output exists")->group(group);
}

}  // namespace silkgen
