# SPDX-License-Identifier: GPL-3.0-or-later
"""Silk for Blender: generate artist-style meshes (Mesh Silksong, grammar-constrained, CPU) from
the active object, step by step inside Blender, through libsilk's C API (ctypes)."""

bl_info = {
    "name": "Silk: Artist Mesh Generation",
    "author": "Silk contributors",
    "version": (0, 0, 0),  # stamped with Silk's version (silk.h) by scripts/make_blender_addon.sh
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Silk; View3D > Object > Silk: Generate Artist Mesh; File > Import/Export > Silk tokens",
    "description": "Point-cloud-conditioned mesh generation (Mesh Silksong) on the CPU through libsilk",
    "category": "Mesh",
}

import bpy  # noqa: E402

from . import operators, sidebar  # noqa: E402


def _menu_generate(self, context):
    self.layout.operator(operators.SILK_OT_generate_mesh.bl_idname)


def _menu_import(self, context):
    self.layout.operator(operators.SILK_OT_import_tokens.bl_idname, text="Silk tokens (.txt)")


def _menu_export(self, context):
    self.layout.operator(operators.SILK_OT_export_tokens.bl_idname, text="Silk tokens (.txt)")


def register():
    for cls in operators.CLASSES:
        bpy.utils.register_class(cls)
    sidebar.register()
    bpy.types.VIEW3D_MT_object.append(_menu_generate)
    bpy.types.TOPBAR_MT_file_import.append(_menu_import)
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    bpy.types.TOPBAR_MT_file_import.remove(_menu_import)
    bpy.types.VIEW3D_MT_object.remove(_menu_generate)
    sidebar.unregister()
    for cls in reversed(operators.CLASSES):
        bpy.utils.unregister_class(cls)
