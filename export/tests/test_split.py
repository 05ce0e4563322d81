# SPDX-License-Identifier: MIT
"""The split is the SHA-1 rule, shape keys identify same-shape copies, and no dev-corpus mesh
(nor a same-shape copy) is ever put in train/val/test — checked on the real 0 A.D. files when
the data cache is present."""

from __future__ import annotations

import hashlib
import json

import numpy as np
import pytest

import silk_mesh
from silk_export.data.dataset_index import dev_exclusion, encode_one
from silk_export.data.mesh_files import default_0ad_root
from silk_export.paths import data_dir
from silk_export.data.splits import DEV, hash_split, read_dev_manifest, shape_key


def test_hash_split_rule():
    seen = {}
    for i in range(400):
        p = f"art/meshes/props/x{i}.dae.cached.pmd"
        d = hashlib.sha1(p.encode()).hexdigest()[0]
        seen.setdefault(hash_split(p), set()).add(d)
    assert seen["train"] == set("0123456789abcd") and seen["val"] == {"e"} and seen["test"] == {"f"}


def test_shape_key_semantics():
    rng = np.random.default_rng(0)
    v = rng.integers(-5000, 5000, size=(30, 3)) * 1e-3  # on a grid: +2e-7 cannot cross a rounding edge
    k = shape_key(v, 20)
    assert shape_key(v[::-1], 20) == k  # a set: order does not matter
    assert shape_key(np.vstack([v, v[:5]]), 20) == k  # nor duplicates (unwelded copies)
    assert shape_key(v + 2e-7, 20) == k  # below the 1e-5 rounding
    assert shape_key(v, 21) != k
    w = v.copy()
    w[3, 1] += 1e-3
    assert shape_key(w, 20) != k


@pytest.fixture(scope="module")
def dev(dev_dir):
    root = default_0ad_root()
    return dev_exclusion(dev_dir, root if (root / "art" / "meshes").is_dir() else None)


def test_dev_meshes_and_copies_get_dev_split(dev, dev_dir, tmp_path):
    rows = read_dev_manifest(dev_dir / "MANIFEST.tsv")
    assert len(rows) == 160 and len(dev.zip_paths) == 160
    for r in rows[::16]:
        # the dev OBJ itself under its public.zip path, and a same-shape copy under another path
        copy = tmp_path / "copy.obj"
        copy.write_bytes((dev_dir / r["file"]).read_bytes())
        assert encode_one(r["zip_path"], dev_dir / r["file"], dev_dir, dev)[0]["split"] == DEV
        assert encode_one("art/meshes/other/" + r["file"], copy, tmp_path, dev)[0]["split"] == DEV


def test_real_0ad_dev_sources_are_excluded(dev, dev_dir):
    root = default_0ad_root()
    if not (root / "art" / "meshes").is_dir():
        pytest.skip("0 A.D. meshes not fetched (scripts/fetch_0ad.sh)")
    for r in read_dev_manifest(dev_dir / "MANIFEST.tsv"):
        row = encode_one(r["zip_path"], root / r["zip_path"], root, dev)[0]
        assert row["split"] == DEV, r["zip_path"]
        assert row["faces"] == int(r["faces"])


def test_built_index_never_trains_on_dev(dev):
    path = data_dir() / "index" / "0ad" / "index.jsonl"
    if not path.exists():
        pytest.skip("no 0 A.D. index built (silk-export dataset)")
    rows = [json.loads(line) for line in open(path)]
    assert all(r["split"] == DEV for r in rows if r["key"] in dev.zip_paths)
    assert sum(r["split"] == DEV for r in rows) >= 160
    for r in rows:
        if r["split"] != DEV and r["faces"] <= 8000 and r["key"].startswith("art/meshes/g"):
            v, f = silk_mesh.load_arrays(default_0ad_root() / r["file"])
            assert shape_key(v, f.shape[0]) not in dev.shape_keys, r["key"]
