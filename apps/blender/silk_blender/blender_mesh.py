# SPDX-License-Identifier: GPL-3.0-or-later
"""Between Blender meshes and Silk's arrays: the active object's evaluated mesh as flat
triangles (object frame), a face-less object's vertices + normals as a point cloud, and the
generated mesh (silk_mesh rows: numpy arrays or lists of tuples) back as one object per part
under an empty in the source object's frame."""

from __future__ import annotations

import array

import bpy


def mesh_arrays(obj: bpy.types.Object, depsgraph) -> tuple[list[float], list[int]]:
    """(positions, triangles) of the evaluated mesh in the object's own frame (modifiers applied)."""
    ev = obj.evaluated_get(depsgraph)
    me = ev.to_mesh()
    try:
        me.calc_loop_triangles()
        pos = array.array("f", [0.0]) * (3 * len(me.vertices))
        me.vertices.foreach_get("co", pos)
        tri = array.array("i", [0]) * (3 * len(me.loop_triangles))
        me.loop_triangles.foreach_get("vertices", tri)
        return [float(x) for x in pos], list(tri)
    finally:
        ev.to_mesh_clear()


def point_cloud_arrays(obj: bpy.types.Object, depsgraph) -> list[float]:
    """Rows x y z nx ny nz of a face-less mesh object: a 'normal' point attribute if it has one,
    else the vertex normals."""
    ev = obj.evaluated_get(depsgraph)
    me = ev.to_mesh()
    try:
        n = len(me.vertices)
        pos = array.array("f", [0.0]) * (3 * n)
        me.vertices.foreach_get("co", pos)
        nor = array.array("f", [0.0]) * (3 * n)
        attr = me.attributes.get("normal")
        if attr is not None and attr.domain == "POINT" and attr.data_type == "FLOAT_VECTOR":
            attr.data.foreach_get("vector", nor)
        else:
            me.vertices.foreach_get("normal", nor)
        rows = []
        for i in range(n):
            rows += [pos[3 * i], pos[3 * i + 1], pos[3 * i + 2], nor[3 * i], nor[3 * i + 1], nor[3 * i + 2]]
        return [float(x) for x in rows]
    finally:
        ev.to_mesh_clear()


def rows(values) -> list:
    """silk_mesh's arrays (numpy when Blender's Python has it, else lists) as plain Python lists."""
    return values.tolist() if hasattr(values, "tolist") else list(values)


def split_parts(positions, triangles, components):
    """[(vertices [(x,y,z)], faces [(a,b,c)])] per component, in component order."""
    positions, triangles = rows(positions), rows(triangles)
    by_part: dict[int, list[int]] = {}
    for f, c in enumerate(rows(components)):
        by_part.setdefault(c, []).append(f)
    parts = []
    for c in sorted(by_part):
        remap: dict[int, int] = {}
        verts, faces = [], []
        for f in by_part[c]:
            face = []
            for v in triangles[f]:
                if v not in remap:
                    remap[v] = len(verts)
                    verts.append(tuple(positions[v]))
                face.append(remap[v])
            faces.append(tuple(face))
        parts.append((verts, faces))
    return parts


def new_mesh_object(name: str, verts, faces, collection, parent=None) -> bpy.types.Object:
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    me.validate(clean_customdata=False)
    me.update()
    obj = bpy.data.objects.new(name, me)
    collection.objects.link(obj)
    if parent is not None:
        obj.parent = parent
    return obj


def set_mesh_data(obj: bpy.types.Object, positions, triangles) -> None:
    """Replaces an object's mesh data (the growing preview)."""
    me = obj.data
    me.clear_geometry()
    me.from_pydata(rows(positions), [], rows(triangles))
    me.update()


def build_result(context, source: bpy.types.Object, positions, triangles, components, stats) -> bpy.types.Object:
    """An empty in the source's frame (named after it) with one child object per generated part."""
    coll = source.users_collection[0] if source.users_collection else context.scene.collection
    empty = bpy.data.objects.new(f"Silk {source.name}", None)
    empty.empty_display_type = "PLAIN_AXES"
    coll.objects.link(empty)
    empty.matrix_world = source.matrix_world.copy()
    for i, (verts, faces) in enumerate(split_parts(positions, triangles, components)):
        new_mesh_object(f"{source.name}.silk_part_{i:03d}", verts, faces, coll, parent=empty)
    for key in ("tokens", "faces", "components", "stop_reason"):
        empty[f"silk_{key}"] = stats[key]
    return empty
