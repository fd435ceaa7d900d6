"""The example Fairlines node graph, built by script with the add-on's scripting API
(fairlines_blender.api) in Blender (GUI, `blender -b`, or the `bpy` module). Used by `make demo`
(examples/blender_demo.py), the latency bench and the headless tests.

The whole Panamax container ship, designed from its particulars exactly as the Python example
does (`fl.design_hull(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73,
bulb=True)`, saved as examples/container_ship.json): Particulars -> SAC basic curve (volume and
LCB switchable) -> sections and the fair-skinned bare hull (hydrostatics on the node) -> the
hull's bulbous bow -> blending surface (C1 to hull and bulb) -> Boolean union -> the Ship object
(mirrored and welded by the engine, painted to the design waterline). The bare hull is also
tessellated with curvature attributes (zebra material) and drawn as lines.
"""

import os

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DESCRIPTION = os.path.join(HERE, "container_ship.json")
# The particulars of examples/container_ship.json (metres; LCB from the AP).
PARTICULARS = dict(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)
LPP, BEAM, DRAFT, DEPTH = (PARTICULARS[k] for k in ("lpp", "breadth", "draft", "depth"))
TREE_NAME = "Fairlines Ship"


def description_text(name="container_ship.json"):
    """The hull description as a text block, so a saved .blend carries its own input."""
    text = bpy.data.texts.get(name) or bpy.data.texts.new(name)
    text.clear()
    with open(DESCRIPTION, encoding="utf-8") as f:
        text.write(f.read())
    return text


def points_object(grid, name):
    """A point-cloud mesh holding a (rows, cols, 3) grid row by row (input of Points From
    Object; used by the tests)."""
    me = bpy.data.meshes.get(name) or bpy.data.meshes.new(name)
    me.clear_geometry()
    me.vertices.add(grid.shape[0] * grid.shape[1])
    me.vertices.foreach_set("co", grid.reshape(-1).astype(np.float32))
    me.update()
    obj = bpy.data.objects.get(name) or bpy.data.objects.new(name, me)
    if not obj.users_collection:
        bpy.context.scene.collection.objects.link(obj)
    obj.hide_render = True
    return obj


def build(tree_name=TREE_NAME):
    """Create (or rebuild) the example tree; returns it. Node names are stable for scripts."""
    api = _addon_module("api")
    tree = api.new_tree(tree_name)
    P = PARTICULARS
    ship = api.add(tree, "Particulars", "Particulars", (-1450, 300), Lpp=P["lpp"], B=P["breadth"], T=P["draft"],
                   D=P["depth"], Cb=P["cb"], LCB=P["lcb"], bulb=P["bulb"], ship_name="Panamax container ship")
    sac = api.add(tree, "Basic Curve", "SAC", (-1150, 350), curve="sac")
    sections = api.add(tree, "Sections", "Sections", (-850, 650))
    sections_out = api.add(tree, "Lines Output", "Sections Output", (-550, 650), object_name="Sections")
    bare = api.add(tree, "Bare Hull", "Bare Hull", (-850, 350))
    knot = api.add(tree, "Insert Knot", "Refine", (-550, 350), direction="v", Parameter=0.85)
    tess = api.add(tree, "Tessellate", "Tessellate Hull", (-250, 850), Resolution_U=48, Resolution_V=160)
    curv = api.add(tree, "Curvature Analysis", "Curvature", (0, 850))
    hull_out = api.add(tree, "Mesh Output", "Hull Output", (250, 850), object_name="Bare Hull", mirror=True,
                       material="zebra")
    iso = api.add(tree, "Iso Lines", "Lines", (-250, 600), Count_U=9, Count_V=25)
    lines_out = api.add(tree, "Lines Output", "Lines Output", (0, 600), object_name="Hull Lines")
    bow = api.add(tree, "Hull Bulb", "Bulbous Bow", (-850, -100), C_LPR=0.025)  # the default, on a slider
    blend = api.add(tree, "Blend Surface", "Blend", (-250, 0))
    comp = api.add(tree, "Compose (Union)", "Compose", (0, 250), output="full")
    ship_out = api.add(tree, "Mesh Output", "Ship Output", (250, 250), object_name="Ship", mirror=False,
                       material="paint")
    for a, x, b, y in ((ship, "Hull", sac, "Hull"), (sac, "Hull", sections, "Hull"),
                       (sections, "Lines", sections_out, "Lines"), (sac, "Hull", bare, "Hull"),
                       (bare, "Surface", knot, "Surface"), (knot, "Surface", tess, "Surface"),
                       (tess, "Mesh", curv, "Mesh"), (curv, "Mesh", hull_out, "Mesh"),
                       (knot, "Surface", iso, "Surface"), (iso, "Lines", lines_out, "Lines"),
                       (sac, "Hull", bow, "Hull"), (knot, "Surface", blend, "Hull"), (bow, "Surface", blend, "Bulb"),
                       (knot, "Surface", comp, "Hull"), (bow, "Surface", comp, "Bulb"), (blend, "Blend", comp, "Blend"),
                       (comp, "Mesh", ship_out, "Mesh"), (ship, "T", ship_out, "Waterline"),
                       (ship, "T", hull_out, "Waterline")):
        api.link(tree, a, x, b, y)
    return tree


OUTPUTS_TREE_NAME = "Fairlines Ship Outputs"


def build_outputs(tree_name=OUTPUTS_TREE_NAME):
    """A second tree with the output nodes on the same ship: the engine's quad-dominant Hull
    Mesh (into an object and to a mesh file), Hydrostatics of the bare hull at T on Lpp and B,
    and the file writers (CAD, lines plan, curves of form; they write when Export is pressed).
    Kept apart from build()'s tree, whose every change must redraw within a frame."""
    api = _addon_module("api")
    tree = api.new_tree(tree_name)
    P = PARTICULARS
    ship = api.add(tree, "Particulars", "Particulars", (-1000, 250), Lpp=P["lpp"], B=P["breadth"], T=P["draft"],
                   D=P["depth"], Cb=P["cb"], LCB=P["lcb"], bulb=P["bulb"], ship_name="Panamax container ship")
    bare = api.add(tree, "Bare Hull", "Bare Hull", (-650, 650))
    hydro = api.add(tree, "Hydrostatics", "Hydrostatics", (-300, 700))
    mesh = api.add(tree, "Hull Mesh", "Hull Mesh", (-650, 150), Size=8.0)
    mesh_out = api.add(tree, "Mesh Output", "Quad Hull Output", (-300, 250), object_name="Quad Hull", mirror=True)
    export_mesh = api.add(tree, "Export Mesh", "Export Mesh", (-300, -150))
    cad = api.add(tree, "Export CAD", "Export CAD", (100, 700))
    plan = api.add(tree, "Lines Plan", "Lines Plan", (100, 350))
    cof = api.add(tree, "Curves of Form", "Curves of Form", (100, 0))
    for a, x, b, y in ((ship, "Hull", bare, "Hull"), (bare, "Surface", hydro, "Surface"), (ship, "T", hydro, "Draft"),
                       (ship, "Lpp", hydro, "Lpp"), (ship, "B", hydro, "Beam"), (ship, "Hull", mesh, "Hull"),
                       (mesh, "Mesh", mesh_out, "Mesh"), (ship, "T", mesh_out, "Waterline"),
                       (mesh, "Mesh", export_mesh, "Mesh"), (ship, "Hull", cad, "Hull"),
                       (ship, "Hull", plan, "Hull"), (ship, "Hull", cof, "Hull")):
        api.link(tree, a, x, b, y)
    return tree


def enable_addon(zip_path, tmp_user_dir=None):
    """Install and enable the packaged add-on the way a user does: as an extension on
    Blender 4.2+, as a legacy add-on before. Returns the add-on's module name."""
    import addon_utils

    def fail(exc):
        raise exc
    if bpy.app.version >= (4, 2, 0):
        bpy.ops.extensions.package_install_files(filepath=zip_path, repo="user_default",
                                                 enable_on_install=True)
        return "bl_ext.user_default.fairlines"
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    addon_utils.enable("fairlines_blender", default_set=True, handle_error=fail)
    return "fairlines_blender"


def _addon_module(sub):
    """The installed add-on's submodule, whichever way it was installed (extension or legacy)."""
    import sys
    for name in ("fairlines_blender", "bl_ext.user_default.fairlines"):
        mod = sys.modules.get(name + "." + sub)
        if mod is not None:
            return mod
    raise RuntimeError("the Fairlines add-on is not enabled")
