# SPDX-License-Identifier: MIT
"""Shared fixtures: libsilk is found as the package finds it ($SILK_LIBRARY, else build/ in the
checkout); silkgen and silktok from the same build folder; spec files from the shared folder.
Those four come from tests/python/silk_test_fixtures.py, shared with the silk_mesh tests."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "export"))  # works without `pip install -e export`
sys.path.insert(0, str(ROOT / "tests" / "python"))  # the fixtures shared with tests/python

import torch  # noqa: E402

import silk_export  # noqa: E402,F401  (export/silk_mesh links to the binding)

torch.set_num_threads(1)  # deterministic, and fast on a shared machine (no thread oversubscription)
from silk_test_fixtures import generate_unconstrained, lib_path, shared, silkgen, silktok  # noqa: E402,F401


@pytest.fixture(scope="session")
def golden_dir(shared) -> Path:
    return shared / "spec" / "golden"


@pytest.fixture(scope="session")
def dev_dir(shared) -> Path:
    return shared / "corpus" / "dev"


@pytest.fixture(scope="session")
def mesh_folder(tmp_path_factory):
    """mesh_folder(src_dir, names) -> a new folder holding copies of src_dir/<name>.obj."""

    def make(src: Path, names) -> Path:
        dest = tmp_path_factory.mktemp("meshes")
        for n in names:
            shutil.copy(Path(src) / f"{n}.obj", dest / f"{n}.obj")
        return dest

    return make
