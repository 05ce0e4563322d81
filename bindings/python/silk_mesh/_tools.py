"""The pip wheel's console scripts `silkgen` and `silktok` (pyproject.toml [project.scripts]): each runs
the binary the wheel carries in silk_mesh/bin/ with the same arguments (exec, so exit status, stdin
and signals are the binary's own). Python entry points rather than binaries in the scripts folder:
the binaries find libsilk (RPATH $ORIGIN/../lib), the bundled model (../model) and onnxruntime
(site-packages/onnxruntime/capi) relative to their own file, and a scripts folder (venv/bin,
~/.local/bin) has no fixed relation to site-packages (it depends on the Python version and scheme)."""
from __future__ import annotations

import os
import sys

from ._library import PACKAGE_DIR


def tool_path(name: str) -> str:
    """The bundled binary `name` (silk_mesh/bin/<name>); present in the pip wheel only."""
    return os.path.join(PACKAGE_DIR, "bin", name)


def _run(name: str) -> int:
    exe = tool_path(name)
    if not os.access(exe, os.X_OK):
        sys.stderr.write(f"{name}: '{exe}' is missing or not executable: only the pip wheel carries a bundled "
                         f"{name} (in a checkout, run build/apps/{name})\n")
        return 127
    os.execv(exe, [name, *sys.argv[1:]])
    return 127  # not reached: execv replaces this process or raises


def silkgen() -> int:
    return _run("silkgen")


def silktok() -> int:
    return _run("silktok")
