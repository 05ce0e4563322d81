# SPDX-License-Identifier: MIT
"""Where a command's model folder goes: -o/--out FOLDER, or --name NAME in the user's models folder
(libsilk's rule, asked through silk_mesh.models_dir, so silkgen --model NAME finds what was written)."""

from __future__ import annotations

from pathlib import Path


def add_output_arguments(parser, what: str) -> None:
    """-o/--out and --name, exactly one of them."""
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("-o", "--out", help=f"{what} folder to create")
    where.add_argument(
        "--name",
        help="a model name (A-Z a-z 0-9 . _ -): writes the user's models folder's NAME "
        "($SILK_MODELS, else ~/.local/share/silk/models; %%LOCALAPPDATA%%\\silk\\models on Windows), "
        "which silkgen --model NAME, silk_mesh.Model(NAME) and the Blender add-on find",
    )


def output_folder(out: str | None, name: str | None) -> Path:
    """The folder to write; ValueError (naming the rule) for a name that is not a model name."""
    if out:
        return Path(out)
    import silk_mesh

    try:
        return Path(silk_mesh.models_dir(name))
    except silk_mesh.SilkError as e:
        raise ValueError(e.message) from e
