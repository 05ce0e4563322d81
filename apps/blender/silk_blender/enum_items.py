# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's choice lists of libsilk's enums (hole policy, orientation, face guidance) for the
operator and the sidebar alike: each identifier is libsilk's name of the value (silk_mesh.enum_names,
C API 1.4), upper-cased as Blender spells identifiers (silk_mesh takes either case); the label and
tooltip are the add-on's words for it."""

from . import silk_mesh


def enum_items(enum: str, ui: dict) -> list[tuple[str, str, str]]:
    """EnumProperty items of silk_<enum>, in libsilk's order; a name the add-on has no words for is
    shown as it is."""
    return [(name.upper(), *ui.get(name, (name.title(), ""))) for name in silk_mesh.enum_names(enum)]


HOLE_POLICY = enum_items(
    "hole_policy",
    {"off": ("Off", "Keep holes"), "report": ("Report", "Count holes"), "repair": ("Repair", "Close small holes")},
)
ORIENTATION = enum_items(
    "orientation",
    {
        "input": ("Face the input", "Reverse every part whose winding disagrees with the source's normals"),
        "tokens": ("As generated", "The winding the generated ids carry"),
    },
)
# "MODEL" (the add-on's own choice) leaves the field unset: the model's value.
FACE_GUIDANCE = [
    ("MODEL", "Model default", "The model's (model.json sampling), else libsilk's measured default")
] + enum_items(
    "face_guidance",
    {
        "hard": (
            "Hard",
            "Connections whose faces stray from the source's surface are never made (the closest ones when none fits)",
        ),
        "soft": ("Soft", "Such connections are made less likely"),
        "off": ("Off", "Connections as the model draws them"),
    },
)
