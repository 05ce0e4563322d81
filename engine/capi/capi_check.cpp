// SPDX-License-Identifier: MIT
// C API: a token stream checked against the grammar (token_format.md §9, §11): the first rejected id, its
// stable reason code and the rule it breaks.
#include <algorithm>
#include <cstring>

#include "capi/capi_internal.h"
#include "decoder/grammar.h"

using silk::capi::Guard;
using silk::capi::Ok;

extern "C" {

silk_check_params silk_check_default_params(void) {
  silk_check_params p;
  p.struct_size = sizeof(p);
  p.max_length = silk::GrammarOptions{}.max_length;
  p.window_rule = SILK_WINDOW_CANONICAL;
  p.allow_prefix = 0;
  return p;
}

const char* silk_reject_reason_name(int32_t reason) {
  if (reason < 0 || reason > static_cast<int32_t>(silk::RejectReason::kIncomplete)) return "unknown";
  return silk::RejectReasonName(static_cast<silk::RejectReason>(reason));
}

silk_status silk_tokens_check(const silk_tokens* tokens, const silk_check_params* params, silk_check_result* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(tokens && out, "silk_tokens_check: tokens or out is NULL");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_tokens_check", "silk_check_result", out));
    SILK_CAPI_TRY(
        silk::capi::CheckParamsSize("silk_tokens_check", "silk_check_params", params, "silk_check_default_params()"));
    silk::capi::StoreOut(out, silk::capi::Blank<silk_check_result>());
    const silk_check_params p = silk::capi::ReadParams(params, silk_check_default_params());
    SILK_CAPI_REQUIRE(p.max_length >= 0, "silk_tokens_check: max_length must be >= 0 (0 = unlimited)");
    SILK_CAPI_CHECK("silk_tokens_check", silk::capi::CheckEnum("window_rule", p.window_rule, SILK_WINDOW_CANONICAL,
                                                               SILK_WINDOW_UNION, "silk_window_rule"));
    SILK_CAPI_CHECK("silk_tokens_check", silk::capi::CheckFlag("allow_prefix", p.allow_prefix));
    silk::GrammarOptions opt;
    opt.max_length = p.max_length;
    opt.window_rule = p.window_rule == SILK_WINDOW_UNION ? silk::WindowRule::kUnion : silk::WindowRule::kCanonical;
    size_t pos = 0;
    const silk::Rejection r = silk::CheckTokens(tokens->ids, opt, &pos, p.allow_prefix == 0);
    silk_check_result o = silk::capi::Blank<silk_check_result>();
    o.accepted = r.ok() ? 1 : 0;
    o.reason = static_cast<int32_t>(r.reason);
    o.position = r.ok() ? -1 : static_cast<int64_t>(pos);
    o.id = !r.ok() && pos < tokens->ids.size() ? tokens->ids[pos] : -1;
    std::memcpy(o.message, r.message.data(), std::min(r.message.size(), sizeof(o.message) - 1));
    silk::capi::StoreOut(out, o);
    return Ok();
  });
}

}  // extern "C"
