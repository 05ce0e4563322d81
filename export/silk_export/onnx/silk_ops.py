# SPDX-License-Identifier: MIT
"""libsilk's onnxruntime operator domain and its operators' names (docs/model_contract.md), for the
graph rewrites that target them (kv_precision.py, cross_attention.py, int4_matmul.py, half_logits.py)."""

SILK_DOMAIN = "ai.silk"
SILK_ATTENTION, SILK_CROSS, SILK_INT4 = "CachedAttention", "CrossAttention", "Int4MatMul"
SILK_HALF = "HalfMatMul"
