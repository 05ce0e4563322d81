# SPDX-License-Identifier: MIT
"""Renders input meshes beside what Silk generated from them, headless in Blender (Workbench), so
the README and docs can show real outputs and anyone can re-render them after a model change.

Run inside Blender (scripts/render_pictures.sh does this):
    blender -b --factory-startup --python-exit-code 1 --python scripts/render_pairs.py -- \
        --out docs/images/x.png [--cols 2] [--size 960x480] [--label] \
        --pair INPUT.obj OUTPUT.glb [--pair ...]
INPUT is an OBJ/PLY/STL/GLB/glTF the importers read (the shell script converts other formats
through libsilk first); OUTPUT is silkgen's GLB (one object per generated part) or OBJ/PLY.
Each pair gets a cell of the grid: the input (grey) on the left, the generated parts (one colour
per part) on the right, both at the input's scale.
"""

from __future__ import annotations

import argparse
import math
import os
import sys

import bpy  # noqa: E402  (Blender's own module)
from mathutils import Vector  # noqa: E402


def parse_args() -> argparse.Namespace:
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_pairs.py")
    p.add_argument("--out", required=True)
    p.add_argument("--pair", nargs=2, action="append", required=True, metavar=("INPUT", "OUTPUT"))
    p.add_argument("--cols", type=int, default=0, help="pairs per row; 0 = all in one row")
    p.add_argument("--size", default="", help="WIDTHxHEIGHT in pixels; default 480 px per mesh")
    p.add_argument(
        "--fit-each",
        action="store_true",
        help="scale the output by its own size, not the input's (for inputs that were normalised "
        "apart from the output, as `silk-export generate` writes its references)",
    )
    return p.parse_args(argv)


def import_file(path: str) -> list:
    """Imports one file and returns its new mesh objects (Blender converts Y-up files to Z-up)."""
    if not os.path.exists(path):
        raise SystemExit(f"render_pairs: {path}: no such file")
    before = set(bpy.data.objects)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".obj":
        bpy.ops.wm.obj_import(filepath=path)
    elif ext == ".ply":
        bpy.ops.import_mesh.ply(filepath=path)
    elif ext == ".stl":
        bpy.ops.import_mesh.stl(filepath=path)
    elif ext in (".glb", ".gltf"):
        import numpy  # Blender 3.4's glTF importer uses np.bool, gone since numpy 1.24

        if not hasattr(numpy, "bool"):
            numpy.bool = bool
        bpy.ops.import_scene.gltf(filepath=path)
    else:
        raise SystemExit(f"render_pairs: {path}: unsupported extension '{ext}' (obj, ply, stl, glb, gltf)")
    objs = [o for o in set(bpy.data.objects) - before if o.type == "MESH"]
    for o in set(bpy.data.objects) - before:  # importers may add empties; keep the meshes only
        if o.type != "MESH":
            o.select_set(False)
    return objs


def bounds(objs: list) -> tuple[Vector, Vector]:
    bpy.context.view_layer.update()
    pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
    if not pts:
        return Vector((0, 0, 0)), Vector((0, 0, 0))
    lo = Vector((min(p.x for p in pts), min(p.y for p in pts), min(p.z for p in pts)))
    hi = Vector((max(p.x for p in pts), max(p.y for p in pts), max(p.z for p in pts)))
    return lo, hi


def move(objs: list, offset: Vector, scale: float) -> None:
    """Scales about the origin then translates (parents first: children follow)."""
    for o in objs:
        if o.parent is None or o.parent not in objs:
            top = o
            while top.parent is not None:
                top = top.parent
            top.scale = top.scale * scale
            top.location = top.location * scale + offset


def place_pair(inp: str, out: str, cell: Vector, fit_each: bool) -> list:
    """The input at the cell's left, the output at its right, both scaled by the input's size
    (or each by its own with fit_each)."""
    src = import_file(inp)
    gen = import_file(out)
    lo, hi = bounds(src)
    scale = 2.0 / max((hi - lo).length, 1e-9)
    centre = (lo + hi) / 2
    move(src, cell + Vector((-1.15, 0, 0)) - centre * scale, scale)
    if fit_each:
        lo, hi = bounds(gen)
        scale = 2.0 / max((hi - lo).length, 1e-9)
        centre = (lo + hi) / 2
    move(gen, cell + Vector((1.15, 0, 0)) - centre * scale, scale)
    for o in src:
        o.color = (0.78, 0.78, 0.78, 1.0)
    for i, o in enumerate(sorted(gen, key=lambda o: o.name)):
        o.color = (0.35 + 0.6 * ((i * 0.618) % 1.0), 0.55, 0.9 - 0.5 * ((i * 0.37) % 1.0), 1.0)
    return src + gen


def setup_render(objs: list, out: str, width: int, height: int) -> None:
    sc = bpy.context.scene
    sc.render.engine = "BLENDER_WORKBENCH"
    sc.display.shading.color_type = "OBJECT"
    sc.display.shading.light = "STUDIO"
    sc.display.shading.show_cavity = True
    sc.render.resolution_x, sc.render.resolution_y = width, height
    sc.render.resolution_percentage = 100
    sc.render.film_transparent = False
    sc.render.image_settings.file_format = "PNG"
    if sc.world is None:  # an empty factory scene has no world: Workbench would render black
        sc.world = bpy.data.worlds.new("silk_world")
    sc.world.color = (0.23, 0.23, 0.25)
    sc.render.filepath = os.path.abspath(out)
    cam_data = bpy.data.cameras.new("silk_cam")
    cam_data.type = "ORTHO"
    cam = bpy.data.objects.new("silk_cam", cam_data)
    sc.collection.objects.link(cam)
    sc.camera = cam
    # A three-quarter view from the front (Blender: -Y is the front, Z up), framed by hand (no 3D
    # view in background mode): orthographic, scale from the bounds projected on the image plane.
    cam.rotation_euler = (math.radians(70), 0.0, math.radians(20))
    bpy.context.view_layer.update()
    lo, hi = bounds(objs)
    centre = (lo + hi) / 2
    rot = cam.rotation_euler.to_matrix()
    right, up, back = rot @ Vector((1, 0, 0)), rot @ Vector((0, 1, 0)), rot @ Vector((0, 0, 1))
    pts = [o.matrix_world @ Vector(c) for o in objs for c in o.bound_box]
    xs = [(p - centre).dot(right) for p in pts]
    ys = [(p - centre).dot(up) for p in pts]
    aspect = width / height
    span_x, span_y = max(xs) - min(xs), max(ys) - min(ys)
    cam_data.ortho_scale = 1.08 * max(span_x, span_y * aspect)
    shift = right * (max(xs) + min(xs)) / 2 + up * (max(ys) + min(ys)) / 2
    cam.location = centre + shift + back * ((hi - lo).length + 10.0)
    cam_data.clip_end = 10.0 * ((hi - lo).length + 10.0)


def main() -> None:
    args = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    n = len(args.pair)
    cols = args.cols if args.cols > 0 else n
    rows = math.ceil(n / cols)
    objs = []
    for k, (inp, out) in enumerate(args.pair):
        r, c = divmod(k, cols)
        objs += place_pair(inp, out, Vector((c * 5.2, 0, -r * 2.9)), args.fit_each)
    if args.size:
        width, height = (int(v) for v in args.size.lower().split("x"))
    else:
        width, height = 480 * 2 * cols, 480 * rows
    setup_render(objs, args.out, width, height)
    bpy.ops.render.render(write_still=True)
    if not os.path.exists(args.out):
        raise SystemExit(f"render_pairs: {args.out} was not written")
    print(f"render_pairs: wrote {args.out} ({n} pair(s), {width}x{height})")


main()
