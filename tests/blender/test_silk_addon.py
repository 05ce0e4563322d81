# SPDX-License-Identifier: MIT
"""Headless check of the Blender add-on, run as
  blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_silk_addon.py
by tests/blender/run_blender_test.sh (ctest blender_addon), or in PyPI's bpy module after `import bpy`
(ctest blender_addon_bpy_*, blender_extension_bpy_*). Environment: SILK_ADDON_ZIP (the installable
zip, its bundled model = the tiny test model), SILK_ADDON_KIND (addon or extension), SILKGEN, SILK_TEST_MODEL, SILK_DEV_MESH,
SILK_WORK (scratch folder), SILK_RENDER (picture to write), SILK_MESH_CHECK (../shared/tools/mesh_check.py). It installs + enables the add-on,
imports a dev-corpus mesh, generates with a fixed seed and checks the objects against
`silkgen --stats` on the same mesh as Blender holds it (object frame) and with mesh_check.py; checks that a cancel leaves
nothing behind, drives the Silk tab of the sidebar (sidebar_checks.py), that silkgen's GLB imports with the same
object/face counts, and renders a picture."""

import json
import os
import subprocess
import sys

import bmesh
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_setup  # noqa: E402

env = os.environ
SEED, MAX_TOKENS = int(env.get("SILK_SEED", "5")), int(env.get("SILK_MAX_TOKENS", "300"))
work = env["SILK_WORK"]
os.makedirs(work, exist_ok=True)
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


# -- install the zip and enable the add-on ------------------------------------------------------
kind = env.get("SILK_ADDON_KIND", "addon")  # addon (legacy zip) or extension (Blender 4.2+)
print(f"Blender {bpy.app.version_string}, {kind} {os.path.basename(env['SILK_ADDON_ZIP'])}")
addon = addon_setup.install_and_enable(env["SILK_ADDON_ZIP"], failures, kind)
check(addon is not None, f"{kind} enabled (silk.generate_mesh registered)")
if addon is None:
    sys.exit(f"blender add-on test: cannot go on ({failures})")
blender_mesh = addon_setup.submodule(addon, "blender_mesh")  # the installed copy
silk_mesh = addon_setup.submodule(addon, "silk_mesh")  # its vendored binding

silk_mesh.load_library()
check(
    silk_mesh.library_path().startswith(os.path.join(os.path.dirname(silk_mesh.__file__), "lib")),
    f"libsilk is the copy inside the add-on: {silk_mesh.library_path()}",
)
check(
    os.path.isfile(os.path.join(silk_mesh.bundled_model_dir(), "model.json")),
    f"the bundled model is beside it: {silk_mesh.bundled_model_dir()}",
)

# -- a dev-corpus mesh, placed off the origin ---------------------------------------------------
src = addon_setup.import_active_mesh(env["SILK_DEV_MESH"])

# silkgen on the same mesh as Blender holds it (evaluated, object frame).
pos, tri = blender_mesh.mesh_arrays(src, bpy.context.evaluated_depsgraph_get())
with silk_mesh.Mesh(pos, tri) as m:
    m.save(os.path.join(work, "source.obj"))
glb, stats_path = os.path.join(work, "silkgen.glb"), os.path.join(work, "silkgen.json")
subprocess.run(
    [
        env["SILKGEN"],
        os.path.join(work, "source.obj"),
        "-o",
        glb,
        "--model",
        env["SILK_TEST_MODEL"],
        "--seed",
        str(SEED),
        "--max-tokens",
        str(MAX_TOKENS),
        "--threads",
        "1",
        "--stats",
        stats_path,
        "-q",
    ],
    check=True,
)
want = json.load(open(stats_path))
print(
    f"silkgen --stats: {want['faces']} faces, {want['components']} part(s), {want['tokens']} tokens, "
    f"candidate {want['chosen_candidate']} of {len(want['candidates'])}"
)
if env.get("SILK_EXPECT_BEST_OF"):  # the model's own N ran (the bundled model's defaults)
    check(
        len(want["candidates"]) == int(env["SILK_EXPECT_BEST_OF"]),
        f"silkgen ran the model's best of {env['SILK_EXPECT_BEST_OF']} ({len(want['candidates'])} candidates)",
    )

# -- generate in Blender (model_dir empty: the model bundled in the zip) ------------------------
before = set(bpy.data.objects)
res = bpy.ops.silk.generate_mesh(seed=SEED, max_tokens=MAX_TOKENS)
check(res == {"FINISHED"}, f"silk.generate_mesh finished ({res})")
new = set(bpy.data.objects) - before
empties = [o for o in new if o.type == "EMPTY"]
parts = sorted((o for o in new if o.type == "MESH"), key=lambda o: o.name)
check(len(empties) == 1 and all(p.parent == empties[0] for p in parts), "one empty holds every part")
empty = empties[0]
check(
    all(abs(a - b) < 1e-6 for ra, rb in zip(empty.matrix_world, src.matrix_world) for a, b in zip(ra, rb)),
    "the empty sits in the source object's frame",
)
faces = sum(len(p.data.polygons) for p in parts)
print(f"blender: {faces} faces in {len(parts)} object(s)")
check(len(parts) == want["components"], f"objects {len(parts)} == parts {want['components']}")
check(faces == want["faces"], f"faces {faces} == silkgen --stats faces {want['faces']}")
for p in parts:
    bm = bmesh.new()
    bm.from_mesh(p.data)
    nonmanifold_v = sum(1 for v in bm.verts if not v.is_manifold)
    nonmanifold_e = sum(1 for e in bm.edges if not (e.is_manifold or e.is_boundary))
    inconsistent = sum(1 for e in bm.edges if not e.is_boundary and not e.is_contiguous)
    bm.free()
    if "vertex_manifold" in want.get("verdicts", {}):  # a libsilk whose decoder guarantees one fan per vertex
        check(nonmanifold_v == 0, f"{p.name}: vertex-manifold ({nonmanifold_v} non-manifold vertices)")
    else:
        print(
            f"note {p.name}: {nonmanifold_v} non-manifold vertices (this libsilk reports no vertex_manifold "
            "verdict, so its decoder does not guarantee it; not checked)"
        )
    check(nonmanifold_e == 0, f"{p.name}: edge-manifold ({nonmanifold_e} edges with 3+ faces)")
    check(inconsistent == 0, f"{p.name}: consistently oriented ({inconsistent} edges with opposing faces)")

# -- the parts as Blender holds them, judged by the independent checker (../shared/tools) -------
if env.get("SILK_MESH_CHECK"):
    objs = []
    for p in parts:
        ppos, ptri = blender_mesh.mesh_arrays(p, bpy.context.evaluated_depsgraph_get())
        objs.append(os.path.join(work, f"part_{len(objs)}.obj"))
        with silk_mesh.Mesh(ppos, ptri) as m:
            m.save(objs[-1])
    run = subprocess.run(["python3", env["SILK_MESH_CHECK"], "--json"] + objs, capture_output=True, text=True)
    verdicts = json.loads(run.stdout[: run.stdout.rindex("}") + 1])
    bad = {os.path.basename(k): v for k, v in verdicts.items() if not v.get("ok")}
    check(
        run.returncode == 0 and not bad,
        f"mesh_check.py: {len(objs)} part(s) edge/vertex-manifold, oriented, "
        f"no degenerate or duplicate faces{'' if not bad else f' (failed: {bad})'}",
    )
    check(sum(v.get("faces", 0) for v in verdicts.values()) == want["faces"], "mesh_check.py counts silkgen's faces")

# -- a cancel after a few steps leaves no object ------------------------------------------------
before = set(bpy.data.objects)
mesh_count = len(bpy.data.meshes)
res = bpy.ops.silk.generate_mesh(seed=SEED, max_tokens=MAX_TOKENS, cancel_after_steps=2)
check(res == {"CANCELLED"}, f"cancelled run returns CANCELLED ({res})")
check(set(bpy.data.objects) == before and len(bpy.data.meshes) == mesh_count, "a cancelled run leaves no object")

# -- best of N: every candidate shown while they run (the modal run's previews) -----------------
import candidate_preview_checks  # noqa: E402

candidate_preview_checks.run(addon, src, check)

# -- the Silk tab in the sidebar: models by name, settings, progress, scores, cancel -------------
import sidebar_checks  # noqa: E402

sidebar_checks.run(addon, src, env, work, SEED, check)

# -- silkgen's GLB imports with the expected objects and faces ----------------------------------
before = set(bpy.data.objects)
import numpy  # noqa: E402

if bpy.app.version < (3, 5, 0):  # Blender 3.4's glTF importer uses np.bool, gone since numpy 1.24 (Debian's)
    numpy.bool = bool
bpy.ops.import_scene.gltf(filepath=glb)
glb_objs = [o for o in set(bpy.data.objects) - before if o.type == "MESH"]
glb_faces = sum(len(o.data.polygons) for o in glb_objs)
check(len(glb_objs) == want["components"], f"GLB objects {len(glb_objs)} == parts {want['components']}")
check(glb_faces == want["faces"], f"GLB faces {glb_faces} == {want['faces']}")
for o in glb_objs:
    bpy.data.objects.remove(o, do_unlink=True)

# -- a picture: the source beside the generated parts (Workbench) -------------------------------
if env.get("SILK_RENDER"):

    def x_extent(objs):
        from mathutils import Vector

        xs = [(o.matrix_world @ Vector(c)).x for o in objs for c in o.bound_box]
        return min(xs), max(xs)

    s_lo, s_hi = x_extent([src])
    g_lo, g_hi = x_extent(parts)
    empty.location.x += (s_hi - g_lo) + 0.15 * (s_hi - s_lo)  # side by side, a small gap
    bpy.context.view_layer.update()
    for i, p in enumerate(parts):
        p.color = (0.35 + 0.6 * ((i * 0.618) % 1.0), 0.55, 0.9 - 0.5 * ((i * 0.37) % 1.0), 1.0)
    src.color = (0.8, 0.8, 0.8, 1.0)
    cam_data = bpy.data.cameras.new("cam")
    cam = bpy.data.objects.new("cam", cam_data)
    bpy.context.scene.collection.objects.link(cam)
    bpy.context.scene.camera = cam
    sc = bpy.context.scene
    sc.render.engine = "BLENDER_WORKBENCH"
    sc.display.shading.color_type = "OBJECT"
    sc.display.shading.light = "STUDIO"
    sc.display.shading.show_cavity = True
    sc.render.resolution_x, sc.render.resolution_y = 960, 480
    sc.render.film_transparent = False
    bpy.ops.object.select_all(action="DESELECT")
    src.select_set(True)
    for p in parts:
        p.select_set(True)
    cam.rotation_euler = (1.2, 0.0, 0.35)
    cam_data.lens = 35
    sc.render.filepath = env["SILK_RENDER"]
    bpy.context.view_layer.update()
    # Frame both by hand (no 3D view in background mode): back off along the view axis.
    from mathutils import Vector

    pts = [o.matrix_world @ Vector(c) for o in [src] + parts for c in o.bound_box]
    lo = Vector((min(p.x for p in pts), min(p.y for p in pts), min(p.z for p in pts)))
    hi = Vector((max(p.x for p in pts), max(p.y for p in pts), max(p.z for p in pts)))
    center, radius = (lo + hi) / 2, (hi - lo).length / 2
    direction = cam.rotation_euler.to_matrix() @ Vector((0, 0, 1))
    cam.location = center + direction * radius * 2.8
    bpy.ops.render.render(write_still=True)
    check(os.path.exists(env["SILK_RENDER"]), f"rendered {env['SILK_RENDER']}")

print(f"blender add-on test: {len(failures)} failure(s)")
if failures:
    sys.exit(1)
