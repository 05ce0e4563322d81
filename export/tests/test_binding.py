# SPDX-License-Identifier: MIT
"""The ctypes binding (silk_mesh) gives exactly the tokens `silktok encode` writes (and the official token
files), reports errors and refusals with their names, and decodes back to a mesh."""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

import silk_mesh
from silk_export.vocab import load_vocab

GOLDENS = ["cube", "torus_12x8", "nonmanifold_book", "two_components", "grid", "dirty_cube"]
DEV = ["gaia__fern_tropical_a", "props__brick_pile_04", "props__helmet__rome_coolus_c"]


def silktok_tokens(exe, mesh, tmp_path) -> bytes:
    out = tmp_path / (mesh.stem + ".txt")
    subprocess.run([str(exe), "encode", str(mesh), "-o", str(out)], check=True, capture_output=True)
    return out.read_bytes()


def as_text(tokens) -> bytes:
    return "".join(f"{int(t)}\n" for t in tokens).encode()


@pytest.mark.parametrize("name", GOLDENS)
def test_golden_tokens_equal_silktok_and_official(name, golden_dir, silktok, tmp_path):
    mesh = golden_dir / f"{name}.obj"
    with silk_mesh.Mesh.load(mesh) as m:
        tokens, stats = silk_mesh.encode(m, return_stats=True)
    assert all(type(t) is int for t in tokens) and stats["tokens"] == len(tokens) > 0
    assert as_text(tokens) == silktok_tokens(silktok, mesh, tmp_path)
    official = np.loadtxt(golden_dir / f"{name}.tokens.txt", dtype=np.int64).reshape(-1)
    assert np.array_equal(tokens, official)


@pytest.mark.parametrize("name", DEV)
def test_dev_tokens_equal_silktok_and_official(name, dev_dir, silktok, tmp_path):
    mesh = dev_dir / f"{name}.obj"
    tokens = silk_mesh.encode(silk_mesh.load_arrays(mesh))  # through silk_mesh_create
    assert as_text(tokens) == silktok_tokens(silktok, mesh, tmp_path)
    official = dev_dir.parent.parent / "spec" / "golden-dev" / f"{name}.tokens.txt"
    assert np.array_equal(tokens, np.loadtxt(official, dtype=np.int64).reshape(-1))


def test_refused_dev_mesh_is_refused_by_both(dev_dir, silktok, tmp_path):
    mesh = dev_dir / "gaia__bush_la_5.obj"  # every component too small (official: division by zero)
    with pytest.raises(silk_mesh.SilkError) as e:
        silk_mesh.encode(silk_mesh.Mesh.load(mesh))
    assert e.value.status == silk_mesh.SILK_ERR_REFUSED and e.value.reason == "all-components-dropped"
    r = subprocess.run([str(silktok), "encode", str(mesh), "-o", str(tmp_path / "x.txt")], capture_output=True)
    assert r.returncode == 1 and b"all-components-dropped" in r.stderr


def test_vocab_matches_layout_file():
    info, v = silk_mesh.vocab(), load_vocab()
    assert info["format_vocab_size"] == v.format_vocab_size
    assert (info["eos_id"], info["pad_id"], info["model_vocab_size"]) == (v.eos_id, v.pad_id, v.model_vocab_size)
    for cls in ("X", "S", "B", "K", "O"):
        lo, hi = v.layout["ranges"][cls]
        assert (info[f"{cls.lower()}_begin"], info[f"{cls.lower()}_end"]) == (lo, hi)
    assert v.bos_id == v.model_vocab_size == 10269 and v.embedding_rows == 10270


def test_decode_round_trip_keeps_every_face(golden_dir):
    v, f = silk_mesh.load_arrays(golden_dir / "torus_12x8.obj")
    tokens = silk_mesh.encode((v, f))
    with silk_mesh.decode(tokens) as m:
        assert m.triangle_count == f.shape[0]
        assert m.vertex_count == len(np.unique(v, axis=0))
        again = silk_mesh.encode(m)
    assert again == tokens


def test_errors_carry_status_and_message(tmp_path):
    with pytest.raises(silk_mesh.SilkError) as e:
        silk_mesh.Mesh.load(tmp_path / "missing.obj")
    assert e.value.status == 2 and "missing.obj" in e.value.message
    (tmp_path / "broken.obj").write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(silk_mesh.SilkError):
        silk_mesh.Mesh.load(tmp_path / "broken.obj")


def test_refusal_is_named():
    # A Möbius strip cannot be consistently oriented: the tokenizer refuses it by name.
    n = 12
    v, f = [], []
    for i in range(n):
        a = 2 * np.pi * i / n
        for s in (-0.3, 0.3):
            r = 1 + s * np.cos(a / 2)
            v.append((r * np.cos(a), r * np.sin(a), s * np.sin(a / 2)))
    for i in range(n):
        a, b = 2 * i, 2 * i + 1
        c, d = (2 * (i + 1), 2 * (i + 1) + 1) if i + 1 < n else (1, 0)  # the half twist
        f += [(a, b, d), (a, d, c)]
    with pytest.raises(silk_mesh.SilkError) as e:
        silk_mesh.encode((np.array(v), np.array(f)))
    assert e.value.status == silk_mesh.SILK_ERR_REFUSED and e.value.reason == "mobius"
