#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A caller built against libsilk 1.0 keeps working (docs/c_api.md "Struct growth"): the 1.0 symbol
silk_model_default_params@SILK_1.0 still returns the 1.0 layout of silk_model_params (12 bytes,
no kv_precision), silk_model_load and silk_model_get_info accept the 1.0 sizes and write nothing
past them, and the current symbol returns today's size; the functions 1.3 added are bound to the
SILK_1.3 node alone. Linux (ELF symbol versions) only.

    capi_abi_check.py LIBSILK MODEL_DIR
"""
import ctypes
import sys


class Params10(ctypes.Structure):
    _fields_ = [("struct_size", ctypes.c_uint32), ("threads", ctypes.c_int32), ("decoder", ctypes.c_int32)]


class Params11(ctypes.Structure):
    _fields_ = Params10._fields_ + [("kv_precision", ctypes.c_int32)]


SILK_1_3 = ("silk_models_dir", "silk_model_default_dir", "silk_model_find", "silk_models_list")
INFO_INTS = ("d_model", "n_layers", "n_heads", "head_dim", "n_latents", "default_points", "max_seq_len", "threads",
             "int8", "decoder", "arch", "encoder_points")


class Info10(ctypes.Structure):
    _fields_ = [("struct_size", ctypes.c_uint32), ("config", ctypes.c_char * 32)] + [(n, ctypes.c_int32) for n in INFO_INTS]


def main(lib_path, model_dir):
    lib = ctypes.CDLL(lib_path)
    libc = ctypes.CDLL(None)
    libc.dlvsym.restype = ctypes.c_void_p
    libc.dlvsym.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_char_p]
    failures = []
    old = libc.dlvsym(lib._handle, b"silk_model_default_params", b"SILK_1.0")
    new = libc.dlvsym(lib._handle, b"silk_model_default_params", b"SILK_1.1")
    if not old or not new:
        return [f"silk_model_default_params: SILK_1.0 {bool(old)}, SILK_1.1 {bool(new)} (both must exist)"]
    p10 = ctypes.CFUNCTYPE(Params10)(old)()
    p11 = ctypes.CFUNCTYPE(Params11)(new)()
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
    elif any(b != 0xAB for b in buf[ctypes.sizeof(Info10):]) or info.n_layers <= 0:
        failures.append("silk_model_get_info wrote past the 1.0 size of silk_model_info (or filled nothing)")
    bad = Params10(13, 0, 0)
    if lib.silk_model_load(model_dir.encode(), ctypes.byref(bad), ctypes.byref(ctypes.c_void_p())) == 0 or \
            b"or 12 as libsilk 1.0" not in lib.silk_last_error():
        failures.append(f"struct_size 13 accepted or badly named: {lib.silk_last_error()}")
    lib.silk_model_destroy.argtypes = [ctypes.c_void_p]
    lib.silk_model_destroy(model)
    for fn in SILK_1_3:  # added in 1.3: bound to that node alone, so an older libsilk is refused by name
        if not libc.dlvsym(lib._handle, fn.encode(), b"SILK_1.3") or libc.dlvsym(lib._handle, fn.encode(), b"SILK_1.0"):
            failures.append(f"{fn}: must be exported as {fn}@@SILK_1.3 only (engine/libsilk.map)")
    return failures


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    problems = main(sys.argv[1], sys.argv[2])
    print("\n".join(problems) or "capi ABI 1.0: the 1.0 model params symbol and sizes still work")
    sys.exit(1 if problems else 0)
