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

from ..paths import REPO_ROOT

from .silk_c import *  # noqa: F401,F403  (status codes, structs, callback types)
from .silk_c import _c_double_p, _c_int32_p, declare as _declare


def _copied(copy, handle, dtype, ctype) -> np.ndarray:
    """All elements of a silk.h copy function: the size query, then the copy (flat array)."""
    n = ctypes.c_size_t()
    _check(copy(handle, None, 0, ctypes.byref(n)))
    out = np.empty(n.value, dtype=dtype)
    if n.value:
        _check(copy(handle, out.ctypes.data_as(ctypes.POINTER(ctype)), out.size, ctypes.byref(n)))
    return out


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
    v = VocabInfo()
    _check(lib().silk_vocab_get_info(ctypes.byref(v)))
    return v.as_dict()


class _Handle:
    """An owned libsilk handle: close() (idempotent, also on garbage collection) and `with`."""

    _h = None
    _destroy = ""  # name of the silk_*_destroy function

    def close(self) -> None:
        if self._h:
            getattr(lib(), self._destroy)(self._h)
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


class Mesh(_Handle):
    """Owned silk_mesh handle. Build with Mesh.load(path) or Mesh.from_arrays(v, f)."""

    _destroy = "silk_mesh_destroy"

    def __init__(self, handle: ctypes.c_void_p):
        self._h = handle

    @classmethod
    def load(cls, path: str | os.PathLike) -> "Mesh":
        h = ctypes.c_void_p()
        _check(lib().silk_mesh_load(os.fsencode(path), None, ctypes.byref(h)))
        return cls(h)

    @classmethod
    def from_arrays(cls, positions: np.ndarray, triangles: np.ndarray) -> "Mesh":
        v = np.ascontiguousarray(positions, dtype=np.float64).reshape(-1, 3)
        f = np.ascontiguousarray(triangles, dtype=np.int32).reshape(-1, 3)
        h = ctypes.c_void_p()
        _check(lib().silk_mesh_create(v.ctypes.data_as(_c_double_p), v.shape[0],
                                      f.ctypes.data_as(_c_int32_p), f.shape[0], ctypes.byref(h)))
        return cls(h)

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._h:
            raise ValueError("mesh is closed")
        return self._h

    def _count(self, copy) -> int:
        n = ctypes.c_size_t()
        _check(copy(self.handle, None, 0, ctypes.byref(n)))
        return n.value

    def vertex_count(self) -> int:
        return self._count(lib().silk_mesh_copy_positions) // 3

    def triangle_count(self) -> int:
        return self._count(lib().silk_mesh_copy_triangles) // 3

    def positions(self) -> np.ndarray:
        return _copied(lib().silk_mesh_copy_positions, self.handle, np.float64, ctypes.c_double).reshape(-1, 3)

    def triangles(self) -> np.ndarray:
        return _copied(lib().silk_mesh_copy_triangles, self.handle, np.int32, ctypes.c_int32).reshape(-1, 3)

    def triangle_components(self) -> np.ndarray:
        return _copied(lib().silk_mesh_copy_triangle_components, self.handle, np.int32, ctypes.c_int32)

    def save(self, path: str | os.PathLike) -> None:
        _check(lib().silk_mesh_save(self.handle, os.fsencode(path), None))


def load_arrays(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """(positions float64 [V,3], triangles int32 [F,3]) of any format libsilk reads."""
    with Mesh.load(path) as m:
        return m.positions(), m.triangles()


def _tokens_to_numpy(h: ctypes.c_void_p) -> np.ndarray:
    L = lib()
    try:
        return _copied(L.silk_tokens_copy, h, np.int32, ctypes.c_int32)
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
    _check(L.silk_mesh_encode(mesh.handle, ctypes.byref(params), ctypes.byref(h), ctypes.byref(stats)))
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
        _check(L.silk_tokens_decode(th, ctypes.byref(params), ctypes.byref(mh), None))
        return Mesh(mh)
    finally:
        L.silk_tokens_destroy(th)


class Model(_Handle):
    """A loaded model folder (silk_model). Generators keep it alive; close() may come first."""

    _destroy = "silk_model_destroy"

    def __init__(self, model_dir: str | os.PathLike, threads: int = 0, decoder: str = "default"):
        L = lib()
        opts = L.silk_model_default_params()
        if decoder not in DECODERS:
            raise ValueError(f"decoder must be one of {sorted(DECODERS)}, not {decoder!r}")
        opts.threads, opts.decoder = int(threads), DECODERS[decoder]
        self._h = ctypes.c_void_p()
        _check(L.silk_model_load(os.fsencode(model_dir), ctypes.byref(opts), ctypes.byref(self._h)))

    def info(self) -> dict:
        i = ModelInfo()
        _check(lib().silk_model_get_info(self._h, ctypes.byref(i)))
        d = i.as_dict()
        d["config"] = i.config.decode(errors="replace")
        return d



def generate_params(seed: int = 0, temperature: float | None = MODEL_VALUE, top_k: int | None = MODEL_VALUE,
                    top_p: float | None = MODEL_VALUE,
                    max_tokens: int = 0, max_faces: int = 0, repair: str = "off", n_points: int = 0,
                    surface_tolerance: int | None = None, candidates: int | None = None,
                    orient: str | None = None) -> GenerateParams:
    """silk_generate_params; None or -1 (MODEL_VALUE) sampling values mean the model's (model.json "sampling"),
    any other negative or NaN value is refused by libsilk (SilkError, naming the field);
    surface_tolerance / orient ("input" or "tokens") None: libsilk's defaults; candidates None: the
    model's N (model.json "sampling.candidates", 1 when absent)."""
    p = lib().silk_generate_default_params()
    if orient is not None:
        if orient not in ORIENT:
            raise ValueError(f"orient must be one of {sorted(ORIENT)}, not {orient!r}")
        p.orient = ORIENT[orient]
    if surface_tolerance is not None:
        p.surface_tolerance = int(surface_tolerance)
    if candidates is not None:
        p.candidates = int(candidates)
    or_model = lambda v: MODEL_VALUE if v is None else v  # noqa: E731  (None: the model's, like -1)
    p.seed, p.temperature = int(seed), float(or_model(temperature))
    p.top_k, p.top_p = int(or_model(top_k)), float(or_model(top_p))
    p.max_tokens, p.max_faces, p.n_points = int(max_tokens), int(max_faces), int(n_points)
    if repair not in HOLES:
        raise ValueError(f"repair must be one of {sorted(HOLES)}, not {repair!r}")
    p.holes = HOLES[repair]
    return p


class Generator(_Handle):
    """One generation at a time (silk_generator), step-wise or in one call. Use one per thread."""

    _destroy = "silk_generator_destroy"

    def __init__(self, model: Model):
        self._model = model  # the C side keeps its own reference too
        self._h = ctypes.c_void_p()
        _check(lib().silk_generator_create(model._h, ctypes.byref(self._h)))
        self._keep = None  # input arrays referenced by a started generation

    def _input(self, mesh: Mesh | None, points: np.ndarray | None) -> GenerateInput:
        gi = GenerateInput()
        if mesh is not None:
            gi.mesh = mesh.handle
            self._keep = mesh
        else:
            pts = np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 6)
            gi.points, gi.n_points = pts.ctypes.data_as(_c_double_p), pts.shape[0]
            self._keep = pts
        return gi

    def start(self, mesh: Mesh | None = None, points: np.ndarray | None = None, **params) -> None:
        p = generate_params(**params)
        _check(lib().silk_generator_start(self._h, ctypes.byref(self._input(mesh, points)), ctypes.byref(p)))

    def advance(self, max_ids: int = 1, until_layer: bool = False) -> bool:
        """Adds up to max_ids ids (or up to the next completed layer); True once finished."""
        done = ctypes.c_int32()
        _check(lib().silk_generator_advance(self._h, int(max_ids), 1 if until_layer else 0, ctypes.byref(done)))
        return bool(done.value)

    def cancel(self) -> None:
        lib().silk_generator_cancel(self._h)

    def tokens(self) -> np.ndarray:
        h = ctypes.c_void_p()
        _check(lib().silk_generator_tokens(self._h, ctypes.byref(h)))
        return _tokens_to_numpy(h)

    def mesh_so_far(self) -> Mesh:
        h = ctypes.c_void_p()
        _check(lib().silk_generator_mesh(self._h, ctypes.byref(h)))
        return Mesh(h)

    def stats(self) -> dict:
        st = GenerateStats()
        _check(lib().silk_generator_stats(self._h, ctypes.byref(st)))
        return st.as_dict()

    def finish(self) -> tuple[Mesh, np.ndarray, dict]:
        mh, th, st = ctypes.c_void_p(), ctypes.c_void_p(), GenerateStats()
        _check(lib().silk_generator_finish(self._h, ctypes.byref(mh), ctypes.byref(th), ctypes.byref(st)))
        self._keep = None
        return Mesh(mh), _tokens_to_numpy(th), st.as_dict()

    def report_json(self, trace: bool = False) -> str:
        L, report = lib(), ctypes.c_void_p()
        _check(L.silk_generator_report(self._h, int(trace), ctypes.byref(report)))
        try:
            return L.silk_report_json(report).decode()
        finally:
            L.silk_report_destroy(report)

    def generate(self, mesh: Mesh | None = None, points: np.ndarray | None = None,
                 progress=None, cancel=None, **params) -> tuple[Mesh, np.ndarray, dict]:
        """One call: (mesh in the input's frame, ids, stats). progress(dict) after every id;
        cancel() -> truthy stops with SilkError(status=SILK_ERR_CANCELLED)."""
        p = generate_params(**params)
        if progress is not None:
            p.progress = PROGRESS_FN(lambda pr, _u: progress({n: getattr(pr[0], n) for n, _ in GenerateProgress._fields_}))
        if cancel is not None:
            p.cancel = CANCEL_FN(lambda _u: 1 if cancel() else 0)
        gi = self._input(mesh, points)
        mh, th, st = ctypes.c_void_p(), ctypes.c_void_p(), GenerateStats()
        try:
            _check(lib().silk_generate_input_run(self._h, ctypes.byref(gi), ctypes.byref(p), ctypes.byref(mh),
                                                 ctypes.byref(th), ctypes.byref(st)))
        finally:
            self._keep = None
        return Mesh(mh), _tokens_to_numpy(th), st.as_dict()


def prepare_points(positions: np.ndarray, triangles: np.ndarray | None, kind: str = "silk",
                   n_points: int = 4096, seed: int = 0, **overrides) -> tuple[np.ndarray, np.ndarray, float]:
    """The encoder's points by libsilk's pre-processing (silk_points_prepare), the same code
    generation runs: a mesh (triangles given) or an oriented cloud (positions [N, 6], triangles
    None). `kind` "silk" or "official" picks the defaults; `overrides` set PreprocessParams
    fields (normalize_bound, merge_distance_fraction, surface_samples, round_float16).
    Returns (float32 [n, 6] normalised xyz + normal, centre [3], scale): model = (input - centre) * scale."""
    L = lib()
    params = L.silk_preprocess_default_params(PREPROCESS_KINDS[kind])
    params.point_count = int(n_points)
    for name, value in overrides.items():
        if name not in dict(PreprocessParams._fields_) or name in ("kind", "point_count", "struct_size"):
            raise TypeError(f"prepare_points: unknown pre-processing field '{name}'")
        setattr(params, name, type(getattr(params, name))(value))
    transform = np.zeros(4, dtype=np.float64)
    floats = ctypes.c_size_t()
    seed = ctypes.c_uint64(int(seed) & (2**64 - 1))

    def run(*source) -> np.ndarray:  # size query, then the rows
        _check(L.silk_points_prepare(*source, ctypes.byref(params), seed, None, 0, ctypes.byref(floats), None))
        out = np.empty((floats.value // 6, 6), dtype=np.float32)
        _check(L.silk_points_prepare(*source, ctypes.byref(params), seed,
                                     out.ctypes.data_as(ctypes.POINTER(ctypes.c_float)), out.size,
                                     ctypes.byref(floats), transform.ctypes.data_as(_c_double_p)))
        return out

    if triangles is None:
        cloud = np.ascontiguousarray(positions, dtype=np.float64).reshape(-1, 6)
        out = run(None, cloud.ctypes.data_as(_c_double_p), cloud.shape[0])
    else:
        with Mesh.from_arrays(positions, triangles) as m:
            out = run(m.handle, None, 0)
    return out, transform[:3].copy(), float(transform[3])
