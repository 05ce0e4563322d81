# SPDX-License-Identifier: MIT
"""silk_mesh: Python binding of libsilk (Mesh Silksong mesh tokenization and generation) over its
C API, engine/include/silk/silk.h, with ctypes only (no compiled extension; numpy optional).

    import silk_mesh
    ids = silk_mesh.encode("bunny.obj")                 # list[int]
    mesh = silk_mesh.decode(ids)                        # silk_mesh.Mesh
    mesh.positions, mesh.triangles, mesh.parts          # numpy arrays when numpy is importable
    result = silk_mesh.generate("bunny.obj", model="models/default", seed=1)
    result.mesh.save("out.glb"); result.ids; result.stats

Arrays: inputs are numpy arrays or Python sequences; geometry results are numpy arrays when numpy
is importable, else lists of tuples; token ids are always list[int] (_arrays.py states the rule).
Errors: SilkError(status, message) with libsilk's message. The library: load_library(path), else
$SILK_LIBRARY, else silk_mesh/lib/, else a build tree of the checkout (_library.py)."""

from ._capi import (
    SILK_ERR_BUFFER_TOO_SMALL,
    SILK_ERR_BUSY,
    SILK_ERR_CANCELLED,  # noqa: F401
    SILK_ERR_INVALID_ARGUMENT,
    SILK_ERR_IO,
    SILK_ERR_REFUSED,
    SILK_OK,
)
from ._library import SilkError, library_path, load_library
from . import _capi, _native
from .codec import decode, encode, read_ids, write_ids
from .batch import Batch, BatchItem
from .generation import Generator, Model, Result, generate
from .models import bundled_model_dir, find_model, list_models, models_dir
from .mesh import Mesh, load_arrays
from .points import prepare_points

__all__ = [
    "Mesh",
    "Model",
    "Generator",
    "Result",
    "Batch",
    "BatchItem",
    "SilkError",
    "encode",
    "decode",
    "generate",
    "read_ids",
    "write_ids",
    "load_arrays",
    "prepare_points",
    "load_library",
    "library_path",
    "bundled_model_dir",
    "models_dir",
    "find_model",
    "list_models",
    "version",
    "vocab",
    "generation_available",
    "enum_names",
]


def version() -> str:
    """libsilk's version string."""
    return _native.version()


def vocab() -> dict:
    """The token vocabulary's layout (silk_vocab_info by field name)."""
    from ._params import as_dict

    return as_dict(_native.vocab())


def enum_names(enum: str) -> dict:
    """{name: value} of a silk.h enum as libsilk names it (C API 1.4): enum is the part of its
    silk_<enum>_name function, e.g. "hole_policy", "decoder_precision", "stop_reason"."""
    if enum not in _capi.ENUM_FIRST:
        raise ValueError(f"enum_names: unknown enum {enum!r} (one of: {', '.join(_capi.ENUM_FIRST)})")
    return dict(_native.enum_names(enum))


def generation_available() -> bool:
    """True when libsilk was built with onnxruntime (generation); else Model() raises SilkError."""
    return _native.generation_available()
