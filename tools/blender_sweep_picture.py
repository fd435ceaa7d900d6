"""docs/blender_sweep.png: the Sweep node's variants side by side, rendered by Workbench in the
bpy module (headless):

    BLENDER_USER_RESOURCES=build/sweep_pic .venv-bpy/bin/python tools/blender_sweep_picture.py \
        --zip dist/fairlines_blender-0.1.0-extension.zip --out docs/blender_sweep.png
"""

import argparse
import importlib
import math
import os
import sys
import tempfile

import bpy
from mathutils import Vector  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "examples"))
import blender_graph  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--zip", required=True)
ap.add_argument("--out", required=True)
args = ap.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:])

api = importlib.import_module(blender_graph.enable_addon(os.path.abspath(args.zip)) + ".api")
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
tree = api.new_tree("Sweep")
api.add(tree, "Particulars", name="Ship")
sweep = api.add(tree, "Sweep", name="Sweep", vary_volume=4.0, vary_lcb=2.0, vary_bulb=0.0, levels=3)
sweep.filepath = os.path.join(tempfile.mkdtemp(), "sweep.parquet")
api.link(tree, "Ship", "Hull", sweep, "Hull")
api.evaluate(tree)
api.export(tree, sweep)
print(sweep.fl_info)

coll = bpy.data.collections["Fairlines Sweep"]
meshes = [o for o in coll.objects if o.type == "MESH"]
lo = Vector([min(v[i] for o in meshes for v in o.bound_box) for i in range(3)])
hi = Vector([max(v[i] for o in meshes for v in o.bound_box) for i in range(3)])
centre = (lo + hi) / 2
scene = bpy.context.scene
cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
scene.collection.objects.link(cam)
# Top view, bow up, the variants side by side from left to right.
cam.location = Vector((centre.x - 0.1 * (hi.x - lo.x), centre.y, hi.z + 500.0))
cam.rotation_euler = (0.0, 0.0, math.radians(-90))
cam.data.type = "ORTHO"
cam.data.ortho_scale = 1.1 * max(hi.y - lo.y, (hi.x - lo.x) * 1.25 * 1800 / 1000)
cam.data.clip_end = 2000.0
scene.camera = cam
scene.render.engine = "BLENDER_WORKBENCH"
scene.display.shading.light = "STUDIO"
scene.display.shading.color_type = "OBJECT"
for obj in coll.objects:  # red hulls, near-black labels
    obj.color = (0.85, 0.3, 0.2, 1.0) if obj.type == "MESH" else (0.05, 0.05, 0.08, 1.0)
scene.display.shading.show_cavity = True
scene.world = scene.world or bpy.data.worlds.new("World")
scene.world.color = (0.9, 0.91, 0.93)  # a light page: dark labels and the red hulls stand out
scene.render.resolution_x, scene.render.resolution_y = 1800, 1000
scene.render.filepath = os.path.abspath(args.out)
bpy.ops.render.render(write_still=True)
print("wrote", args.out)
