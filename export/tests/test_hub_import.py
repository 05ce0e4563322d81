# SPDX-License-Identifier: MIT
"""`silk-export import-official hf:ORG/NAME[@REVISION]/PATH` against a model hub on 127.0.0.1
(tests/tools/local_hub.py: the official fixture in the hub's URL layout and headers), no network:
the import from the hub equals the import of the same file by path (every ONNX file byte for byte,
model.json but for timings and the recorded source), --name writes the models folder libsilk names,
a download cut off mid-file resumes with byte ranges, and a closed port, a wrong
repository / file / revision, a truncated download and a hash mismatch each exit non-zero with a
message naming the hub URL, leaving no model folder. Each command runs as a subprocess, as a user
runs it (huggingface_hub reads HF_ENDPOINT / HF_HOME when it is imported)."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "tools"))
from local_hub import COMMIT, LocalHub  # noqa: E402

pytest.importorskip("huggingface_hub")
REPO = "gcsong/mesh_silksong"
TIMINGS = ("ms_per_token", "seconds")


@pytest.fixture(scope="module")
def fixture_dir(shared) -> Path:
    d = shared / "official-fixture"
    if not (d / "model.safetensors").is_file():
        pytest.skip(f"no {d}")
    return d


def run(args, env_extra, cwd) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if not k.startswith("HF_")}
    env.update(PYTHONPATH=str(ROOT / "export"), HF_HUB_DISABLE_TELEMETRY="1", **env_extra)
    return subprocess.run(
        [sys.executable, "-m", "silk_export", *map(str, args)],
        env=env,
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=900,
    )


def without_timings(obj):
    if isinstance(obj, dict):
        return {k: without_timings(v) for k, v in obj.items() if k not in TIMINGS}
    if isinstance(obj, list):
        return [without_timings(v) for v in obj]
    return obj


def leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir()) if folder.exists() else []


def test_hub_import_equals_path_import(fixture_dir, tmp_path):
    models = tmp_path / "models"
    by_path = tmp_path / "by-path"
    p = run(
        [
            "import-official",
            fixture_dir / "model.safetensors",
            "--config",
            fixture_dir / "config.json",
            "-o",
            by_path,
            "--precision",
            "fp32",
            "--no-progress",
        ],
        {},
        tmp_path,
    )
    assert p.returncode == 0, p.stderr
    with LocalHub({REPO: fixture_dir}) as hub:
        env = {"HF_ENDPOINT": hub.endpoint, "HF_HOME": str(tmp_path / "hf"), "SILK_MODELS": str(models)}
        p = run(
            [
                "import-official",
                f"hf:{REPO}/model.safetensors",
                "--config",
                f"hf:{REPO}/config.json",
                "--name",
                "fixture",
                "--precision",
                "fp32",
                "--no-progress",
            ],
            env,
            tmp_path,
        )
        assert p.returncode == 0, p.stderr
    from_hub = models / "fixture"
    files = sorted(f.name for f in by_path.iterdir())
    assert files == sorted(f.name for f in from_hub.iterdir())
    for name in files:
        if name.endswith(".onnx"):
            assert (by_path / name).read_bytes() == (from_hub / name).read_bytes(), name
    a, b = (json.loads((d / "model.json").read_text()) for d in (by_path, from_hub))
    assert b["source"].pop("hub") == f"hf:{REPO}@{COMMIT}/model.safetensors"
    assert b["source"].pop("url") == f"{hub.endpoint}/{REPO}/resolve/main/model.safetensors"
    assert without_timings(a) == without_timings(b)
    assert leftovers(models) == ["fixture"]  # no .fixture.importing-* left beside it
    # the folder libsilk resolves the name to (silkgen --model fixture, silk_mesh.Model("fixture"))
    q = subprocess.run(
        [sys.executable, "-c", "import silk_mesh; print(silk_mesh.find_model('fixture'))"],
        env={**os.environ, "PYTHONPATH": str(ROOT / "export"), "SILK_MODELS": str(models)},
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=True,
    )
    assert q.stdout.strip() == str(from_hub)


def closed_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()  # nothing listens there now
    return port


@pytest.mark.parametrize(
    "case,source,hub_kw,words",
    [
        ("closed port", f"hf:{REPO}/model.safetensors", None, ["cannot connect", "Connection refused"]),
        (
            "wrong repository",
            "hf:gcsong/no_such_repo/model.safetensors",
            {},
            ["repository 'gcsong/no_such_repo' not found"],
        ),
        (
            "404 file",
            f"hf:{REPO}/release-100K/model.safetensors",
            {},
            ["file 'release-100K/model.safetensors' not found"],
        ),
        ("wrong revision", f"hf:{REPO}@v9/model.safetensors", {}, ["revision 'v9' not found"]),
        (
            "truncated",
            f"hf:{REPO}/model.safetensors",
            {"truncate_gets": 1000},
            ["download interrupted", "run the command again"],
        ),
        ("hash mismatch", f"hf:{REPO}/model.safetensors", {"wrong_hash": True}, ["SHA-256", "differs from the hub's"]),
    ],
)
def test_hub_errors_name_the_url_and_write_nothing(fixture_dir, tmp_path, case, source, hub_kw, words):
    models = tmp_path / "models"
    hub = LocalHub({REPO: fixture_dir}, **(hub_kw or {}))
    endpoint = hub.endpoint if hub_kw is not None else f"http://127.0.0.1:{closed_port()}"
    env = {"HF_ENDPOINT": endpoint, "HF_HOME": str(tmp_path / "hf"), "SILK_MODELS": str(models)}
    with hub:
        p = run(["import-official", source, "--name", "fx", "--no-progress"], env, tmp_path)
    url = endpoint + "/" + source[3:].split("/", 2)[0] + "/" + source[3:].split("/", 2)[1].split("@")[0]
    print(f"{case}: exit {p.returncode}\n{p.stderr.strip().splitlines()[-1]}")
    assert p.returncode == 1, p.stderr
    last = p.stderr.strip().splitlines()[-1]
    assert last.startswith("silk-export import-official: error: " + url), last
    for w in words:
        assert w in last, last
    assert "nothing was written" in last
    assert leftovers(models) == []
    if case == "hash mismatch":  # the bad file left the cache: a rerun downloads it again
        assert not list((tmp_path / "hf").rglob("model.safetensors"))


def test_interrupted_download_resumes_with_a_range(tmp_path):
    """Connections cut off mid-file (three in a row): each retry asks only for the rest (a byte range), and
    the file that arrives is the hub's, byte for byte."""
    repo = tmp_path / "repo"
    repo.mkdir()
    (repo / "big.bin").write_bytes(os.urandom(48 << 20))  # several 10 MB download chunks per cut
    code = (
        "import sys; from silk_export.official.hub import download; p, info = download(sys.argv[1], False); "
        "print(info['bytes'], info['sha256'])"
    )
    env = {"HF_HOME": str(tmp_path / "hf"), "PYTHONPATH": str(ROOT / "export"), "HF_HUB_DISABLE_TELEMETRY": "1"}
    with LocalHub({"org/big": repo}, truncate_gets=3) as hub:
        p = subprocess.run(
            [sys.executable, "-c", code, "hf:org/big/big.bin"],
            env={**os.environ, **env, "HF_ENDPOINT": hub.endpoint},
            capture_output=True,
            text=True,
            timeout=300,
        )
        ranges = [r for m, path, r in hub.requests if m == "GET" and path.endswith("/big.bin")]
    assert p.returncode == 0, p.stderr
    assert p.stdout.split() == [str(48 << 20), hub.sha256(repo / "big.bin")]
    assert len(ranges) == 4 and ranges[0] is None, ranges
    starts = [int(r.split("=")[1].rstrip("-")) for r in ranges[1:]]
    assert starts == sorted(starts) and starts[0] > 0, ranges  # each retry resumes further on


def test_name_that_is_a_path_is_refused(tmp_path):
    p = run(
        ["import-official", "x.safetensors", "--name", "../elsewhere"], {"SILK_MODELS": str(tmp_path / "m")}, tmp_path
    )
    assert p.returncode == 2 and "'../elsewhere' is not a model name" in p.stderr, p.stderr
    assert not (tmp_path / "m").exists() and not (tmp_path / "elsewhere").exists()
