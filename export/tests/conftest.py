"""Shared fixtures: libsilk is found as the package finds it ($SILK_LIBRARY, else build/ in the
checkout); silktok is taken from the same build folder; spec files from the shared folder."""
from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # works without `pip install -e export`

import torch  # noqa: E402

import silk_export  # noqa: E402,F401  (puts the checkout's silk_mesh on the path when not installed)
import silk_mesh  # noqa: E402

torch.set_num_threads(1)  # deterministic, and fast on a shared machine (no thread oversubscription)
from silk_export.paths import shared_dir  # noqa: E402


@pytest.fixture(scope="session")
def lib_path() -> Path:
    silk_mesh.load_library()  # fails loudly, naming the file, when no library can be loaded
    return Path(silk_mesh.library_path())


@pytest.fixture(scope="session")
def silktok(lib_path) -> Path:
    env = os.environ.get("SILKTOK")
    exe = Path(env) if env else lib_path.resolve().parents[1] / "apps" / "silktok"
    if not exe.is_file():
        pytest.skip(f"silktok not built beside {lib_path} (set SILKTOK)")
    return exe


@pytest.fixture(scope="session")
def golden_dir() -> Path:
    return shared_dir() / "spec" / "golden"


@pytest.fixture(scope="session")
def dev_dir() -> Path:
    return shared_dir() / "corpus" / "dev"


@pytest.fixture(scope="session")
def shared() -> Path:
    return shared_dir()


@pytest.fixture(scope="session")
def mesh_folder(tmp_path_factory):
    """mesh_folder(src_dir, names) -> a new folder holding copies of src_dir/<name>.obj."""
    def make(src: Path, names) -> Path:
        dest = tmp_path_factory.mktemp("meshes")
        for n in names:
            shutil.copy(Path(src) / f"{n}.obj", dest / f"{n}.obj")
        return dest
    return make
