# SPDX-License-Identifier: MIT
"""The Pythonic API of silk_mesh (bindings/python): encode gives the official ids, decode gives a
mesh the independent checker (shared/tools/mesh_check.py) accepts, generate gives silkgen's ids
for the same seed, step-wise equals one call, callbacks work, errors name the file, and the
plain-Python (no numpy) results equal the numpy ones."""

from __future__ import annotations

import ctypes
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import silk_mesh

ROOT = Path(__file__).resolve().parents[2]
TINY = ROOT / "tests" / "models" / "tiny"
KNOT = ROOT / "samples" / "torus_knot.obj"
CLOUD = ROOT / "tests" / "models" / "golden" / "torus_knot_points.ply"
GOLDENS = ["cube", "torus_12x8", "nonmanifold_book", "two_components", "icosphere2"]


def official_ids(shared: Path, name: str) -> list[int]:
    return [int(x) for x in (shared / "spec" / "golden" / f"{name}.tokens.txt").read_text().split()]


@pytest.mark.parametrize("name", GOLDENS)
def test_encode_of_a_golden_mesh_equals_its_official_ids(name, shared, lib_path):
    path = shared / "spec" / "golden" / f"{name}.obj"
    ids = silk_mesh.encode(path)
    assert isinstance(ids, list) and all(type(i) is int for i in ids)
    assert ids == official_ids(shared, name)
    with silk_mesh.Mesh.load(path) as m:  # a Mesh, and arrays, give the same ids
        assert silk_mesh.encode(m) == ids == silk_mesh.encode((m.positions, m.triangles))


@pytest.mark.parametrize("name", ["torus_12x8", "two_components"])
def test_decode_gives_a_mesh_the_independent_checker_accepts(name, shared, tmp_path, lib_path):
    mesh, stats = silk_mesh.decode(official_ids(shared, name), return_stats=True)
    with mesh:
        assert stats["faces"] == mesh.triangle_count > 0 and len(mesh.triangles) == mesh.triangle_count
        assert len(set(mesh.parts.tolist() if hasattr(mesh.parts, "tolist") else mesh.parts)) == stats["components"]
        mesh.save(tmp_path / f"{name}.obj")
    r = subprocess.run(
        [sys.executable, str(shared / "tools" / "mesh_check.py"), str(tmp_path / f"{name}.obj"), "--json"],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stdout + r.stderr
    verdict = json.loads(r.stdout[: r.stdout.rindex("}") + 1])[str(tmp_path / f"{name}.obj")]
    assert verdict["ok"] and verdict["faces"] == stats["faces"] and verdict["components"] == stats["components"]


def test_token_files_round_trip_through_libsilk(shared, tmp_path, lib_path):
    ids = official_ids(shared, "cube")
    silk_mesh.write_ids(tmp_path / "cube.txt", ids)
    assert (tmp_path / "cube.txt").read_text().split() == [str(i) for i in ids]
    assert silk_mesh.read_ids(tmp_path / "cube.txt") == ids
    with silk_mesh.decode(tmp_path / "cube.txt") as m:  # a token file path decodes too
        assert m.triangle_count == 12


def test_generate_with_the_tiny_model_gives_silkgens_ids(silkgen, generation, tmp_path):
    subprocess.run(
        [
            str(silkgen),
            str(KNOT),
            "--model",
            str(TINY),
            "--seed",
            "11",
            "--max-tokens",
            "250",
            "--threads",
            "1",
            "--tokens",
            str(tmp_path / "ids.txt"),
            "--stats",
            str(tmp_path / "s.json"),
            "-q",
        ],
        check=True,
    )
    want = silk_mesh.read_ids(tmp_path / "ids.txt")
    with silk_mesh.Model(TINY, threads=1) as model:
        result = silk_mesh.generate(KNOT, model=model, seed=11, max_tokens=250)
    with result.mesh as m:
        assert result.ids == want and len(want) > 14
        assert result.stats["faces"] == m.triangle_count == json.loads((tmp_path / "s.json").read_text())["faces"]


def test_kv_precision_picks_the_cache_as_silkgen_does(silkgen, generation, tmp_path):
    """Model(kv_precision=...) is silk_model_params.kv_precision: the same ids as silkgen's
    --kv-precision, the cache in use in info(), and a precision the folder lacks named."""
    for kv in ("fp32", "fp16", "int8"):
        subprocess.run(
            [
                str(silkgen),
                str(KNOT),
                "--model",
                str(TINY),
                "--seed",
                "3",
                "--max-tokens",
                "200",
                "--threads",
                "1",
                "--kv-precision",
                kv,
                "--tokens",
                str(tmp_path / f"{kv}.txt"),
                "-q",
            ],
            check=True,
        )
        with silk_mesh.Model(TINY, threads=1, kv_precision=kv) as model:
            assert model.info()["kv_precision"] == silk_mesh.enum_names("kv_precision")[kv]
            ids = silk_mesh.generate(KNOT, model=model, seed=3, max_tokens=200).ids
        assert ids == silk_mesh.read_ids(tmp_path / f"{kv}.txt") and len(ids) > 14
    with pytest.raises(ValueError, match="kv_precision must be one of"):
        silk_mesh.Model(TINY, kv_precision="bf16")
    lacking = tmp_path / "no_variant"
    lacking.mkdir()
    meta = json.loads((TINY / "model.json").read_text())
    meta["files"].pop("kv_fp16")
    (lacking / "model.json").write_text(json.dumps(meta))
    for f in ("encoder.onnx", "decoder.onnx"):
        (lacking / f).write_bytes((TINY / f).read_bytes())
    with pytest.raises(silk_mesh.SilkError) as e:
        silk_mesh.Model(lacking, kv_precision="fp16")
    assert str(lacking) in e.value.message and "fp16" in e.value.message


def test_step_wise_equals_one_call_and_reports_progress(generation):
    with silk_mesh.Generator(str(TINY)) as gen:  # a folder path: the generator loads (and owns) the model
        whole = gen.run(KNOT, seed=3, max_tokens=200, surface_tolerance=0)
        seen, faces = [], []
        gen.start(KNOT, seed=3, max_tokens=200, surface_tolerance=0, progress=seen.append)
        while not gen.advance(10_000, until_layer=True):
            with gen.preview() as p:
                faces.append(p.triangle_count)
        assert gen.done and faces == sorted(faces) and len(set(faces)) > 1
        assert gen.ids() == whole.ids
        mesh, ids, stats = gen.finish()
        with mesh, whole.mesh:
            assert ids == whole.ids and stats["faces"] == whole.stats["faces"] == mesh.triangle_count
            assert mesh.positions.tolist() == whole.mesh.positions.tolist()
            assert mesh.triangles.tolist() == whole.mesh.triangles.tolist()
        assert len(seen) == len(ids) and seen[-1]["tokens"] == len(ids)


def test_cancel_and_a_failing_callback(generation):
    with silk_mesh.Generator(TINY) as gen:
        calls = []
        with pytest.raises(silk_mesh.SilkError) as e:
            gen.run(KNOT, seed=1, max_tokens=200, progress=calls.append, cancel=lambda: len(calls) >= 5)
        assert e.value.status == silk_mesh.SILK_ERR_CANCELLED and len(calls) == 5

        def boom(progress):
            raise KeyError("from the callback")

        with pytest.raises(KeyError, match="from the callback"):
            gen.run(KNOT, seed=1, max_tokens=200, progress=boom)
        result = gen.run(KNOT, seed=1, max_tokens=60)  # the generator is still usable
        assert len(result.ids) > 0


def test_point_cloud_input_and_normals(generation):
    with silk_mesh.Mesh.load(CLOUD) as cloud:
        normals, positions = cloud.normals, cloud.positions
        assert cloud.triangle_count == 0 and len(normals) == len(positions) > 0
        rows = (
            [tuple(p) + tuple(n) for p, n in zip(positions.tolist(), normals.tolist())]
            if hasattr(positions, "tolist")
            else [p + n for p, n in zip(positions, normals)]
        )
        with silk_mesh.Model(TINY, threads=1) as model:
            a = silk_mesh.generate(cloud, model=model, seed=2, max_tokens=120)
            b = silk_mesh.generate(points=rows, model=model, seed=2, max_tokens=120)
    assert a.ids == b.ids and len(a.ids) > 0
    with silk_mesh.Mesh.load(KNOT) as m:
        assert m.normals is None


def test_errors_name_the_file(tmp_path, lib_path):
    with pytest.raises(silk_mesh.SilkError) as e:
        silk_mesh.encode(tmp_path / "missing.obj")
    assert e.value.status == silk_mesh.SILK_ERR_IO and "missing.obj" in str(e.value)
    with pytest.raises(TypeError, match="unknown parameter 'bogus'"):
        silk_mesh.encode(KNOT, bogus=1)


def test_out_of_range_settings_get_libsilks_message(generation):
    """The binding keeps no range of its own (issue 32): values go to libsilk as given and its one
    range table's message, naming the setting, the value and the range, is raised."""
    with silk_mesh.Generator(str(TINY)) as gen:
        for kw, text in [
            ({"temperature": 150}, "temperature 150 is not in [0, 100]"),
            ({"top_k": 10270}, "top_k 10270 is not in [0, 10269]"),
            ({"candidates": 65}, "candidates 65 is not in [1, 64]"),
            ({"rows": 0}, "rows 0 is not in [1, 64]"),
            ({"rows": 65}, "rows 65 is not in [1, 64]"),
            ({"max_tokens": 13}, "max_tokens 13 is not 0 or at least 14"),
        ]:
            with pytest.raises(silk_mesh.SilkError) as e:
                gen.run(KNOT, seed=3, **kw)
            assert text in e.value.message, (kw, e.value.message)


def test_rows_is_passed_on_and_reported(generation):
    """rows= (C API 1.5) goes to libsilk as given: the report's settings show it, the stats the
    rows used (min(rows, candidates)); unset it is the model's, else libsilk's 8."""
    with silk_mesh.Generator(str(TINY)) as gen:
        res = gen.run(KNOT, seed=3, max_tokens=120, candidates=2, rows=3)
        assert json.loads(gen.report_json())["settings"]["rows"] == 3
        assert 1 <= res.stats["rows"] <= 2
        gen.run(KNOT, seed=3, max_tokens=120)
        assert json.loads(gen.report_json())["settings"]["rows"] == 8  # the tiny model names none
    res = silk_mesh.generate(KNOT, model=TINY, seed=3, max_tokens=120, rows=1)
    assert res.stats["rows"] == 1


def test_model_errors_name_the_folder_and_the_value(tmp_path, generation):
    with pytest.raises(silk_mesh.SilkError) as e:
        silk_mesh.Model(tmp_path)
    assert str(tmp_path) in e.value.message
    with pytest.raises(ValueError, match="holes must be one of"):
        silk_mesh.generate(KNOT, model=TINY, holes="sometimes")


def test_a_library_that_cannot_be_loaded_is_named_with_the_reason(tmp_path, lib_path):
    bad = tmp_path / "libsilk.so"
    bad.write_text("not a library")
    code = (
        "import silk_mesh\ntry:\n    silk_mesh.encode([])\nexcept silk_mesh.SilkError as e:\n"
        "    print(e.status, e.name, e.message)\n"
    )
    env = {**os.environ, "SILK_LIBRARY": str(bad), "PYTHONPATH": str(ROOT / "bindings" / "python")}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    with pytest.raises(OSError) as reason:  # what the OS says about that file
        ctypes.CDLL(str(bad))
    assert out.startswith(f"2 library cannot load libsilk from '{bad}'") and str(reason.value) in out
    env["SILK_LIBRARY"] = str(tmp_path / "absent.so")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    assert str(tmp_path / "absent.so") in out and "No such file" in out


def test_the_bundled_model_is_libsilks(lib_path):
    """silk_mesh asks libsilk (silk_model_default_dir): a build tree's library finds the source tree's model."""
    assert silk_mesh.bundled_model_dir() == str(ROOT / "models" / "default")
    if silk_mesh.generation_available():
        with silk_mesh.Model() as m:
            assert m.dir == silk_mesh.bundled_model_dir()


def test_models_by_name(lib_path, tmp_path):
    """A model in $SILK_MODELS is found by name (Model, find_model, list_models); a path wins; a name that
    is a path is refused naming the rule; a missing name names the models folder and the import command."""
    shutil.copytree(ROOT / "tests" / "models" / "tiny", tmp_path / "models" / "tiny-b")
    (tmp_path / "cwd" / "tiny-b").mkdir(parents=True)
    code = """import json, os, silk_mesh
out = {"dir": silk_mesh.models_dir(), "named": silk_mesh.models_dir("x"), "find": silk_mesh.find_model("tiny-b"),
       "list": [(m["name"], m["bundled"]) for m in silk_mesh.list_models()["models"]]}
os.chdir("cwd")
out["path_wins"] = silk_mesh.find_model("tiny-b")
os.chdir("..")
if silk_mesh.generation_available():
    with silk_mesh.Model("tiny-b") as m:
        out["loaded"] = m.dir
for bad, call in (("../x", silk_mesh.models_dir), ("nope", silk_mesh.Model)):
    try:
        call(bad)
    except silk_mesh.SilkError as e:
        out[bad] = e.message
print(json.dumps(out))
"""
    env = {
        **os.environ,
        "SILK_LIBRARY": str(lib_path),
        "PYTHONPATH": str(ROOT / "bindings" / "python"),
        "SILK_MODELS": str(tmp_path / "models"),
    }
    r = json.loads(
        subprocess.run(
            [sys.executable, "-c", code], env=env, cwd=tmp_path, capture_output=True, text=True, check=True
        ).stdout
    )
    models = str(tmp_path / "models")
    assert r["dir"] == models and r["named"] == os.path.join(models, "x")
    assert r["find"] == os.path.join(models, "tiny-b") and r["path_wins"] == "tiny-b"
    assert r["list"] == [["default", True], ["tiny-b", False]]
    assert r.get("loaded", r["find"]) == r["find"]
    assert "'../x' is not a model name" in r["../x"]
    assert f"'nope' is neither a folder nor a model in {os.path.join(models, 'nope')}" in r["nope"]
    assert "silk-export import-official --name nope" in r["nope"]


def test_plain_python_results_equal_numpy_ones(shared, lib_path):
    """SILK_MESH_NUMPY=0: lists of tuples where numpy gives arrays; the values are the same."""
    np = pytest.importorskip("numpy")
    code = (
        "import json, silk_mesh\nm = silk_mesh.decode(silk_mesh.encode(%r))\n"
        "print(json.dumps([type(m.positions).__name__, m.positions, m.triangles, m.parts]))\n"
        % str(shared / "spec" / "golden" / "two_components.obj")
    )
    env = {
        **os.environ,
        "SILK_MESH_NUMPY": "0",
        "SILK_LIBRARY": str(lib_path),
        "PYTHONPATH": str(ROOT / "bindings" / "python"),
    }
    kind, pos, tri, parts = json.loads(
        subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    )
    with silk_mesh.decode(silk_mesh.encode(shared / "spec" / "golden" / "two_components.obj")) as m:
        assert kind == "list" and isinstance(m.positions, np.ndarray) and m.positions.shape == (len(pos), 3)
        assert m.positions.tolist() == pos and m.triangles.tolist() == tri and m.parts.tolist() == parts
        assert m.triangles.dtype == np.int32 and len(set(parts)) == 2


def test_save_parameters(tmp_path, lib_path):
    with silk_mesh.Mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [0, 1, 2]) as m:  # rows and flat inputs alike
        m.save(tmp_path / "t.txt", format="obj", obj_comment="made by silk_mesh")
        with pytest.raises(ValueError, match="format must be one of"):
            m.save(tmp_path / "t.obj", format="fbx")
    text = (tmp_path / "t.txt").read_text()
    assert text.startswith("# made by silk_mesh") and "f 1 2 3" in text
    with pytest.raises(ValueError, match="triangles: 2 values"):
        silk_mesh.Mesh([0, 0, 0], [0, 1])


def test_face_guidance_keywords(generation):
    """face_guidance / face_tolerance reach libsilk (C API 1.3): off changes nothing, hard and soft
    judge ids (stats), a name outside the enum and a tolerance out of range are refused by name."""
    with silk_mesh.Generator(str(TINY)) as gen:
        plain = gen.run(KNOT, seed=3, max_tokens=300, surface_tolerance=0, candidates=1, face_guidance="off")
        assert plain.stats["face_guided_tokens"] == 0
        for mode in ("hard", "soft"):
            r = gen.run(
                KNOT, seed=3, max_tokens=300, surface_tolerance=2, candidates=1, face_guidance=mode, face_tolerance=3.0
            )
            r.mesh.close()
            assert r.stats["face_guided_tokens"] > 0 and r.stats["face_fallbacks"] <= r.stats["face_guided_tokens"]
        again = gen.run(KNOT, seed=3, max_tokens=300, surface_tolerance=0, candidates=1, face_guidance="off")
        assert list(again.ids) == list(plain.ids)
        plain.mesh.close()
        again.mesh.close()
        with pytest.raises(ValueError, match="face_guidance"):
            gen.run(KNOT, seed=3, face_guidance="strong")
        with pytest.raises(silk_mesh.SilkError, match="face_tolerance"):
            gen.run(KNOT, seed=3, face_tolerance=0.1)
