"""silk_export: the Python side of Silk — data through libsilk, training, ONNX export, evaluation.

Everything that touches tokens goes through libsilk, by its Python binding silk_mesh
(bindings/python/silk_mesh, ctypes); this package never re-implements the tokenizer."""

__version__ = "0.1.0"
