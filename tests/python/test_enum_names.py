# SPDX-License-Identifier: MIT
"""The binding's enum names are libsilk's (C API 1.4, silk_<enum>_name): every enum silk.h declares
has its names in the library, silk_mesh.enum_names gives exactly those (each one round-trips through
silk_<enum>_from_name), the stop reason of a running generation is C's "none" (not "running"), and
an enum keyword of generate() takes the library's names and refuses others naming them."""

from __future__ import annotations

import ctypes
import re
from pathlib import Path

import pytest

import silk_mesh
from silk_mesh import _capi, _native, _params

SILK_H = Path(__file__).resolve().parents[2] / "engine" / "include" / "silk" / "silk.h"
NAMED_ELSEWHERE = {"silk_status"}  # silk_status_name: the status's readable text ("invalid argument")


def declared_enums() -> dict[str, list[int]]:
    """{enum type: its values} of every `typedef enum silk_x {...} silk_x;` in silk.h."""
    text = re.sub(r"/\*.*?\*/", "", SILK_H.read_text(encoding="utf-8"), flags=re.S)
    enums = {}
    for name, body in re.findall(r"typedef enum (silk_\w+)\s*\{(.*?)\}", text, flags=re.S):
        enums[name] = [int(v) for v in re.findall(r"SILK_\w+\s*=\s*(-?\d+)", body)]
    return enums


def test_every_enum_of_silk_h_has_the_librarys_names(lib_path):
    enums = declared_enums()
    assert len(enums) >= 12, f"silk.h enums not found: {sorted(enums)}"
    for enum, values in enums.items():
        if enum in NAMED_ELSEWHERE:
            continue
        short = enum[len("silk_") :]
        assert short in _capi.ENUM_FIRST, f"{enum}: not in the binding's _capi.ENUM_FIRST"
        names = silk_mesh.enum_names(short)
        assert sorted(names.values()) == sorted(values), f"{enum}: {names} against silk.h's {values}"
        assert all(n and n != "unknown" for n in names), names


@pytest.mark.parametrize("enum", sorted(_capi.ENUM_FIRST))
def test_the_bindings_names_are_the_librarys_both_ways(enum, lib_path):
    lib = silk_mesh.load_library()
    names = silk_mesh.enum_names(enum)
    assert names, enum
    from_name = getattr(lib, f"silk_{enum}_from_name")
    for name, value in names.items():
        out = ctypes.c_int32(-99)
        assert from_name(name.encode(), ctypes.byref(out)) == _capi.SILK_OK
        assert out.value == value
        assert getattr(lib, f"silk_{enum}_name")(value).decode() == name
    past = max(names.values()) + 1
    assert getattr(lib, f"silk_{enum}_name")(past) == b"unknown"
    out = ctypes.c_int32(-99)
    assert from_name(b"no such name", ctypes.byref(out)) == _capi.SILK_ERR_INVALID_ARGUMENT
    assert out.value == -99
    assert f"silk_{enum}" in lib.silk_last_error().decode()


def test_a_running_generations_stop_reason_is_cs_none(lib_path):
    st = _capi.GenerateStats()
    st.stop_reason = -1  # SILK_STOP_NONE: what silk_generator_get_stats says while running
    assert _native.stats_dict(st)["stop_reason"] == "none"
    st.stop_reason = 3
    assert _native.stats_dict(st)["stop_reason"] == "grammar_dead_end"


def test_an_enum_keyword_takes_the_librarys_names_only(lib_path):
    p = _native.generate_defaults()
    enums = {"holes": silk_mesh.enum_names("hole_policy")}
    assert _params.fill(p, {"holes": "REPORT"}, "generate", enums).holes == enums["holes"]["report"]
    with pytest.raises(ValueError, match=r"holes must be one of \['off', 'repair', 'report'\], not 'mend'"):
        _params.fill(p, {"holes": "mend"}, "generate", enums)


def test_enum_names_refuses_an_unknown_enum(lib_path):
    with pytest.raises(ValueError, match="unknown enum 'colour'"):
        silk_mesh.enum_names("colour")
