# SPDX-License-Identifier: MIT
"""What each rank trains on. Sample `slot` of global step `step` is a pure function of
(seed, step, slot): its own numpy generator picks the mesh (progressive-balanced), the
augmentation and the point cloud, redrawing when libsilk refuses or the sequence is too long.
So the global batch is the same at every world size, rank r takes the contiguous slots
[r·B/W, (r+1)·B/W), and a resumed run needs no data state. DataLoader workers (optional)
prepare whole steps ahead of the trainer, tokenising through libsilk in their own processes."""

from __future__ import annotations

import numpy as np
import torch

import silk_mesh
from ..data.samples import TooLong

TRIES_PER_SLOT = 50


def rank_slots(batch_size: int, rank: int, world: int) -> range:
    if batch_size % world:
        raise ValueError(f"--batch-size {batch_size} (the global batch) must be a multiple of the {world} ranks")
    per = batch_size // world
    return range(rank * per, (rank + 1) * per)


def draw_sample(source, sampler, seed: int, step: int, slot: int, cfg, augment: bool):
    rng = np.random.default_rng([seed, step, slot])
    for _ in range(TRIES_PER_SLOT):
        i = int(sampler.sample(step, 1, rng)[0])
        try:
            return source.sample(i, rng, cfg.max_tokens, augment=augment, n_points=cfg.n_points)
        except (TooLong, silk_mesh.SilkError, ValueError):
            continue
    raise RuntimeError(f"step {step} slot {slot}: {TRIES_PER_SLOT} draws refused or too long; check the data")


class StepSamples(torch.utils.data.Dataset):
    """Item `step` = this rank's samples of that step (a list, in slot order)."""

    def __init__(self, source, sampler, seed: int, cfg, augment: bool, slots: range, steps: int):
        self.source, self.sampler, self.seed, self.cfg = source, sampler, seed, cfg
        self.augment, self.slots, self.steps = augment, slots, steps

    def __len__(self) -> int:
        return self.steps

    def __getitem__(self, step: int):
        return [draw_sample(self.source, self.sampler, self.seed, step, s, self.cfg, self.augment) for s in self.slots]


def _as_is(item):
    return item


def step_loader(data: StepSamples, start_step: int, workers: int):
    """Yields data[start_step], data[start_step + 1], ... in order (workers prefetch)."""
    return torch.utils.data.DataLoader(
        data,
        batch_size=None,
        sampler=range(start_step, data.steps),
        num_workers=workers,
        collate_fn=_as_is,
        prefetch_factor=2 if workers else None,
    )
