# SPDX-License-Identifier: GPL-3.0-or-later
"""The generation settings the operator and the sidebar both show, declared once: the same name,
choices, default and tooltip in either place."""

from bpy.props import EnumProperty, FloatProperty, IntProperty

from . import enum_items


def orient_property():
    return EnumProperty(name="Orientation", items=enum_items.ORIENTATION, default="INPUT")


def face_guidance_property():
    return EnumProperty(name="Face guidance", items=enum_items.FACE_GUIDANCE, default="MODEL")


def face_tolerance_property():
    return FloatProperty(
        name="Face tolerance",
        description="How far (grid cells of 128) a face may stray from the source's surface (-1 = the model's default)",
        default=-1.0,
        soft_min=-1.0,
        soft_max=64.0,
    )


def rows_property():
    return IntProperty(
        name="Rows",
        description="Best of N: how many candidates are decoded together, at most (1 = one after another); "
        "the meshes do not depend on it, only the time does (-1 = the model's, else 8)",
        default=-1,
        soft_min=-1,
        soft_max=64,
    )
