"""`make demo` (Blender part): build the Panamax forebody node graph (hull description ->
bare hull -> bulbous bow -> blend -> Boolean union -> output) in headless Blender, save the
.blend and render the hull with Cycles on the CPU.

    .venv-bpy/bin/python examples/blender_demo.py --zip dist/fairlines_blender-*-extension.zip --out out/blender
    blender -b --python examples/blender_demo.py -- --zip dist/...-legacy.zip --out out/blender
"""

import argparse
import importlib
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_graph  # noqa: E402


def stage(scene):
    """Camera, sun and world for a three-quarter bow view of the composed forebody."""
    L = blender_graph.LPP
    target = (0.86 * L, 0.0, 8.0)
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.lens = 50
    cam = bpy.data.objects.new("Camera", cam_data)
    cam.location = (L + 95.0, -120.0, 55.0)
    scene.collection.objects.link(cam)
    aim = bpy.data.objects.new("Aim", None)
    aim.location = target
    scene.collection.objects.link(aim)
    c = cam.constraints.new("TRACK_TO")
    c.target = aim
    scene.camera = cam
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(50), math.radians(10), math.radians(-30))
    scene.collection.objects.link(sun)
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    if bpy.app.version < (5, 0, 0):  # always node-based from 5.0 on
        world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    if bg is not None:
        bg.inputs[0].default_value = (0.62, 0.72, 0.85, 1.0)
        bg.inputs[1].default_value = 0.8
    paint = bpy.data.materials.new("Hull Paint")
    paint.diffuse_color = (0.55, 0.08, 0.06, 1.0)
    if bpy.app.version < (5, 0, 0):
        paint.use_nodes = True
    bsdf = paint.node_tree.nodes.get("Principled BSDF")
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = (0.55, 0.08, 0.06, 1.0)
    fore = bpy.data.objects["Forebody"]
    if not fore.data.materials:
        fore.data.materials.append(paint)
    # The composed hull is the picture; the bare hull it contains and the lines stay in the
    # viewport only.
    for name in ("Bare Forebody", "Forebody Lines", "Sections"):
        bpy.data.objects[name].hide_render = True


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("--zip", required=True, help="packaged add-on (tools/package_addon.py)")
    ap.add_argument("--out", default="out/blender")
    ap.add_argument("--samples", type=int, default=24)
    ap.add_argument("--size", type=int, nargs=2, default=(1280, 720))
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    module = blender_graph.enable_addon(os.path.abspath(a.zip))
    evaluator = importlib.import_module(module + ".evaluator")
    tree = blender_graph.build()
    evaluator.flush()
    failed = ["%s: %s" % (n.name, n.fl_message) for n in tree.nodes if n.fl_state != "OK"]
    if failed:
        sys.exit("demo graph failed: %s" % failed)
    for n in tree.nodes:
        print("  %-16s %8.2f ms  %s" % (n.name, n.fl_time_ms, n.fl_info.replace("\n", "; ")))
    # The graph's default cells are for live editing; the picture gets twice as many each way
    # (smooth shading of a coarse mesh shows its triangles at the deck edge and the seam).
    comp = tree.nodes["Compose"]
    for name in ("Hull Cells U", "Hull Cells V", "Bulb Cells U", "Bulb Cells V"):
        comp.inputs[name].default_value *= 2
    evaluator.flush()
    if comp.fl_state != "OK" or tree.nodes["Forebody Output"].fl_state != "OK":
        sys.exit("finer composition failed: %s" % comp.fl_message)
    print("  render mesh: %s" % comp.fl_info.replace("\n", "; "))
    scene = bpy.context.scene
    stage(scene)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = a.samples
    scene.render.resolution_x, scene.render.resolution_y = a.size
    scene.render.resolution_percentage = 100
    scene.render.filepath = os.path.join(out, "forebody.png")
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "forebody.blend"))
    bpy.ops.render.render(write_still=True)
    print("wrote %s and %s" % (os.path.join(out, "forebody.blend"), scene.render.filepath))


main()
