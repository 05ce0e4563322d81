# SPDX-License-Identifier: MIT
"""silk_mesh.Mesh: a triangle mesh (or a point cloud with normals) held by libsilk, built from
arrays or read from a file, with its arrays copied out on request and saved in libsilk's formats."""

from __future__ import annotations

import ctypes
import os

from . import _arrays, _native, _params
from ._library import _Owned


class Mesh(_Owned):
    """An owned libsilk mesh. Mesh(positions, triangles) copies the arrays (rows or flat, numpy or
    sequences); Mesh.load(path) reads OBJ, PLY, STL, OFF, glTF/GLB, PMD (optionally .gz). Every
    array property copies out of libsilk (see silk_mesh's array rule). close() frees it at once
    (also `with`, and garbage collection)."""

    _h = None

    def __init__(self, positions=(), triangles=()):
        pos, nv, keep_p = _arrays.to_c(positions, ctypes.c_double, 3, "positions")
        tri, nt, keep_t = _arrays.to_c(triangles, ctypes.c_int32, 3, "triangles")
        self._h = _native.mesh_create(pos, nv, tri, nt)

    @classmethod
    def _adopt(cls, handle: ctypes.c_void_p) -> "Mesh":
        mesh = cls.__new__(cls)
        mesh._h = handle
        return mesh

    @classmethod
    def load(cls, path: str | os.PathLike, point_clouds: bool = True) -> "Mesh":
        """point_clouds: a PLY without faces (with normals) is a point cloud; False: read as a mesh."""
        return cls._adopt(_native.mesh_load(os.fsencode(path), point_clouds))

    def save(self, path: str | os.PathLike, **params) -> None:
        """By extension (.obj, .ply, .glb: one node per part) or `format` ("obj", "ply", "glb");
        part_colors (.glb), obj_comment (.obj header text). Written atomically."""
        p = _params.fill(_native.save_defaults(), params, "Mesh.save", {"format": _native.enum_names("mesh_format")})
        _native.mesh_save(self.handle, os.fsencode(path), p)

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._h:
            raise ValueError("silk_mesh.Mesh: the mesh is closed")
        return self._h

    @property
    def vertex_count(self) -> int:
        return _native.mesh_vertex_count(self.handle)

    @property
    def triangle_count(self) -> int:
        return _native.mesh_triangle_count(self.handle)

    @property
    def positions(self):
        """Vertex positions: numpy (n, 3) float64, else a list of (x, y, z)."""
        return _arrays.from_c(_native.mesh_positions(self.handle), 3)

    @property
    def triangles(self):
        """Vertex indices per triangle: numpy (m, 3) int32, else a list of (a, b, c)."""
        return _arrays.from_c(_native.mesh_triangles(self.handle), 3)

    @property
    def parts(self):
        """Part (component) index per triangle, in generation/decoding order; 0 for loaded meshes."""
        return _arrays.from_c(_native.mesh_parts(self.handle), 1)

    @property
    def normals(self):
        """Per-vertex normals of a point cloud (as positions), or None when the mesh has none."""
        buf = _native.mesh_normals(self.handle)
        return None if buf is None else _arrays.from_c(buf, 3)

    def _free(self) -> None:
        if self._h:
            _native.mesh_destroy(self._h)
            self._h = None

    def __repr__(self) -> str:
        if not self._h:
            return "<silk_mesh.Mesh (closed)>"
        return f"<silk_mesh.Mesh {self.vertex_count} vertices, {self.triangle_count} triangles>"


def load_arrays(path: str | os.PathLike):
    """(positions, triangles) of a mesh file (see Mesh.positions / Mesh.triangles)."""
    with Mesh.load(path) as m:
        return m.positions, m.triangles


class _Borrowed:
    """A mesh for one call: a Mesh as given (not closed), or one made from a path or a
    (positions, triangles) pair (closed after the call)."""

    SOURCES = (Mesh, str, bytes, os.PathLike)  # what is a mesh on its own (not a pair of arrays)

    def __init__(self, source, what: str):
        self.owned = not isinstance(source, Mesh)
        if isinstance(source, (str, bytes, os.PathLike)):
            self.mesh = Mesh.load(source)
        elif isinstance(source, Mesh):
            self.mesh = source
        elif isinstance(source, (tuple, list)) and len(source) == 2:
            self.mesh = Mesh(*source)
        else:
            raise TypeError(f"{what}: expected a Mesh, a path or (positions, triangles), not {type(source).__name__}")

    def __enter__(self) -> Mesh:
        return self.mesh

    def __exit__(self, *exc) -> None:
        if self.owned:
            self.mesh.close()
