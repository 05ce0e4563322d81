# SPDX-License-Identifier: MIT
"""Runs an exported model folder's graphs with onnxruntime from Python (no libsilk): encoder,
decoder chunks over a growing KV cache, greedy decoding. Used by the importer's fidelity check
and by the tests; the C++ runtime is the production path."""

from __future__ import annotations

import numpy as np


def silk_ops_library() -> str:
    """libsilk_ops, onnxruntime's custom-op library for the ai.silk ops of the fp16- and int8-cache
    decoders (onnx/kv_precision.py): $SILK_OPS_LIBRARY, else the file beside the libsilk that
    silk_mesh finds ($SILK_LIBRARY, the package's lib/, the build tree, ...)."""
    import os
    from silk_mesh import _platform_libs
    from silk_mesh._library import library_path

    env = os.environ.get("SILK_OPS_LIBRARY")
    if env:
        return env
    return os.path.join(os.path.dirname(library_path()), _platform_libs.ops_library_name())


def uses_silk_ops(path) -> bool:
    """Whether graph `path` imports libsilk's ai.silk operator domain (read without its external
    data). False for a file onnx cannot read: onnxruntime then names the problem."""
    import onnx
    from .silk_ops import SILK_DOMAIN

    try:
        model = onnx.load(str(path), load_external_data=False)
    except Exception:
        return False
    return any(o.domain == SILK_DOMAIN for o in model.opset_import)


def session(path, threads: int = 1):
    """An onnxruntime session on the CPU; a graph with ai.silk ops gets libsilk_ops registered."""
    import onnxruntime as ort

    so = ort.SessionOptions()
    so.intra_op_num_threads = threads
    so.log_severity_level = 3
    if uses_silk_ops(path):
        lib = silk_ops_library()
        try:
            so.register_custom_ops_library(lib)
        except Exception as e:
            raise RuntimeError(
                f"{path}: uses libsilk's ai.silk ops, and libsilk_ops ('{lib}') cannot be "
                f"registered with onnxruntime: {e} (set SILK_LIBRARY to a built libsilk with "
                f"libsilk_ops beside it, or SILK_OPS_LIBRARY)"
            ) from e
    return ort.InferenceSession(str(path), so, providers=["CPUExecutionProvider"])


class DecoderState:
    """Per-layer caches (past of exactly P rows; onnxruntime returns P+T rows) and cross K/V."""

    def __init__(self, decoder, cross_kv: np.ndarray):
        self.decoder = decoder
        self.n_layers, _, h, _, d = cross_kv.shape
        # cross_* are float16 in the silk form of the cache variants (converted once, as libsilk does).
        types = {i.name: i.type for i in decoder.get_inputs()}
        self.rows = "new_positions" in types  # contract v4: run as one row (R = S = 1)
        cross_dtype = np.float16 if types.get("cross_key_0") == "tensor(float16)" else np.float32
        self.cross = {}
        for l in range(self.n_layers):
            self.cross[f"cross_key_{l}"] = np.ascontiguousarray(cross_kv[l, 0][None], cross_dtype)
            self.cross[f"cross_value_{l}"] = np.ascontiguousarray(cross_kv[l, 1][None], cross_dtype)
        # The cache's element type is the graph's (float16 for a files.kv_fp16 variant; int8 rows
        # of d values + a float32 scale for a files.kv_int8 one).
        cache = types.get("past_key_0", "tensor(float)")
        dtype = {"tensor(float16)": np.float16, "tensor(int8)": np.int8}.get(cache, np.float32)
        row = d + 4 if dtype == np.int8 else d
        self.past = [np.zeros((1, h, 0, row), dtype) for _ in range(2 * self.n_layers)]
        self.length = 0

    def run(self, ids, positions=None) -> np.ndarray:
        """Feeds ids (contract positions length.. by default); returns logits [T, 10269]."""
        ids = np.asarray(ids, np.int64).reshape(1, -1)
        t = ids.shape[1]
        if positions is None:
            positions = np.arange(self.length, self.length + t)
        feeds = {
            "input_ids": ids,
            "positions": np.asarray(positions, np.int64).reshape(1, -1),
            "seqlens_k": np.array([self.length + t - 1], np.int32),
            "total_sequence_length": np.array(self.length + t, np.int32),
            **self.cross,
        }
        if self.rows:
            feeds.update(new_positions=np.array([t], np.int32), cross_source=np.array([0], np.int32))
        for l in range(self.n_layers):
            feeds[f"past_key_{l}"], feeds[f"past_value_{l}"] = self.past[2 * l], self.past[2 * l + 1]
        out = self.decoder.run(None, feeds)
        self.past = out[1:]
        self.length += t
        return out[0][0]


def greedy(decoder, cross_kv: np.ndarray, bos_id: int, eos_id: int, max_tokens: int) -> list[int]:
    """Argmax decoding from BOS, one token per step with the cache; stops after EOS (kept)."""
    state = DecoderState(decoder, cross_kv)
    logits = state.run([bos_id])
    out = []
    while len(out) < max_tokens:
        tok = int(np.argmax(logits[-1]))
        out.append(tok)
        if tok == eos_id:
            break
        logits = state.run([tok])
    return out


def teacher_forced(decoder, cross_kv: np.ndarray, ids) -> np.ndarray:
    """Logits of the whole sequence (BOS first) in one chunk, [len(ids), 10269]."""
    return DecoderState(decoder, cross_kv).run(ids)
