# SPDX-License-Identifier: MIT
"""One dataset shard on disk: a compact, memory-mappable cache of the meshes one build job
encoded. Raw little-endian arrays, appended while the job runs (constant memory), plus offsets:

  tokens.i16    int16  all token sequences back to back (ids < 10269 fit; no BOS/EOS/PAD)
  vertices.f64  float64 [V, 3] positions exactly as loaded (training re-tokenises after
                augmentation; float32 would change the tokens of a few meshes in a hundred)
  faces.i32     int32 [F, 3] triangles, indices local to their mesh
  offsets.npy   int64 [n + 1, 3] start of mesh i in (tokens, vertices, faces); row n = the ends
  meshes.jsonl  one row per listed file, encoded or refused (the index rows; encoded ones carry
                `slot`, their position in the arrays)
  refused.tsv   key, file, named reason, message of every mesh libsilk refused or could not read
  shard.json    format, shard i/N, counts

A shard folder appears only complete: it is written as `<name>.tmp` and renamed at the end."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np

from ..json_io import jsonl_line, write_json

FORMAT = "silk-shard/1"
TOKEN_DTYPE = np.int16


def shard_name(i: int, n: int) -> str:
    return f"shard-{i:05d}-of-{n:05d}"


def parse_shard(text: str) -> tuple[int, int]:
    """'I/N' -> (I, N) with 0 <= I < N."""
    try:
        i, n = (int(x) for x in text.split("/"))
    except ValueError:
        raise ValueError(f"--shard '{text}': expected I/N, e.g. 0/8") from None
    if n < 1 or not 0 <= i < n:
        raise ValueError(f"--shard '{text}': need 0 <= I < N")
    return i, n


def write_refused(fh, rows: list[dict]) -> None:
    """refused.tsv: key, file, named reason, libsilk's message (tabs and newlines blanked)."""
    fh.write("key\tfile\treason\tdetail\n")
    for r in rows:
        detail = " ".join(str(r.get("detail", "")).split())
        fh.write(f"{r['key']}\t{r['file']}\t{r['refused']}\t{detail}\n")


class ShardWriter:
    def __init__(self, out_dir: Path, i: int, n: int):
        self.final = Path(out_dir) / shard_name(i, n)
        self.dir = self.final.with_name(self.final.name + ".tmp")
        if self.dir.exists():
            shutil.rmtree(self.dir)
        self.dir.mkdir(parents=True)
        self.i, self.n = i, n
        self._files = {k: open(self.dir / k, "wb") for k in ("tokens.i16", "vertices.f64", "faces.i32")}
        self._rows = open(self.dir / "meshes.jsonl", "w")
        self.offsets = [(0, 0, 0)]
        self.refused: list[dict] = []

    def add(self, row: dict, tokens=None, vertices=None, faces=None) -> None:
        """An encoded mesh (with its arrays) or a refused one (row['refused'] set, no arrays)."""
        if row.get("refused") is None:
            if tokens.size and int(tokens.max()) > np.iinfo(TOKEN_DTYPE).max:
                raise ValueError(f"{row['key']}: token id {int(tokens.max())} does not fit int16")
            row = {**row, "slot": len(self.offsets) - 1}
            self._files["tokens.i16"].write(np.ascontiguousarray(tokens, TOKEN_DTYPE).tobytes())
            self._files["vertices.f64"].write(np.ascontiguousarray(vertices, np.float64).tobytes())
            self._files["faces.i32"].write(np.ascontiguousarray(faces, np.int32).tobytes())
            t, v, f = self.offsets[-1]
            self.offsets.append((t + tokens.size, v + vertices.shape[0], f + faces.shape[0]))
        else:
            self.refused.append(row)
        self._rows.write(jsonl_line(row, what=f"meshes.jsonl: row {row.get('key')}"))

    def close(self, summary: dict) -> Path:
        for fh in (*self._files.values(), self._rows):
            fh.close()
        np.save(self.dir / "offsets.npy", np.asarray(self.offsets, np.int64))
        with open(self.dir / "refused.tsv", "w") as fh:
            write_refused(fh, self.refused)
        info = {
            "format": FORMAT,
            "shard": self.i,
            "of": self.n,
            "encoded": len(self.offsets) - 1,
            "refused": len(self.refused),
            **summary,
        }
        write_json(self.dir / "shard.json", info)
        if self.final.exists():
            shutil.rmtree(self.final)
        self.dir.rename(self.final)
        return self.final


class Shard:
    """Read side: memory-mapped arrays of one finished shard."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self.info = json.loads((self.path / "shard.json").read_text())
        if self.info.get("format") != FORMAT:
            raise ValueError(f"{self.path}: not a {FORMAT} shard")
        self.offsets = np.load(self.path / "offsets.npy")
        t, v, f = (int(x) for x in self.offsets[-1])
        self.tokens = self._map("tokens.i16", TOKEN_DTYPE, (t,))
        self.vertices = self._map("vertices.f64", np.float64, (v, 3))
        self.faces = self._map("faces.i32", np.int32, (f, 3))

    def _map(self, name: str, dtype, shape):
        p = self.path / name
        expected = int(np.prod(shape)) * np.dtype(dtype).itemsize
        if p.stat().st_size != expected:
            raise ValueError(f"{p}: {p.stat().st_size} bytes, offsets.npy says {expected}")
        return np.memmap(p, dtype=dtype, mode="r", shape=shape) if expected else np.zeros(shape, dtype)

    def rows(self) -> list[dict]:
        with open(self.path / "meshes.jsonl") as fh:
            return [json.loads(line) for line in fh if line.strip()]

    def __len__(self) -> int:
        return self.offsets.shape[0] - 1

    def mesh_tokens(self, slot: int) -> np.ndarray:
        a, b = self.offsets[slot, 0], self.offsets[slot + 1, 0]
        return np.asarray(self.tokens[a:b], np.int32)

    def mesh_arrays(self, slot: int) -> tuple[np.ndarray, np.ndarray]:
        (_, v0, f0), (_, v1, f1) = self.offsets[slot], self.offsets[slot + 1]
        return np.asarray(self.vertices[v0:v1], np.float64), np.asarray(self.faces[f0:f1], np.int32)
