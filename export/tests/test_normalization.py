# SPDX-License-Identifier: MIT
"""Python takes libsilk's normalisation and never one of its own: the evaluation's reference frame
is libsilk's transform (bit for bit the token_format.md §2.1 rule, written out below as this test's
oracle, on dev meshes), training points are normalised once, by libsilk, from the raw vertices,
and a mesh with all vertices at one point is refused with libsilk's message (numpy used to take
scale 1.0 for it)."""

from __future__ import annotations

import numpy as np
import pytest

import silk_mesh
from silk_export.data.normalization import normalize_vertices
from silk_export.data.samples import make_sample

ZERO_EXTENT = "zero or infinite extent"  # libsilk's ComputeNormalization message


def spec_normalize(v: np.ndarray, bound: float = 0.95) -> np.ndarray:
    """token_format.md §2.1: centre the bounding box of all vertices, longest side to 2 * bound."""
    lo, hi = v.min(axis=0), v.max(axis=0)
    return (v - (hi + lo) / 2) * ((2 * bound) / (hi - lo).max())


def dev_meshes(dev_dir, n: int = 6):
    return [silk_mesh.load_arrays(p) for p in sorted(dev_dir.glob("*.obj"))[::20][:n]]


def test_reference_frame_is_libsilks_transform_bit_for_bit(lib_path, dev_dir):
    for v, f in dev_meshes(dev_dir):
        got = normalize_vertices(v, f)
        assert got.dtype == np.float64 and np.array_equal(got, spec_normalize(np.asarray(v, np.float64)))
        assert np.isclose(np.abs(got).max(), 0.95)
        assert np.array_equal(normalize_vertices(v, f, 0.5), spec_normalize(np.asarray(v, np.float64), 0.5))


def test_training_points_are_normalised_once_by_libsilk(lib_path, dev_dir):
    """make_sample's condition = silk_points_prepare on the raw vertices with the sample's seed."""
    checked = 0
    for v, f in dev_meshes(dev_dir):
        try:
            s = make_sample(v, f, np.random.default_rng(5), 100_000, augment=False, n_points=256)
        except silk_mesh.SilkError as e:  # a mesh the tokenizer refuses has no training sample
            assert e.name == "refused"
            continue
        seed = int(np.random.default_rng(5).integers(0, 2**63))  # the one draw point_cloud makes
        want, _, _ = silk_mesh.prepare_points(v, f, "silk", n_points=256, seed=seed)
        assert np.array_equal(s.points, want)
        checked += 1
    assert checked >= 3


def test_zero_extent_is_refused_with_libsilks_message(lib_path, tmp_path):
    v, f = np.full((3, 3), 2.5), np.array([[0, 1, 2]], np.int32)
    with pytest.raises(silk_mesh.SilkError, match=ZERO_EXTENT):
        normalize_vertices(v, f)
    with pytest.raises(silk_mesh.SilkError, match=ZERO_EXTENT):
        make_sample(v, f, np.random.default_rng(0), 100, augment=False)


@pytest.mark.skipif(not silk_mesh.generation_available(), reason="libsilk without onnxruntime")
def test_generate_records_a_zero_extent_input_and_goes_on(lib_path, dev_dir, tmp_path):
    from pathlib import Path

    from silk_export.evaluation.generate import generate_paths

    flat = tmp_path / "point.obj"
    flat.write_text("v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\n")
    good = sorted(dev_dir.glob("*.obj"))[0]
    tiny = Path(__file__).resolve().parents[2] / "tests/models/tiny"
    res = generate_paths(tiny, [flat, good], tmp_path / "gen", seed=1, max_tokens=30)
    bad, ok = res["meshes"]
    assert ZERO_EXTENT in bad["error"] and not bad["eos"]
    assert not (tmp_path / "gen" / "reference" / "point.obj").exists()  # no reference in a made-up frame
    assert "error" not in ok and (tmp_path / "gen" / "reference" / f"{good.name.split('.')[0]}.obj").exists()
