"""`make demo` (Blender part): build the whole container ship's node graph (Particulars -> hull
-> bulb -> blend -> Boolean union -> Ship object) in headless Blender with the scripting API,
save the .blend and render two pictures with Cycles on the CPU:

  ship.png   the whole ship, mirrored, on a sea surface at the design draught, its paint split
             at the design waterline (antifouling below, a black boot-top band above);
  zebra.png  the same hull out of the water with the zebra (reflection-line) material the Mesh
             Output node offers: smooth, unbroken stripes mean a fair surface.

    .venv-bpy/bin/python examples/blender_demo.py --zip dist/fairlines_blender-*-extension.zip --out out/blender [--docs docs]
    blender -b --python examples/blender_demo.py -- --zip dist/...-legacy.zip --out out/blender
"""

import argparse
import math
import os
import shutil
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_graph  # noqa: E402

L, B, T = blender_graph.LPP, blender_graph.BEAM, blender_graph.DRAFT


def camera(scene, location, target, lens=50):
    cam = scene.camera
    if cam is None:
        cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
        scene.collection.objects.link(cam)
        aim = bpy.data.objects.new("Aim", None)
        scene.collection.objects.link(aim)
        cam.constraints.new("TRACK_TO").target = aim
        scene.camera = cam
    cam.data.lens = lens
    cam.location = location
    cam.constraints[0].target.location = target


def world(scene, colour, strength):
    w = scene.world or bpy.data.worlds.new("World")
    scene.world = w
    if bpy.app.version < (5, 0, 0):  # always node-based from 5.0 on
        w.use_nodes = True
    bg = w.node_tree.nodes.get("Background")
    if bg is not None:
        bg.inputs[0].default_value = colour
        bg.inputs[1].default_value = strength


def sea(scene):
    """A large plane at z = T with a dark, glossy, slightly see-through water material."""
    me = bpy.data.meshes.new("Sea")
    s = 4.0 * L
    me.from_pydata([(-s, -s, T), (s, -s, T), (s, s, T), (-s, s, T)], [], [(0, 1, 2, 3)])
    obj = bpy.data.objects.new("Sea", me)
    scene.collection.objects.link(obj)
    mat = bpy.data.materials.new("Sea")
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    bsdf.inputs["Base Color"].default_value = (0.02, 0.07, 0.10, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.08
    bsdf.inputs["Alpha"].default_value = 0.8
    me.materials.append(mat)
    return obj


def sun(scene):
    light = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    light.data.energy = 6.0
    light.rotation_euler = (math.radians(45), math.radians(10), math.radians(-40))
    scene.collection.objects.link(light)


def high_contrast(scene):
    """The colour management's high-contrast look (AgX from 4.0, Filmic before)."""
    items = [i.identifier for i in scene.view_settings.bl_rna.properties["look"].enum_items_static] or []
    for look in ("AgX - High Contrast", "High Contrast", "Filmic - High Contrast"):
        try:
            scene.view_settings.look = look
            return
        except TypeError:
            continue
    print("no high-contrast look among %s" % items)


def render(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print("wrote %s" % path)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("--zip", required=True, help="packaged add-on (tools/package_addon.py)")
    ap.add_argument("--out", default="out/blender")
    ap.add_argument("--docs", default="", help="also copy the pictures into this folder (README images)")
    ap.add_argument("--samples", type=int, default=32)
    ap.add_argument("--size", type=int, nargs=2, default=(1600, 800))
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    blender_graph.enable_addon(os.path.abspath(a.zip))
    api = blender_graph._addon_module("api")
    tree = blender_graph.build()
    api.evaluate(tree)
    for n in tree.nodes:
        print("  %-16s %8.2f ms  %s" % (n.name, n.fl_time_ms, n.fl_info.replace("\n", "; ")))
    # The graph's cells are for live editing; the pictures get finer meshes. The zebra stripes
    # follow the mesh's interpolated normals: at 160 x 48 hull cells (1.5 m long) their edges
    # stepped cell by cell where they bunch toward the bow; at 480 x 120 they run smooth.
    for name, value in (("Hull Cells U", 480), ("Hull Cells V", 120), ("Bulb Cells U", 120), ("Bulb Cells V", 160)):
        api.set(tree, "Compose", name, value)
    api.evaluate(tree)
    print("  render mesh: %s" % tree.nodes["Compose"].fl_info.replace("\n", "; "))
    scene = bpy.context.scene
    for name in ("Bare Hull", "Hull Lines", "Sections"):
        bpy.data.objects[name].hide_render = True
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = a.samples
    scene.render.resolution_x, scene.render.resolution_y = a.size
    scene.render.resolution_percentage = 100
    high_contrast(scene)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "ship.blend"))
    pictures = []
    # 1. The ship afloat: bow three-quarter view from above the water.
    sun(scene)
    world(scene, (0.42, 0.56, 0.78, 1.0), 0.5)
    water = sea(scene)
    camera(scene, (L + 118.0, -142.0, 50.0), (0.6 * L, 0.0, 7.0), lens=50)
    pictures.append(os.path.join(out, "ship.png"))
    render(scene, pictures[-1])
    # 2. Zebra: the same hull, out of the water, reflection-line stripes, closer on the bow.
    water.hide_render = True
    api.set(tree, "Ship Output", "material", "zebra")
    api.evaluate(tree)
    world(scene, (0.5, 0.5, 0.5, 1.0), 1.0)
    camera(scene, (L + 55.0, -70.0, 4.0), (0.78 * L, 0.0, 7.0), lens=45)
    pictures.append(os.path.join(out, "zebra.png"))
    render(scene, pictures[-1])
    if a.docs:
        for p in pictures:
            shutil.copy(p, os.path.join(os.path.abspath(a.docs), "ship_" + os.path.basename(p)
                                        if not os.path.basename(p).startswith("ship") else os.path.basename(p)))


main()
