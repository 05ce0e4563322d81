"""Fixtures of the silk_mesh tests (ctest python_silk_mesh): the binding from this checkout's
bindings/python, libsilk from $SILK_LIBRARY (ctest sets the build's) or the checkout's build,
silkgen from $SILKGEN or beside the library, spec files from $SILK_SHARED_DIR or ../shared."""
from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bindings" / "python"))

import silk_mesh  # noqa: E402


@pytest.fixture(scope="session")
def lib_path() -> Path:
    silk_mesh.load_library()
    return Path(silk_mesh.library_path())


@pytest.fixture(scope="session")
def shared() -> Path:
    return Path(os.environ.get("SILK_SHARED_DIR", ROOT.parent / "shared"))


@pytest.fixture(scope="session")
def silkgen(lib_path) -> Path:
    env = os.environ.get("SILKGEN")
    exe = Path(env) if env else lib_path.resolve().parents[1] / "apps" / "silkgen"
    if not exe.is_file():
        pytest.skip(f"silkgen not built beside {lib_path} (set SILKGEN)")
    return exe


@pytest.fixture(scope="session")
def generation(lib_path) -> None:
    if not silk_mesh.generation_available():
        pytest.skip("libsilk without onnxruntime")
