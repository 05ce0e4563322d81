# SPDX-License-Identifier: MIT
"""silk_mesh.encode / decode: a mesh to its Mesh Silksong token ids and back (bit-exact with the
reference tokenizer), and token files (one id per line) read and written by libsilk."""

from __future__ import annotations

import ctypes
import os

from . import _arrays, _native, _params
from .mesh import Mesh, _Borrowed


def encode(source, return_stats: bool = False, **params):
    """Token ids (format ids, no BOS/EOS/PAD) of a Mesh, a mesh file path or a (positions,
    triangles) pair. params: normalize (default True), normalize_bound (0.95),
    nonmanifold_processing (True). return_stats=True: (ids, encode statistics dict).
    A refused mesh raises SilkError with status SILK_ERR_REFUSED and the reason in e.reason."""
    p = _params.fill(_native.encode_defaults(), params, "encode")
    with _Borrowed(source, "encode") as mesh:
        h, stats = _native.encode(mesh.handle, p)
    ids = _native.tokens_take(h)
    return (ids, stats.as_dict()) if return_stats else ids


def _tokens_handle(ids) -> ctypes.c_void_p:
    if isinstance(ids, (str, bytes, os.PathLike)):
        return _native.tokens_load(os.fsencode(ids))
    ptr, n, _keep = _arrays.to_c(ids, ctypes.c_int32, 1, "ids")
    return _native.tokens_create(ptr, n)


def decode(ids, return_stats: bool = False, **params):
    """The mesh of token ids (a sequence, or a token file path): every face they carry.
    params: grid_coordinates (False: positions in [-1, 1]; True: grid integers 0..127),
    split_nonmanifold_vertices (False). return_stats=True: (Mesh, decode statistics dict)."""
    p = _params.fill(_native.decode_defaults(), params, "decode")
    th = _tokens_handle(ids)
    try:
        mh, stats = _native.decode(th, p)
    finally:
        _native.tokens_destroy(th)
    mesh = Mesh._adopt(mh)
    return (mesh, _params.as_dict(stats)) if return_stats else mesh


def read_ids(path: str | os.PathLike) -> list[int]:
    """The ids of a token file (one id per line, as silktok writes them)."""
    return _native.tokens_take(_native.tokens_load(os.fsencode(path)))


def write_ids(path: str | os.PathLike, ids) -> None:
    """Writes ids as a token file (one id per line)."""
    th = _tokens_handle(ids)
    try:
        _native.tokens_save(th, os.fsencode(path))
    finally:
        _native.tokens_destroy(th)
