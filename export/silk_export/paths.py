# SPDX-License-Identifier: MIT
"""Where the package finds its files: the vocabulary layout ships inside the package (read with
importlib.resources), everything else is named by environment variables. No path into a checkout,
so the installed wheel works from any folder.

vocabulary_layout.json in this package is engine/tokenizer/vocabulary_layout.json itself: a symbolic
link in the checkout, the file's contents in the wheel (pyproject.toml) — one source, never a copy
kept by hand."""

from __future__ import annotations

import os
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


def shared_dir() -> Path | None:
    """$SILK_SHARED_DIR (spec, goldens, dev corpus), or None when it is not set."""
    env = os.environ.get("SILK_SHARED_DIR")
    return Path(env) if env else None
