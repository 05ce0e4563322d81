# SPDX-License-Identifier: MIT
"""Keyword parameters onto a C params struct: each keyword names a field of the struct (as in
silk.h); None keeps libsilk's default; an enum field takes its name ("repair", "input", ...) or
its number. An unknown keyword or enum name raises TypeError / ValueError naming it."""

from __future__ import annotations

import ctypes

from . import _checks


def fill(
    struct: ctypes.Structure, params: dict, where: str, enums: dict | None = None, hidden: tuple = ()
) -> ctypes.Structure:
    """Sets struct fields from params (see the module docstring) and returns the struct."""
    enums = enums or {}
    fields = {name: ctype for name, ctype in type(struct)._fields_ if name not in hidden and name != "struct_size"}
    for name, value in params.items():
        if name not in fields:
            raise TypeError(f"{where}: unknown parameter '{name}' (known: {', '.join(sorted(fields))})")
        if value is None:
            continue
        if name in enums and isinstance(value, str):
            key = value.lower()
            if key not in enums[name]:
                raise ValueError(f"{where}: {name} must be one of {sorted(enums[name])}, not {value!r}")
            value = enums[name][key]
        elif fields[name] is ctypes.c_char_p and isinstance(value, str):
            value = value.encode()
        elif _checks.is_int_type(fields[name]):
            value = _checks.integer(value, fields[name], f"{where}: {name}")
        elif fields[name] in (ctypes.c_double, ctypes.c_float):
            value = _checks.real(value, f"{where}: {name}")
        try:
            setattr(struct, name, value)
        except TypeError as e:
            raise TypeError(f"{where}: {name}={value!r}: {e}") from e
    return struct


def as_dict(struct: ctypes.Structure) -> dict:
    """Every field by name (char arrays as str)."""
    out = {}
    for name, _ in type(struct)._fields_:
        value = getattr(struct, name)
        out[name] = value.decode(errors="replace") if isinstance(value, bytes) else value
    return out
