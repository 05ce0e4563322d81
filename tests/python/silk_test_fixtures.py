# SPDX-License-Identifier: MIT
"""The fixtures both pytest suites share (tests/python, and export/tests through its conftest):
libsilk as silk_mesh loads it, the shared folder, and Silk's tools from the library's build folder.
Each conftest imports them by name (pytest registers the fixtures it finds in a conftest); the
caller puts bindings/python (silk_mesh) on sys.path first."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

import silk_mesh

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "export"))  # this checkout's silk_export (an installed one may be older)
from silk_export.paths import shared_dir  # noqa: E402  (the one shared-folder rule of Python)


@pytest.fixture(scope="session")
def lib_path() -> Path:
    silk_mesh.load_library()  # fails loudly, naming the file, when no library can be loaded
    return Path(silk_mesh.library_path())


@pytest.fixture(scope="session")
def shared() -> Path:
    """The shared material folder by the one rule (silk_export.paths.shared_dir); an error naming
    the places looked in when there is none."""
    return shared_dir(required=True)


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
