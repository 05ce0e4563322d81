# SPDX-License-Identifier: MIT
"""libsilk's pre-processing through the binding (silk_points_prepare): the training point
clouds come from the same code as generation; the official kind is seeded, float16-valued and
on the surface; bad arguments raise SilkError."""

from __future__ import annotations

import numpy as np
import pytest

import silk_mesh
from silk_export.data import pointcloud

# A box [0,2]x[0,1]x[0,1] of 12 triangles.
V = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0], [0, 0, 1], [2, 0, 1], [2, 1, 1], [0, 1, 1]], float)
F = np.array(
    [
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ],
    np.int32,
)


def test_official_points_are_seeded_float16_and_on_the_box(lib_path):
    a, centre, scale = silk_mesh.prepare_points(V, F, "official", n_points=4096, seed=5)
    b, _, _ = silk_mesh.prepare_points(V, F, "official", n_points=4096, seed=5)
    c, _, _ = silk_mesh.prepare_points(V, F, "official", n_points=4096, seed=6)
    assert a.shape == (4096, 6) and a.dtype == np.float32
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    assert np.array_equal(a.astype(np.float16).astype(np.float32), a)
    assert np.allclose(centre, [1, 0.5, 0.5]) and scale == pytest.approx(0.95)
    np.testing.assert_allclose(np.linalg.norm(a[:, 3:], axis=1), 1, atol=1e-3)
    on_face = np.abs(np.abs(a[:, :3]) - [0.95, 0.475, 0.475]) < 1e-3
    assert on_face.any(axis=1).all()


def test_training_point_cloud_uses_the_library(lib_path):
    rng = np.random.default_rng(3)
    seed = int(np.random.default_rng(3).integers(0, 2**63))
    pts = pointcloud.point_cloud(V, F, rng, n=256, noise=False)
    want, _, _ = silk_mesh.prepare_points(V, F, "silk", n_points=256, seed=seed)
    assert np.array_equal(pts, want)
    p, n = pointcloud.sample_surface(V, F, 500, np.random.default_rng(1))
    assert (
        p.shape == (500, 3) and (p.min(axis=0) >= -1e-6).all() and (p.max(axis=0) <= np.array([2, 1, 1]) + 1e-6).all()
    )
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1, atol=1e-6)


def test_clouds_and_errors(lib_path):
    cloud = np.concatenate([np.random.default_rng(0).random((100, 3)), np.tile([0, 0, 3.0], (100, 1))], axis=1)
    rows, _, _ = silk_mesh.prepare_points(cloud, None, "official", n_points=64, seed=1)
    assert rows.shape == (64, 6) and (rows[:, 5] == 1).all()
    with pytest.raises(silk_mesh.SilkError, match="surface_samples"):
        silk_mesh.prepare_points(V, F, "official", n_points=64, surface_samples=-1)
    with pytest.raises(TypeError):
        silk_mesh.prepare_points(V, F, "silk", bogus=1)
