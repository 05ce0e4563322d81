# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's operators: silk.generate_mesh (modal with Esc cancel, status-bar progress and a
preview that grows per completed layer, with best of N one per candidate side by side, the best so
far named (candidate_previews.py); synchronous from scripts and in background mode, with the same
result), silk.import_tokens and silk.export_tokens."""

from __future__ import annotations

import os
import time

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from . import (
    blender_mesh,
    candidate_previews,
    enum_items,
    run_progress,
    shared_settings,
    silk_mesh,
)  # silk_mesh: bindings/python/silk_mesh, vendored unchanged

PREVIEW_NAME = "Silk preview"


def _model_dir(path: str) -> str | None:
    """None: the model bundled with the add-on (silk_mesh/model beside silk_mesh/lib); a folder (Blender's
    // relative paths resolved) or a model name (libsilk finds it in the models folder)."""
    return bpy.path.abspath(path) if path else None


def _given(value):
    """None for -1 (the properties' "libsilk's / the model's default"), else the value for libsilk to check."""
    return None if value == -1 else value


def _cancel_requested(context) -> bool:
    """The Silk tab's Cancel button (sidebar.py)."""
    s = getattr(context.window_manager, "silk_run", None)
    return bool(s and s.cancel_requested)


class SILK_OT_generate_mesh(bpy.types.Operator):
    """Generate an artist-style mesh (one object per part) from the active object's surface or points"""

    # The numeric settings' soft_min / soft_max are slider limits only (UI): the valid ranges are
    # libsilk's one table (silk_param_range); a value typed outside it reaches libsilk, whose error
    # naming the setting and its range is reported.

    bl_idname = "silk.generate_mesh"
    bl_label = "Silk: Generate Artist Mesh"
    bl_options = {"REGISTER", "UNDO"}

    seed: IntProperty(name="Seed", default=0, min=0)
    temperature: FloatProperty(
        name="Temperature",
        description="-1 = the model's default (model.json sampling, else 0.5); 0 = greedy",
        default=-1.0,
        soft_min=-1.0,
        soft_max=10.0,
    )
    top_k: IntProperty(
        name="Top-k", description="-1 = the model's default (else 50); 0 = off", default=-1, soft_min=-1, soft_max=200
    )
    max_faces: IntProperty(
        name="Max faces",
        description="At most this many faces: stop at the first layer end with this many, "
        "keep a valid subset (0 = off)",
        default=0,
        soft_min=0,
    )
    max_tokens: IntProperty(
        name="Max tokens", description="Cap on generated ids (0 = the model's limit; else >= 14)", default=0, soft_min=0
    )
    surface_tolerance: IntProperty(
        name="Surface tolerance",
        description="New vertices only within this many grid cells (of 128) of the "
        "input surface (0 = off, -1 = libsilk's measured default)",
        default=-1,
        soft_min=-1,
        soft_max=127,
    )
    face_guidance: shared_settings.face_guidance_property()
    face_tolerance: shared_settings.face_tolerance_property()
    candidates: IntProperty(
        name="Candidates",
        description="Best of N: generate N meshes one after another and "
        "keep the one closest to the input (-1 = the model's N, model.json sampling)",
        default=-1,
        soft_min=-1,
        soft_max=64,
    )
    rows: shared_settings.rows_property()
    orient: shared_settings.orient_property()
    model_dir: StringProperty(
        name="Model",
        description="A model folder, or the name of a model in the models folder "
        "(silkgen --list-models); empty: the model bundled with the add-on",
        default="",
        subtype="DIR_PATH",
    )
    repair: EnumProperty(
        name="Holes",
        items=enum_items.HOLE_POLICY,
        default="OFF",
    )
    cancel_after_steps: IntProperty(
        name="Cancel after steps",
        description="Testing: cancel after this many steps",
        default=0,
        min=0,
        options={"HIDDEN", "SKIP_SAVE"},
    )

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH"

    # -- shared by the modal and the synchronous path ------------------------------------------
    def _start(self, context):
        src = context.active_object
        dg = context.evaluated_depsgraph_get()
        # None (a property at -1): libsilk's default (sampling: the model's own values). Any other value
        # goes to libsilk as it is, which checks it by its one range table and names it in the error.
        settings = dict(
            seed=self.seed,
            temperature=_given(self.temperature),
            top_k=_given(self.top_k),
            max_faces=self.max_faces,
            max_tokens=self.max_tokens,
            holes=self.repair,
            orient=self.orient,
            candidates=_given(self.candidates),
            rows=_given(self.rows),
            surface_tolerance=_given(self.surface_tolerance),
            face_guidance=None if self.face_guidance == "MODEL" else self.face_guidance,
            face_tolerance=_given(self.face_tolerance),
        )
        job = silk_mesh.Generator(_model_dir(self.model_dir))
        cap = job.model.info()["max_seq_len"] - 1  # max_seq_len counts BOS: the ids libsilk allows after it
        self._run = run_progress.RunProgress(
            getattr(context.window_manager, "silk_run", None), min(self.max_tokens, cap) if self.max_tokens else cap
        )
        try:
            if len(src.data.polygons) > 0:
                pos, tri = blender_mesh.mesh_arrays(src, dg)
                with silk_mesh.Mesh(pos, tri) as m:
                    job.start(m, **settings)
            else:
                job.start(points=blender_mesh.point_cloud_arrays(src, dg), **settings)
            self._run.publish()
        except BaseException:
            job.close()
            raise
        return src, job

    def _finish(self, context, job, src):
        mesh, _, stats = job.finish()
        self._run.finish(job.report_json(), stats["chosen_candidate"])
        with mesh:
            pos, tri, comp = mesh.positions, mesh.triangles, mesh.parts
        empty = blender_mesh.build_result(context, src, pos, tri, comp, stats)
        best = (
            f", best of {stats['candidates']} (candidate {stats['chosen_candidate'] + 1})"
            if stats["candidates"] > 1
            else ""
        )
        self.report(
            {"INFO"},
            f"Silk: {stats['faces']} faces in {stats['components']} part(s), "
            f"{stats['tokens']} tokens ({stats['stop_reason']}){best}",
        )
        return empty

    def execute(self, context):
        """Synchronous: scripts and background mode."""
        try:
            src, job = self._start(context)
        except silk_mesh.SilkError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        try:
            steps = 0
            while not job.done:
                if (self.cancel_after_steps and steps >= self.cancel_after_steps) or _cancel_requested(context):
                    job.cancel()
                try:
                    job.advance(32, until_layer=True)
                except silk_mesh.SilkError as e:
                    if e.status == silk_mesh.SILK_ERR_CANCELLED:
                        self._run.finish("{}", -1, "cancelled")
                        self.report({"WARNING"}, "Silk: generation cancelled")
                        return {"CANCELLED"}
                    raise
                self._run.after_advance(job.stats(), 32, job.done)
                self._run.publish(job.done)
                steps += 1
            self._finish(context, job, src)
            return {"FINISHED"}
        except silk_mesh.SilkError as e:
            self._run.finish("{}", -1, "failed")
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        finally:
            job.close()

    # -- interactive: modal, Esc cancels, the preview grows per completed layer --------------------
    def invoke(self, context, event):
        if bpy.app.background:
            return self.execute(context)
        try:
            self._src, self._job = self._start(context)
        except silk_mesh.SilkError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        coll = self._src.users_collection[0] if self._src.users_collection else context.scene.collection
        self._preview, self._candidates = None, None
        try:
            n = len(self._job.candidates())
        except silk_mesh.SilkError as e:
            self._job.close()
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        if n > 1:  # best of N: every candidate side by side, the best so far named
            self._candidates = candidate_previews.CandidatePreviews(self._src, coll)
            self._run.after_candidates(self._candidates.update(self._job))  # the first shows at once
        else:  # one candidate: its preview over the source
            self._preview = blender_mesh.new_mesh_object(PREVIEW_NAME, [], [], coll)
            self._preview.matrix_world = self._src.matrix_world.copy()
            self._preview.display_type = "WIRE"
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.05, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _cleanup(self, context):
        context.window_manager.event_timer_remove(self._timer)
        context.workspace.status_text_set(None)
        if self._preview is not None:
            mesh = self._preview.data
            bpy.data.objects.remove(self._preview, do_unlink=True)
            bpy.data.meshes.remove(mesh)
            self._preview = None
        if self._candidates is not None:
            self._candidates.remove()
            self._candidates = None
        self._job.close()

    def modal(self, context, event):
        if event.type == "ESC" or _cancel_requested(context):
            self._job.cancel()
            self._run.finish("{}", -1, "cancelled")
            self._cleanup(context)
            self.report({"WARNING"}, "Silk: generation cancelled")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        try:
            t_end = time.monotonic() + 0.1  # keep the UI responsive
            while not self._job.done and time.monotonic() < t_end:
                self._job.advance(64, until_layer=True)
                self._run.after_advance(self._job.stats(), 64, self._job.done)
            st = self._job.stats()
            if self._candidates is not None:
                self._run.after_candidates(self._candidates.update(self._job))
            else:
                with self._job.preview() as m:
                    pos, tri = m.positions, m.triangles
                if len(tri) != len(self._preview.data.polygons):
                    blender_mesh.set_mesh_data(self._preview, pos, tri)
            self._run.publish(self._job.done)
            context.workspace.status_text_set(
                f"Silk: {self._run.text()}, {st['faces']} faces in {st['components']} part(s) - Esc to cancel"
            )
            for area in context.screen.areas if context.screen else ():
                if area.type == "VIEW_3D":  # the sidebar's progress bar: its region, when it is open
                    for region in area.regions:
                        if region.type == "UI" and region.width > 1 and area.spaces.active.show_region_ui:
                            region.tag_redraw()
            if self._job.done:
                self._finish(context, self._job, self._src)
                self._cleanup(context)
                return {"FINISHED"}
        except silk_mesh.SilkError as e:
            self._run.finish("{}", -1, "failed")
            self._cleanup(context)
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"RUNNING_MODAL"}


class SILK_OT_import_tokens(bpy.types.Operator, ImportHelper):
    """Decode a Mesh Silksong token file (one id per line) into a mesh object"""

    bl_idname = "silk.import_tokens"
    bl_label = "Silk: Import Tokens"
    filename_ext = ".txt"
    filter_glob: StringProperty(default="*.txt", options={"HIDDEN"})

    def execute(self, context):
        try:
            with silk_mesh.decode(self.filepath) as m:
                verts, faces = blender_mesh.rows(m.positions), blender_mesh.rows(m.triangles)
        except silk_mesh.SilkError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        name = os.path.splitext(os.path.basename(self.filepath))[0]
        obj = blender_mesh.new_mesh_object(name, verts, faces, context.collection)
        context.view_layer.objects.active = obj
        self.report({"INFO"}, f"Silk: {len(faces)} faces from {len(verts)} vertices")
        return {"FINISHED"}


class SILK_OT_export_tokens(bpy.types.Operator, ExportHelper):
    """Tokenize the active mesh (evaluated, object frame) into a token file"""

    bl_idname = "silk.export_tokens"
    bl_label = "Silk: Export Tokens"
    filename_ext = ".txt"
    filter_glob: StringProperty(default="*.txt", options={"HIDDEN"})

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH"

    def execute(self, context):
        try:
            pos, tri = blender_mesh.mesh_arrays(context.active_object, context.evaluated_depsgraph_get())
            silk_mesh.write_ids(self.filepath, silk_mesh.encode((pos, tri)))
        except silk_mesh.SilkError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Silk: tokens written to {self.filepath}")
        return {"FINISHED"}


CLASSES = (SILK_OT_generate_mesh, SILK_OT_import_tokens, SILK_OT_export_tokens)
