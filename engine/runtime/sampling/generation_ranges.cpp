// SPDX-License-Identifier: MIT
// The generation settings' range check and the hardware-dependent thread bound.
#include "runtime/sampling/generation_ranges.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>

#include "core/value_text.h"

namespace silk {

namespace {

// An integer setting's whole values as integers ("100000", not "1e+05"), anything else as ValueText.
std::string Text(const SettingRange& r, double v) {
  return r.integer && std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1e18 ? std::to_string(int64_t(v))
                                                                                    : ValueText(v);
}

}  // namespace

SettingRange ranges::Threads() {
  const double hi = std::max(64, static_cast<int>(std::thread::hardware_concurrency()));
  return SettingRange{"threads", 0, hi, true, false, "0 = the physical cores"};
}

std::optional<SettingRange> FindSetting(std::string_view name) {
  for (const SettingRange& r :
       {ranges::kTemperature, ranges::kTopK, ranges::kTopP, ranges::kTopPTemperature, ranges::kMaxTokens,
        ranges::kMaxFaces, ranges::kSurfaceTolerance, ranges::kFaceTolerance, ranges::kCandidates, ranges::kRows,
        ranges::kParallel, ranges::kPointCount, ranges::Threads()})
    if (name == r.name) return r;
  return std::nullopt;
}

Status CheckSetting(const SettingRange& r, double value) {
  if ((value >= r.lo && value <= r.hi) || (r.zero_is_off && value == 0)) return Status::Ok();
  std::string valid =
      r.hi >= INT32_MAX ? "at least " + Text(r, r.lo) : "in [" + Text(r, r.lo) + ", " + Text(r, r.hi) + "]";
  if (r.zero_is_off) valid = "0 or " + valid;
  std::string message = std::string(r.name) + " " + Text(r, value) + " is not " + valid;
  if (*r.meaning) message += std::string(" (") + r.meaning + ")";
  return InvalidArgument(message);
}

}  // namespace silk
