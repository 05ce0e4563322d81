# SPDX-License-Identifier: MIT
"""silk_mesh.prepare_points: the encoder's input points by libsilk's pre-processing (the same code
generation runs, and training uses), from a mesh or an oriented point cloud."""

from __future__ import annotations

import ctypes

from . import _arrays, _checks, _native, _params
from .mesh import _Borrowed


def prepare_points(source, triangles=None, kind: str = "silk", n_points: int = 4096, seed: int = 0, **params):
    """(points, centre, scale): points (n_points rows of x y z nx ny nz, normalised; numpy float32
    (n, 6) or a list of 6-tuples), centre (x, y, z) and scale with model = (input - centre) * scale.
    source: a Mesh, a path, positions (with `triangles`), or, with triangles None and not a Mesh or
    path, a point cloud of rows x y z nx ny nz. kind "silk" or "official" picks the defaults;
    params: normalize_bound, merge_distance_fraction, surface_samples, round_float16."""
    kinds = _native.enum_names("preprocess_kind")
    if kind not in kinds:
        raise ValueError(f"prepare_points: kind must be one of {sorted(kinds)}, not {kind!r}")
    p = _params.fill(
        _native.preprocess_defaults(kinds[kind]),
        params,
        "prepare_points",
        hidden=("struct_size", "kind", "point_count"),
    )
    p.point_count = _checks.integer(n_points, ctypes.c_int32, "prepare_points: n_points")
    seed = _checks.integer(seed, ctypes.c_uint64, "prepare_points: seed")
    if triangles is not None:
        source = (source, triangles)
    if triangles is None and not isinstance(source, _Borrowed.SOURCES):
        cloud, rows, _keep = _arrays.to_c(source, ctypes.c_double, 6, "prepare_points: cloud")
        out, transform = _native.prepare_points(None, cloud, rows, p, seed)
    else:
        with _Borrowed(source, "prepare_points") as mesh:
            out, transform = _native.prepare_points(mesh.handle, None, 0, p, seed)
    return _arrays.from_c(out, 6), tuple(transform[:3]), float(transform[3])
