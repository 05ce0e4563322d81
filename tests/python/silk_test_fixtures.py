# SPDX-License-Identifier: MIT
"""The fixtures both pytest suites share (tests/python, and export/tests through its conftest):
libsilk as silk_mesh loads it, the shared folder, and Silk's tools from the library's build folder.
Each conftest imports them by name (pytest registers the fixtures it finds in a conftest); the
caller puts bindings/python (silk_mesh) on sys.path first."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import silk_mesh

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def lib_path() -> Path:
    silk_mesh.load_library()  # fails loudly, naming the file, when no library can be loaded
    return Path(silk_mesh.library_path())


@pytest.fixture(scope="session")
def shared() -> Path:
    """$SILK_SHARED_DIR, else ../shared beside the checkout (as silk_export.paths.shared_dir)."""
    env = os.environ.get("SILK_SHARED_DIR")
    return Path(env) if env else ROOT.parent / "shared"


def tool_beside_library(lib_path: Path, name: str, folder: str = "apps") -> Path:
    """$<NAME> (e.g. $SILKGEN), else <folder>/<name> of the build folder holding lib_path; skips
    the test when neither is there."""
    env = os.environ.get(name.upper())
    exe = Path(env) if env else lib_path.resolve().parents[1] / folder / name
    if not exe.is_file():
        pytest.skip(f"{name} not built beside {lib_path} (set {name.upper()})")
    return exe


@pytest.fixture(scope="session")
def silkgen(lib_path) -> Path:
    return tool_beside_library(lib_path, "silkgen")


@pytest.fixture(scope="session")
def silktok(lib_path) -> Path:
    return tool_beside_library(lib_path, "silktok")


@pytest.fixture(scope="session")
def generate_unconstrained(lib_path) -> Path:
    """tests/tools/generate_unconstrained.cpp (a test build's): generation without the grammar mask."""
    return tool_beside_library(lib_path, "generate_unconstrained", "tests")
