"""The example Fairlines node graph, built by script in Blender (GUI, `blender -b`, or the
`bpy` module). Used by `make demo` (examples/blender_demo.py) and the headless tests.

The Panamax container ship's forebody (examples/panamax_forebody.json, Lpp 244.8 m, B 32.25 m,
T 11.0 m): principal dimensions -> hull description (the JSON, kept in the .blend as a text
block) -> SAC basic curve (displaced volume and LCB as switchable form parameters) -> sections
and the fair-skinned bare hull -> bulbous bow from its Kracht coefficients -> blending surface
(C1 to hull and bulb) -> Boolean union -> the Forebody object (mirrored and welded by the
engine). The bare hull is also tessellated with curvature attributes and drawn as lines.
"""

import os

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DESCRIPTION = os.path.join(HERE, "panamax_forebody.json")
LPP, BEAM, DRAFT, DEPTH = 244.8, 32.25, 11.0, 19.0  # metres (SPEC section 2; depth to the deck)
MIDSHIP_AREA = 349.4           # m^2, Am = 0.985 B T as in the description's SAC
DISPLACEMENT = 0.65 * LPP * BEAM * DRAFT  # m^3, the ship's (Cb 0.65) for the Kracht volume
TREE_NAME = "Fairlines Forebody"


def description_text(name="panamax_forebody.json"):
    """The hull description as a text block, so the saved .blend carries its own input."""
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
    ids = _addon_module("ids")
    old = bpy.data.node_groups.get(tree_name)
    if old is not None:
        bpy.data.node_groups.remove(old)
    tree = bpy.data.node_groups.new(tree_name, ids.TREE)

    def node(idname, name, x, y, **values):
        n = tree.nodes.new(idname)
        n.name = n.label = name
        n.location = (x, y)
        for key, value in values.items():
            if key.startswith("in_"):
                n.inputs[key[3:].replace("_", " ")].default_value = value
            else:
                setattr(n, key, value)
        return n

    def switch_on(n, socket, value):
        n.inputs[socket].use = True
        n.inputs[socket].default_value = value

    dims = node(ids.NODE_PRINCIPAL_DIMENSIONS, "Principal Dimensions", -1450, 300,
                in_Lpp=LPP, in_B=BEAM, in_T=DRAFT, in_D=DEPTH)
    desc = node(ids.NODE_HULL_DESCRIPTION, "Hull Description", -1150, 350, text=description_text())
    sac = node(ids.NODE_BASIC_CURVE, "SAC", -850, 350, curve="sac")
    switch_on(sac, "Area", 26500.0)   # forebody displaced volume, m^3
    switch_on(sac, "xC", 166.5)       # its LCB, m from AP
    sections = node(ids.NODE_SECTIONS, "Sections", -550, 650)
    sections_out = node(ids.NODE_LINES_OUTPUT, "Sections Output", -300, 650, object_name="Sections")
    bare = node(ids.NODE_BARE_HULL, "Bare Hull", -550, 350)
    knot = node(ids.NODE_INSERT_KNOT, "Refine", -300, 350, direction="v", in_Parameter=0.85)
    tess = node(ids.NODE_TESSELLATE, "Tessellate Hull", 0, 850, flip=True)  # u deck -> keel: S_u x S_v inward
    tess.inputs["Resolution U"].default_value = 48
    tess.inputs["Resolution V"].default_value = 96
    curv = node(ids.NODE_CURVATURE, "Curvature", 250, 850)
    hull_out = node(ids.NODE_MESH_OUTPUT, "Hull Output", 500, 850, object_name="Bare Forebody", mirror=True)
    iso = node(ids.NODE_ISO_LINES, "Lines", 0, 600)
    iso.inputs["Count U"].default_value = 9
    iso.inputs["Count V"].default_value = 13
    lines_out = node(ids.NODE_LINES_OUTPUT, "Lines Output", 250, 600, object_name="Forebody Lines")

    bow = node(ids.NODE_BULBOUS_BOW, "Bulbous Bow", -850, -150)
    bow.inputs["Midship Area"].default_value = MIDSHIP_AREA
    bow.inputs["Displacement"].default_value = DISPLACEMENT
    blend = node(ids.NODE_BLEND, "Blend", -300, 0)
    comp = node(ids.NODE_COMPOSE, "Compose", 0, 250, output="full")
    fore_out = node(ids.NODE_MESH_OUTPUT, "Forebody Output", 250, 250, object_name="Forebody", mirror=False)

    L = tree.links.new
    for name in ("Lpp", "B", "T", "D"):
        L(dims.outputs[name], desc.inputs[name])
    L(dims.outputs["Lpp"], bow.inputs["Lpp"])
    L(dims.outputs["B"], bow.inputs["Beam"])
    L(dims.outputs["T"], bow.inputs["Draft FP"])
    L(desc.outputs["Hull"], sac.inputs["Hull"])
    L(sac.outputs["Hull"], sections.inputs["Hull"])
    L(sections.outputs["Lines"], sections_out.inputs["Lines"])
    L(sac.outputs["Hull"], bare.inputs["Hull"])
    L(bare.outputs["Surface"], knot.inputs["Surface"])
    L(knot.outputs["Surface"], tess.inputs["Surface"])
    L(tess.outputs["Mesh"], curv.inputs["Mesh"])
    L(curv.outputs["Mesh"], hull_out.inputs["Mesh"])
    L(knot.outputs["Surface"], iso.inputs["Surface"])
    L(iso.outputs["Lines"], lines_out.inputs["Lines"])
    L(knot.outputs["Surface"], blend.inputs["Hull"])
    L(bow.outputs["Surface"], blend.inputs["Bulb"])
    L(knot.outputs["Surface"], comp.inputs["Hull"])
    L(bow.outputs["Surface"], comp.inputs["Bulb"])
    L(blend.outputs["Blend"], comp.inputs["Blend"])
    L(comp.outputs["Mesh"], fore_out.inputs["Mesh"])
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
    for name in ("bl_ext.user_default.fairlines", "fairlines_blender"):
        mod = sys.modules.get(name + "." + sub)
        if mod is not None:
            return mod
    raise RuntimeError("the Fairlines add-on is not enabled")
