# SPDX-License-Identifier: GPL-3.0-or-later
"""View3D > Sidebar > Silk, the convention of generation add-ons: a model drop-down (the bundled model
and every model in the user's models folder, with architecture and size, as libsilk lists them), the
main settings before the run, Generate and Cancel, a progress bar with the candidate and layer in
progress, and the candidates' scores after the run. Generate runs silk.generate_mesh with these
settings, so the menu entry and the tab are one generation path."""

from __future__ import annotations

import bpy
from bpy.props import (
    BoolProperty,
    CollectionProperty,
    EnumProperty,
    FloatProperty,
    IntProperty,
    PointerProperty,
    StringProperty,
)

from . import shared_settings, silk_mesh

# Blender keeps no reference to a dynamic enum's strings: they must live here (refreshed on demand,
# not on every redraw, since listing reads every model.json).
_model_items: list[tuple[str, str, str, int]] = []


def _size(n: int) -> str:
    return f"{n / 1e9:.2f} GB" if n >= 1e9 else f"{n / 1e6:.1f} MB"


def refresh_models() -> list[dict]:
    """Re-reads the model list (silk_models_list); returns the usable models."""
    try:
        catalog = silk_mesh.list_models()
    except silk_mesh.SilkError as e:
        catalog = {"models": [], "models_dir_error": str(e)}
    models = [m for m in catalog.get("models", []) if "error" not in m]
    _model_items.clear()
    for i, m in enumerate(models):
        name = m["arch"] if m["config"] == m["arch"] else f"{m['arch']} {m['config']}"
        arch = f"{name}, {m['parameters']['n_layers']} layers x {m['parameters']['d_model']}"
        label = f"{m['name']}{' (bundled)' if m['bundled'] else ''}: {m['arch']}, {_size(m['bytes'])}"
        _model_items.append(
            (m["dir"], label, f"{arch}; {_size(m['bytes'])}; decoders {', '.join(m['decoders'])}; {m['dir']}", i)
        )
    if not _model_items:
        _model_items.append(("", "No model found", catalog.get("models_dir_error", "no usable model"), 0))
    return models


def _model_enum(self, context):
    if not _model_items:
        refresh_models()
    return _model_items


class SilkCandidateScore(bpy.types.PropertyGroup):
    index: IntProperty()
    seed: StringProperty()
    score: FloatProperty(description="Chamfer distance to the input's points (lower is closer)")
    faces: IntProperty()
    chosen: BoolProperty()


class SilkSettings(bpy.types.PropertyGroup):
    # soft_min / soft_max: slider limits only (UI); libsilk checks every value by its one range table
    # (silk_param_range) and its error is reported.
    model: EnumProperty(
        name="Model",
        items=_model_enum,
        description="The bundled model or one in the models folder (silk-export import-official --name)",
    )
    candidates: IntProperty(
        name="Candidates",
        default=0,
        soft_min=0,
        soft_max=64,
        description="Best of N: keep the one closest to the input (0 = the model's N)",
    )
    rows: shared_settings.rows_property()
    seed: IntProperty(name="Seed", default=0, min=0)
    temperature: FloatProperty(
        name="Temperature",
        default=-1.0,
        soft_min=-1.0,
        soft_max=10.0,
        description="-1 = the model's default; 0 = greedy",
    )
    max_faces: IntProperty(name="Face limit", default=0, soft_min=0, description="At most this many faces (0 = off)")
    orient: shared_settings.orient_property()
    face_guidance: shared_settings.face_guidance_property()
    face_tolerance: shared_settings.face_tolerance_property()


class SilkRunState(bpy.types.PropertyGroup):
    """The run in progress and its outcome: on the window manager, not the scene, so updating the progress
    bar never tags the scene for a depsgraph update (and nothing transient is saved in the .blend)."""

    running: BoolProperty(default=False)
    cancel_requested: BoolProperty(default=False)
    progress: FloatProperty(name="Progress", subtype="FACTOR", min=0.0, max=1.0)
    status: StringProperty()
    scores: CollectionProperty(type=SilkCandidateScore)


class SILK_OT_refresh_models(bpy.types.Operator):
    """Read the models folder again (after importing a model)"""

    bl_idname = "silk.refresh_models"
    bl_label = "Refresh Models"

    def execute(self, context):
        n = len(refresh_models())
        self.report({"INFO"}, f"Silk: {n} model(s)")
        return {"FINISHED"}


class SILK_OT_sidebar_generate(bpy.types.Operator):
    """Generate from the active object with the Silk tab's settings"""

    bl_idname = "silk.sidebar_generate"
    bl_label = "Generate"

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH" and not context.window_manager.silk_run.running

    def execute(self, context):
        s = context.scene.silk
        context.window_manager.silk_run.cancel_requested = False
        return bpy.ops.silk.generate_mesh(
            "INVOKE_DEFAULT",
            model_dir=s.model,
            seed=s.seed,
            temperature=s.temperature,
            candidates=s.candidates or -1,
            rows=s.rows,
            max_faces=s.max_faces,
            orient=s.orient,
            face_guidance=s.face_guidance,
            face_tolerance=s.face_tolerance,
        )


class SILK_OT_sidebar_cancel(bpy.types.Operator):
    """Stop the generation in progress (as Esc does: nothing is added)"""

    bl_idname = "silk.sidebar_cancel"
    bl_label = "Cancel"

    @classmethod
    def poll(cls, context):
        return context.window_manager.silk_run.running

    def execute(self, context):
        context.window_manager.silk_run.cancel_requested = True
        return {"FINISHED"}


class SILK_PT_sidebar(bpy.types.Panel):
    bl_label = "Silk"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Silk"

    def draw(self, context):
        s, run, layout = context.scene.silk, context.window_manager.silk_run, self.layout
        row = layout.row(align=True)
        row.prop(s, "model", text="")
        row.operator(SILK_OT_refresh_models.bl_idname, text="", icon="FILE_REFRESH")
        col = layout.column(align=True)
        for name in (
            "candidates",
            "rows",
            "seed",
            "temperature",
            "max_faces",
            "orient",
            "face_guidance",
            "face_tolerance",
        ):
            col.prop(s, name)
        row = layout.row(align=True)
        row.operator(SILK_OT_sidebar_generate.bl_idname, icon="PLAY")
        row.operator(SILK_OT_sidebar_cancel.bl_idname, icon="CANCEL")
        if run.running or run.status:
            col = layout.column(align=True)
            rows, _, rest = run.status.rpartition("; ")  # "candidates running 2, done 3 of 8" (best of N, modal)
            lines = ([rows] if rows else []) + rest.split(", ", 1)  # "done: candidate 2 of 2", "layer 5, ..."
            for line in lines:
                col.label(text=line)
            if hasattr(layout, "progress"):  # Blender 4.0+: a real progress bar
                col.progress(factor=run.progress, text=f"{round(100 * run.progress)} %")
            else:
                col.prop(run, "progress", text="Progress", slider=True)
        if run.scores:
            box = layout.box()
            box.label(text="Scores (lower = closer)")
            for c in run.scores:
                row = box.row()
                row.label(
                    text=f"{c.index + 1}: {c.score:.4f}, {c.faces} faces", icon="CHECKMARK" if c.chosen else "BLANK1"
                )


CLASSES = (
    SilkCandidateScore,
    SilkSettings,
    SilkRunState,
    SILK_OT_refresh_models,
    SILK_OT_sidebar_generate,
    SILK_OT_sidebar_cancel,
    SILK_PT_sidebar,
)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.silk = PointerProperty(type=SilkSettings)
    bpy.types.WindowManager.silk_run = PointerProperty(type=SilkRunState)


def unregister():
    del bpy.types.WindowManager.silk_run
    del bpy.types.Scene.silk
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
