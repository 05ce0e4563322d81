# SPDX-License-Identifier: MIT
"""`silk-export dataset` over a folder tree of mixed formats: a build in two shards (--shard 0/2,
--shard 1/2, --merge) holds exactly the samples of one unsharded build; cached tokens are the
official golden tokens; refused meshes are listed with their named reasons; the cache is read
back memory-mapped and gives the training pipeline's samples."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

import silk_mesh
from silk_export.cli import main
from silk_export.data.dataset_index import build_index, merge_shards
from silk_export.data.samples import make_sample
from silk_export.data.shard_store import Shard, parse_shard
from silk_export.data.sharded_dataset import ShardedSource, dataset_rows

BAD = {"degenerate_only.obj": "no-faces", "garbage_bytes.obj": "error:parse error", "empty.obj": "error:parse error"}


def write_off(path, v, f):
    path.write_text(
        f"OFF\n{len(v)} {len(f)} 0\n"
        + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in v)
        + "".join(f"3 {a} {b} {c}\n" for a, b, c in f)
    )


def write_stl(path, v, f):
    lines = ["solid t"]
    for tri in f:
        lines += [
            "facet normal 0 0 0",
            "outer loop",
            *(f"vertex {v[i][0]!r} {v[i][1]!r} {v[i][2]!r}" for i in tri),
            "endloop",
            "endfacet",
        ]
    path.write_text("\n".join(lines + ["endsolid t"]) + "\n")


@pytest.fixture(scope="module")
def tree(golden_dir, tmp_path_factory):
    root = tmp_path_factory.mktemp("tree")
    (root / "a" / "b").mkdir(parents=True)
    (root / "c").mkdir()
    (root / "bad").mkdir()
    shutil.copy(golden_dir / "cube.obj", root / "a" / "cube.obj")
    shutil.copy(golden_dir / "grid.obj", root / "grid.obj")
    shutil.copy(golden_dir / "icosphere2.obj", root / "c" / "icosphere2.obj")
    silk_mesh.Mesh.load(golden_dir / "torus_12x8.obj").save(root / "a" / "b" / "torus_12x8.ply")
    v, f = silk_mesh.load_arrays(golden_dir / "octahedron.obj")
    write_off(root / "c" / "octahedron.off", v.tolist(), f.tolist())
    v, f = silk_mesh.load_arrays(golden_dir / "tetrahedron.obj")
    write_stl(root / "c" / "tetrahedron.stl", v.tolist(), f.tolist())
    for name in BAD:
        shutil.copy(golden_dir.parents[1] / "corpus" / "bad" / name, root / "bad" / name)
    return root


@pytest.fixture(scope="module")
def builds(tree, dev_dir, tmp_path_factory):
    one = tmp_path_factory.mktemp("one")
    build_index(tree, one, dev_dir)
    two = tmp_path_factory.mktemp("two")
    for shard in ("1/2", "0/2"):  # any order, e.g. two array jobs
        assert (
            main(["dataset", "--root", str(tree), "--out", str(two), "--shard", shard, "--dev-dir", str(dev_dir)]) == 0
        )
    assert not (two / "dataset.json").exists()
    assert main(["dataset", "--out", str(two), "--merge"]) == 0
    return one, two


def strip(rows):
    return [{k: v for k, v in r.items() if k not in ("shard", "slot")} for r in rows]


def test_sharded_build_has_the_samples_of_the_unsharded_build(builds):
    one, two = builds
    ra, rb = dataset_rows(one), dataset_rows(two)
    assert len(ra) == 9 and strip(ra) == strip(rb)
    assert sorted({r["shard"] for r in rb}) == [0, 1]
    assert [r["file"] for r in ra] == sorted(r["file"] for r in ra)  # file order, not shard order
    enc_a = [r for r in ra if r["refused"] is None]
    enc_b = [r for r in rb if r["refused"] is None]
    sa, sb = ShardedSource(one, enc_a), ShardedSource(two, enc_b)
    assert len(enc_a) == 6
    for i, r in enumerate(enc_a):
        assert np.array_equal(sa.tokens(i), sb.tokens(i)) and sa.tokens(i).size == r["tokens"]
        for x, y in zip(sa.arrays(i), sb.arrays(i)):
            assert np.array_equal(x, y)
    assert json.loads((two / "summary.json").read_text())["shards"] == 2
    assert (one / "refused.tsv").read_text() == (two / "refused.tsv").read_text()


def test_cache_holds_the_official_tokens_and_the_loaded_arrays(builds, tree, golden_dir):
    one, _ = builds
    rows = [r for r in dataset_rows(one) if r["refused"] is None]
    src = ShardedSource(one, rows)
    for i, r in enumerate(rows):
        stem = r["file"].rsplit("/", 1)[-1].split(".")[0]
        golden = np.loadtxt(golden_dir / f"{stem}.tokens.txt", dtype=np.int32)
        assert np.array_equal(src.tokens(i), golden), r["file"]
        v, f = silk_mesh.load_arrays(tree / r["file"])
        assert np.array_equal(src.arrays(i)[0], v) and np.array_equal(src.arrays(i)[1], f)
    assert isinstance(Shard(one / "shard-00000-of-00001").tokens, np.memmap)


def test_refused_meshes_are_listed_with_named_reasons(builds):
    one, _ = builds
    lines = (one / "refused.tsv").read_text().splitlines()
    assert lines[0] == "key\tfile\treason\tdetail"
    got = {ln.split("\t")[1].split("/")[-1]: ln.split("\t")[2] for ln in lines[1:]}
    assert got == BAD
    assert all(ln.split("\t")[3] for ln in lines[1:])  # libsilk's message


def test_cached_tokens_give_the_tokenising_pipeline_samples(builds):
    one, _ = builds
    rows = [r for r in dataset_rows(one) if r["refused"] is None]
    src = ShardedSource(one, rows)
    for i in range(len(rows)):
        a = src.sample(i, np.random.default_rng(5), 10_000, augment=False, n_points=64)
        b = make_sample(*src.arrays(i), np.random.default_rng(5), 10_000, augment=False, n_points=64)
        assert np.array_equal(a.tokens, b.tokens) and np.array_equal(a.points, b.points)


def test_merge_needs_every_shard(tree, dev_dir, tmp_path):
    main(["dataset", "--root", str(tree), "--out", str(tmp_path), "--shard", "0/2", "--dev-dir", str(dev_dir)])
    with pytest.raises(ValueError, match="shard-00001-of-00002"):
        merge_shards(tmp_path)
    for bad in ("2/2", "1", "a/b", "0/0"):
        with pytest.raises(ValueError, match="--shard"):
            parse_shard(bad)
