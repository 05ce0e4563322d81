# SPDX-License-Identifier: MIT
"""Where the package finds its files: the vocabulary layout ships inside the package (read with
importlib.resources), everything else is named by environment variables. The one path into a
checkout is the shared material's fallback (shared_dir), taken only when the package runs from a
checkout, so the installed wheel works from any folder.

vocabulary_layout.json in this package is engine/tokenizer/vocabulary_layout.json itself: a symbolic
link in the checkout, the file's contents in the wheel (pyproject.toml) — one source, never a copy
kept by hand."""

from __future__ import annotations

import os
import subprocess
from importlib import resources
from pathlib import Path


def vocabulary_layout_text() -> str:
    """The vocabulary layout JSON: $SILK_VOCAB_LAYOUT (a file), else the package's own copy."""
    env = os.environ.get("SILK_VOCAB_LAYOUT")
    if env:
        return Path(env).read_text(encoding="utf-8")
    return resources.files("silk_export").joinpath("vocabulary_layout.json").read_text(encoding="utf-8")


def data_dir() -> Path:
    """$SILK_DATA_DIR (default /tmp/silk-data), the cache scripts/fetch_0ad.sh fills."""
    return Path(os.environ.get("SILK_DATA_DIR", "/tmp/silk-data"))


def _checkout() -> Path | None:
    """The checkout this module runs from (export/silk_export/paths.py in it), else None (a wheel)."""
    root = Path(__file__).resolve().parents[2]
    return root if (root / "engine" / "include" / "silk" / "silk.h").is_file() else None


def shared_dir(required: bool = False) -> Path | None:
    """The shared material folder (spec/, corpus/, tools/): Python's copy of the one rule
    (scripts/shared_dir.sh states it, cmake/SilkSharedDir.cmake is CMake's). $SILK_SHARED_DIR when
    set (it must be a folder); else, run from a checkout, ../shared beside it, else beside the
    checkout it was cloned from (git's remote.origin.url, a local folder), when that holds spec/.
    Nothing found: None, or with required=True a ValueError naming the places looked in."""
    env = os.environ.get("SILK_SHARED_DIR")
    if env:
        if not Path(env).is_dir():
            raise ValueError(f"no shared material: SILK_SHARED_DIR={env} is not a folder")
        return Path(env).resolve()
    looked = []
    root = _checkout()
    if root is not None:
        looked.append(root.parent / "shared")
        git = subprocess.run(
            ["git", "-C", str(root), "config", "--get", "remote.origin.url"], capture_output=True, text=True
        )
        if git.returncode == 0 and git.stdout.strip():
            looked.append(Path(git.stdout.strip()) / ".." / "shared")
    for candidate in looked:
        if (candidate / "spec").is_dir():
            return candidate.resolve()
    if required:
        where = " nor ".join(str(p) for p in looked) or "(not run from a checkout)"
        raise ValueError(
            f"no shared material (spec/, corpus/): SILK_SHARED_DIR is not set and neither {where} holds spec/; "
            "set SILK_SHARED_DIR to the folder that does"
        )
    return None
