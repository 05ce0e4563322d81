// C API: the round-trip check (encode, decode, compare faces with the encoder's processed mesh),
// the tokenizer's exactness measure as one call.
#include <cstring>

#include "capi/capi_internal.h"
#include "mesh/normalize.h"
#include "tokenizer/roundtrip_check.h"
#include "tokenizer/tokenizer.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

extern "C" {

silk_status silk_roundtrip(const silk_mesh* mesh, const silk_encode_params* params, silk_roundtrip_report* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(mesh && out, "silk_roundtrip: mesh or out is NULL");
    std::memset(out, 0, sizeof(*out));
    const silk_encode_params p = params ? *params : silk_encode_default_params();
    SILK_CAPI_REQUIRE((p.normalize == 0 || p.normalize == 1) && (p.nonmanifold_processing == 0 || p.nonmanifold_processing == 1),
                      "silk_roundtrip: normalize and nonmanifold_processing take 0 or 1");
    SILK_CAPI_REQUIRE(!p.normalize || (p.normalize_bound > 0 && p.normalize_bound <= 1),
                      "silk_roundtrip: normalize_bound must lie in (0, 1]");
    silk::IoMesh normalized;
    if (p.normalize) {
      auto n = silk::NormalizeMesh(mesh->mesh, p.normalize_bound);
      if (!n.ok()) return SetError(n.status());
      normalized = std::move(*n);
    }
    silk::EncodeOptions opt;
    opt.nonmanifold_processing = p.nonmanifold_processing != 0;
    auto enc = silk::EncodeMesh(p.normalize ? normalized : mesh->mesh, opt);
    if (!enc.ok()) return SetError(enc.status());
    auto dec = silk::DecodeTokens(enc->tokens);
    if (!dec.ok()) return SetError(dec.status().WithContext("decoding our own tokens: "));
    const silk::RoundTripReport r = silk::CompareRoundTrip(*enc, *dec);
    out->tokens = static_cast<int64_t>(enc->tokens.size());
    out->processed_faces = r.processed_faces;
    out->representable_faces = r.representable_faces;
    out->recovered = r.recovered;
    out->reversed = r.reversed;
    out->missing = r.missing;
    out->extra = r.extra;
    out->decoded_faces = static_cast<int64_t>(dec->faces.size());
    out->exact = r.exact() ? 1 : 0;
    return Ok();
  });
}

}  // extern "C"
