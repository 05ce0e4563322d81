"""ctypes binding over libsilk's C API (engine/include/silk/silk.h), the same API embedders use.

No compiler and no C++ ABI are involved: the shared library is loaded at run time and only the
plain C functions and structs of silk.h are declared here. Library discovery: $SILK_LIBRARY,
else <repo>/build/engine/libsilk.so, else the newest <repo>/build*/engine/libsilk.so, else the
system loader ("libsilk.so")."""
from __future__ import annotations

import ctypes
import os
from functools import lru_cache
from pathlib import Path

import numpy as np

from .paths import REPO_ROOT

_c_int32_p = ctypes.POINTER(ctypes.c_int32)
_c_double_p = ctypes.POINTER(ctypes.c_double)

SILK_OK = 0
SILK_ERR_REFUSED = 5


class SilkError(RuntimeError):
    """A libsilk call failed; `status` is the silk_status code, the message silk_last_error()."""

    def __init__(self, status: int, name: str, message: str):
        super().__init__(f"{name}: {message}")
        self.status, self.name, self.message = status, name, message


class SilkRefused(SilkError):
    """The tokenizer refuses the mesh (SILK_ERR_REFUSED); `reason` is the named refusal."""

    @property
    def reason(self) -> str:
        return self.message.split(":", 1)[0].strip()


class VocabInfo(ctypes.Structure):
    _fields_ = [(n, ctypes.c_int32) for n in (
        "token_format_version", "format_vocab_size", "eos_id", "pad_id", "model_vocab_size",
        "c_id", "u_id", "e_id", "x_begin", "x_end", "s_begin", "s_end", "b_begin", "b_end",
        "k_begin", "k_end", "o_begin", "o_end", "quant_bins", "layer_vertex_limit",
        "layer_count_limit", "max_faces", "max_seq_length")]


class EncodeParams(ctypes.Structure):
    _fields_ = [("normalize", ctypes.c_int32), ("normalize_bound", ctypes.c_double),
                ("nonmanifold_processing", ctypes.c_int32)]


class EncodeStats(ctypes.Structure):
    _fields_ = [(n, ctypes.c_int32) for n in (
        "input_vertices", "input_faces", "processed_vertices", "processed_faces",
        "emitted_vertices", "encodable_faces", "components_found", "components_encoded",
        "components_dropped_small", "layers", "max_layer_size", "max_layer_count")] + [
        ("tokens", ctypes.c_int64), ("seconds", ctypes.c_double)]

    def as_dict(self) -> dict:
        return {name: getattr(self, name) for name, _ in self._fields_}


class DecodeParams(ctypes.Structure):
    _fields_ = [("grid_coordinates", ctypes.c_int32)]


class PreprocessParams(ctypes.Structure):
    _fields_ = [("kind", ctypes.c_int32), ("normalize_bound", ctypes.c_double),
                ("merge_distance_fraction", ctypes.c_double), ("surface_samples", ctypes.c_int32),
                ("round_float16", ctypes.c_int32), ("n_points", ctypes.c_int32)]


PREPROCESS_KINDS = {"silk": 0, "official": 1}


def library_candidates() -> list[Path]:
    """Built libraries in the checkout, in the order they are tried."""
    first = REPO_ROOT / "build" / "engine" / "libsilk.so"
    others = [p for p in REPO_ROOT.glob("build*/engine/libsilk.so") if p != first]
    others.sort(key=lambda p: p.stat().st_mtime, reverse=True)
    return ([first] if first.exists() else []) + others


def library_path() -> str:
    env = os.environ.get("SILK_LIBRARY")
    if env:
        return env
    found = library_candidates()
    return str(found[0]) if found else "libsilk.so"


def _declare(lib: ctypes.CDLL) -> None:
    sig = {
        "silk_last_error": (ctypes.c_char_p, []),
        "silk_status_name": (ctypes.c_char_p, [ctypes.c_int]),
        "silk_version": (ctypes.c_char_p, []),
        "silk_vocab": (VocabInfo, []),
        "silk_mesh_create": (ctypes.c_int, [_c_double_p, ctypes.c_size_t, _c_int32_p, ctypes.c_size_t,
                                            ctypes.POINTER(ctypes.c_void_p)]),
        "silk_mesh_load": (ctypes.c_int, [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)]),
        "silk_mesh_save": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p]),
        "silk_mesh_destroy": (None, [ctypes.c_void_p]),
        "silk_mesh_vertex_count": (ctypes.c_size_t, [ctypes.c_void_p]),
        "silk_mesh_triangle_count": (ctypes.c_size_t, [ctypes.c_void_p]),
        "silk_mesh_copy_positions": (ctypes.c_int, [ctypes.c_void_p, _c_double_p, ctypes.c_size_t]),
        "silk_mesh_copy_triangles": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p, ctypes.c_size_t]),
        "silk_mesh_copy_triangle_components": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p, ctypes.c_size_t]),
        "silk_tokens_create": (ctypes.c_int, [_c_int32_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_void_p)]),
        "silk_tokens_destroy": (None, [ctypes.c_void_p]),
        "silk_tokens_count": (ctypes.c_size_t, [ctypes.c_void_p]),
        "silk_tokens_copy": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p, ctypes.c_size_t]),
        "silk_encode_default_params": (EncodeParams, []),
        "silk_encode": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(EncodeParams),
                                       ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(EncodeStats)]),
        "silk_preprocess_default_params": (PreprocessParams, [ctypes.c_int32]),
        "silk_prepare_points": (ctypes.c_int, [ctypes.c_void_p, _c_double_p, ctypes.c_size_t,
                                               ctypes.POINTER(PreprocessParams), ctypes.c_uint64,
                                               ctypes.POINTER(ctypes.c_float), ctypes.c_size_t,
                                               ctypes.POINTER(ctypes.c_size_t), _c_double_p]),
        "silk_decode_default_params": (DecodeParams, []),
        "silk_decode": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(DecodeParams),
                                       ctypes.POINTER(ctypes.c_void_p)]),
    }
    for name, (res, args) in sig.items():
        fn = getattr(lib, name)
        fn.restype, fn.argtypes = res, args


@lru_cache(maxsize=1)
def lib() -> ctypes.CDLL:
    """The loaded library (loaded once per process)."""
    path = library_path()
    try:
        handle = ctypes.CDLL(path)
    except OSError as e:
        raise OSError(f"cannot load libsilk from '{path}' ({e}); build it (scripts/build.sh) "
                      "or set SILK_LIBRARY to the path of libsilk.so") from e
    _declare(handle)
    return handle


def _check(status: int) -> None:
    if status == SILK_OK:
        return
    L = lib()
    name = L.silk_status_name(status).decode()
    msg = L.silk_last_error().decode(errors="replace")
    raise (SilkRefused if status == SILK_ERR_REFUSED else SilkError)(status, name, msg)


def version() -> str:
    return lib().silk_version().decode()


def vocab_info() -> dict:
    v = lib().silk_vocab()
    return {name: getattr(v, name) for name, _ in VocabInfo._fields_}


class Mesh:
    """Owned silk_mesh handle. Build with Mesh.load(path) or Mesh.from_arrays(v, f)."""

    def __init__(self, handle: ctypes.c_void_p):
        self._h = handle

    @classmethod
    def load(cls, path: str | os.PathLike) -> "Mesh":
        h = ctypes.c_void_p()
        _check(lib().silk_mesh_load(os.fsencode(path), ctypes.byref(h)))
        return cls(h)

    @classmethod
    def from_arrays(cls, positions: np.ndarray, triangles: np.ndarray) -> "Mesh":
        v = np.ascontiguousarray(positions, dtype=np.float64).reshape(-1, 3)
        f = np.ascontiguousarray(triangles, dtype=np.int32).reshape(-1, 3)
        h = ctypes.c_void_p()
        _check(lib().silk_mesh_create(v.ctypes.data_as(_c_double_p), v.shape[0],
                                      f.ctypes.data_as(_c_int32_p), f.shape[0], ctypes.byref(h)))
        return cls(h)

    def close(self) -> None:
        if self._h:
            lib().silk_mesh_destroy(self._h)
            self._h = None

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._h:
            raise ValueError("mesh is closed")
        return self._h

    def vertex_count(self) -> int:
        return int(lib().silk_mesh_vertex_count(self.handle))

    def triangle_count(self) -> int:
        return int(lib().silk_mesh_triangle_count(self.handle))

    def positions(self) -> np.ndarray:
        out = np.empty((self.vertex_count(), 3), dtype=np.float64)
        _check(lib().silk_mesh_copy_positions(self.handle, out.ctypes.data_as(_c_double_p), out.size))
        return out

    def triangles(self) -> np.ndarray:
        out = np.empty((self.triangle_count(), 3), dtype=np.int32)
        _check(lib().silk_mesh_copy_triangles(self.handle, out.ctypes.data_as(_c_int32_p), out.size))
        return out

    def triangle_components(self) -> np.ndarray:
        out = np.empty(self.triangle_count(), dtype=np.int32)
        _check(lib().silk_mesh_copy_triangle_components(self.handle, out.ctypes.data_as(_c_int32_p), out.size))
        return out

    def save(self, path: str | os.PathLike) -> None:
        _check(lib().silk_mesh_save(self.handle, os.fsencode(path)))


def load_arrays(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """(positions float64 [V,3], triangles int32 [F,3]) of any format libsilk reads."""
    with Mesh.load(path) as m:
        return m.positions(), m.triangles()


def _tokens_to_numpy(h: ctypes.c_void_p) -> np.ndarray:
    L = lib()
    try:
        n = int(L.silk_tokens_count(h))
        out = np.empty(n, dtype=np.int32)
        _check(L.silk_tokens_copy(h, out.ctypes.data_as(_c_int32_p), n))
        return out
    finally:
        L.silk_tokens_destroy(h)


def encode(mesh: Mesh, normalize: bool = True, normalize_bound: float = 0.95,
           nonmanifold_processing: bool = True) -> tuple[np.ndarray, dict]:
    """Tokenize: (int32 token ids without BOS/EOS/PAD, encode statistics). Raises SilkRefused."""
    L = lib()
    params = L.silk_encode_default_params()
    params.normalize = int(bool(normalize))
    params.normalize_bound = float(normalize_bound)
    params.nonmanifold_processing = int(bool(nonmanifold_processing))
    stats = EncodeStats()
    h = ctypes.c_void_p()
    _check(L.silk_encode(mesh.handle, ctypes.byref(params), ctypes.byref(h), ctypes.byref(stats)))
    return _tokens_to_numpy(h), stats.as_dict()


def encode_arrays(positions: np.ndarray, triangles: np.ndarray, **kw) -> tuple[np.ndarray, dict]:
    with Mesh.from_arrays(positions, triangles) as m:
        return encode(m, **kw)


def decode(tokens: np.ndarray, grid_coordinates: bool = False) -> Mesh:
    """Tokens (format ids only) -> mesh with every face they carry."""
    L = lib()
    ids = np.ascontiguousarray(tokens, dtype=np.int32).ravel()
    th = ctypes.c_void_p()
    _check(L.silk_tokens_create(ids.ctypes.data_as(_c_int32_p), ids.size, ctypes.byref(th)))
    try:
        params = L.silk_decode_default_params()
        params.grid_coordinates = int(bool(grid_coordinates))
        mh = ctypes.c_void_p()
        _check(L.silk_decode(th, ctypes.byref(params), ctypes.byref(mh)))
        return Mesh(mh)
    finally:
        L.silk_tokens_destroy(th)


def prepare_points(positions: np.ndarray, triangles: np.ndarray | None, kind: str = "silk",
                   n_points: int = 4096, seed: int = 0, **overrides) -> tuple[np.ndarray, np.ndarray, float]:
    """The encoder's points by libsilk's pre-processing (silk_prepare_points), the same code
    generation runs: a mesh (triangles given) or an oriented cloud (positions [N, 6], triangles
    None). `kind` "silk" or "official" picks the defaults; `overrides` set PreprocessParams
    fields (normalize_bound, merge_distance_fraction, surface_samples, round_float16).
    Returns (float32 [n, 6] normalised xyz + normal, centre [3], scale): model = (input - centre) * scale."""
    L = lib()
    params = L.silk_preprocess_default_params(PREPROCESS_KINDS[kind])
    params.n_points = int(n_points)
    for name, value in overrides.items():
        if name not in dict(PreprocessParams._fields_) or name in ("kind", "n_points"):
            raise TypeError(f"prepare_points: unknown pre-processing field '{name}'")
        setattr(params, name, type(getattr(params, name))(value))
    transform = np.zeros(4, dtype=np.float64)
    rows = ctypes.c_size_t()
    seed = ctypes.c_uint64(int(seed) & (2**64 - 1))

    def run(*source) -> np.ndarray:  # size query, then the rows
        _check(L.silk_prepare_points(*source, ctypes.byref(params), seed, None, 0, ctypes.byref(rows), None))
        out = np.empty((rows.value, 6), dtype=np.float32)
        _check(L.silk_prepare_points(*source, ctypes.byref(params), seed,
                                     out.ctypes.data_as(ctypes.POINTER(ctypes.c_float)), out.size,
                                     ctypes.byref(rows), transform.ctypes.data_as(_c_double_p)))
        return out

    if triangles is None:
        cloud = np.ascontiguousarray(positions, dtype=np.float64).reshape(-1, 6)
        out = run(None, cloud.ctypes.data_as(_c_double_p), cloud.shape[0])
    else:
        with Mesh.from_arrays(positions, triangles) as m:
            out = run(m.handle, None, 0)
    return out, transform[:3].copy(), float(transform[3])
