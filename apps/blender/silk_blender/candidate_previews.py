# SPDX-License-Identifier: GPL-3.0-or-later
"""Best of N's candidates shown while they run (issue 34): one wire object per started candidate,
"Silk candidate 3/8", side by side along X to the right of the source (one source width and a gap
apart, in the source's frame), the best so far named "(best)" and drawn in the accent colour; the
modal run removes them all at its end, leaving only the result (as the single preview is removed).
Fed by silk_mesh's Generator.candidates() / candidate_preview(i) after each advance."""

from __future__ import annotations

import bpy
from mathutils import Matrix, Vector

from . import blender_mesh

PREFIX = "Silk candidate"
BEST_COLOR = (1.0, 0.55, 0.1, 1.0)  # the best so far (object colour: Solid shading, Color: Object)
PLAIN_COLOR = (0.8, 0.8, 0.8, 1.0)


def candidate_name(index: int, n: int, best: bool) -> str:
    return f"{PREFIX} {index + 1}/{n}" + (" (best)" if best else "")


class CandidatePreviews:
    """The wire objects of one run's candidates, made as each candidate starts."""

    def __init__(self, source: bpy.types.Object, collection):
        self.source, self.collection = source, collection
        self.objects = {}  # candidate index -> its object
        self._shown = {}  # candidate index -> (state, tokens) its object shows
        corners = [source.matrix_world @ Vector(c) for c in source.bound_box]
        width = max(c.x for c in corners) - min(c.x for c in corners)
        self.step = (width if width > 0 else 1.0) * 1.15  # one source width and a gap

    def update(self, job) -> list[dict]:
        """Makes or refreshes the object of every started candidate from job (a silk_mesh Generator
        between start and finish); returns the candidates' views."""
        views = job.candidates()
        for c in views:
            i = c["index"]
            if c["state"] == "waiting":
                continue
            obj = self.objects.get(i)
            if obj is None:
                obj = blender_mesh.new_mesh_object(candidate_name(i, len(views), False), [], [], self.collection)
                obj.display_type = "WIRE"
                obj.matrix_world = Matrix.Translation((self.step * (i + 1), 0.0, 0.0)) @ self.source.matrix_world
                self.objects[i] = obj
            if self._shown.get(i) != (c["state"], c["tokens"]):
                with job.candidate_preview(i) as m:
                    pos, tri = m.positions, m.triangles
                if len(tri) != len(obj.data.polygons):
                    blender_mesh.set_mesh_data(obj, pos, tri)
                self._shown[i] = (c["state"], c["tokens"])
            name = candidate_name(i, len(views), c["best"])
            if obj.name != name:
                obj.name = name
            obj.color = BEST_COLOR if c["best"] else PLAIN_COLOR
        return views

    def remove(self) -> None:
        """Deletes every candidate object and its mesh."""
        for obj in self.objects.values():
            mesh = obj.data
            bpy.data.objects.remove(obj, do_unlink=True)
            bpy.data.meshes.remove(mesh)
        self.objects, self._shown = {}, {}
