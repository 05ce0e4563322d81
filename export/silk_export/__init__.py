# SPDX-License-Identifier: MIT
"""silk_export: the Python side of Silk — data through libsilk, training, ONNX export, evaluation.

Everything that touches tokens goes through libsilk, by its Python binding silk_mesh
(bindings/python/silk_mesh, ctypes); this package never re-implements the tokenizer. silk_mesh is
installed with this package (the silk-mesh wheel, or `pip install -e export`); a checkout run with
PYTHONPATH=export finds it through export/silk_mesh, a symbolic link to the binding."""

__version__ = "0.1.0"
