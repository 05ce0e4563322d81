# SPDX-License-Identifier: MIT
"""silk_export: the Python side of Silk — data through libsilk, training, ONNX export, evaluation.

Everything that touches tokens goes through libsilk, by its Python binding silk_mesh
(bindings/python/silk_mesh, ctypes); this package never re-implements the tokenizer."""

import importlib.util
import sys
from pathlib import Path

__version__ = "0.1.0"

# silk_mesh is installed with this package (pyproject.toml); a checkout run with PYTHONPATH=export
# (ctest, scripts/*.sh, `python -m silk_export`) finds it beside export/ instead.
if importlib.util.find_spec("silk_mesh") is None:
    sys.path.append(str(Path(__file__).resolve().parents[2] / "bindings" / "python"))
