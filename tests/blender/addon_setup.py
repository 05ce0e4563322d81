# SPDX-License-Identifier: MIT
"""What both Blender add-on tests do first (imported by them inside Blender, or in PyPI's bpy module):
install the zip into the scratch user folders the runner set up and enable it, either as a legacy
add-on (the add-on zip; Blender 3.x and later) or as an extension (Blender 4.2+'s extensions API,
SILK_ADDON_KIND=extension), and import a dev-corpus mesh as the active object at the origin."""

import importlib

import addon_utils
import bpy

EXTENSION_REPO = "user_default"  # Blender 4.2+'s local repository for extensions installed from files


def install_and_enable(zip_path, failures, kind="addon"):
    """Installs and enables the add-on; returns its installed package (module), None on failure."""
    if kind == "extension":
        res = bpy.ops.extensions.package_install_files(filepath=zip_path, repo=EXTENSION_REPO, enable_on_install=True)
        if res != {"FINISHED"}:
            failures.append(f"extensions.package_install_files: {res}")
            return None
        name = f"bl_ext.{EXTENSION_REPO}.silk_blender"
    else:
        bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
        name = "silk_blender"
        addon_utils.enable(name, default_set=True, handle_error=lambda e: failures.append(f"enable: {e}"))
    if name not in bpy.context.preferences.addons or not hasattr(bpy.ops.silk, "generate_mesh"):
        failures.append(f"{name} is not enabled")
        return None
    return importlib.import_module(name)


def submodule(package, name):
    """The installed add-on's own module (silk_blender.<name>, whatever package it was installed as)."""
    return importlib.import_module(f"{package.__name__}.{name}")


def import_active_mesh(path):
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    bpy.ops.wm.obj_import(filepath=path)
    src = [o for o in bpy.context.scene.objects if o.type == "MESH"][0]
    src.location = (0.0, 0.0, 0.0)
    bpy.context.view_layer.objects.active = src
    src.select_set(True)
    bpy.context.view_layer.update()
    return src
