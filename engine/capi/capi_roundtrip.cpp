// SPDX-License-Identifier: MIT
// C API: the round-trip check (encode, decode, compare faces with the encoder's processed mesh),
// the tokenizer's exactness measure as one call.
#include "capi/capi_internal.h"
#include "tokenizer/roundtrip_check.h"
#include "tokenizer/tokenizer.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

extern "C" {

silk_status silk_mesh_roundtrip(const silk_mesh* mesh, const silk_encode_params* params, silk_roundtrip_report* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(mesh && out, "silk_mesh_roundtrip: mesh or out is NULL");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_mesh_roundtrip", "silk_roundtrip_report", out));
    silk::capi::StoreOut(out, silk::capi::Blank<silk_roundtrip_report>());
    SILK_CAPI_TRY(silk::capi::CheckEncodeParams("silk_mesh_roundtrip", params));
    auto enc = silk::capi::EncodeWithParams(*mesh, params);
    if (!enc.ok()) return SetError(enc.status());
    auto dec = silk::DecodeTokens(enc->tokens);
    if (!dec.ok()) return SetError(dec.status().WithContext("decoding our own tokens: "));
    const silk::RoundTripReport r = silk::CompareRoundTrip(*enc, *dec);
    silk_roundtrip_report o = silk::capi::Blank<silk_roundtrip_report>();
    o.tokens = static_cast<int64_t>(enc->tokens.size());
    o.processed_faces = r.processed_faces;
    o.representable_faces = r.representable_faces;
    o.recovered = r.recovered;
    o.reversed = r.reversed;
    o.missing = r.missing;
    o.extra = r.extra;
    o.decoded_faces = static_cast<int64_t>(dec->faces.size());
    o.exact = r.exact() ? 1 : 0;
    silk::capi::StoreOut(out, o);
    return Ok();
  });
}

}  // extern "C"
