# SPDX-License-Identifier: MIT
"""Issue 35 item 11: silk_mesh checks what it hands to libsilk (bindings/python/silk_mesh/_checks.py)
before any cast. Integers out of their C type's range, arrays of the wrong dtype or shape, and
values a cast would change are refused with ValueError / TypeError naming the argument; nothing is
truncated (max_tokens=2**32+14 ran with 14), cast (float or int64 triangle indices) or reshaped (a
(3, 4) positions array became 4 vertices; points=<4096 x 3> became 2,048 rows of 6)."""

from __future__ import annotations

from pathlib import Path

import pytest

import silk_mesh

np = pytest.importorskip("numpy")

ROOT = Path(__file__).resolve().parents[2]
TINY = ROOT / "tests" / "models" / "tiny"
KNOT = ROOT / "samples" / "torus_knot.obj"
TRI = [[0, 1, 2], [0, 2, 3]]
QUAD = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]


def test_integer_parameters_are_range_checked_against_their_c_type(lib_path):
    with pytest.raises(
        ValueError,
        match=r"encode: normalize=4294967297 is out of range: it must be in "
        r"\[-2147483648, 2147483647\] \(int32\)",
    ):
        silk_mesh.encode(KNOT, normalize=2**32 + 1)
    with pytest.raises(TypeError, match="encode: normalize: expected an integer, not float"):
        silk_mesh.encode(KNOT, normalize=1.0)
    with pytest.raises(TypeError, match="encode: normalize_bound: expected a number, not str"):
        silk_mesh.encode(KNOT, normalize_bound="0.9")
    assert silk_mesh.encode(KNOT, normalize=np.int64(1)) == silk_mesh.encode(KNOT)  # numpy integers are integers
    with pytest.raises(
        ValueError, match=r"prepare_points: seed=-1 is out of range: it must be in \[0, 18446744073709551615\]"
    ):
        silk_mesh.prepare_points(KNOT, seed=-1)
    with pytest.raises(ValueError, match="prepare_points: n_points=2147483648 is out of range"):
        silk_mesh.prepare_points(KNOT, n_points=2**31)


def test_generation_integers_are_refused_not_truncated(generation):
    with silk_mesh.Generator(TINY) as gen:
        with pytest.raises(
            ValueError,
            match=r"generate: max_tokens=4294967310 is out of range: it must be in "
            r"\[-2147483648, 2147483647\] \(int32\)",
        ):
            gen.run(KNOT, seed=1, max_tokens=2**32 + 14)
        with pytest.raises(ValueError, match="generate: seed=-1 is out of range"):
            gen.run(KNOT, seed=-1, max_tokens=60)
        gen.start(KNOT, seed=1, max_tokens=60)
        with pytest.raises(ValueError, match="advance: max_ids=2147483648 is out of range"):
            gen.advance(2**31)
        gen.finish().mesh.close()
    with pytest.raises(ValueError, match="Model: threads=4294967297 is out of range"):
        silk_mesh.Model(TINY, threads=2**32 + 1)


def test_triangle_indices_must_be_integers_that_fit_int32(lib_path):
    with silk_mesh.Mesh(QUAD, np.array(TRI, dtype=np.int64)) as m:  # exactly representable: taken
        assert m.triangles.tolist() == TRI
    with silk_mesh.Mesh(QUAD, np.array(TRI, dtype=np.uint8)) as m:
        assert m.triangles.tolist() == TRI
    with pytest.raises(
        TypeError,
        match=r"triangles: dtype float64 is not an integer type \(convert it with "
        r"\.astype\(numpy\.int32\)",
    ):
        silk_mesh.Mesh(QUAD, np.array(TRI, dtype=np.float64))
    with pytest.raises(ValueError, match=r"triangles: value 4294967296 is out of range for int32"):
        silk_mesh.Mesh(QUAD, np.array([[0, 1, 2**32]], dtype=np.int64))
    with pytest.raises(TypeError, match=r"triangles\[2\]: expected an integer, not float 2.0"):
        silk_mesh.Mesh(QUAD, [[0, 1, 2.0]])
    with pytest.raises(ValueError, match=r"triangles\[2\]=4294967298 is out of range"):
        silk_mesh.Mesh(QUAD, [[0, 1, 2**32 + 2]])
    with pytest.raises(TypeError, match="triangles: dtype bool is not an integer type"):
        silk_mesh.Mesh(QUAD, np.ones((1, 3), dtype=bool))
    with pytest.raises(TypeError, match="ids: dtype float32 is not an integer type"):
        silk_mesh.decode(np.zeros(8, dtype=np.float32))


def test_arrays_are_never_reshaped(lib_path):
    with pytest.raises(ValueError, match=r"positions: an array of shape \(3, 4\) is not \(n, 3\) or flat"):
        silk_mesh.Mesh(np.zeros((3, 4)), [])
    with pytest.raises(ValueError, match=r"positions: an array of shape \(2, 2, 3\)"):
        silk_mesh.Mesh(np.zeros((2, 2, 3)), [])
    with pytest.raises(ValueError, match=r"prepare_points: cloud: an array of shape \(4096, 3\) is not \(n, 6\)"):
        silk_mesh.prepare_points(np.zeros((4096, 3)))
    with silk_mesh.Mesh(np.array(QUAD, dtype=np.float64).ravel(), np.array(TRI).ravel()) as m:  # flat is rows
        assert m.positions.tolist() == QUAD and m.triangles.tolist() == TRI


def test_points_of_three_columns_are_refused_by_generate(generation):
    with silk_mesh.Generator(TINY) as gen:
        with pytest.raises(
            ValueError,
            match=r"points: an array of shape \(4096, 3\) is not \(n, 6\) or flat .*"
            r"x y z nx ny nz",
        ):
            gen.run(points=np.random.default_rng(0).random((4096, 3)), seed=1, max_tokens=60)


def test_dtypes_are_checked_and_strided_arrays_copied_exactly(lib_path):
    rows = np.arange(24, dtype=np.float64).reshape(4, 6)
    with silk_mesh.Mesh(rows[:, :3], TRI) as m:  # a non-contiguous view: its own values
        assert m.positions.tolist() == rows[:, :3].tolist()
    with silk_mesh.Mesh(np.array(QUAD, dtype=">f4"), TRI) as m:  # byte-swapped float32: exact in float64
        assert m.positions.tolist() == QUAD
    with silk_mesh.Mesh(np.array(QUAD, dtype=np.int64), TRI) as m:
        assert m.positions.tolist() == QUAD
    with pytest.raises(ValueError, match="positions: integer values beyond 2\\*\\*53"):
        silk_mesh.Mesh(np.array([[2**60, 0, 0]], dtype=np.int64), [])
    with pytest.raises(ValueError, match=r"positions\[0\]=1152921504606846977 is not exactly representable"):
        silk_mesh.Mesh([[2**60 + 1, 0, 0]], [])
    with pytest.raises(TypeError, match="positions: dtype complex128 is not a real number type"):
        silk_mesh.Mesh(np.zeros((1, 3), dtype=complex), [])
    with pytest.raises(TypeError, match="positions: dtype object is not a real number type"):
        silk_mesh.Mesh(np.array([[0, 0, "x"]], dtype=object), [])
    with pytest.raises(TypeError, match=r"positions\[2\]: expected a number, not str"):
        silk_mesh.Mesh([[0, 0, "1"]], [])
