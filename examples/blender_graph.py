"""The example Fairlines node graph, built by script in Blender (GUI, `blender -b`, or the
`bpy` module). Used by `make demo` (examples/blender_demo.py) and the headless tests.

Until the hull operators land (design curves, fair skin, bulbous bow), the example forebody is
a fitted surface: an offsets grid (stations x waterlines) of a full-bodied forebody with the
Panamax principal dimensions, fitted by the engine, refined by knot insertion, tessellated,
analysed for curvature and drawn as iso-lines; plus a bulb, an ellipse revolved about its
axis (length set on the Ellipse node), half of it revolved, as its own subdomain object.
"""

import bpy
import numpy as np

LPP, BEAM, DEPTH = 244.8, 32.25, 19.0  # metres (Lpp and B of SPEC §2; depth to the deck)
TREE_NAME = "Fairlines Forebody"


def offsets_grid(n_stations=13, n_waterlines=9):
    """Half-breadths of an illustrative forebody: stations from midship (x = Lpp/2) to the FP,
    waterlines from the keel to the deck. Example input data, not an engine operator."""
    x = np.linspace(0.5 * LPP, LPP, n_stations)
    z = np.linspace(0.0, DEPTH, n_waterlines)
    xi = (x - 0.5 * LPP) / (0.5 * LPP)            # 0 at midship, 1 at the FP
    zeta = z / DEPTH
    waterplane = 1.0 - xi[:, None] ** 3            # fine entrance toward the bow
    section = 1.0 - (1.0 - zeta[None, :]) ** 6    # full sections with a bilge radius
    y = 0.5 * BEAM * np.clip(waterplane * section, 0.0, None) + 0.05
    X, Z = np.meshgrid(x, z, indexing="ij")
    return np.stack([X, y, Z], axis=-1)           # (stations, waterlines, 3)


def offsets_object(name="Forebody Offsets"):
    """A point-cloud mesh holding the offsets grid, row by row (stations)."""
    grid = offsets_grid()
    me = bpy.data.meshes.get(name) or bpy.data.meshes.new(name)
    me.clear_geometry()
    me.vertices.add(grid.shape[0] * grid.shape[1])
    me.vertices.foreach_set("co", grid.reshape(-1).astype(np.float32))
    me.update()
    obj = bpy.data.objects.get(name) or bpy.data.objects.new(name, me)
    if not obj.users_collection:
        bpy.context.scene.collection.objects.link(obj)
    obj.hide_render = True
    return obj, grid.shape


def build(tree_name=TREE_NAME):
    """Create (or rebuild) the example tree; returns it. Node names are stable for scripts."""
    ids = _addon_module("ids")
    old = bpy.data.node_groups.get(tree_name)
    if old is not None:
        bpy.data.node_groups.remove(old)
    tree = bpy.data.node_groups.new(tree_name, ids.TREE)
    obj, shape = offsets_object()

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

    pts = node(ids.NODE_POINTS_FROM_OBJECT, "Offsets", -900, 200, source=obj, columns=shape[1])
    fit = node(ids.NODE_FIT_SURFACE, "Fit Forebody", -650, 200)
    fit.inputs["Control Points U"].use = True
    fit.inputs["Control Points U"].default_value = 9
    fit.inputs["Control Points V"].use = True
    fit.inputs["Control Points V"].default_value = 7
    knot = node(ids.NODE_INSERT_KNOT, "Refine", -400, 200, direction="u", in_Parameter=0.85)
    tess = node(ids.NODE_TESSELLATE, "Tessellate Hull", -150, 300)
    tess.inputs["Resolution U"].default_value = 96
    tess.inputs["Resolution V"].default_value = 48
    curv = node(ids.NODE_CURVATURE, "Curvature", 100, 300)
    hull_out = node(ids.NODE_MESH_OUTPUT, "Hull Output", 350, 300, object_name="Forebody", mirror=True)
    iso = node(ids.NODE_ISO_LINES, "Lines", -150, 0)
    iso.inputs["Count U"].default_value = 13
    iso.inputs["Count V"].default_value = 9
    lines_out = node(ids.NODE_LINES_OUTPUT, "Lines Output", 100, 0, object_name="Forebody Lines")

    ell = node(ids.NODE_ELLIPSE, "Bulb Profile", -900, -350)
    ell.inputs["Center"].default_value = (LPP - 1.0, 0.0, 6.0)
    ell.inputs["Semi-axis A"].default_value = (8.0, 0.0, 0.0)    # bulb half-length (m)
    ell.inputs["Semi-axis B"].default_value = (0.0, 0.0, 4.2)    # bulb half-height (m)
    half = node(ids.NODE_TRIM_CURVE, "Bulb Half Profile", -650, -350)  # nose, over the top, tail
    half.inputs["Start"].default_value = 0.0
    half.inputs["End"].default_value = 0.5
    rev = node(ids.NODE_REVOLVE, "Bulb", -400, -350)
    rev.inputs["Axis Point"].default_value = (LPP - 1.0, 0.0, 6.0)
    rev.inputs["Axis Direction"].default_value = (-1.0, 0.0, 0.0)  # S_u x S_v outward
    btess = node(ids.NODE_TESSELLATE, "Tessellate Bulb", -150, -350)
    btess.inputs["Resolution U"].default_value = 64
    btess.inputs["Resolution V"].default_value = 48
    bulb_out = node(ids.NODE_MESH_OUTPUT, "Bulb Output", 100, -350, object_name="Bulb", mirror=False)

    L = tree.links.new
    L(pts.outputs["Points"], fit.inputs["Points"])
    L(fit.outputs["Surface"], knot.inputs["Surface"])
    L(knot.outputs["Surface"], tess.inputs["Surface"])
    L(tess.outputs["Mesh"], curv.inputs["Mesh"])
    L(curv.outputs["Mesh"], hull_out.inputs["Mesh"])
    L(knot.outputs["Surface"], iso.inputs["Surface"])
    L(iso.outputs["Lines"], lines_out.inputs["Lines"])
    L(ell.outputs["Curve"], half.inputs["Curve"])
    L(half.outputs["Curve"], rev.inputs["Profile"])
    L(rev.outputs["Surface"], btess.inputs["Surface"])
    L(btess.outputs["Mesh"], bulb_out.inputs["Mesh"])
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
