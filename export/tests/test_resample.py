# SPDX-License-Identifier: MIT
"""Progressive-balanced resampling follows p_j(t) = (1 - t/T)·p_j^IB + (t/T)·p_j^CB with one class
per 100 faces, and sampling frequencies follow those probabilities."""

from __future__ import annotations

import numpy as np

from silk_export.data.resample import ProgressiveBalancedSampler

# classes: [0,100) x6, [100,200) x3, [500,600) x1  -> sizes 6, 3, 1 of N = 10
FACES = [5, 20, 50, 99, 0, 60, 100, 150, 199, 512]


def test_class_probabilities_follow_the_formula():
    s = ProgressiveBalancedSampler(FACES, total_steps=100)
    assert s.classes.tolist() == [0, 1, 5]
    ib, cb = np.array([0.6, 0.3, 0.1]), np.full(3, 1 / 3)
    for t in (0, 25, 50, 100, 150):
        a = min(t / 100, 1.0)
        np.testing.assert_allclose(s.class_probs(t), (1 - a) * ib + a * cb, atol=1e-12)


def test_item_probabilities_uniform_within_class():
    s = ProgressiveBalancedSampler(FACES, total_steps=10)
    p = s.item_probs(10)  # class balanced: each class 1/3
    assert np.isclose(p.sum(), 1.0)
    np.testing.assert_allclose(p[:6], (1 / 3) / 6)  # items 0..5 (class 0, including faces 0 and 60)
    np.testing.assert_allclose(p[6:9], (1 / 3) / 3)
    np.testing.assert_allclose(p[9], 1 / 3)
    np.testing.assert_allclose(s.item_probs(0), np.full(10, 0.1))  # instance balanced = uniform items


def test_sampling_frequencies_match():
    s = ProgressiveBalancedSampler(FACES, total_steps=4)
    rng = np.random.default_rng(0)
    n = 60000
    for t in (0, 2, 4):
        idx = s.sample(t, n, rng)
        freq = np.bincount(s.inverse[idx], minlength=3) / n
        np.testing.assert_allclose(freq, s.class_probs(t), atol=0.01)
