# SPDX-License-Identifier: MIT
"""Learning-rate schedule: linear warm-up, then cosine from the peak LR down to the final LR
(Mesh Silksong: 1e-4 -> 5e-5)."""

from __future__ import annotations

import math


def cosine_lr(step: int, total_steps: int, lr_max: float, lr_min: float, warmup: int = 0) -> float:
    if warmup > 0 and step < warmup:
        return lr_max * (step + 1) / warmup
    span = max(total_steps - warmup, 1)
    a = min(max((step - warmup) / span, 0.0), 1.0)
    return lr_min + 0.5 * (lr_max - lr_min) * (1 + math.cos(math.pi * a))
