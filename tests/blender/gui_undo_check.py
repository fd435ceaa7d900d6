"""Undo and redo in Blender with its interface (undo needs a window), run under Xvfb:

    xvfb-run -a blender --factory-startup --python gui_undo_check.py -- --zip ...-legacy.zip

Builds the example graph, lengthens the bulb, undoes and redoes, and checks that the node
value, the evaluated mesh and its volume follow. Then, in a node editor showing the tree with
its sidebar, opens the Add menu and every Fairlines submenu and shows a failing node, so every
draw callback runs in a real interface (a traceback there fails the calling test). Prints
FAIRLINES-CHECKS <json>; exits 1 on failure.
"""

import importlib
import json
import os
import sys
import traceback

import bpy
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "examples"))
import blender_graph  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
ZIP = argv[argv.index("--zip") + 1]
state = {"step": 0}
report = {"blender": bpy.app.version_string}


def volume(obj):
    dg = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(dg)
    me = ev.to_mesh()
    me.calc_loop_triangles()
    v = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", v)
    t = np.empty(len(me.loop_triangles) * 3, dtype=np.int64)
    me.loop_triangles.foreach_get("vertices", t)
    ev.to_mesh_clear()
    v, t = v.reshape(-1, 3), t.reshape(-1, 3)
    return float(np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6.0)


def length():
    """The bulb's protrusion coefficient C_LPR (protrusion / Lpp) on the Bulbous Bow node."""
    tree = bpy.data.node_groups[blender_graph.TREE_NAME]
    return round(tree.nodes["Bulbous Bow"].inputs["C_LPR"].default_value, 4)


def nose():
    """Foremost x of the composed forebody (the bulb's nose), metres."""
    me = bpy.data.objects["Ship"].data
    v = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", v)
    return float(v.reshape(-1, 3)[:, 0].max())


SHORT, LONG = 0.025, 0.035
DX = (LONG - SHORT) * blender_graph.LPP  # how far the nose moves forward


def ctx():
    win = bpy.context.window_manager.windows[0]
    area = max(win.screen.areas, key=lambda a: a.width * a.height)
    return bpy.context.temp_override(window=win, area=area)


def finish(ok, error=""):
    report["ok"] = ok
    if error:
        report["error"] = error
    print("FAIRLINES-CHECKS " + json.dumps(report))
    sys.stdout.flush()
    os._exit(0 if ok else 1)


def check(cond, message):
    if not cond:
        raise AssertionError(message)


class _NotYet(Exception):
    pass


def wait_for(cond):
    """Results arrive from the add-on's own timer; a first redraw under Xvfb's software GL can
    hold the event loop for a while, so a step retries (up to ~6 s) until its result is in."""
    if cond():
        state["tries"] = 0
        return
    state["tries"] = state.get("tries", 0) + 1
    if state["tries"] > 30:
        return  # let the step's own check report what is wrong
    raise _NotYet


def tick():
    # One step per timer tick: undo handlers queue an evaluation that the add-on's own timer
    # runs between ticks, exactly as in an interactive session.
    try:
        state["step"] += 1
        s = state["step"]
        if s == 1:
            module = blender_graph.enable_addon(os.path.abspath(ZIP))
            state["ev"] = importlib.import_module(module + ".evaluator")
            blender_graph.build()
            state["ev"].flush()
            with ctx():
                bpy.ops.ed.undo_push(message="example graph")
            report["v_short"] = volume(bpy.data.objects["Ship"])
            report["nose_short"] = nose()
        elif s == 2:
            tree = bpy.data.node_groups[blender_graph.TREE_NAME]
            tree.nodes["Bulbous Bow"].inputs["C_LPR"].default_value = LONG
        elif s == 3:
            wait_for(lambda: abs(nose() - report["nose_short"] - DX) < 0.02 * DX)
            report["v_long"] = volume(bpy.data.objects["Ship"])
            report["nose_long"] = nose()
            check(abs(report["nose_long"] - report["nose_short"] - DX) < 0.02 * DX, "bulb did not lengthen live")
            check(report["v_long"] != report["v_short"], "the volume did not change with the bulb")
            with ctx():
                bpy.ops.ed.undo_push(message="longer bulb")
                bpy.ops.ed.undo()
        elif s == 4:
            wait_for(lambda: abs(volume(bpy.data.objects["Ship"]) / report["v_short"] - 1) < 1e-6)
            check(length() == SHORT, "undo left C_LPR at %s" % length())
            v = volume(bpy.data.objects["Ship"])
            report["v_after_undo"] = v
            check(abs(v / report["v_short"] - 1) < 1e-6, "undo: volume %.3f, expected %.3f" % (v, report["v_short"]))
            tree = bpy.data.node_groups[blender_graph.TREE_NAME]
            bad = [n.name for n in tree.nodes if n.fl_state != "OK"]
            check(not bad, "nodes not OK after undo: %s" % bad)
            with ctx():
                bpy.ops.ed.redo()
        elif s == 5:
            wait_for(lambda: abs(volume(bpy.data.objects["Ship"]) / report["v_long"] - 1) < 1e-6)
            check(length() == LONG, "redo left C_LPR at %s" % length())
            v = volume(bpy.data.objects["Ship"])
            report["v_after_redo"] = v
            check(abs(v / report["v_long"] - 1) < 1e-6, "redo: volume %.3f, expected %.3f" % (v, report["v_long"]))
            tree = bpy.data.node_groups[blender_graph.TREE_NAME]
            win = bpy.context.window_manager.windows[0]
            area = max(win.screen.areas, key=lambda a: a.width * a.height)
            area.type = "NODE_EDITOR"
            area.ui_type = tree.bl_idname
            area.spaces.active.node_tree = tree
            area.spaces.active.show_region_ui = True
            tree.nodes["Refine"].inputs["Parameter"].default_value = 5.0
        elif s == 6:
            tree = bpy.data.node_groups[blender_graph.TREE_NAME]
            wait_for(lambda: tree.nodes["Refine"].fl_state == "ERROR")
            check(tree.nodes["Refine"].fl_state == "ERROR", "bad knot not shown in the interface")
            win = bpy.context.window_manager.windows[0]
            area = next(a for a in win.screen.areas if a.type == "NODE_EDITOR")
            region = next(r for r in area.regions if r.type == "WINDOW")
            menus = [name for name in dir(bpy.types) if name.startswith("NODE_MT_fairlines_add_")]
            check(len(menus) >= 7, "Fairlines add menus: %s" % menus)
            with bpy.context.temp_override(window=win, area=area, region=region):
                bpy.ops.wm.call_menu(name="NODE_MT_add")
                for name in menus:
                    bpy.ops.wm.call_menu(name=name)
            report["menus"] = len(menus)
        elif s == 7:
            tree = bpy.data.node_groups[blender_graph.TREE_NAME]
            tree.nodes["Refine"].inputs["Parameter"].default_value = 0.85
        elif s == 8:
            tree = bpy.data.node_groups[blender_graph.TREE_NAME]
            wait_for(lambda: all(n.fl_state == "OK" for n in tree.nodes))
            check(all(n.fl_state == "OK" for n in tree.nodes), "graph did not recover")
            # An export from the interface runs inside the progress indicator and status text.
            exp = tree.nodes.new("FLNodeExportOBJ")
            exp.name = "GUI Export"
            exp.filepath = os.path.join(bpy.app.tempdir, "gui_export.obj")
            tree.links.new(tree.nodes["Curvature"].outputs["Mesh"], exp.inputs["Mesh"])
            with ctx():
                check(bpy.ops.fairlines.export_node(tree=tree.name, node=exp.name) == {"FINISHED"}, "GUI export")
            check(os.path.getsize(exp.filepath) > 0, "GUI export wrote nothing")
            report["gui_export"] = exp.filepath
            finish(True)
        return 0.3
    except _NotYet:
        state["step"] -= 1
        return 0.2
    except Exception:
        finish(False, traceback.format_exc())


bpy.app.timers.register(tick, first_interval=0.5)
