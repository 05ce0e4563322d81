#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A caller built against libsilk 1.0 keeps working (docs/c_api.md "Struct growth"): the 1.0 symbol
silk_model_default_params@SILK_1.0 still returns the 1.0 layout of silk_model_params (12 bytes,
no kv_precision), silk_model_load and silk_model_get_info accept the 1.0 sizes and write nothing
past them, and the current symbol returns today's size. The same for silk_generate_default_params
(@SILK_1.0: the struct before 1.3's face guidance fields; @SILK_1.3: before 1.5's rows; @SILK_1.5:
today's): their bytes equal the first bytes of today's defaults, and silk_generator_run accepts the
1.0 and 1.3 params and stats sizes without writing past them. The functions 1.3 added are bound to the SILK_1.3 node alone, those 1.4
added (the enum names) to SILK_1.4 alone, those 1.5 added (best of N's candidates; and
silk_generate_default_params@@SILK_1.5) to SILK_1.5 alone, those 1.6 added (the batch,
silk_batch_*) to SILK_1.6 alone. Linux
(ELF symbol versions) only.

    capi_abi_check.py LIBSILK MODEL_DIR
"""

import ctypes
import sys


class Params10(ctypes.Structure):
    _fields_ = [("struct_size", ctypes.c_uint32), ("threads", ctypes.c_int32), ("decoder", ctypes.c_int32)]


class Params11(ctypes.Structure):
    _fields_ = Params10._fields_ + [("kv_precision", ctypes.c_int32)]


SILK_1_3 = ("silk_models_dir", "silk_model_default_dir", "silk_model_find", "silk_models_list")
# C API 1.4: silk_<enum>_name and silk_<enum>_from_name (silk_stop_reason_name is 1.0's), and the
# generation settings' ranges (silk_param_range, silk_param_check).
SILK_1_4_ENUMS = (
    "log_level",
    "mesh_format",
    "window_rule",
    "hole_policy",
    "preprocess_kind",
    "decoder_precision",
    "kv_precision",
    "arch",
    "orientation",
    "face_guidance",
    "advance_until",
)
SILK_1_4 = tuple(f"silk_{e}_{kind}" for e in SILK_1_4_ENUMS for kind in ("name", "from_name")) + (
    "silk_stop_reason_from_name",
    "silk_param_range",
    "silk_param_check",
)
# C API 1.5: best of N's candidates while they run.
SILK_1_5 = (
    "silk_candidate_state_name",
    "silk_candidate_state_from_name",
    "silk_generator_candidate_count",
    "silk_generator_get_candidate",
    "silk_generator_get_candidate_mesh",
)
SILK_1_6 = (
    "silk_batch_default_params",
    "silk_batch_create",
    "silk_batch_destroy",
    "silk_batch_add",
    "silk_batch_close",
    "silk_batch_next",
    "silk_batch_counts",
    "silk_batch_cancel",
)
INFO_INTS = (
    "d_model",
    "n_layers",
    "n_heads",
    "head_dim",
    "n_latents",
    "default_points",
    "max_seq_len",
    "threads",
    "int8",
    "decoder",
    "arch",
    "encoder_points",
)


class Info10(ctypes.Structure):
    _fields_ = [("struct_size", ctypes.c_uint32), ("config", ctypes.c_char * 32)] + [
        (n, ctypes.c_int32) for n in INFO_INTS
    ]


def both_versions(lib, libc, name, old_type, version, new_type):
    """The default params `name` returns through its SILK_1.0 symbol and through `version`'s."""
    old = libc.dlvsym(lib._handle, name.encode(), b"SILK_1.0")
    new = libc.dlvsym(lib._handle, name.encode(), version.encode())
    if not old or not new:
        raise LookupError(f"{name}: SILK_1.0 {bool(old)}, {version} {bool(new)} (both must exist)")
    return ctypes.CFUNCTYPE(old_type)(old)(), ctypes.CFUNCTYPE(new_type)(new)()


def main(lib_path, model_dir):
    lib = ctypes.CDLL(lib_path)
    libc = ctypes.CDLL(None)
    libc.dlvsym.restype = ctypes.c_void_p
    libc.dlvsym.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_char_p]
    failures = []
    try:
        p10, p11 = both_versions(lib, libc, "silk_model_default_params", Params10, "SILK_1.1", Params11)
    except LookupError as e:
        return [str(e)]
    if (p10.struct_size, p10.decoder) != (ctypes.sizeof(Params10), 0):
        failures.append(f"1.0 default params: struct_size {p10.struct_size}, decoder {p10.decoder}")
    if (p11.struct_size, p11.kv_precision) != (ctypes.sizeof(Params11), 0):
        failures.append(f"1.1 default params: struct_size {p11.struct_size}, kv_precision {p11.kv_precision}")
    lib.silk_model_load.argtypes = [ctypes.c_char_p, ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)]
    lib.silk_last_error.restype = ctypes.c_char_p
    model = ctypes.c_void_p()
    if lib.silk_model_load(model_dir.encode(), ctypes.byref(p10), ctypes.byref(model)) != 0:
        return failures + [f"silk_model_load with the 1.0 params: {lib.silk_last_error().decode()}"]
    buf = (ctypes.c_ubyte * (ctypes.sizeof(Info10) + 16))(*([0xAB] * (ctypes.sizeof(Info10) + 16)))
    info = Info10.from_buffer(buf)
    info.struct_size = ctypes.sizeof(Info10)
    if lib.silk_model_get_info(model, ctypes.byref(buf)) != 0:
        failures.append(f"silk_model_get_info with the 1.0 size: {lib.silk_last_error().decode()}")
    elif any(b != 0xAB for b in buf[ctypes.sizeof(Info10) :]) or info.n_layers <= 0:
        failures.append("silk_model_get_info wrote past the 1.0 size of silk_model_info (or filled nothing)")
    bad = Params10(13, 0, 0)
    if (
        lib.silk_model_load(model_dir.encode(), ctypes.byref(bad), ctypes.byref(ctypes.c_void_p())) == 0
        or b"or 12 as libsilk 1.0" not in lib.silk_last_error()
    ):
        failures.append(f"struct_size 13 accepted or badly named: {lib.silk_last_error()}")
    failures += check_generate(lib, libc, model)
    lib.silk_model_destroy.argtypes = [ctypes.c_void_p]
    lib.silk_model_destroy(model)
    # Added in 1.3 / 1.4 / 1.5: bound to that node alone, so an older libsilk is refused by name.
    for node, functions in (
        (b"SILK_1.3", SILK_1_3),
        (b"SILK_1.4", SILK_1_4),
        (b"SILK_1.5", SILK_1_5),
        (b"SILK_1.6", SILK_1_6),
    ):
        for fn in functions:
            if not libc.dlvsym(lib._handle, fn.encode(), node) or libc.dlvsym(lib._handle, fn.encode(), b"SILK_1.0"):
                failures.append(f"{fn}: must be exported as {fn}@@{node.decode()} only (engine/libsilk.map)")
    return failures


GEN_PARAMS_10 = 120  # offsetof(silk_generate_params, face_guidance) on x86-64 / aarch64 Linux
GEN_STATS_10 = 232  # offsetof(silk_generate_stats, face_guided_tokens)
GEN_PARAMS_13 = 136  # offsetof(silk_generate_params, rows): the 1.3-1.4 size
GEN_STATS_13 = 256  # offsetof(silk_generate_stats, rows)


class GenParams10(ctypes.Structure):
    _fields_ = [("bytes", ctypes.c_uint64 * (GEN_PARAMS_10 // 8))]


class GenParams13(ctypes.Structure):
    _fields_ = GenParams10._fields_ + [("face_guidance", ctypes.c_int32), ("face_tolerance", ctypes.c_double)]


class GenParams15(ctypes.Structure):
    _fields_ = GenParams13._fields_ + [("rows", ctypes.c_int32)]


def generate_defaults(lib, libc):
    """silk_generate_default_params through @SILK_1.0, @SILK_1.3 and @SILK_1.5."""
    out = []
    for node, kind in ((b"SILK_1.0", GenParams10), (b"SILK_1.3", GenParams13), (b"SILK_1.5", GenParams15)):
        fn = libc.dlvsym(lib._handle, b"silk_generate_default_params", node)
        if not fn:
            raise LookupError(f"silk_generate_default_params@{node.decode()} is missing")
        out.append(ctypes.CFUNCTYPE(kind)(fn)())
    return out


def run_sized(lib, gen, params, stats_size, what):
    """One run of 64 points with `params` (max_tokens set to 60) and stats of `stats_size`."""
    pts = (ctypes.c_double * (6 * 64))(*[v for i in range(64) for v in (i / 64, (i % 8) / 8, 0.1, 0, 0, 1)])

    class Input(ctypes.Structure):
        _fields_ = [
            ("struct_size", ctypes.c_uint32),
            ("mesh", ctypes.c_void_p),
            ("points", ctypes.c_void_p),
            ("point_rows", ctypes.c_size_t),
        ]

    inp = Input(ctypes.sizeof(Input), None, ctypes.cast(pts, ctypes.c_void_p), 64)
    max_tokens_offset = 40  # offsetof(silk_generate_params, max_tokens)
    ctypes.c_int32.from_buffer(params, max_tokens_offset).value = 60
    stats = (ctypes.c_ubyte * (stats_size + 32))(*([0xAB] * (stats_size + 32)))
    ctypes.c_uint32.from_buffer(stats).value = stats_size
    mesh = ctypes.c_void_p()
    lib.silk_generator_run.argtypes = [
        ctypes.c_void_p,
        ctypes.c_void_p,
        ctypes.c_void_p,
        ctypes.POINTER(ctypes.c_void_p),
        ctypes.c_void_p,
        ctypes.c_void_p,
    ]
    rc = lib.silk_generator_run(gen, ctypes.byref(inp), ctypes.byref(params), ctypes.byref(mesh), None, stats)
    lib.silk_mesh_destroy.argtypes = [ctypes.c_void_p]
    lib.silk_mesh_destroy(mesh)
    if rc != 0:
        return [f"silk_generator_run with the {what} params and stats: {lib.silk_last_error().decode()}"]
    if any(b != 0xAB for b in stats[stats_size:]):
        return [f"silk_generator_run wrote past the {what} size of silk_generate_stats"]
    return []


def check_generate(lib, libc, model):
    """silk_generate_default_params@SILK_1.0 / @SILK_1.3 / @SILK_1.5, and 1.0- and 1.3-sized runs."""
    try:
        p10, p13, p15 = generate_defaults(lib, libc)
    except LookupError as e:
        return [str(e)]
    failures = []
    sizes = [p.bytes[0] & 0xFFFFFFFF for p in (p10, p13, p15)]
    want = [GEN_PARAMS_10, GEN_PARAMS_13, ctypes.sizeof(GenParams15)]
    if sizes != want:
        failures.append(f"generate params sizes (1.0, 1.3, 1.5): {sizes}, want {want}")
    if list(p10.bytes)[1:] != list(p13.bytes)[1:] or list(p13.bytes)[1:] != list(p15.bytes)[1:]:
        failures.append("the 1.0 / 1.3 default params differ from today's first bytes")
    if (p13.face_guidance, p13.face_tolerance, p15.face_guidance, p15.face_tolerance, p15.rows) != (
        -1,
        -1.0,
        -1,
        -1.0,
        -1,
    ):
        failures.append(
            "the face guidance or rows defaults are not SILK_MODEL_VALUE: "
            f"1.3 ({p13.face_guidance}, {p13.face_tolerance}), 1.5 ({p15.face_guidance}, {p15.face_tolerance}, "
            f"{p15.rows})"
        )
    gen = ctypes.c_void_p()
    lib.silk_generator_create.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)]
    if lib.silk_generator_create(model, ctypes.byref(gen)) != 0:
        return failures + [f"silk_generator_create: {lib.silk_last_error().decode()}"]
    failures += run_sized(lib, gen, p10, GEN_STATS_10, "1.0")
    failures += run_sized(lib, gen, p13, GEN_STATS_13, "1.3")
    lib.silk_generator_destroy.argtypes = [ctypes.c_void_p]
    lib.silk_generator_destroy(gen)
    return failures


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    problems = main(sys.argv[1], sys.argv[2])
    print("\n".join(problems) or "capi ABI 1.0: the 1.0 model params symbol and sizes still work")
    sys.exit(1 if problems else 0)
