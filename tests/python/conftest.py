# SPDX-License-Identifier: MIT
"""Fixtures of the silk_mesh tests (ctest python_silk_mesh): the binding from this checkout's
bindings/python, libsilk from $SILK_LIBRARY (ctest sets the build's) or the checkout's build,
silkgen from $SILKGEN or beside the library, spec files from $SILK_SHARED_DIR or ../shared."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bindings" / "python"))

import silk_mesh  # noqa: E402
from silk_test_fixtures import lib_path, shared, silkgen  # noqa: E402,F401  (fixtures, registered here)


@pytest.fixture(scope="session")
def generation(lib_path) -> None:
    if not silk_mesh.generation_available():
        pytest.skip("libsilk without onnxruntime")
