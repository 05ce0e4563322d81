# SPDX-License-Identifier: MIT
"""Refuses weights holding NaN or Inf before they become a model folder: graphs computed from
them are garbage, and figures derived from them (model.json fidelity, scores) are not even JSON.
One check for both exporters (`silk-export export`, `silk-export import-official`)."""

from __future__ import annotations

from typing import Iterable

import torch


def nonfinite_summary(t: torch.Tensor) -> str | None:
    """'1 NaN, 3 Inf of 4096 values' (Inf counts both signs), or None when every value is finite."""
    if not t.is_floating_point() or bool(torch.isfinite(t).all()):
        return None
    nan, inf = int(torch.isnan(t).sum()), int(torch.isinf(t).sum())
    found = [f"{n} {word}" for n, word in ((nan, "NaN"), (inf, "Inf")) if n]
    return f"{', '.join(found)} of {t.numel()} values"


def nonfinite_message(source: str, problems: list[str]) -> str:
    return (
        f"{source}: {len(problems)} tensor(s) hold non-finite weights (NaN or Inf); refusing to export "
        "a model from them:\n  " + "\n  ".join(problems)
    )


def check_finite(named: Iterable[tuple[str, torch.Tensor]], source: str) -> None:
    """Raises ValueError naming every tensor (its state_dict key) with NaN / Inf and their counts."""
    problems = [f"key '{k}': {s}" for k, t in named if (s := nonfinite_summary(t)) is not None]
    if problems:
        raise ValueError(nonfinite_message(source, problems))
