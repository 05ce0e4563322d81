// SPDX-License-Identifier: MIT
// silkgen --batch's own options (the generation options are silkgen's usual ones, applied to
// every input); their help text is the one description of the batch mode on the command line.
#pragma once
#include <string>

namespace CLI {
class App;
}

namespace silkgen {

struct BatchArgs {
  std::string source;  // --batch LIST_OR_DIR; empty: a single-input run
  std::string format = "glb", shard, report;
  int parallel = 1;  // --parallel: meshes decoded together, at most
  bool overwrite = false;
  bool shard_given = false, report_given = false;  // the option was on the command line (even as "")
};

// `parallel_range`: libsilk's range text for --parallel (" [1..16]").
void AddBatchOptions(CLI::App& app, BatchArgs& b, const std::string& parallel_range);

}  // namespace silkgen
