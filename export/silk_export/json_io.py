# SPDX-License-Identifier: MIT
"""The one way silk_export writes JSON: always valid JSON (RFC 8259). Python's json module writes
NaN / Infinity as the bare words `NaN` / `Infinity` by default, which no other JSON reader accepts
(silkgen: "not a JSON object"). Each writer chooses what a non-finite float becomes, by what the
file's reader expects: "refuse" (a ValueError naming the field; for files read as inputs, e.g.
model.json, the dataset index) or "null" (for reports and logs, where a missing figure is fine)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Iterator

NONFINITE_POLICIES = ("refuse", "null")


class NonFiniteJSONError(ValueError):
    """A value that JSON cannot hold (NaN, Infinity) in a document whose reader needs a number."""


def nonfinite_fields(obj: Any, path: str = "") -> Iterator[tuple[str, float]]:
    """(field path such as 'import.fidelity.decoder_int8.kl_mean' or 'meshes[3].cd', value) for
    every NaN / +-Infinity float inside dicts, lists and tuples."""
    if isinstance(obj, float):
        if not math.isfinite(obj):
            yield path or "(the document)", obj
    elif isinstance(obj, dict):
        for k, v in obj.items():
            yield from nonfinite_fields(v, f"{path}.{k}" if path else str(k))
    elif isinstance(obj, (list, tuple)):
        for i, v in enumerate(obj):
            yield from nonfinite_fields(v, f"{path}[{i}]")


def nonfinite_to_null(obj: Any) -> Any:
    """A copy of obj with every non-finite float replaced by None (JSON null)."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: nonfinite_to_null(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [nonfinite_to_null(v) for v in obj]
    return obj


def dumps(obj: Any, nonfinite: str = "refuse", what: str = "JSON document", **kwargs) -> str:
    """json.dumps that never writes NaN / Infinity: `nonfinite` "refuse" raises NonFiniteJSONError
    naming `what` and every offending field; "null" writes them as null."""
    if nonfinite not in NONFINITE_POLICIES:
        raise ValueError(f"nonfinite '{nonfinite}': expected one of {', '.join(NONFINITE_POLICIES)}")
    if nonfinite == "null":
        obj = nonfinite_to_null(obj)
    else:
        bad = list(nonfinite_fields(obj))
        if bad:
            fields = ", ".join(f"'{p}' = {v}" for p, v in bad[:10]) + (
                f" (and {len(bad) - 10} more)" if len(bad) > 10 else ""
            )
            raise NonFiniteJSONError(f"{what}: non-finite value(s), which JSON cannot hold: {fields}")
    return json.dumps(obj, allow_nan=False, **kwargs)


def write_json(path: Path, obj: Any, nonfinite: str = "refuse", indent: int | None = 2) -> Path:
    """Writes obj to path as JSON with a final newline (see dumps; the error names the file)."""
    path = Path(path)
    path.write_text(dumps(obj, nonfinite, what=str(path), indent=indent) + "\n")
    return path


def jsonl_line(obj: Any, nonfinite: str = "refuse", what: str = "JSON Lines record") -> str:
    """One JSON Lines record (compact, newline-terminated)."""
    return dumps(obj, nonfinite, what=what) + "\n"
