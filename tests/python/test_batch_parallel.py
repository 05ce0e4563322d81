# SPDX-License-Identifier: MIT
"""silk_mesh.Batch (issue 34, C API 1.6): several meshes decoded together. Each input's Result
equals Generator.run's with the same params (ids, triangles, positions, chosen candidate, score) at
parallel 3 on the contract v4 tiny-rows folder and on the batch-1 tiny folder (one after another); a
broken input fails alone with its own error; a cancel ends the inputs in flight; misuse raises."""

from __future__ import annotations

from pathlib import Path

import pytest

import silk_mesh

ROOT = Path(__file__).resolve().parents[2]
KNOT = ROOT / "samples" / "torus_knot.obj"
PARAMS = [
    dict(seed=3, candidates=3, max_tokens=150),
    dict(seed=5, candidates=1, max_tokens=150),
    dict(seed=9, candidates=4, temperature=0, max_tokens=150),
    dict(seed=11, candidates=2, rows=1, max_tokens=150),
]


def sphere(n=2000):
    import math

    pts = []
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n
        r, phi = math.sqrt(1 - z * z), 2.399963229728653 * i
        p = (r * math.cos(phi), r * math.sin(phi), z)
        pts.append(p + p)
    return pts


def same(a: silk_mesh.Result, b: silk_mesh.Result) -> None:
    assert a.ids == b.ids
    assert [tuple(t) for t in a.mesh.triangles] == [tuple(t) for t in b.mesh.triangles]
    assert [tuple(p) for p in a.mesh.positions] == [tuple(p) for p in b.mesh.positions]
    for key in ("candidates", "chosen_candidate", "score", "stop_reason", "rows"):
        assert a.stats[key] == b.stats[key], key


@pytest.mark.parametrize("folder", ["tiny-rows", "tiny"])
def test_each_input_is_its_run_alone(generation, folder):
    model = ROOT / "tests" / "models" / folder
    points = sphere()
    inputs = [dict(input=KNOT), dict(points=points), dict(input=KNOT), dict(points=points)]
    with silk_mesh.Generator(model) as gen:
        alone = [gen.run(**inp, **p) for inp, p in zip(inputs, PARAMS)]
    seen = set()
    with silk_mesh.Batch(model, parallel=3, progress=lambda i, p: seen.add(i)) as batch:
        indexes = [batch.add(**inputs[0], **PARAMS[0]), batch.add(**inputs[1], **PARAMS[1])]
        broken = [list(p) for p in points]
        broken[3][1] = float("nan")
        indexes.append(batch.add(points=broken, **PARAMS[1]))
        indexes += [batch.add(**inputs[i], **PARAMS[i]) for i in (2, 3)]
        assert indexes == [0, 1, 2, 3, 4]
        assert sum(batch.counts()) == 5
        batch.close_inputs()
        with pytest.raises(silk_mesh.SilkError, match="closed"):
            batch.add(KNOT)
        items = {item.index: item for item in batch}
    assert sorted(items) == [0, 1, 2, 3, 4]
    assert items[2].result is None and items[2].error.status == silk_mesh.SILK_ERR_INVALID_ARGUMENT
    for i, index in enumerate((0, 1, 3, 4)):
        assert items[index].error is None, items[index].error
        same(items[index].result, alone[i])
    assert seen == {0, 1, 3, 4}


def test_a_cancel_ends_the_inputs_in_flight(generation):
    reports = []
    with silk_mesh.Batch(
        ROOT / "tests" / "models" / "tiny-rows",
        parallel=2,
        cancel=lambda: len(reports) >= 80,
        progress=lambda i, p: reports.append(i),
    ) as batch:
        for p in PARAMS:
            batch.add(KNOT, **p)
        items = list(batch)
    cancelled = [it for it in items if it.error is not None]
    assert cancelled and all(it.error.status == silk_mesh.SILK_ERR_CANCELLED for it in cancelled)
    assert sorted(it.index for it in items) == list(range(len(PARAMS)))  # each comes back once
    assert "before it started" in str(items[-1].error)  # the last queued never started


def test_misuse_raises(generation):
    model = ROOT / "tests" / "models" / "tiny-rows"
    with pytest.raises(silk_mesh.SilkError, match=r"parallel 17 is not in \[1, 16\]"):
        silk_mesh.Batch(model, parallel=17)
    with silk_mesh.Batch(model, parallel=2) as batch:
        assert batch.next() is None  # nothing added
        with pytest.raises(TypeError, match="progress"):
            batch.add(KNOT, progress=print)
        with pytest.raises(TypeError, match="unknown parameter"):
            batch.add(KNOT, sede=1)
        index = batch.add(KNOT, candidates=65)
        item = batch.next()
        assert item.index == index and item.result is None and "candidates 65" in str(item.error)
    with pytest.raises(ValueError, match="closed"):
        batch.add(KNOT)
