# SPDX-License-Identifier: MIT
"""Best of N's candidates shown while they run (issue 34; apps/blender/silk_blender/candidate_previews.py, which
the modal silk.generate_mesh feeds after each advance), checked headless in every Blender test_silk_addon.py runs
in: best of 3 on the bundled model, step by step: one wire object per started candidate ("Silk candidate 2/3"),
side by side along X right of the source, its faces those of the candidate's mesh, exactly one "(best)" once one is
scored (the lowest score), the progress line "candidates running k, done m of 3"; remove() leaves no object or mesh."""

import re

import bpy

import addon_setup


def run(addon, src, check):
    previews_mod = addon_setup.submodule(addon, "candidate_previews")
    progress_mod = addon_setup.submodule(addon, "run_progress")
    blender_mesh = addon_setup.submodule(addon, "blender_mesh")
    silk_mesh = addon_setup.submodule(addon, "silk_mesh")
    objects, meshes = set(bpy.data.objects), len(bpy.data.meshes)
    coll = src.users_collection[0] if src.users_collection else bpy.context.scene.collection
    pos, tri = blender_mesh.mesh_arrays(src, bpy.context.evaluated_depsgraph_get())
    problems, started, texts, best_seen = [], set(), [], set()
    with silk_mesh.Generator(None) as job:
        with silk_mesh.Mesh(pos, tri) as m:
            job.start(m, seed=5, max_tokens=200, candidates=3)
        previews = previews_mod.CandidatePreviews(src, coll)
        progress = progress_mod.RunProgress(None, 200)
        while True:
            views = previews.update(job)
            progress.after_candidates(views)
            texts.append(progress.text())
            shown = {o.name: o for o in set(bpy.data.objects) - objects}
            live = [c for c in views if c["state"] != "waiting"]
            started |= {c["index"] for c in live}
            if len(shown) != len(live):
                problems.append(f"{len(shown)} objects for {len(live)} started candidates")
            scored = [c["score"] for c in views if c["state"] == "scored"]
            for c in live:
                name = f"Silk candidate {c['index'] + 1}/3" + (" (best)" if c["best"] else "")
                obj = shown.get(name)
                if obj is None:
                    problems.append(f"no object '{name}' ({sorted(shown)})")
                    continue
                want_x = src.matrix_world.translation.x + previews.step * (c["index"] + 1)
                if abs(obj.matrix_world.translation.x - want_x) > 1e-5 or obj.display_type != "WIRE":
                    problems.append(f"{name} at x {obj.matrix_world.translation.x}, not {want_x} in wire")
                if c["faces"] is not None and len(obj.data.polygons) != c["faces"]:
                    problems.append(f"{name}: {len(obj.data.polygons)} faces, the candidate has {c['faces']}")
                if c["best"]:
                    best_seen.add(c["index"])
                    if c["score"] != min(scored):
                        problems.append(f"{name} is not the lowest score {scored}")
            if sum(n.endswith("(best)") for n in shown) != (1 if scored else 0):
                problems.append(f"one '(best)' among the scored: {sorted(shown)}")
            if job.done:
                break
            job.advance(32, until_layer=True)
            progress.after_advance(job.stats(), 32, job.done)
        previews.remove()
        job.finish()
    print(f"candidate previews: started {sorted(started)}, best marked {sorted(best_seen)}; last line '{texts[-1]}'")
    check(not problems, f"one wire object per started candidate, side by side, the best named ({problems[:3]})")
    check(started == {0, 1, 2} and best_seen, "all 3 candidates were shown and a best was marked")
    check(
        all(re.match(r"candidates running \d, done \d of 3; candidate \d of 3, layer", t) for t in texts[1:])
        and any(t.startswith("candidates running 1, done 2 of 3") for t in texts),
        f"the progress says 'candidates running k, done m of 3' ({texts[-1]})",
    )
    check(
        set(bpy.data.objects) == objects and len(bpy.data.meshes) == meshes,
        "remove() leaves no candidate object or mesh",
    )
