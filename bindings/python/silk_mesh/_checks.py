# SPDX-License-Identifier: MIT
"""The one place the binding checks what it hands to libsilk, so nothing is truncated, cast or
reshaped on the way: integers against the range of their C type, arrays for dtype, shape and
exact representability before any conversion. Every error names the argument (ValueError for a
value out of range or a wrong shape, TypeError for a wrong type).

The array rule (docs: bindings/python/silk_mesh/README.md):
- positions, normals, points (float64 in C): any float dtype, or an integer dtype whose values
  are exactly representable as float64 (|v| <= 2**53); bool, complex, object and text refused.
- triangles and token ids (int32 in C): integer dtypes only (a float array is refused, even with
  whole values: convert it yourself, e.g. .astype(numpy.int32)); every value must fit int32.
- shape: (n, width) rows, or flat (width * n,); any other shape is refused, never reshaped.
- strides and byte order: a non-contiguous or byte-swapped array is copied (values unchanged)."""

from __future__ import annotations

import ctypes
import numbers

_INT_RANGES = {
    ctypes.c_int8: (-(2**7), 2**7 - 1),
    ctypes.c_uint8: (0, 2**8 - 1),
    ctypes.c_int16: (-(2**15), 2**15 - 1),
    ctypes.c_uint16: (0, 2**16 - 1),
    ctypes.c_int32: (-(2**31), 2**31 - 1),
    ctypes.c_uint32: (0, 2**32 - 1),
    ctypes.c_int64: (-(2**63), 2**63 - 1),
    ctypes.c_uint64: (0, 2**64 - 1),
}
_INT_RANGES[ctypes.c_size_t] = (0, 2 ** (8 * ctypes.sizeof(ctypes.c_size_t)) - 1)
_C_NAMES = {
    ctypes.c_int32: "int32",
    ctypes.c_uint32: "uint32",
    ctypes.c_int64: "int64",
    ctypes.c_uint64: "uint64",
    ctypes.c_int8: "int8",
    ctypes.c_uint8: "uint8",
    ctypes.c_int16: "int16",
    ctypes.c_uint16: "uint16",
    ctypes.c_double: "float64",
    ctypes.c_float: "float32",
}
_FLOAT_EXACT = 2**53  # the largest magnitude up to which every integer is a float64


def is_int_type(ctype) -> bool:
    return ctype in _INT_RANGES


def c_name(ctype) -> str:
    return _C_NAMES.get(ctype, getattr(ctype, "__name__", str(ctype)))


def integer(value, ctype, name: str) -> int:
    """value as a Python int within ctype's range; bool counts as 0/1, numpy integers are taken,
    floats (even 3.0) and anything else raise TypeError naming `name`."""
    if isinstance(value, bool):
        value = int(value)
    if not isinstance(value, numbers.Integral):
        raise TypeError(f"{name}: expected an integer, not {type(value).__name__} {value!r}")
    value = int(value)
    lo, hi = _INT_RANGES[ctype]
    if not lo <= value <= hi:
        raise ValueError(f"{name}={value} is out of range: it must be in [{lo}, {hi}] ({c_name(ctype)})")
    return value


def real(value, name: str) -> float:
    """value as a float (a Python or numpy real; bool refused): TypeError naming `name` otherwise."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name}: expected a number, not {type(value).__name__} {value!r}")
    try:
        return float(value)
    except OverflowError:
        raise ValueError(f"{name}={value} is out of range for float64") from None


def array_shape(shape: tuple, width: int, name: str) -> int:
    """The number of rows of an array of `shape`: (n, width) or flat (width * n,), else ValueError."""
    what = f"(n, {width})" if width > 1 else "(n,)"
    if len(shape) == 2 and shape[1] == width and width > 1:
        return shape[0]
    if len(shape) == 1 and shape[0] % width == 0:
        return shape[0] // width
    raise ValueError(
        f"{name}: an array of shape {tuple(shape)} is not {what} or flat ({width} values a row); "
        f"it is not reshaped" + (" (points are rows of x y z nx ny nz)" if width == 6 else "")
    )


def array_dtype(arr, ctype, name: str) -> None:
    """Refuses a numpy array whose dtype cannot go to ctype exactly (see the module's rule)."""
    kind = arr.dtype.kind
    if is_int_type(ctype):
        if kind not in "iu":
            hint = " (convert it with .astype(numpy.int32) if its values are whole)" if kind == "f" else ""
            raise TypeError(f"{name}: dtype {arr.dtype} is not an integer type{hint}")
        lo, hi = _INT_RANGES[ctype]
        if arr.size and (int(arr.min()) < lo or int(arr.max()) > hi):
            bad = int(arr.min()) if int(arr.min()) < lo else int(arr.max())
            raise ValueError(f"{name}: value {bad} is out of range for {c_name(ctype)} [{lo}, {hi}]")
        return
    if kind == "f":
        if arr.dtype.itemsize > 8:
            raise TypeError(f"{name}: dtype {arr.dtype} does not fit float64 exactly")
        return
    if kind in "iu":
        if arr.size and max(abs(int(arr.min())), abs(int(arr.max()))) > _FLOAT_EXACT:
            raise ValueError(f"{name}: integer values beyond 2**53 are not exactly representable as float64")
        return
    raise TypeError(f"{name}: dtype {arr.dtype} is not a real number type")


def sequence_values(flat: list, ctype, name: str) -> list:
    """The values of a Python sequence checked like an array's (ints for int types, range, exact)."""
    if is_int_type(ctype):
        return [integer(v, ctype, f"{name}[{i}]") for i, v in enumerate(flat)]
    out = []
    for i, v in enumerate(flat):
        x = real(v, f"{name}[{i}]")
        if isinstance(v, numbers.Integral) and int(x) != int(v):
            raise ValueError(f"{name}[{i}]={v} is not exactly representable as float64")
        out.append(x)
    return out
