# SPDX-License-Identifier: MIT
"""The Silk tab (View3D > Sidebar > Silk, apps/blender/silk_blender/sidebar.py) driven through its operators, as
test_silk_addon.py's last part in every Blender it runs in: a user models folder holding a copy of the test model
appears in the drop-down beside the bundled model (architecture and size in the label); Generate with the tab's
settings (that model, best of 2, 3 rows: passed on to the generation) gives silkgen's faces and chosen candidate, the progress reaches candidate 2 of 2
and 100 %, the candidates' scores are silkgen's; the tab's Cancel flag cancels a run and leaves nothing."""

import json
import os
import re
import shutil
import subprocess

import bpy

import addon_setup


def _silkgen_stats(env, work, model_dir, seed):
    stats = os.path.join(work, "sidebar_silkgen.json")
    subprocess.run(
        [
            env["SILKGEN"],
            os.path.join(work, "source.obj"),
            "-o",
            os.path.join(work, "sidebar.glb"),
            "--model",
            model_dir,
            "--seed",
            str(seed),
            "--candidates",
            "2",
            "--threads",
            "1",
            "--stats",
            stats,
            "-q",
        ],
        check=True,
    )
    return json.load(open(stats))


def run(addon, src, env, work, seed, check):
    sidebar = addon_setup.submodule(addon, "sidebar")
    check(
        getattr(bpy.types, "SILK_PT_sidebar", None) is not None
        and bpy.types.SILK_PT_sidebar.bl_category == "Silk"
        and bpy.types.SILK_PT_sidebar.bl_region_type == "UI",
        "the Silk tab is registered (View3D > Sidebar > Silk)",
    )
    models = os.path.join(work, "user_models")
    shutil.rmtree(models, ignore_errors=True)
    shutil.copytree(env["SILK_TEST_MODEL"], os.path.join(models, "imported-tiny"))
    os.environ["SILK_MODELS"] = models
    check(bpy.ops.silk.refresh_models() == {"FINISHED"}, "silk.refresh_models finished")
    items = list(sidebar._model_items)
    for ident, label, _desc, _n in items:
        print(f"drop-down: {label}    [{ident}]")
    mine = os.path.join(models, "imported-tiny")
    check(len(items) == 2 and "(bundled)" in items[0][1], "the drop-down starts with the bundled model")
    check(
        any(i[0] == mine and i[1].startswith("imported-tiny: silk, ") and i[1].endswith(" MB") for i in items),
        "the drop-down lists the models folder's model with its architecture and size",
    )

    s, run = bpy.context.scene.silk, bpy.context.window_manager.silk_run
    check(
        s.rows == -1 and "rows" in bpy.ops.silk.generate_mesh.get_rna_type().properties,
        "a Rows setting, -1 (the model's)",
    )
    s.model, s.candidates, s.rows, s.seed, s.orient = mine, 2, 3, seed, "INPUT"
    want = _silkgen_stats(env, work, "imported-tiny", seed)  # silkgen finds the same model by name
    bpy.context.view_layer.objects.active = src
    before = set(bpy.data.objects)
    generator = addon_setup.submodule(addon, "operators").silk_mesh.Generator
    given, start = {}, generator.start
    generator.start = lambda self, *a, **kw: given.update(kw) or start(self, *a, **kw)
    try:
        res = bpy.ops.silk.sidebar_generate()
    finally:
        generator.start = start
    check(
        given.get("rows") == 3 and given.get("candidates") == 2,
        f"the tab's Rows is passed on (rows={given.get('rows')})",
    )
    s.rows = -1
    new = set(bpy.data.objects) - before
    faces = sum(len(o.data.polygons) for o in new if o.type == "MESH")
    print(
        f"sidebar: {res}, {faces} faces; status '{run.status}', progress {run.progress:.2f}; scores "
        + ", ".join(f"{c.index + 1}:{c.score:.4f}{'*' if c.chosen else ''}" for c in run.scores)
    )
    check(res == {"FINISHED"} and faces == want["faces"], f"Generate: {faces} faces == silkgen's {want['faces']}")
    check(
        # The candidates run as rows (2 of the default 8): the status ends on the one that ended last.
        not run.running and run.progress == 1.0 and re.match(r"done: .*candidate [12] of 2, layer ", run.status),
        f"the progress bar ends at 100 % on candidate 1 or 2 of 2 ('{run.status}')",
    )
    scores = [c.score for c in run.scores]
    check(
        len(scores) == 2 and all(abs(a - b["score"]) <= 1e-6 * b["score"] for a, b in zip(scores, want["candidates"])),
        f"the candidates' scores are silkgen's (float32 in Blender: {scores})",
    )
    check([c.chosen for c in run.scores].index(True) == want["chosen_candidate"], "the chosen candidate is marked")
    check(not bpy.ops.silk.sidebar_cancel.poll(), "Cancel is greyed out when nothing runs")
    for o in new:  # the later checks and the picture see the scene as before
        bpy.data.objects.remove(o, do_unlink=True)

    run.cancel_requested = True  # what the tab's Cancel button sets while a run is in progress
    before, n_meshes = set(bpy.data.objects), len(bpy.data.meshes)
    res = bpy.ops.silk.generate_mesh(model_dir=mine, seed=seed)
    run.cancel_requested = False
    check(
        res == {"CANCELLED"}
        and set(bpy.data.objects) == before
        and len(bpy.data.meshes) == n_meshes
        and run.status.startswith("cancelled"),
        f"the tab's Cancel stops a run and leaves nothing ('{run.status}')",
    )
