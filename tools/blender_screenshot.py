"""Screenshot of the node editor with the example graph (for the README). Runs Blender with
its interface, under Xvfb when there is no display:

    xvfb-run -a -s "-screen 0 2560x1440x24" blender \
        --python tools/blender_screenshot.py -- --zip dist/...-legacy.zip --out docs/node_editor.png

--outputs shows the example's second tree instead, the output nodes (blender_graph.build_outputs);
--site DIR appends a folder of optional packages (matplotlib, ezdxf, rhino3dm, meshio) to
Blender's Python path so the file nodes show what they do rather than the pip line.

Use a throw-away BLENDER_USER_CONFIG whose userpref.blend has the splash screen off (the
Makefile target writes one with --prefs-only first).
"""

import argparse
import importlib
import os
import sys

import bpy

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "examples"))
import blender_graph  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
ap = argparse.ArgumentParser()
ap.add_argument("--zip", required=True)
ap.add_argument("--out", default="")
ap.add_argument("--prefs-only", action="store_true", help="save preferences without the splash, quit")
ap.add_argument("--outputs", action="store_true", help="the tree of output nodes instead of the example graph")
ap.add_argument("--site", default="", help="folder of optional packages to append to sys.path")
args = ap.parse_args(argv)
if args.site:
    sys.path.append(os.path.abspath(args.site))

state = {"step": 0}
ZOOM_STEPS = 7


def setup():
    module = blender_graph.enable_addon(os.path.abspath(args.zip))
    ev = importlib.import_module(module + ".evaluator")
    if args.outputs:
        tree = blender_graph.build_outputs()
        tree.nodes["Export CAD"].filepath = "//hull.3dm"  # Rhino: rhino3dm, no OpenCASCADE needed
    else:
        tree = blender_graph.build()
    ev.flush()
    window = bpy.context.window_manager.windows[0]
    screen = window.screen
    areas = sorted(screen.areas, key=lambda a: a.width * a.height, reverse=True)
    big = areas[0]
    big.type = "NODE_EDITOR"
    big.ui_type = tree.bl_idname
    space = big.spaces.active
    space.node_tree = tree
    space.show_region_ui = False
    for node in tree.nodes:
        node.select = False
    return big, window


def tick():
    state["step"] += 1
    if state["step"] == 1:
        state["area"], state["window"] = setup()
        return 0.5
    area, window = state["area"], state["window"]
    region = next(r for r in area.regions if r.type == "WINDOW")
    if state["step"] in (2, 3):  # twice: the first runs before the region has its final size
        with bpy.context.temp_override(window=window, area=area, region=region):
            bpy.ops.node.view_all()
        return 0.5
    if state["step"] == 4:
        # view_all leaves a wide margin at this window size; zoom in to make the text legible.
        with bpy.context.temp_override(window=window, area=area, region=region):
            for _ in range(ZOOM_STEPS):
                bpy.ops.view2d.zoom_in()
        return 0.5
    if state["step"] == 5:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        with bpy.context.temp_override(window=window, area=area, region=region):
            bpy.ops.screen.screenshot_area(filepath=os.path.abspath(args.out))
        print("wrote", args.out)
        bpy.ops.wm.quit_blender()
        return None
    return 0.5


if args.prefs_only:
    bpy.context.preferences.view.show_splash = False
    bpy.context.preferences.view.ui_scale = 1.5
    bpy.ops.wm.save_userpref()
else:
    bpy.app.timers.register(tick, first_interval=1.0)
