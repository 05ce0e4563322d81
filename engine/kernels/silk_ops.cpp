// SPDX-License-Identifier: MIT
// One ai.silk domain per onnxruntime API table, made once and kept for the process: sessions
// refer to its op tables for as long as they live.
#include "kernels/silk_ops.h"

#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "kernels/attention/cached_attention_op.h"
#include "kernels/attention/cross_attention_op.h"
#include "kernels/quant/half_matmul_op.h"
#include "kernels/quant/int4_matmul_op.h"

namespace silk {

namespace {

struct Registration {
  CachedAttentionOp attention[2];  // float16 and int8 caches, one op name
  CrossAttentionOp cross[2];       // float32 and float16 key/value rows, one op name
  Int4MatMulOp int4;
  HalfMatMulOp half;
  OrtCustomOpDomain* domain = nullptr;
};

OrtStatus* MakeDomain(Registration* r, const OrtApi* api) {
  InitCachedAttentionOp(&r->attention[0], api, CacheElement::kFloat16);
  InitCachedAttentionOp(&r->attention[1], api, CacheElement::kInt8);
  InitCrossAttentionOp(&r->cross[0], api, CacheElement::kFloat32);
  InitCrossAttentionOp(&r->cross[1], api, CacheElement::kFloat16);
  InitInt4MatMulOp(&r->int4, api);
  InitHalfMatMulOp(&r->half, api);
  SILK_ORT_TRY(api->CreateCustomOpDomain(kSilkOpDomain, &r->domain));
  OrtCustomOp* ops[] = {&r->attention[0], &r->attention[1], &r->cross[0], &r->cross[1], &r->int4, &r->half};
  for (OrtCustomOp* op : ops)
    if (OrtStatus* st = api->CustomOpDomain_Add(r->domain, op)) {
      api->ReleaseCustomOpDomain(r->domain);
      return st;
    }
  return nullptr;
}

}  // namespace

OrtStatus* AddSilkOps(OrtSessionOptions* options, const OrtApi* api) {
  static std::mutex mutex;
  // Never destroyed: sessions may outlive static destruction; reachable, so not a leak to LSan.
  static auto* made = new std::vector<std::pair<const OrtApi*, Registration*>>();
  std::lock_guard<std::mutex> lock(mutex);
  Registration* r = nullptr;
  for (auto& m : *made)
    if (m.first == api) r = m.second;
  if (!r) {
    auto fresh = std::make_unique<Registration>();
    SILK_ORT_TRY(MakeDomain(fresh.get(), api));
    r = fresh.release();
    made->emplace_back(api, r);
  }
  return api->AddCustomOpDomain(options, r->domain);
}

}  // namespace silk
