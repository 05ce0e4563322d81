// SPDX-License-Identifier: MIT
// C API: the generation settings' range table (runtime/sampling/generation_ranges.h) by field
// name, so clients show and check ranges without a copy of their own.
#if defined(SILK_HAVE_RUNTIME)
#include <string>

#include "capi/capi_internal.h"
#include "runtime/sampling/generation_ranges.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

namespace {

silk::StatusOr<silk::SettingRange> Find(const char* function, const char* name) {
  if (!name) return silk::InvalidArgument(std::string(function) + ": name is NULL");
  auto r = silk::FindSetting(name);
  if (!r) return silk::InvalidArgument(std::string(function) + ": '" + name + "' is not a generation setting");
  return *r;
}

}  // namespace

extern "C" {

silk_status silk_param_range(const char* name, double* lo, double* hi, int32_t* zero_too) {
  return Guard([&] {
    auto r = Find("silk_param_range", name);
    if (!r.ok()) return SetError(r.status());
    if (lo) *lo = r->lo;
    if (hi) *hi = r->hi;
    if (zero_too) *zero_too = r->zero_is_off ? 1 : 0;
    return Ok();
  });
}

silk_status silk_param_check(const char* name, double value) {
  return Guard([&] {
    auto r = Find("silk_param_check", name);
    if (!r.ok()) return SetError(r.status());
    return SetError(silk::CheckSetting(*r, value));
  });
}

}  // extern "C"
#endif
