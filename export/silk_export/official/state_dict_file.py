# SPDX-License-Identifier: MIT
"""Reads a state dict from disk one tensor at a time, so a multi-GB checkpoint never sits in memory
twice: `.safetensors` (header parsed here; F32/F16/BF16) and PyTorch `.pt`/`.bin` (torch.load
with weights_only=True, memory-mapped when the file is in the zip format)."""

from __future__ import annotations

import hashlib
import json
import math
import struct
from pathlib import Path

import torch

SAFETENSORS_DTYPES = {"F32": torch.float32, "F16": torch.float16, "BF16": torch.bfloat16}
MAX_HEADER_BYTES = 100 * 1024 * 1024


class StateDictError(ValueError):
    """A checkpoint that cannot be read or does not fit the expected layout."""


class TensorInfo:
    def __init__(self, shape: tuple[int, ...], dtype: torch.dtype):
        self.shape, self.dtype = tuple(shape), dtype


class SafetensorsFile:
    """name -> TensorInfo from the header; read(name) seeks and reads only that tensor."""

    def __init__(self, path: Path):
        self.path = Path(path)
        size = self.path.stat().st_size
        with open(self.path, "rb") as f:
            raw = f.read(8)
            if len(raw) < 8:
                raise StateDictError(f"{self.path}: too short for a safetensors file")
            (n,) = struct.unpack("<Q", raw)
            if n > min(MAX_HEADER_BYTES, size - 8):
                raise StateDictError(f"{self.path}: safetensors header length {n} is impossible for a {size}-byte file")
            try:
                header = json.loads(f.read(n))
            except (UnicodeDecodeError, json.JSONDecodeError) as e:
                raise StateDictError(f"{self.path}: safetensors header is not JSON ({e})") from None
        if not isinstance(header, dict):
            raise StateDictError(f"{self.path}: safetensors header is not a JSON object")
        self.metadata = header.pop("__metadata__", {}) or {}
        self.data_start = 8 + n
        self.entries: dict[str, tuple[TensorInfo, int, int]] = {}
        for name, e in header.items():
            self.entries[name] = self._entry(name, e, size - self.data_start)

    def _entry(self, name: str, e, data_size: int) -> tuple[TensorInfo, int, int]:
        try:
            dtype_name, shape, (begin, end) = e["dtype"], [int(d) for d in e["shape"]], e["data_offsets"]
        except (TypeError, KeyError, ValueError):
            raise StateDictError(f"{self.path}: tensor '{name}': malformed header entry") from None
        if dtype_name not in SAFETENSORS_DTYPES:
            raise StateDictError(
                f"{self.path}: tensor '{name}': dtype {dtype_name} is not supported "
                f"(expected one of {', '.join(SAFETENSORS_DTYPES)})"
            )
        dtype = SAFETENSORS_DTYPES[dtype_name]
        nbytes = math.prod(shape) * dtype.itemsize
        if any(d < 0 for d in shape) or not (0 <= begin <= end <= data_size) or end - begin != nbytes:
            raise StateDictError(
                f"{self.path}: tensor '{name}': data offsets [{begin}, {end}) do not fit "
                f"shape {shape} {dtype_name} inside the file"
            )
        return TensorInfo(shape, dtype), self.data_start + begin, nbytes

    def infos(self) -> dict[str, TensorInfo]:
        return {k: v[0] for k, v in self.entries.items()}

    def read(self, name: str) -> torch.Tensor:
        info, offset, nbytes = self.entries[name]
        out = torch.empty(info.shape, dtype=info.dtype)
        with open(self.path, "rb") as f:
            f.seek(offset)
            got = f.readinto(memoryview(out.reshape(-1).view(torch.uint8).numpy()))
        if got != nbytes:
            raise StateDictError(f"{self.path}: tensor '{name}': file ends inside its data")
        return out


class TorchFile:
    """A torch.save'd state dict (possibly under a 'state_dict' / 'model' / 'module' key)."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self.metadata = {}
        try:
            try:
                obj = torch.load(self.path, map_location="cpu", weights_only=True, mmap=True)
            except RuntimeError:  # the legacy (non-zip) format cannot be memory-mapped
                obj = torch.load(self.path, map_location="cpu", weights_only=True)
        except Exception as e:  # noqa: BLE001 - unpickling errors come in many types
            raise StateDictError(f"{self.path}: not a readable PyTorch state dict ({e})") from None
        for key in ("state_dict", "model", "module"):
            if isinstance(obj, dict) and isinstance(obj.get(key), dict):
                self.metadata = {"nested_under": key}
                obj = obj[key]
                break
        if not isinstance(obj, dict) or not all(isinstance(v, torch.Tensor) for v in obj.values()):
            raise StateDictError(f"{self.path}: expected a dict of tensors (a state_dict)")
        for name, t in obj.items():
            if t.dtype not in SAFETENSORS_DTYPES.values():
                raise StateDictError(f"{self.path}: tensor '{name}': dtype {t.dtype} is not supported")
        self.tensors = obj

    def infos(self) -> dict[str, TensorInfo]:
        return {k: TensorInfo(v.shape, v.dtype) for k, v in self.tensors.items()}

    def read(self, name: str) -> torch.Tensor:
        return self.tensors[name]


def open_state_dict(path: Path):
    path = Path(path)
    if not path.is_file():
        raise StateDictError(f"{path}: no such file")
    if path.suffix == ".safetensors":
        return SafetensorsFile(path)
    if path.suffix in (".pt", ".pth", ".bin", ".ckpt"):
        return TorchFile(path)
    raise StateDictError(f"{path}: unknown checkpoint type '{path.suffix}' (expected .safetensors, .pt, .bin)")


def sha256_of(path: Path) -> str:
    """The SHA-256 of a checkpoint file (the model card's and the hub check's digest), read in 16 MiB chunks."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        while chunk := f.read(1 << 24):
            h.update(chunk)
    return h.hexdigest()
