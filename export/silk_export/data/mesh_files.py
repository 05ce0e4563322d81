# SPDX-License-Identifier: MIT
"""Finds mesh files: the 0 A.D. art set ($SILK_DATA_DIR/0ad/art/meshes, keyed by the path
inside public.zip) or any folder of meshes libsilk reads (keyed by the path under that folder)."""

from __future__ import annotations

from pathlib import Path

MESH_SUFFIXES = (".obj", ".ply", ".stl", ".off", ".glb", ".gltf", ".pmd")


def is_mesh_file(p: Path) -> bool:
    name = p.name.lower()
    if name.endswith(".gz"):
        name = name[:-3]
    return name.endswith(MESH_SUFFIXES)


def list_meshes(root: Path) -> list[tuple[str, Path]]:
    """Sorted (key, file) pairs. For a 0 A.D. cache (root/art/meshes exists, or root is that
    folder's parent chain), the key is the path inside public.zip, e.g. art/meshes/gaia/x.pmd."""
    root = Path(root)
    if (root / "art" / "meshes").is_dir():
        base = root
    elif root.name == "meshes" and root.parent.name == "art":
        base = root.parent.parent
    else:
        base = root
    files = sorted(p for p in root.rglob("*") if p.is_file() and is_mesh_file(p))
    return [(p.relative_to(base).as_posix(), p) for p in files]


def default_0ad_root() -> Path:
    from ..paths import data_dir

    return data_dir() / "0ad"
