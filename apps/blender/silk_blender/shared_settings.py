# SPDX-License-Identifier: GPL-3.0-or-later
"""The generation settings the operator and the sidebar both show, declared once: the same name,
choices, default and tooltip in either place."""

from bpy.props import EnumProperty, FloatProperty

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
