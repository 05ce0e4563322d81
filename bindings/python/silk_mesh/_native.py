# SPDX-License-Identifier: MIT
"""The thin internal layer: every call into libsilk is made here (declarations in _capi), so a
change of the C API (a renamed function, a count query folded into its copy call) is adapted in
this file alone. Handles are ctypes.c_void_p, arrays ctypes arrays; nothing Pythonic."""

from __future__ import annotations

import ctypes
import functools
from ctypes import byref, c_void_p

from . import _capi
from ._library import check, lib


def _out(fn, *args) -> c_void_p:
    h = c_void_p()
    check(fn(*args, byref(h)))
    return h


def _count(copy_fn, h) -> int:
    """Elements a copy function would write: its size query (out NULL, capacity 0)."""
    n = ctypes.c_size_t()
    check(copy_fn(h, None, 0, byref(n)))
    return n.value


def _copy(copy_fn, h, ctype):
    """Every element of a silk.h copy function: the size query, then the copy."""
    n = _count(copy_fn, h)
    buf = (ctype * n)()
    if n:
        check(copy_fn(h, buf, n, None))
    return buf


# -- library ---------------------------------------------------------------------------------
def version() -> str:
    return lib().silk_version().decode()


def vocab() -> _capi.VocabInfo:
    info = _capi.VocabInfo()
    check(lib().silk_vocab_get_info(byref(info)))
    return info


def generation_available() -> bool:
    return bool(lib().silk_generation_available())


@functools.lru_cache(maxsize=None)
def enum_names(enum: str) -> dict[str, int]:
    """{name: value} of silk_<enum> (_capi.ENUM_FIRST) as libsilk spells it: silk_<enum>_name from
    the enum's first value on, until it says "unknown"."""
    name_of = getattr(lib(), f"silk_{enum}_name")
    names, value = {}, _capi.ENUM_FIRST[enum]
    while (name := name_of(value).decode()) != "unknown":
        names[name] = value
        value += 1
    return names


def enum_name(enum: str, value: int) -> str:
    """libsilk's name of one value ("unknown" out of range)."""
    return getattr(lib(), f"silk_{enum}_name")(value).decode()


def stats_dict(st: _capi.GenerateStats) -> dict:
    """silk_generate_stats by field name, the stop reason by libsilk's name ("none" while running)."""
    d = st.as_dict()
    d["stop_reason"] = enum_name("stop_reason", st.stop_reason)
    return d


# -- meshes ----------------------------------------------------------------------------------
def mesh_create(positions, n_vertices: int, triangles, n_triangles: int) -> c_void_p:
    return _out(lib().silk_mesh_create, positions, n_vertices, triangles, n_triangles)


def mesh_load(path: bytes, point_clouds: bool) -> c_void_p:
    L = lib()
    params = L.silk_load_default_params()
    params.point_clouds = int(bool(point_clouds))
    return _out(L.silk_mesh_load, path, byref(params))


def mesh_save(h: c_void_p, path: bytes, params: _capi.SaveParams) -> None:
    check(lib().silk_mesh_save(h, path, byref(params)))


def save_defaults() -> _capi.SaveParams:
    return lib().silk_save_default_params()


def mesh_destroy(h: c_void_p) -> None:
    lib().silk_mesh_destroy(h)


def mesh_vertex_count(h: c_void_p) -> int:
    return _count(lib().silk_mesh_copy_positions, h) // 3


def mesh_triangle_count(h: c_void_p) -> int:
    return _count(lib().silk_mesh_copy_triangles, h) // 3


def mesh_positions(h: c_void_p):
    return _copy(lib().silk_mesh_copy_positions, h, ctypes.c_double)


def mesh_triangles(h: c_void_p):
    return _copy(lib().silk_mesh_copy_triangles, h, ctypes.c_int32)


def mesh_parts(h: c_void_p):
    return _copy(lib().silk_mesh_copy_triangle_components, h, ctypes.c_int32)


def mesh_normals(h: c_void_p):
    """Per-vertex normals (3 doubles each), or None when the mesh has none."""
    L = lib()
    if not L.silk_mesh_has_normals(h):
        return None
    return _copy(L.silk_mesh_copy_normals, h, ctypes.c_double)


# -- token sequences -------------------------------------------------------------------------
def tokens_create(ids, count: int) -> c_void_p:
    return _out(lib().silk_tokens_create, ids, count)


def tokens_load(path: bytes) -> c_void_p:
    return _out(lib().silk_tokens_load, path)


def tokens_save(h: c_void_p, path: bytes) -> None:
    check(lib().silk_tokens_save(h, path))


def tokens_destroy(h: c_void_p) -> None:
    lib().silk_tokens_destroy(h)


def tokens_take(h: c_void_p) -> list[int]:
    """The ids of a tokens handle, which is destroyed."""
    L = lib()
    try:
        return list(_copy(L.silk_tokens_copy, h, ctypes.c_int32))
    finally:
        L.silk_tokens_destroy(h)


# -- encode / decode -------------------------------------------------------------------------
def encode_defaults() -> _capi.EncodeParams:
    return lib().silk_encode_default_params()


def encode(mesh: c_void_p, params: _capi.EncodeParams) -> tuple[c_void_p, _capi.EncodeStats]:
    stats, h = _capi.EncodeStats(), c_void_p()
    check(lib().silk_mesh_encode(mesh, byref(params), byref(h), byref(stats)))
    return h, stats


def decode_defaults() -> _capi.DecodeParams:
    return lib().silk_decode_default_params()


def decode(tokens: c_void_p, params: _capi.DecodeParams) -> tuple[c_void_p, _capi.DecodeStats]:
    stats, h = _capi.DecodeStats(), c_void_p()
    check(lib().silk_tokens_decode(tokens, byref(params), byref(h), byref(stats)))
    return h, stats


# -- pre-processing --------------------------------------------------------------------------
def preprocess_defaults(kind: int) -> _capi.PreprocessParams:
    return lib().silk_preprocess_default_params(kind)


def prepare_points(mesh, cloud, n_cloud: int, params: _capi.PreprocessParams, seed: int):
    """(float array of rows * 6, transform double[4]) by silk_points_prepare (size query first)."""
    L, rows, transform = lib(), ctypes.c_size_t(), (ctypes.c_double * 4)()
    s = ctypes.c_uint64(seed)  # range-checked by the caller (_checks.integer)
    check(L.silk_points_prepare(mesh, cloud, n_cloud, byref(params), s, None, 0, byref(rows), None))
    out = (ctypes.c_float * rows.value)()
    check(L.silk_points_prepare(mesh, cloud, n_cloud, byref(params), s, out, len(out), byref(rows), transform))
    return out, transform


# -- models and generators -------------------------------------------------------------------
def model_load(path: bytes, threads: int, decoder: int, kv_precision: int = 0) -> c_void_p:
    L = lib()
    opts = L.silk_model_default_params()
    opts.threads, opts.decoder, opts.kv_precision = threads, decoder, kv_precision
    return _out(L.silk_model_load, path, byref(opts))


def _path(fn, *args) -> str:
    """A path from a silk.h path function (size query in bytes, then the copy), decoded from UTF-8."""
    n = ctypes.c_size_t()
    check(fn(*args, None, 0, byref(n)))
    buf = ctypes.create_string_buffer(n.value)
    check(fn(*args, buf, n.value, None))
    return buf.value.decode("utf-8", "surrogateescape")


def models_dir(name: bytes | None) -> str:
    return _path(lib().silk_models_dir, name)


def model_default_dir() -> str:
    return _path(lib().silk_model_default_dir)


def model_find(name_or_dir: bytes) -> str:
    return _path(lib().silk_model_find, name_or_dir)


def models_list_json() -> str:
    L, report = lib(), c_void_p()
    check(L.silk_models_list(byref(report)))
    try:
        return L.silk_report_json(report).decode()
    finally:
        L.silk_report_destroy(report)


def model_destroy(h: c_void_p) -> None:
    lib().silk_model_destroy(h)


def model_info(h: c_void_p) -> _capi.ModelInfo:
    info = _capi.ModelInfo()
    check(lib().silk_model_get_info(h, byref(info)))
    return info


def generator_create(model: c_void_p) -> c_void_p:
    return _out(lib().silk_generator_create, model)


def generator_destroy(h: c_void_p) -> None:
    lib().silk_generator_destroy(h)


def generate_defaults() -> _capi.GenerateParams:
    return lib().silk_generate_default_params()


def generator_start(g: c_void_p, inp: _capi.GenerateInput, params: _capi.GenerateParams) -> None:
    check(lib().silk_generator_start(g, byref(inp), byref(params)))


def generator_advance(g: c_void_p, max_ids: int, until_layer: bool) -> bool:
    done = ctypes.c_int32()
    check(lib().silk_generator_advance(g, max_ids, 1 if until_layer else 0, byref(done)))
    return bool(done.value)


def generator_cancel(g: c_void_p) -> None:
    lib().silk_generator_cancel(g)


def generator_tokens(g: c_void_p) -> c_void_p:
    return _out(lib().silk_generator_get_tokens, g)


def generator_mesh(g: c_void_p) -> c_void_p:
    return _out(lib().silk_generator_get_mesh, g)


def generator_stats(g: c_void_p) -> _capi.GenerateStats:
    st = _capi.GenerateStats()
    check(lib().silk_generator_get_stats(g, byref(st)))
    return st


def generator_candidates(g: c_void_p) -> list[_capi.CandidateInfo]:
    """silk_generator_get_candidate of every candidate of the generation in progress."""
    n = ctypes.c_int32()
    check(lib().silk_generator_candidate_count(g, byref(n)))
    out = []
    for i in range(n.value):
        c = _capi.CandidateInfo()
        check(lib().silk_generator_get_candidate(g, i, byref(c)))
        out.append(c)
    return out


def generator_candidate_mesh(g: c_void_p, index: int) -> c_void_p:
    return _out(lib().silk_generator_get_candidate_mesh, g, index)


def generator_finish(g: c_void_p) -> tuple[c_void_p, c_void_p, _capi.GenerateStats]:
    mh, th, st = c_void_p(), c_void_p(), _capi.GenerateStats()
    check(lib().silk_generator_finish(g, byref(mh), byref(th), byref(st)))
    return mh, th, st


def generator_run(g: c_void_p, inp: _capi.GenerateInput, params: _capi.GenerateParams):
    """silk_generator_run: (mesh handle, tokens handle, stats)."""
    mh, th, st = c_void_p(), c_void_p(), _capi.GenerateStats()
    check(lib().silk_generator_run(g, byref(inp), byref(params), byref(mh), byref(th), byref(st)))
    return mh, th, st


# -- a batch of inputs (C API 1.6) ------------------------------------------------------------
def batch_defaults() -> _capi.BatchParams:
    return lib().silk_batch_default_params()


def batch_create(model: c_void_p, params: _capi.BatchParams) -> c_void_p:
    return _out(lib().silk_batch_create, model, byref(params))


def batch_destroy(h: c_void_p) -> None:
    lib().silk_batch_destroy(h)


def batch_add(b: c_void_p, inp: _capi.GenerateInput, params: _capi.GenerateParams) -> int:
    index = ctypes.c_int32(-1)
    check(lib().silk_batch_add(b, byref(inp), byref(params), byref(index)))
    return index.value


def batch_close(b: c_void_p) -> None:
    check(lib().silk_batch_close(b))


def batch_next(b: c_void_p):
    """silk_batch_next: (index, status, mesh handle, tokens handle, stats); index -1: nothing left."""
    index, mh, th, st = ctypes.c_int32(-1), c_void_p(), c_void_p(), _capi.GenerateStats()
    status = lib().silk_batch_next(b, byref(index), byref(mh), byref(th), byref(st))
    return index.value, status, mh, th, st


def batch_counts(b: c_void_p) -> tuple[int, int]:
    flight, queued = ctypes.c_int32(), ctypes.c_int32()
    check(lib().silk_batch_counts(b, byref(flight), byref(queued)))
    return flight.value, queued.value


def batch_cancel(b: c_void_p) -> None:
    lib().silk_batch_cancel(b)


def generator_report_json(g: c_void_p, trace: bool) -> str:
    L, report = lib(), c_void_p()
    check(L.silk_generator_report(g, int(trace), byref(report)))
    try:
        return L.silk_report_json(report).decode()
    finally:
        L.silk_report_destroy(report)


def generator_points(g: c_void_p):
    """The encoder's points of the current or last generation, input frame (rows of 6 doubles)."""
    return _copy(lib().silk_generator_copy_points, g, ctypes.c_double)
