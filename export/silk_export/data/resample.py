# SPDX-License-Identifier: MIT
"""Progressive-balanced resampling (Mesh Silksong training recipe): one class per 100 faces;
p_j(t) = (1 - t/T)·p_j^IB + (t/T)·p_j^CB, instance-balanced (class size / N) moving linearly to
class-balanced (uniform over classes); within a class every mesh is equally likely."""

from __future__ import annotations

import numpy as np

CLASS_WIDTH = 100


class ProgressiveBalancedSampler:
    def __init__(self, face_counts, total_steps: int, class_width: int = CLASS_WIDTH):
        faces = np.asarray(face_counts, dtype=np.int64)
        if faces.size == 0:
            raise ValueError("no items to sample from")
        self.total_steps = max(int(total_steps), 1)
        self.labels = faces // class_width
        self.classes, self.inverse, self.class_sizes = np.unique(self.labels, return_inverse=True, return_counts=True)
        self.p_instance = self.class_sizes / faces.size
        self.p_class = np.full(self.classes.size, 1.0 / self.classes.size)

    def class_probs(self, step: int) -> np.ndarray:
        a = min(max(step / self.total_steps, 0.0), 1.0)
        return (1 - a) * self.p_instance + a * self.p_class

    def item_probs(self, step: int) -> np.ndarray:
        p = self.class_probs(step)[self.inverse] / self.class_sizes[self.inverse]
        return p / p.sum()

    def sample(self, step: int, k: int, rng: np.random.Generator) -> np.ndarray:
        return rng.choice(self.labels.size, size=k, replace=True, p=self.item_probs(step))
