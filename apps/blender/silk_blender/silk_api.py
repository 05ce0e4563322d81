"""The add-on's use of libsilk's C API (silk.h) over ctypes: pure Python (Debian's Blender has
no numpy); the declarations come from silk_c. The library is the copy beside the add-on
(lib/libsilk.so*) or $SILK_LIBRARY; a missing one raises SilkLibraryMissing naming the paths."""
from __future__ import annotations

import ctypes
import glob
import os

from . import silk_c  # the C declarations, shared with export/silk_export (a copy in the zip)
from .silk_c import SILK_ERR_CANCELLED, SILK_OK, GenerateInput, GenerateStats  # noqa: F401

ADDON_DIR = os.path.dirname(os.path.abspath(__file__))
BUNDLED_MODEL = os.path.join(ADDON_DIR, "model")


class SilkError(RuntimeError):
    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


class SilkLibraryMissing(RuntimeError):
    pass


_lib = None


def library_candidates() -> list[str]:
    env = os.environ.get("SILK_LIBRARY")
    if env:
        return [env]
    bundled = sorted(glob.glob(os.path.join(ADDON_DIR, "lib", "libsilk.so*")), key=len)
    return bundled or [os.path.join(ADDON_DIR, "lib", "libsilk.so")]


def lib() -> ctypes.CDLL:
    """libsilk, loaded once: $SILK_LIBRARY, else the copy beside the add-on."""
    global _lib
    if _lib is None:
        path = library_candidates()[0]
        if not os.path.exists(path):
            raise SilkLibraryMissing(f"Silk: libsilk not found at {path} (reinstall the add-on zip, "
                                     "or set SILK_LIBRARY to the path of libsilk.so)")
        try:
            handle = ctypes.CDLL(path)
        except OSError as e:
            raise SilkLibraryMissing(f"Silk: cannot load libsilk from {path}: {e}") from e
        silk_c.declare(handle)
        _lib = handle
    return _lib


def check(status: int) -> None:
    if status != SILK_OK:
        raise SilkError(status, lib().silk_last_error().decode(errors="replace"))


class Mesh:
    """An owned silk_mesh; arrays are flat Python lists (no numpy in Debian's Blender)."""

    def __init__(self, handle: ctypes.c_void_p):
        self.handle = handle

    @classmethod
    def from_arrays(cls, positions: list[float], triangles: list[int]) -> "Mesh":
        pos = (ctypes.c_double * len(positions))(*positions)
        tri = (ctypes.c_int32 * len(triangles))(*triangles)
        h = ctypes.c_void_p()
        check(lib().silk_mesh_create(pos, len(positions) // 3, tri, len(triangles) // 3, ctypes.byref(h)))
        return cls(h)

    @classmethod
    def load(cls, path: str) -> "Mesh":
        h = ctypes.c_void_p()
        check(lib().silk_mesh_load(os.fsencode(path), ctypes.byref(h)))
        return cls(h)

    def save(self, path: str) -> None:
        check(lib().silk_mesh_save(self.handle, os.fsencode(path)))

    def arrays(self) -> tuple[list[float], list[int], list[int]]:
        """(positions xyz..., triangles abc..., component per triangle)."""
        L = lib()
        nv, nt = L.silk_mesh_vertex_count(self.handle), L.silk_mesh_triangle_count(self.handle)
        pos, tri, comp = (ctypes.c_double * (3 * nv))(), (ctypes.c_int32 * (3 * nt))(), (ctypes.c_int32 * nt)()
        check(L.silk_mesh_copy_positions(self.handle, pos, 3 * nv))
        check(L.silk_mesh_copy_triangles(self.handle, tri, 3 * nt))
        check(L.silk_mesh_copy_triangle_components(self.handle, comp, nt))
        return list(pos), list(tri), list(comp)

    def close(self) -> None:
        if self.handle:
            lib().silk_mesh_destroy(self.handle)
            self.handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def encode_to_file(mesh: Mesh, path: str) -> None:
    t = ctypes.c_void_p()
    check(lib().silk_encode(mesh.handle, None, ctypes.byref(t), None))
    try:
        check(lib().silk_tokens_save(t, os.fsencode(path)))
    finally:
        lib().silk_tokens_destroy(t)


def decode_file(path: str) -> Mesh:
    t = ctypes.c_void_p()
    check(lib().silk_tokens_load(os.fsencode(path), ctypes.byref(t)))
    try:
        h = ctypes.c_void_p()
        check(lib().silk_decode(t, None, ctypes.byref(h)))
        return Mesh(h)
    finally:
        lib().silk_tokens_destroy(t)


class Generation:
    """One step-wise generation: model + generator + the input it was started with."""

    def __init__(self, model_dir: str, source: Mesh | None, points: list[float] | None, seed: int,
                 temperature: float, top_k: int, max_faces: int, max_tokens: int, repair: str,
                 surface_tolerance: int | None = None, orient: str = "INPUT", candidates: int = -1):
        L = lib()
        if not L.silk_generation_available():
            raise SilkError(4, "this libsilk was built without onnxruntime (no generation)")
        opts = L.silk_model_default_options()
        self.model, self.gen = ctypes.c_void_p(), ctypes.c_void_p()
        check(L.silk_model_load(os.fsencode(model_dir), ctypes.byref(opts), ctypes.byref(self.model)))
        try:
            check(L.silk_generator_create(self.model, ctypes.byref(self.gen)))
        finally:
            L.silk_model_destroy(self.model)  # the generator keeps its own reference
            self.model = None
        p = L.silk_generate_default_params()
        p.seed = seed
        if temperature >= 0:  # < 0: the model's default (model.json "sampling")
            p.temperature = temperature
        if top_k >= 0:
            p.top_k = top_k
        p.max_faces, p.max_tokens, p.holes = max_faces, max_tokens, silk_c.HOLES[repair.lower()]
        if surface_tolerance is not None:  # None: libsilk's measured default
            p.surface_tolerance = surface_tolerance
        p.orient = silk_c.ORIENT[orient.lower()]
        if candidates >= 1:  # < 1: the model's best of N (model.json "sampling.candidates")
            p.candidates = candidates
        gi = GenerateInput()
        if source is not None:
            gi.mesh = source.handle
        else:
            self._points = (ctypes.c_double * len(points))(*points)
            gi.points, gi.n_points = self._points, len(points) // 6
        self.done = False
        check(L.silk_generator_start(self.gen, ctypes.byref(gi), ctypes.byref(p)))
        self.max_tokens = max_tokens

    def advance(self, max_ids: int = 64, until_layer: bool = True) -> bool:
        done = ctypes.c_int32()
        check(lib().silk_generator_advance(self.gen, max_ids, 1 if until_layer else 0, ctypes.byref(done)))
        self.done = bool(done.value)
        return self.done

    def cancel(self) -> None:
        lib().silk_generator_cancel(self.gen)

    def stats(self) -> dict:
        st = GenerateStats()
        check(lib().silk_generator_stats(self.gen, ctypes.byref(st)))
        return st.as_dict()

    def mesh_so_far(self) -> Mesh:
        h = ctypes.c_void_p()
        check(lib().silk_generator_mesh(self.gen, ctypes.byref(h)))
        return Mesh(h)

    def finish(self) -> tuple[Mesh, dict]:
        h, st = ctypes.c_void_p(), GenerateStats()
        check(lib().silk_generator_finish(self.gen, ctypes.byref(h), None, ctypes.byref(st)))
        return Mesh(h), st.as_dict()

    def close(self) -> None:
        if self.gen:
            lib().silk_generator_destroy(self.gen)
            self.gen = None
