# SPDX-License-Identifier: MIT
"""The pip wheel's console scripts `silkgen` and `silktok` (pyproject.toml [project.scripts]): each runs
the binary the wheel carries in silk_mesh/bin/ with the same arguments (exec, so exit status, stdin
and signals are the binary's own). Python entry points rather than binaries in the scripts folder:
the binaries find libsilk (RPATH $ORIGIN/../lib), the bundled model (../model) and onnxruntime
(site-packages/onnxruntime/capi) relative to their own file, and a scripts folder (venv/bin,
~/.local/bin) has no fixed relation to site-packages (it depends on the Python version and scheme).
A package of its own, beside silk_mesh rather than in it: importing silk_mesh imports numpy (0.4 s
measured), which a launcher has no use for; importlib finds silk_mesh's folder without importing it."""

from __future__ import annotations

import os
import sys

import importlib.util


def tool_path(name: str) -> str:
    """The bundled binary `name` (silk_mesh/bin/<name>); present in the pip wheel only."""
    spec = importlib.util.find_spec("silk_mesh")
    folders = list(spec.submodule_search_locations or []) if spec else []
    return os.path.join(folders[0] if folders else "silk_mesh", "bin", name)


def _run(name: str) -> int:
    exe = tool_path(name)
    if not os.access(exe, os.X_OK):
        sys.stderr.write(
            f"{name}: '{exe}' is missing or not executable: only the pip wheel carries a bundled "
            f"{name} (in a checkout, run build/apps/{name})\n"
        )
        return 127
    os.execv(exe, [name, *sys.argv[1:]])
    return 127  # not reached: execv replaces this process or raises


def silkgen() -> int:
    return _run("silkgen")


def silktok() -> int:
    return _run("silktok")
