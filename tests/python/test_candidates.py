# SPDX-License-Identifier: MIT
"""silk_mesh.Generator.candidates() / candidate_preview(i) (issue 34, C API 1.5): while best of N
runs step-wise every candidate is shown with its state, ids, faces, score and the best so far; its
preview has the faces it reports; the calls refuse a generator with no run and an index out of range."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import silk_mesh

ROOT = Path(__file__).resolve().parents[2]
TINY = ROOT / "tests" / "models" / "tiny"
TINY_ROWS = ROOT / "tests" / "models" / "tiny-rows"  # contract v4: best of N runs as rows
KNOT = ROOT / "samples" / "torus_knot.obj"
ORDER = ["waiting", "running", "ended", "scored"]


def check_view(gen: silk_mesh.Generator, now: list[dict], before: list[dict]) -> None:
    scored = [c["score"] for c in now if c["state"] == "scored"]
    assert [c["index"] for c in now] == list(range(len(now)))
    for c, b in zip(now, before or now):
        assert ORDER.index(c["state"]) >= ORDER.index(b["state"]) and c["tokens"] >= b["tokens"], (c, b)
        assert (c["score"] is not None) == (c["state"] == "scored"), c
        assert (c["faces"] is not None) == (c["state"] in ("ended", "scored")), c
        with gen.candidate_preview(c["index"]) as mesh:
            if c["faces"] is not None:
                assert mesh.triangle_count == c["faces"], c
            if c["state"] == "waiting":
                assert mesh.triangle_count == 0 and c["tokens"] == 0, c
    best = [c for c in now if c["best"]]
    assert len(best) == (1 if scored else 0)
    if best:
        assert best[0]["score"] == min(scored)


def test_every_candidate_is_shown_while_best_of_n_runs(generation):
    moved = False
    with silk_mesh.Generator(TINY) as gen:
        for seed in (5, 8):
            gen.start(KNOT, seed=seed, max_tokens=200, candidates=3, rows=1)  # one after another
            before = gen.candidates()
            assert [c["state"] for c in before] == ["running", "waiting", "waiting"]
            assert before[1] == {
                "index": 1,
                "state": "waiting",
                "tokens": 0,
                "faces": None,
                "score": None,
                "best": False,
            }
            check_view(gen, before, [])
            states = [set() for _ in before]
            while not gen.advance(10):
                now = gen.candidates()
                check_view(gen, now, before)
                for c in now:
                    states[c["index"]].add(c["state"])
                    moved |= c["best"] and c["index"] > 0
                before = now
            assert all("running" in s for s in states) and "scored" in states[0]
            mesh, ids, stats = gen.finish()
            with mesh:
                chosen = before[stats["chosen_candidate"]]
                assert chosen["tokens"] == len(ids)
                if chosen["state"] == "scored":
                    assert chosen["best"] and math.isclose(chosen["score"], stats["score"], rel_tol=0, abs_tol=0)
                    assert chosen["faces"] == mesh.triangle_count
    assert moved, "candidate 0 stayed the best every time: pick other seeds"


def test_candidates_as_rows_run_together_and_end_scored(generation):
    """rows=2 on a contract v4 folder: two of the three candidates start at once, the third waits for a
    free row; each one is scored as it ends, and the mesh equals the one-after-another run's. A
    batch-1 folder runs them one after another whatever rows asks."""
    with silk_mesh.Generator(TINY) as gen:
        gen.start(KNOT, seed=5, max_tokens=60, candidates=3, rows=2)
        assert [c["state"] for c in gen.candidates()] == ["running", "waiting", "waiting"]
        gen.finish()[0].close()
    with silk_mesh.Generator(TINY_ROWS) as gen:
        gen.start(KNOT, seed=5, max_tokens=200, candidates=3, rows=1)
        while not gen.advance(1000):
            pass
        one_mesh, one_ids, one_stats = gen.finish()
        one_mesh.close()
        gen.start(KNOT, seed=5, max_tokens=200, candidates=3, rows=2)
        assert [c["state"] for c in gen.candidates()] == ["running", "running", "waiting"]
        while not gen.advance(10):
            now = gen.candidates()
            check_view(gen, now, [])
            assert sum(c["state"] == "running" for c in now) <= 2
        assert [c["state"] for c in gen.candidates()] == ["scored"] * 3
        mesh, ids, stats = gen.finish()
        with mesh:
            assert list(ids) == list(one_ids) and stats["chosen_candidate"] == one_stats["chosen_candidate"]
            assert stats["rows"] == 2


def test_candidates_refuse_no_run_and_an_index_out_of_range(generation):
    with silk_mesh.Generator(TINY) as gen:
        with pytest.raises(silk_mesh.SilkError, match="no generation in progress") as e:
            gen.candidates()
        assert e.value.status == silk_mesh.SILK_ERR_INVALID_ARGUMENT
        gen.start(KNOT, seed=5, max_tokens=60, candidates=3)
        assert len(gen.candidates()) == 3
        for bad in (3, -1):
            with pytest.raises(silk_mesh.SilkError, match=f"candidate {bad} is out of range.*3 candidates"):
                gen.candidate_preview(bad)
        with pytest.raises(TypeError, match="candidate_preview: index"):
            gen.candidate_preview("0")
        gen.finish()
        with pytest.raises(silk_mesh.SilkError, match="no generation in progress"):
            gen.candidate_preview(0)
