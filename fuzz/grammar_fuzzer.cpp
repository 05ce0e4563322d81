// SPDX-License-Identifier: MIT
// libFuzzer target: arbitrary token arrays through the grammar. Checks that Accept agrees with
// the legal mask, that rejected tokens leave the state unchanged, that Rewind reproduces the
// mask, and that accepted prefixes build a mesh meeting the guarantees. Input bounded to 4096
// ids; the grammar's memory is bounded by the accepted tokens.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace silk;
  if (size < 2) return 0;
  GrammarOptions opt;
  opt.window_rule = (data[0] & 1) ? WindowRule::kUnion : WindowRule::kCanonical;
  opt.max_length = (data[0] & 2) ? 10240 : 600;
  Grammar g(opt);
  const size_t n = std::min<size_t>((size - 1) / 2, 4096);
  for (size_t i = 0; i < n; ++i) {
    int32_t raw = data[1 + 2 * i] | (data[2 + 2 * i] << 8);
    // Mostly legal-looking ids: the high bit picks "the k-th legal id" to get deep.
    int32_t id = raw % 10270;
    const TokenMask& m = g.LegalMask();
    if (raw & 0x8000) {
      const int32_t count = m.Count();
      if (count == 0) break;
      int32_t k = (raw & 0x7fff) % count;
      id = m.Next(0);
      while (k-- > 0) id = m.Next(id + 1);
    }
    const bool legal = m.Test(id);
    const size_t before = g.size();
    Rejection r = g.Accept(id);
    if (legal != r.ok()) std::abort();
    if (!r.ok() && g.size() != before) std::abort();
    if (g.Ended()) break;
  }
  if (g.size() > 2 && (data[0] & 4)) {
    Grammar h = g.Clone();
    if (!h.Rewind(g.size() / 2).ok()) std::abort();
    Grammar fresh(opt);
    for (size_t i = 0; i < g.size() / 2; ++i)
      if (!fresh.Accept(g.tokens()[i]).ok()) std::abort();
    if (h.LegalMask().words() != fresh.LegalMask().words()) std::abort();
  }
  auto mesh = BuildMeshSoFar(g, MeshBuildOptions{(data[0] & 8) ? HolePolicy::kRepair : HolePolicy::kOff, 8}, nullptr);
  if (mesh.ok()) {
    // An open component whose layer 1 is not closed yet has no face; all else must hold.
    const std::string why = CheckMeshGuarantees(*mesh);
    const bool complete = g.CanEnd() || g.Ended();
    if (!why.empty() && (complete || why.rfind("component ", 0) != 0)) std::abort();
  }
  return 0;
}
