# SPDX-License-Identifier: MIT
"""Generation through libsilk's C API from Python (no subprocess): the ids equal the committed
silkgen golden, the step-wise API grows by layers and ends with the same ids, destroy order is
free, a model with NaN weights fails with an error naming the model, cancel keeps stats, and
part orientation reverses whole parts in the preview and the result alike."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from pathlib import Path

import silk_mesh
from silk_export.json_io import write_json

REPO_ROOT = Path(__file__).resolve().parents[2]  # this checkout (tests only)

TINY = REPO_ROOT / "tests/models/tiny"
KNOT = REPO_ROOT / "samples/torus_knot.obj"
GOLDEN = REPO_ROOT / "tests/models/golden/torus_knot_s7.tokens.txt"

pytestmark = pytest.mark.skipif(not silk_mesh.generation_available(), reason="libsilk without onnxruntime")


def test_python_generation_matches_the_silkgen_golden():
    want = np.array([int(x) for x in GOLDEN.read_text().split()], np.int32)
    with silk_mesh.Model(TINY, threads=1) as model, silk_mesh.Generator(model) as gen, silk_mesh.Mesh.load(KNOT) as src:
        mesh, ids, stats = gen.run(src, seed=7, max_tokens=300, surface_tolerance=0, candidates=1, face_guidance="off")
        with mesh:
            assert np.array_equal(ids, want)
            assert stats["faces"] == mesh.triangle_count > 0
            assert stats["stop_reason"] == "eos"
        report = json.loads(gen.report_json())
        assert report["tokens"] == len(want) and report["settings"]["seed"] == 7


def test_step_wise_grows_by_layers_and_ends_with_the_same_ids():
    with silk_mesh.Model(TINY, threads=1) as model, silk_mesh.Generator(model) as gen, silk_mesh.Mesh.load(KNOT) as src:
        # A plain run (no surface or face guidance): this seed's stream closes several layers.
        _, whole, _ = gen.run(src, seed=3, max_tokens=200, surface_tolerance=0, face_guidance="off")
        gen.start(src, seed=3, max_tokens=200, surface_tolerance=0, face_guidance="off")
        faces, done = [], False
        while not done:
            done = gen.advance(10_000, until_layer=True)
            with gen.preview() as m:
                faces.append(m.triangle_count)
        assert faces == sorted(faces) and len(set(faces)) > 2
        mesh, ids, stats = gen.finish()
        mesh.close()
        assert np.array_equal(ids, whole)


def test_generator_outlives_its_model():
    model = silk_mesh.Model(TINY, threads=1)
    gen = silk_mesh.Generator(model)
    model.close()  # e.g. a garbage collector picking this order
    with silk_mesh.Mesh.load(KNOT) as src:
        mesh, ids, _ = gen.run(src, seed=1, max_tokens=100)
        mesh.close()
    assert len(ids) > 0
    gen.close()


def test_cancel_keeps_the_stats():
    calls = []
    with silk_mesh.Model(TINY, threads=1) as model, silk_mesh.Generator(model) as gen, silk_mesh.Mesh.load(KNOT) as src:
        with pytest.raises(silk_mesh.SilkError) as e:
            gen.run(src, seed=1, max_tokens=200, progress=calls.append, cancel=lambda: len(calls) >= 12)
        assert e.value.status == silk_mesh.SILK_ERR_CANCELLED
        assert gen.stats()["stop_reason"] in ("cancelled", "running")  # the generation was released
        assert len(calls) == 12 and calls[-1]["tokens"] == 12


def test_nan_weights_fail_naming_the_model(tmp_path):
    onnx = pytest.importorskip("onnx")
    from onnx import numpy_helper

    bad = tmp_path / "nan_model"
    shutil.copytree(TINY, bad)
    m = onnx.load(str(bad / "decoder.onnx"))
    biggest = max(m.graph.initializer, key=lambda t: int(np.prod(t.dims)) if t.data_type == 1 else 0)
    arr = numpy_helper.to_array(biggest).copy()
    arr[...] = np.nan
    biggest.CopyFrom(numpy_helper.from_array(arr, biggest.name))
    onnx.save(m, str(bad / "decoder.onnx"))
    with silk_mesh.Model(bad, threads=1) as model, silk_mesh.Generator(model) as gen, silk_mesh.Mesh.load(KNOT) as src:
        with pytest.raises(silk_mesh.SilkError) as e:
            gen.run(src, seed=1, max_tokens=100)
    assert str(bad) in e.value.message and "non-finite" in e.value.message


def _c_struct_fields(name: str) -> list[tuple[str, str, int]]:
    """(field, C type, array length or 0) of `typedef struct NAME { ... } NAME;` in silk.h, in order."""
    import re

    text = (REPO_ROOT / "engine/include/silk/silk.h").read_text()
    body = re.search(r"typedef struct %s \{(.*?)\} %s;" % (name, name), text, re.S).group(1)
    body = re.sub(r"/\*.*?\*/", "", body, flags=re.S)
    out = []
    for decl in body.split(";"):
        decl = " ".join(decl.split())
        if not decl:
            continue
        ctype, names = decl.split(" ", 1)
        for n in names.split(","):
            array = re.fullmatch(r"(\w+)\[(\d+)\]", n.strip())
            out.append((array.group(1), ctype, int(array.group(2))) if array else (n.strip(), ctype, 0))
    return out


@pytest.mark.parametrize(
    "c_name,py_struct", [("silk_generate_params", "GenerateParams"), ("silk_generate_stats", "GenerateStats")]
)
def test_ctypes_declarations_follow_silk_h(c_name, py_struct):
    import ctypes
    from silk_mesh import _capi as silk_c

    scalar = {
        "int32_t": ctypes.c_int32,
        "int64_t": ctypes.c_int64,
        "uint64_t": ctypes.c_uint64,
        "double": ctypes.c_double,
    }
    want = _c_struct_fields(c_name)
    got = getattr(silk_c, py_struct)._fields_
    assert [n for n, _ in got] == [n for n, _, _ in want]
    for (n, t), (_, ct, length) in zip(got, want):
        if ct in scalar and length:  # e.g. int32_t reserved[2]
            assert t._type_ is scalar[ct] and t._length_ == length, f"{py_struct}.{n}: {t} for C {ct}[{length}]"
        elif ct in scalar:
            assert t is scalar[ct], f"{py_struct}.{n}: {t} for C {ct}"


def test_candidates_and_guidance_through_ctypes():
    with silk_mesh.Model(TINY, threads=1) as model, silk_mesh.Generator(model) as gen, silk_mesh.Mesh.load(KNOT) as src:
        mesh, ids, st = gen.run(src, seed=3, max_tokens=200, surface_tolerance=2, candidates=3)
        with mesh:
            assert st["candidates"] == 3 and 0 <= st["chosen_candidate"] < 3
            assert st["guided_tokens"] > 0 and st["guidance_fallbacks"] >= 0
            assert st["faces"] == mesh.triangle_count
        with pytest.raises(silk_mesh.SilkError, match="candidates 0"):
            gen.run(src, seed=3, max_tokens=200, candidates=0)


def _orient_both(gen, src, seed):
    """One step-wise run per orientation: {orient: (ids, positions, triangles, stats, preview)}.
    One candidate: the preview at the end is then the result (with best of N it is the last
    candidate's, and the result the chosen one)."""
    out = {}
    for orient in ("tokens", "input"):
        gen.start(src, orient=orient, seed=seed, max_tokens=1500, surface_tolerance=0, candidates=1)
        while not gen.advance(10_000):
            pass
        with gen.preview() as m:
            preview = (m.positions.copy(), m.triangles.copy())
        mesh, ids, stats = gen.finish()
        with mesh:
            out[orient] = (ids, mesh.positions.copy(), mesh.triangles.copy(), stats, preview)
    return out


def test_orientation_reverses_whole_parts_in_the_preview_and_the_result():
    """orient="input" (the default) against orient="tokens" with the bundled model (several parts,
    many surface patches): the same ids; the result's faces are the tokens' faces, some patches
    reversed (some when the stats say so); and the step-wise preview at the end equals the result,
    i.e. it is oriented too. Seeds 0.. until one run reverses a patch (eight without one is a
    failure)."""
    default = REPO_ROOT / "models/default"
    with (
        silk_mesh.Model(default, threads=1) as model,
        silk_mesh.Generator(model) as gen,
        silk_mesh.Mesh.load(KNOT) as src,
    ):
        for seed in range(8):
            out = _orient_both(gen, src, seed)
            t_ids, t_pos, t_tri, t_stats, _ = out["tokens"]
            i_ids, i_pos, i_tri, i_stats, (p_pos, p_tri) = out["input"]
            assert np.array_equal(t_ids, i_ids) and np.array_equal(t_pos, i_pos)
            assert t_stats["parts_flipped"] == 0
            same = np.all(t_tri == i_tri, axis=1)
            reversed_ = np.all(t_tri[:, [0, 2, 1]] == i_tri, axis=1)
            assert np.all(same | reversed_)
            assert reversed_.any() == (i_stats["parts_flipped"] >= 1), seed
            # Whole patches: faces sharing a vertex (one fan, one patch) are reversed together.
            flipped_vertices = set(i_tri[reversed_].ravel().tolist())
            assert not flipped_vertices & set(i_tri[same].ravel().tolist())
            assert np.array_equal(p_tri, i_tri)  # the preview of the finished run is the oriented result
            assert np.allclose(p_pos, i_pos)  # (positions in the preview are in the input frame too)
            if i_stats["parts_flipped"] >= 1:
                break
        else:
            pytest.fail("no part reversed in 8 seeds")


def test_model_json_sampling_defaults_apply_unless_overridden(tmp_path):
    """model.json "sampling" (written by `silk-export export --temperature`) is where a model's
    sampling defaults live; explicit parameters still win, and generate.json records the result."""
    from silk_export.evaluation.generate import generate_paths

    greedy = tmp_path / "greedy"
    shutil.copytree(TINY, greedy)
    meta = json.loads((greedy / "model.json").read_text())
    meta["sampling"] = {"temperature": 0.0, "top_k": 1}
    write_json(greedy / "model.json", meta)
    with silk_mesh.Model(TINY, threads=1) as model, silk_mesh.Generator(model) as gen, silk_mesh.Mesh.load(KNOT) as src:
        _, explicit, _ = gen.run(src, seed=5, max_tokens=120, temperature=0.0, top_k=1)
        _, default, _ = gen.run(src, seed=5, max_tokens=120)
        assert json.loads(gen.report_json())["settings"]["temperature"] == 0.5
    assert not np.array_equal(explicit, default)  # the check can tell greedy from the built-in defaults
    with (
        silk_mesh.Model(greedy, threads=1) as model,
        silk_mesh.Generator(model) as gen,
        silk_mesh.Mesh.load(KNOT) as src,
    ):
        _, from_json, _ = gen.run(src, seed=5, max_tokens=120)
        s = json.loads(gen.report_json())["settings"]
        assert (s["temperature"], s["top_k"]) == (0.0, 1)
        gen.run(src, seed=5, max_tokens=120, temperature=0.7)
        assert json.loads(gen.report_json())["settings"]["temperature"] == 0.7
    assert np.array_equal(from_json, explicit)
    res = generate_paths(greedy, [KNOT], tmp_path / "gen", seed=5, max_tokens=120)
    assert res["settings"]["temperature"] == 0.0 and res["settings"]["top_k"] == 1
    res = generate_paths(greedy, [KNOT], tmp_path / "gen2", seed=5, max_tokens=120, temperature=0.9)
    assert res["settings"]["temperature"] == 0.9


def test_model_json_candidates_is_the_default_best_of_n(tmp_path):
    """model.json sampling.candidates (`silk-export export --candidates`) is the N a caller gets
    when it names none; an explicit N wins; generate.json lists every candidate that ran."""
    from silk_export.evaluation.generate import generate_paths

    three = tmp_path / "three"
    shutil.copytree(TINY, three)
    meta = json.loads((three / "model.json").read_text())
    meta["sampling"] = {"candidates": 3}
    write_json(three / "model.json", meta)
    with (
        silk_mesh.Model(three, threads=1) as model,
        silk_mesh.Generator(model) as gen,
        silk_mesh.Mesh.load(KNOT) as src,
    ):
        _, _, st = gen.run(src, seed=5, max_tokens=120)
        assert st["candidates"] == 3 and json.loads(gen.report_json())["settings"]["candidates"] == 3
        _, _, st = gen.run(src, seed=5, max_tokens=120, candidates=1)
        assert st["candidates"] == 1
    res = generate_paths(three, [KNOT], tmp_path / "gen", seed=5, max_tokens=120)
    assert res["settings"]["candidates"] == 3 and res["meshes"][0]["candidates"] == 3
    res = generate_paths(TINY, [KNOT], tmp_path / "gen1", seed=5, max_tokens=120)
    assert res["settings"]["candidates"] == 1  # a model that names no N: one generation
