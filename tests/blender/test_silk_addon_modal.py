# SPDX-License-Identifier: MIT
"""The add-on's interactive path in a real Blender window (Xvfb), run as
  xvfb-run blender --factory-startup --enable-event-simulate --python tests/blender/test_silk_addon_modal.py
by tests/blender/run_blender_test.sh modal (ctest blender_addon_modal). `silk.generate_mesh` is
invoked as a user invokes it (INVOKE_DEFAULT in the 3D view), so it runs as a modal operator
driven by timer events: the wire preview must grow while the UI keeps handling events (this
test's own timer watches it from outside; best of N: one wire object per candidate, side by side,
the best so far named, all removed at the end), and the result must equal the synchronous (script)
run with the same settings. A second invocation gets a real Esc key event (window.event_simulate) while it
runs: no object and no preview may be left. Blender ends with os._exit(status), since a
windowed session's exit code does not follow --python-exit-code."""

import json
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_setup  # noqa: E402

env = os.environ
SEED, MAX_TOKENS = int(env.get("SILK_SEED", "5")), int(env.get("SILK_MODAL_MAX_TOKENS", "2000"))
# The bundled model (models/default: ~2 s for 2,000 ids) rather than the zip's tiny test model,
# which finishes within a tick or two, too fast to watch a preview grow or to press Esc.
MODEL = env["SILK_MODAL_MODEL"]
# The model's best of N (model.json sampling.candidates), which the operator runs by default.
CANDIDATES = json.load(open(os.path.join(MODEL, "model.json"))).get("sampling", {}).get("candidates", 1)
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def finish():
    print(f"blender add-on modal test: {len(failures)} failure(s)", flush=True)
    os._exit(1 if failures else 0)


check(not bpy.app.background, "a windowed session (not -b)")
addon = addon_setup.install_and_enable(env["SILK_ADDON_ZIP"], failures)
check(addon is not None, "add-on enabled")
operators = addon_setup.submodule(addon, "operators")  # the installed copy
PREFIX = addon_setup.submodule(addon, "candidate_previews").PREFIX

src = addon_setup.import_active_mesh(env["SILK_DEV_MESH"])


def is_preview(o):
    return o.name == operators.PREVIEW_NAME or o.name.startswith(PREFIX)


def results(new_objects):
    parts = [o for o in new_objects if o.type == "MESH" and not is_preview(o)]
    return len(parts), sum(len(p.data.polygons) for p in parts)


def previews():
    """The run's wire previews: the single one (N = 1) or one per started candidate (best of N)."""
    return [o for o in bpy.data.objects if is_preview(o)]


def remove(objs):
    for o in objs:
        bpy.data.objects.remove(o, do_unlink=True)


# The synchronous run (what a script gets) is the reference.
before = set(bpy.data.objects)
check(
    bpy.ops.silk.generate_mesh(seed=SEED, max_tokens=MAX_TOKENS, model_dir=MODEL) == {"FINISHED"},
    "synchronous run finished",
)
ref_new = set(bpy.data.objects) - before
want_parts, want_faces = results(ref_new)
print(f"synchronous: {want_faces} faces in {want_parts} part(s)", flush=True)
remove(ref_new)


def view3d():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    return win, dict(window=win, area=area, region=next(r for r in area.regions if r.type == "WINDOW"))


def invoke():
    win, override = view3d()
    with bpy.context.temp_override(**override):
        bpy.context.view_layer.objects.active = src
        return win, bpy.ops.silk.generate_mesh("INVOKE_DEFAULT", seed=SEED, max_tokens=MAX_TOKENS, model_dir=MODEL)


state = {"phase": "run", "before": set(), "preview_faces": {}, "names": set(), "polls": 0, "t0": time.monotonic()}


def poll():
    """Timer: watches the modal operator from outside, as a user would."""
    state["polls"] += 1
    if time.monotonic() - state["t0"] > 240:
        check(False, f"phase {state['phase']} still running after 240 s")
        finish()
    shown = previews()
    if state["phase"] == "run":
        if shown:
            for o in shown:  # faces per candidate, keyed by "Silk candidate 3/8" without "(best)"
                state["preview_faces"].setdefault(o.name.replace(" (best)", ""), []).append(len(o.data.polygons))
                state["names"].add(o.name)
            return 0.02
        parts, total = results(set(bpy.data.objects) - state["before"])
        print(f"modal: {total} faces in {parts} part(s); previews seen {sorted(state['names'])}", flush=True)
        check(
            parts == want_parts and total == want_faces,
            f"modal result ({total} faces, {parts} parts) == synchronous ({want_faces}, {want_parts})",
        )
        # Each preview only grows; best of N shows every candidate side by side, the best so far named.
        faces = state["preview_faces"]
        grows = all(all(b >= a for a, b in zip(f, f[1:])) for f in faces.values())
        check(grows, f"every preview only grows ({ {k: sorted(set(v)) for k, v in faces.items()} })")
        check(any(len(set(x for x in f if x > 0)) >= 2 for f in faces.values()), "a preview shows two stages of growth")
        if CANDIDATES > 1:
            want = {f"{PREFIX} {i + 1}/{CANDIDATES}" for i in range(CANDIDATES)}
            check(set(faces) == want, f"one preview per candidate ({sorted(faces)})")
            check(any(n.endswith(" (best)") for n in state["names"]), "the best so far is named '(best)'")
            status = bpy.context.window_manager.silk_run.status
            check(
                f"of {CANDIDATES}; candidate" in status,
                f"the progress names the candidates running and done ({status})",
            )
        remove(set(bpy.data.objects) - state["before"])
        # Phase 2: Esc while running.
        state.update(phase="esc", before=set(bpy.data.objects), meshes=len(bpy.data.meshes), polls=0)
        win, res = invoke()
        state["win"] = win
        check(res == {"RUNNING_MODAL"}, f"second invocation is modal ({res})")
        return 0.02
    if state["phase"] == "esc":
        if shown:
            faces = sum(len(o.data.polygons) for o in shown)
            if faces > 0 and not state.get("esc_sent"):  # mid-run: some layers shown
                state["esc_faces"] = faces
                state["win"].event_simulate(type="ESC", value="PRESS")
                state["esc_sent"] = True
            return 0.02
        check(
            state.get("esc_sent", False),
            f"Esc was sent while the operator ran (preview at {state.get('esc_faces')} faces)",
        )
        left = set(bpy.data.objects) - state["before"]
        check(
            not left and len(bpy.data.meshes) == state["meshes"],
            f"Esc leaves no object and no mesh behind ({sorted(o.name for o in left)})",
        )
        finish()
    return None


def start():
    state["before"] = set(bpy.data.objects)
    _, res = invoke()
    check(res == {"RUNNING_MODAL"}, f"INVOKE_DEFAULT in the 3D view runs modally ({res})")
    if res != {"RUNNING_MODAL"}:
        finish()
    bpy.app.timers.register(poll, first_interval=0.02)
    return None


bpy.app.timers.register(start, first_interval=0.5)
