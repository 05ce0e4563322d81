# SPDX-License-Identifier: MIT
"""docs/images/blender_sidebar.png: the Silk tab in a real Blender window (Xvfb), taken with Blender's own
screen.screenshot operator, run as
  bash tests/blender/run_blender_test.sh screenshot BUILD_DIR SOURCE_DIR WORK_DIR SILKGEN DEV_MESH
(SILK_SCREENSHOT: the PNG to write). $SILK_MODELS (its first model is picked), else a models folder with
the test model as "imported-tiny", beside the bundled model; the dev mesh imported; Generate pressed with best of 2 (the modal path, as a user runs
it); once it has finished, the sidebar shows the drop-down, settings, the full progress bar and the
scores. Blender ends with os._exit(status)."""

import os
import shutil
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_setup  # noqa: E402

env = os.environ
failures = []
addon = addon_setup.install_and_enable(env["SILK_ADDON_ZIP"], failures)
if addon is None:
    print(f"screenshot: add-on not enabled: {failures}", flush=True)
    os._exit(1)
if env.get("SILK_MODELS"):  # a models folder given (e.g. the official fixture imported with --name)
    models = env["SILK_MODELS"]
    pick = os.path.join(models, sorted(d for d in os.listdir(models) if not d.startswith("."))[0])
else:
    models = os.path.join(env["SILK_WORK"], "user_models")
    shutil.rmtree(models, ignore_errors=True)
    pick = os.path.join(models, "imported-tiny")
    shutil.copytree(env["SILK_TEST_MODEL"], pick)
    os.environ["SILK_MODELS"] = models
src = addon_setup.import_active_mesh(env["SILK_DEV_MESH"])
state = {"ticks": 0}


def view3d():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    return win, area


def start():
    win, area = view3d()
    area.spaces.active.show_region_ui = True
    ui = next(r for r in area.regions if r.type == "UI")
    with bpy.context.temp_override(window=win, area=area, region=ui):
        bpy.ops.silk.refresh_models()
        s = bpy.context.scene.silk
        s.model = pick
        s.candidates, s.seed = 2, 5
        bpy.context.view_layer.objects.active = src
        bpy.ops.silk.sidebar_generate()
    # Open the Silk tab as a user does: a click on it (Blender 3.4 has no API for the active tab). The
    # tabs run down the sidebar's right edge in the factory layout (Item, Tool, View, Silk) of a 1280x720 screen.
    x, y = ui.x + ui.width - 12, ui.y + ui.height - 158
    for kind, value in (("MOUSEMOVE", "NOTHING"), ("LEFTMOUSE", "PRESS"), ("LEFTMOUSE", "RELEASE")):
        win.event_simulate(type=kind, value=value, x=x, y=y)
    bpy.app.timers.register(wait, first_interval=0.5)


def wait():
    s = bpy.context.window_manager.silk_run
    state["ticks"] += 1
    if (s.running or not len(s.scores)) and state["ticks"] < 600:
        return 0.2
    result = bpy.data.objects.get(f"Silk {src.name}")
    if result is not None:  # the generated parts beside the source, not on top of it
        result.location.x += 1.6 * max(src.dimensions)
    win, area = view3d()
    region = next(r for r in area.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=win, area=area, region=region):
        bpy.ops.view3d.view_all()
    area.tag_redraw()
    bpy.app.timers.register(shoot, first_interval=1.0)  # let the window redraw first


def shoot():
    win, area = view3d()
    with bpy.context.temp_override(window=win, area=area):
        bpy.ops.screen.screenshot(filepath=env["SILK_SCREENSHOT"])
    run = bpy.context.window_manager.silk_run
    ok = os.path.isfile(env["SILK_SCREENSHOT"]) and len(run.scores) == 2
    print(f"screenshot {env['SILK_SCREENSHOT']}: {'ok' if ok else 'FAILED'} ({run.status})", flush=True)
    os._exit(0 if ok else 1)


bpy.app.timers.register(start, first_interval=1.0)
