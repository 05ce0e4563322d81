# SPDX-License-Identifier: MIT
"""Where the package finds the repository's files (vocabulary layout, built libsilk, data folder).

All locations are derived from this file's place in the checkout or from environment variables;
nothing machine-specific is stored."""
from __future__ import annotations

import os
from pathlib import Path

# export/silk_export/paths.py -> repository root is two folders up from the package.
REPO_ROOT = Path(__file__).resolve().parents[2]


def vocabulary_layout_path() -> Path:
    """engine/tokenizer/vocabulary_layout.json, or $SILK_VOCAB_LAYOUT."""
    env = os.environ.get("SILK_VOCAB_LAYOUT")
    return Path(env) if env else REPO_ROOT / "engine" / "tokenizer" / "vocabulary_layout.json"


def data_dir() -> Path:
    """$SILK_DATA_DIR (default /tmp/silk-data), the cache scripts/fetch_0ad.sh fills."""
    return Path(os.environ.get("SILK_DATA_DIR", "/tmp/silk-data"))


def shared_dir() -> Path:
    """$SILK_SHARED_DIR, else ../shared beside the checkout (spec, goldens, dev corpus)."""
    env = os.environ.get("SILK_SHARED_DIR")
    return Path(env) if env else REPO_ROOT.parent / "shared"
