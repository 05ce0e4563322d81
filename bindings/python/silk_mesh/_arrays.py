# SPDX-License-Identifier: MIT
"""numpy is optional (Debian's Blender, a bare Python): the one rule for array values.

Inputs: numpy arrays or any Python sequences, rows ([[x, y, z], ...]) or flat ([x, y, z, ...]).
Outputs: geometry (positions, normals, triangles, parts, encoder points) is a numpy array when
numpy is importable ((n, 3) float64, (m, 3) int32, (m,) int32, (n, 6) float32), else a list of
tuples (a list of ints for one value per row). Token ids are always a list of int. Setting the
environment variable SILK_MESH_NUMPY=0 before the import gives the plain-Python results even
where numpy is installed."""

from __future__ import annotations

import ctypes
import os

from . import _checks

try:
    import numpy as _numpy
except ImportError:  # pragma: no cover - exercised through SILK_MESH_NUMPY=0 in the tests
    _numpy = None

# The numpy used for results (None: plain Python), per the rule above.
np = None if os.environ.get("SILK_MESH_NUMPY") == "0" else _numpy

_DTYPES = {ctypes.c_double: "float64", ctypes.c_int32: "int32", ctypes.c_float: "float32"}


def _flatten(values, width: int, what: str) -> list:
    seq = list(values)
    if seq and not isinstance(seq[0], (int, float)) and hasattr(seq[0], "__len__"):
        flat = []
        for i, row in enumerate(seq):
            if not hasattr(row, "__len__") or len(row) != width:
                got = f"{len(row)} values" if hasattr(row, "__len__") else f"a {type(row).__name__}"
                raise ValueError(f"{what}: row {i} has {got}, expected {width}")
            flat.extend(row)
        return flat
    if len(seq) % width:
        raise ValueError(f"{what}: {len(seq)} values is not a multiple of {width}")
    return seq


def to_c(values, ctype, width: int, what: str):
    """(pointer, rows, keep-alive) for values as a C array of ctype, `width` per row. Checked by
    _checks before any conversion (dtype, shape, range); never reshaped or cast inexactly."""
    if _numpy is not None and hasattr(values, "__array_interface__"):
        arr = _numpy.asarray(values)
        rows = _checks.array_shape(arr.shape, width, what)
        _checks.array_dtype(arr, ctype, what)
        arr = _numpy.ascontiguousarray(arr, dtype=_DTYPES[ctype])  # a copy unless already so
        return arr.ctypes.data_as(ctypes.POINTER(ctype)), rows, arr
    if isinstance(values, (str, bytes)):
        raise TypeError(f"{what}: expected numbers, not {type(values).__name__}")
    flat = _checks.sequence_values(_flatten(values, width, what), ctype, what)
    buf = (ctype * len(flat))(*flat)
    return ctypes.cast(buf, ctypes.POINTER(ctype)), len(flat) // width, buf


def from_c(buf, width: int):
    """A ctypes array as the rule's result: numpy (rows, width) or (rows,), else tuples / ints."""
    if np is not None:
        dtype = _DTYPES[buf._type_]
        arr = np.frombuffer(buf, dtype=dtype) if len(buf) else np.empty(0, dtype=dtype)
        return arr if width == 1 else arr.reshape(-1, width)
    if width == 1:
        return list(buf)
    flat = list(buf)
    return [tuple(flat[i : i + width]) for i in range(0, len(flat), width)]
