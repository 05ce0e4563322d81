# SPDX-License-Identifier: MIT
"""Models by name: the user's models folder and the bundled model, as libsilk finds them (silk.h
"models by name": silk_models_dir, silk_model_default_dir, silk_model_find, silk_models_list), so
Python, silkgen and the Blender add-on agree on every path."""

from __future__ import annotations

import json
import os

from . import _native


def models_dir(name: str | None = None) -> str:
    """The user's models folder ($SILK_MODELS, else the platform's user data folder + silk/models);
    with a name, that model's folder in it (SilkError when name is not a model name)."""
    return _native.models_dir(None if name is None else os.fsencode(name))


def bundled_model_dir() -> str:
    """The model shipped beside libsilk (silk_mesh/model in the wheel and the Blender add-on);
    SilkError listing where libsilk looked when there is none."""
    return _native.model_default_dir()


def find_model(name_or_dir: str | os.PathLike | None = None) -> str:
    """The folder a model argument means: None or "" = the bundled model, an existing folder as
    given (a path always wins), a model name = its folder in models_dir()."""
    return _native.model_find(os.fsencode(name_or_dir or ""))


def list_models() -> dict:
    """silk_models_list as a dict: models_dir and models (name, dir, bundled, arch, config,
    parameters, bytes, decoders, default_decoder, kv_precisions, default_kv_precision; or error)."""
    return json.loads(_native.models_list_json())
