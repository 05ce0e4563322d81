#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Generate a mesh through libsilk's C API from Python with nothing but ctypes.

    python3 examples/generate_ctypes.py --library build/engine/libsilk.so \\
        --model models/default --input samples/torus_knot.obj --out out.obj [--seed 1]

Shows the whole API surface of one-call generation: silk_model_load, silk_generator_create,
silk_generator_run with progress and cancel callbacks, stats, the output mesh and its parts.
--check additionally asserts the results (used by ctest capi_generate_ctypes).
"""

import argparse
import ctypes as C
import sys

from pathlib import Path

# The C declarations (structs, callback types, signatures of silk.h) are the single copy, pure
# ctypes, that the silk_mesh binding is built on: bindings/python/silk_mesh/_capi.py.
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bindings" / "python"))
from silk_mesh._capi import (
    CANCEL_FN,
    PROGRESS_FN,
    SILK_ERR_CANCELLED,
    SILK_OK,
    GenerateInput,  # noqa: E402
    GenerateStats as Stats,
    ModelInfo,
    declare,
)


def load(path):
    lib = C.CDLL(path)
    declare(lib)
    return lib


def check(lib, status, what):
    if status != SILK_OK:
        raise RuntimeError(f"{what}: status {status}: {lib.silk_last_error().decode()}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--library", required=True)
    ap.add_argument("--model", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("--out")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--max-tokens", type=int, default=0)
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()

    lib = load(a.library)
    if not lib.silk_generation_available():
        print("this libsilk has no generation (built without onnxruntime)")
        return 1
    opts = lib.silk_model_default_params()
    opts.threads = 1
    model, gen, mesh, out, tokens = C.c_void_p(), C.c_void_p(), C.c_void_p(), C.c_void_p(), C.c_void_p()
    check(lib, lib.silk_model_load(a.model.encode(), C.byref(opts), C.byref(model)), "silk_model_load")
    info = ModelInfo()
    check(lib, lib.silk_model_get_info(model, C.byref(info)), "silk_model_get_info")
    print(f"model {info.config.decode()}: {info.n_layers} layers, d {info.d_model}, {info.threads} thread(s)")
    check(lib, lib.silk_generator_create(model, C.byref(gen)), "silk_generator_create")
    check(lib, lib.silk_mesh_load(a.input.encode(), None, C.byref(mesh)), "silk_mesh_load")

    seen = []

    @PROGRESS_FN
    def on_progress(p, _user):
        seen.append(p.contents.tokens)

    params = lib.silk_generate_default_params()
    params.seed, params.max_tokens, params.progress = a.seed, a.max_tokens, on_progress
    stats = Stats()  # struct_size set (sizeof), as every silk_*_stats the caller passes
    source = GenerateInput(mesh=mesh)  # or points= / point_rows= (rows of x y z nx ny nz)
    check(
        lib,
        lib.silk_generator_run(gen, C.byref(source), C.byref(params), C.byref(out), C.byref(tokens), C.byref(stats)),
        "silk_generator_run",
    )
    n = C.c_size_t()  # the size query, then the copy (silk.h's one rule)
    check(lib, lib.silk_mesh_copy_triangle_components(out, None, 0, C.byref(n)), "count components")
    n_tri = n.value
    parts = (C.c_int32 * max(n_tri, 1))()
    check(lib, lib.silk_mesh_copy_triangle_components(out, parts, n_tri, C.byref(n)), "copy components")
    print(
        f"{stats.tokens} ids ({stats.forced_tokens} forced) -> {stats.faces} faces in "
        f"{len(set(parts[:n_tri]))} part(s), {stats.tokens_per_second:.0f} tok/s, stop reason {stats.stop_reason}, "
        f"edge-manifold {bool(stats.edge_manifold)}, vertex-manifold {bool(stats.vertex_manifold)}, "
        f"oriented {bool(stats.consistently_oriented)}, watertight {bool(stats.watertight)}"
    )
    if a.out:
        check(lib, lib.silk_mesh_save(out, a.out.encode(), None), "silk_mesh_save")

    failures = []
    if a.check:
        if not (stats.faces > 0 and n_tri == stats.faces and stats.edge_manifold and stats.consistently_oriented):
            failures.append("result mesh")
        n_ids = C.c_size_t()
        check(lib, lib.silk_tokens_copy(tokens, None, 0, C.byref(n_ids)), "count ids")
        if n_ids.value != stats.tokens or len(seen) < stats.tokens - 1 or seen != sorted(seen):
            failures.append(f"tokens/progress ({n_ids.value}, {len(seen)} callbacks)")

        @CANCEL_FN
        def cancel_soon(_user):
            cancel_soon.calls += 1
            return 1 if cancel_soon.calls > 10 else 0

        cancel_soon.calls = 0
        params.cancel = cancel_soon
        out2 = C.c_void_p()
        st = lib.silk_generator_run(gen, C.byref(source), C.byref(params), C.byref(out2), None, None)
        if st != SILK_ERR_CANCELLED or out2.value:
            failures.append(f"cancel gave status {st}")
        bad = C.c_void_p()
        st = lib.silk_model_load(b"/nonexistent/model", None, C.byref(bad))
        if st == SILK_OK or b"not found" not in lib.silk_last_error():
            failures.append(f"bad model dir gave status {st}")
    for h, f in (
        (tokens, lib.silk_tokens_destroy),
        (out, lib.silk_mesh_destroy),
        (mesh, lib.silk_mesh_destroy),
        (gen, lib.silk_generator_destroy),
        (model, lib.silk_model_destroy),
    ):
        f(h)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
