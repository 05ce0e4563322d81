"""What both Blender add-on tests do first (imported by them inside Blender): install the zip
into the scratch user folder the runner set up, enable the add-on, and import a dev-corpus mesh
as the active object at the origin."""
import addon_utils
import bpy


def install_and_enable(zip_path, failures):
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    addon_utils.enable("silk_blender", default_set=True, handle_error=lambda e: failures.append(f"enable: {e}"))
    return hasattr(bpy.ops.silk, "generate_mesh")


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
