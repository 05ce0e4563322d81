# SPDX-License-Identifier: MIT
"""The pip wheel's `silk-export` console script: the training side ships inside the silk-mesh wheel,
its dependencies in the extra silk-mesh[train]; without them this says which are missing and the pip
command, instead of a traceback from deep inside a sub-command."""

from __future__ import annotations

import importlib.util
import sys

# What `pip install 'silk-mesh[train]'` adds (pyproject.toml [project.optional-dependencies] train).
TRAIN_MODULES = ("torch", "onnx", "onnxscript", "tqdm", "matplotlib", "huggingface_hub")


def missing_modules() -> list[str]:
    return [m for m in TRAIN_MODULES if importlib.util.find_spec(m) is None]


def main(argv=None) -> int:
    missing = missing_modules()
    if missing:
        sys.stderr.write(
            f"silk-export: the training dependencies are not installed ({', '.join(missing)} missing): "
            "pip install 'silk-mesh[train]'\n"
        )
        return 2
    from .cli import main as cli_main

    return cli_main(argv)
