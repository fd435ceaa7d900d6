"""Checks that run inside a real Blender: the `bpy` module from PyPI (4.2+ extension install)
or a Blender executable such as Debian's 3.4 (legacy add-on install).

    python  blender_checks.py --zip dist/...-extension.zip --mode extension --tmp DIR
    blender -b --factory-startup --python-exit-code 1 --python blender_checks.py -- \
            --zip dist/...-legacy.zip --mode legacy --tmp DIR

The add-on is installed the way a user installs it (from the packaged zip), so the shipped
engine wheel / vendored engine is what gets imported. Every check asserts behaviour; the
script exits 1 on the first failure with the reason. --bench N times property changes instead.
"""

import argparse
import importlib
import json
import math
import os
import statistics
import sys
import time
import traceback

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "examples"))
import blender_graph  # noqa: E402

sys.path.insert(0, HERE)
import random_properties  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
ap = argparse.ArgumentParser()
ap.add_argument("--zip", required=True)
ap.add_argument("--mode", choices=("extension", "legacy"), required=True)
ap.add_argument("--tmp", required=True)
ap.add_argument("--bench", type=int, default=0)
ap.add_argument("--json", default="")
ap.add_argument("--random-changes", type=int, default=1500, help="random property changes (0: skip)")
args = ap.parse_args(argv)
os.makedirs(args.tmp, exist_ok=True)

MODULE = "bl_ext.user_default.fairlines" if args.mode == "extension" else "fairlines_blender"
results = {"blender": bpy.app.version_string, "python": sys.version.split()[0], "mode": args.mode}


# ---- helpers --------------------------------------------------------------------------------
def install():
    name = blender_graph.enable_addon(args.zip)
    check(name == MODULE, "installed as %s, expected %s" % (name, MODULE))
    return importlib.import_module(MODULE)


def _raise(exc):
    raise exc


def disable():
    import addon_utils
    addon_utils.disable(MODULE, default_set=True, handle_error=_raise)


def sub(name):
    return importlib.import_module(MODULE + "." + name)


def mesh_arrays(obj, evaluated=True):
    """Vertices and fan-triangulated faces of an object (after modifiers when evaluated)."""
    if evaluated:
        dg = bpy.context.evaluated_depsgraph_get()
        ev = obj.evaluated_get(dg)
        me = ev.to_mesh()
    else:
        ev, me = None, obj.data
    try:
        v = np.empty(len(me.vertices) * 3)
        me.vertices.foreach_get("co", v)
        start = np.empty(len(me.polygons), dtype=np.int64)
        total = np.empty(len(me.polygons), dtype=np.int64)
        me.polygons.foreach_get("loop_start", start)
        me.polygons.foreach_get("loop_total", total)
        loops = np.empty(len(me.loops), dtype=np.int64)
        me.loops.foreach_get("vertex_index", loops)
    finally:
        if ev is not None:
            ev.to_mesh_clear()
    v = v.reshape(-1, 3)
    tris = [np.column_stack([loops[start[m]], loops[start[m] + i], loops[start[m] + i + 1]])
            for i in range(1, int(total.max()) - 1) for m in [total > i + 1]] if len(total) else []
    return v, (np.concatenate(tris) if tris else np.zeros((0, 3), dtype=np.int64))


def volume(obj, evaluated=True):
    """Signed enclosed volume (divergence theorem): positive when the normals point outward."""
    v, t = mesh_arrays(obj, evaluated)
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0


def coords(obj):
    me = obj.data
    v = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", v)
    return v.reshape(-1, 3)


def registered(idname):
    """The Python class registered under a bl_idname (bpy.types does not list add-on types)."""
    for base in (bpy.types.NodeTree, bpy.types.Node, bpy.types.NodeSocket):
        cls = base.bl_rna_get_subclass_py(idname)
        if cls is not None:
            return cls
    return None


def check(cond, message):
    if not cond:
        raise AssertionError(message)


# ---- checks -----------------------------------------------------------------------------------
def t_register():
    addon = install()
    ids = sub("ids")
    check(registered(ids.TREE) is not None, "tree type %s not registered" % ids.TREE)
    names = {k: v for k, v in vars(ids).items() if k.isupper() and isinstance(v, str)}
    idnames = [v for k, v in names.items() if k.startswith(("NODE_", "SOCKET_", "TREE"))]
    check(len(idnames) == len(set(idnames)), "duplicate bl_idname in ids.py")
    for idname in idnames:
        check(registered(idname) is not None, "%s not registered" % idname)
    eng = sub("engine")
    check(eng.available(), "engine did not import: " + eng.IMPORT_ERROR)
    results["engine_from"] = os.path.dirname(eng.fl.__file__)
    prefs = bpy.context.preferences.addons[MODULE].preferences
    check(prefs is not None and type(prefs).__name__ == "FairlinesPreferences", "no add-on preferences")
    if args.mode == "legacy":
        # Re-installing over the running add-on reloads it; the loaded engine library must
        # not be rewritten under Blender's feet (Blender crashes when it is).
        eng.fl.sphere((0.0, 0.0, 0.0), 1.0)
        install()
        check(sub("engine").available(), "engine lost after re-install")
        tree = bpy.data.node_groups.new("Reinstall", sub("ids").TREE)
        node = tree.nodes.new(sub("ids").NODE_ELLIPSE)
        sub("evaluator").evaluate(tree)
        check(node.fl_state == "OK", "after re-install: %s" % node.fl_message)
        bpy.data.node_groups.remove(tree)
    return addon


def closed_edges(obj):
    """True when every edge of the object's mesh is shared by exactly two faces (watertight)."""
    me = obj.data
    ev = np.empty(len(me.edges) * 2, dtype=np.int64)
    me.edges.foreach_get("vertices", ev)
    v, t = mesh_arrays(obj, evaluated=False)
    e = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return bool(len(counts) and (counts == 2).all())


def package_forebody(tree, **bulb_changes):
    """The composed ship computed by the engine package alone from the graph's own hull
    surface and the Hull Bulb node's hull (with Kracht changes): what the nodes must reproduce."""
    import fairlines as fl
    ev = sub("evaluator")
    surface = ev.outputs_of(tree, "Refine")["Surface"]
    hull = ev.outputs_of(tree, "SAC")["Hull"]
    bulb = hull.bulbous_bow(**bulb_changes)
    blend = fl.seam_blend_placement(surface, bulb).blend_surface()
    return fl.compose([surface, bulb, blend]), hull.ship_particulars()


def python_example():
    """The Python example's hull (the same ship the example graph designs)."""
    import fairlines as fl
    return fl.Hull.from_json(blender_graph.DESCRIPTION)


def hydro_equal(a, b, rel=1e-6):
    """Every field of two fl.Hydrostatics agrees to rel (the nodes' sockets hold single precision)."""
    da, db = a.as_dict(), b.as_dict()
    bad = {k: (da[k], db[k]) for k in da if abs(da[k] - db[k]) > rel * max(1.0, abs(db[k]))}
    return not bad, bad


def signed_volume_positive(names):
    """Signed volume (divergence theorem about the origin) of every named object after its
    modifiers: > 0 when the faces point outward."""
    return {name: volume(bpy.data.objects[name]) for name in names}


def t_build():
    ev = sub("evaluator")
    tree = blender_graph.build()
    ev.flush()
    ran = ev.evaluate(tree)  # nothing changed since the flush: nothing may run again
    check(ran == [], "re-evaluating an unchanged tree ran %s" % ran)
    bad = ["%s: %s" % (n.name, n.fl_message) for n in tree.nodes if n.fl_state != "OK"]
    check(not bad, "nodes not OK after build: %s" % bad)
    hull = bpy.data.objects["Bare Hull"]
    check(len(hull.data.vertices) == 48 * 160, "hull has %d vertices" % len(hull.data.vertices))
    check(len(hull.data.polygons) == 47 * 159, "hull has %d faces" % len(hull.data.polygons))
    ids = sub("ids")
    for attr in (ids.ATTR_GAUSSIAN, ids.ATTR_MEAN):
        a = hull.data.attributes.get(attr)
        check(a is not None and a.domain == "POINT" and len(a.data) == 48 * 160, "attribute %s missing" % attr)
    k = np.empty(48 * 160, dtype=np.float32)
    hull.data.attributes[ids.ATTR_GAUSSIAN].data.foreach_get("value", k)
    check(np.isfinite(k).all() and np.ptp(k) > 0, "gaussian curvature not finite/varying")
    mod = hull.modifiers.get(ids.GN_MODIFIER)
    check(mod is not None and mod.node_group is not None and mod.node_group.name == ids.GN_GROUP,
          "hull lacks the Fairlines Geometry Nodes modifier")
    v_eval, _ = mesh_arrays(hull)
    # The weld joins the two halves where they meet on the centre plane (keel line and stem)
    # and the points a degenerate edge repeats (the deck line ends on the stem): the mirrored
    # hull has the distinct points of both halves.
    half = coords(hull)
    on_plane = int((np.abs(half[:, 1]) < 1e-4).sum())
    check(on_plane >= 160 + 48 - 1, "only %d vertices on the keel line and stem" % on_plane)
    both = np.concatenate([half, half * (1.0, -1.0, 1.0)])
    distinct = len(np.unique(np.round(both / 1e-4).astype(np.int64), axis=0))
    check(abs(len(v_eval) - distinct) <= 2, "mirrored hull has %d vertices, expected %d" % (len(v_eval), distinct))
    check(v_eval[:, 1].min() < -10 and v_eval[:, 1].max() > 10, "mirror did not produce the port side")
    lines = bpy.data.objects["Hull Lines"]
    check(lines.type == "CURVE" and len(lines.data.splines) == 25 + 9,
          "lines object has %d splines" % len(lines.data.splines))
    # The composed forebody: bare hull + bulb + blend, one closed full hull.
    fore = bpy.data.objects["Ship"]
    check(closed_edges(fore), "composed forebody is not watertight")
    vol = volume(fore, evaluated=False)
    node_vol = ev.outputs_of(tree, "Compose")["Volume"]
    # Blender stores vertices in single precision: object and engine agree to ~1e-7.
    check(abs(vol / node_vol - 1) < 1e-6, "object volume %.3f vs Compose node %.3f" % (vol, node_vol))
    ref, ship = package_forebody(tree)
    check(abs(vol / (2 * ref.volume) - 1) < 1e-6, "nodes %.6f m3, package %.6f m3" % (vol, 2 * ref.volume))
    # The Python example (the JSON the designer wrote) is the same hull: same surface, same
    # hydrostatics, and its composed hull has the graph's volume.
    example = python_example()
    cp_graph = np.asarray(ev.outputs_of(tree, "Bare Hull")["Surface"].control_points)
    cp_example = np.asarray(example.bare_hull_surface().control_points)
    check(cp_graph.shape == cp_example.shape and np.allclose(cp_graph, cp_example, atol=1e-6),
          "the graph's bare hull is not the Python example's")
    ok, bad = hydro_equal(sub("api").hydrostatics(tree, "Bare Hull"), example.hydrostatics())
    check(ok, "Bare Hull node hydrostatics differ from Hull.hydrostatics(): %s" % bad)
    composed = example.composed_hull()
    check(abs(vol / (2 * composed.volume) - 1) < 1e-6, "nodes %.3f m3, Python example composed_hull %.3f m3" % (
        vol, 2 * composed.volume))
    results["composed_vs_python_example"] = [round(vol, 3), round(2 * composed.volume, 3)]
    v = coords(fore)
    nose = v[:, 0].max() - blender_graph.LPP
    protrusion = ev.outputs_of(tree, "Bulbous Bow")["Protrusion"]
    check(abs(nose / protrusion - 1) < 0.01, "bulb protrudes %.3f m, node says %.3f" % (nose, protrusion))
    check(v[:, 1].min() < -15 and v[:, 1].max() > 15, "composed hull is not the full (mirrored) hull")
    check("blend" in tree.nodes["Compose"].fl_info, "no blend reported: %s" % tree.nodes["Compose"].fl_info)
    vols = signed_volume_positive(["Ship", "Bare Hull"])
    check(all(x > 0 for x in vols.values()), "inside-out output meshes: %s" % vols)
    results["signed_volumes_m3"] = {k: round(x, 1) for k, x in vols.items()}
    results["forebody_volume_m3"] = round(vol, 2)
    results["compose_info"] = tree.nodes["Compose"].fl_info
    return tree


def forward_volume(obj, x_fp):
    """Volume of the closed full mesh forward of x = x_fp below the waterline (divergence
    theorem with the field (x - x_fp, 0, 0) over the surface forward of the cut, which
    vanishes on it; measure_kracht's clip at the draft)."""
    import fairlines as fl
    v, t = mesh_arrays(obj, evaluated=False)
    k = fl.measure_kracht(fl.Mesh(v, t), x_fp=x_fp, lpp=1.0, beam=1.0, draft_fp=blender_graph.DRAFT, midship_area=1.0,
                          displacement_volume=1.0)
    return k["c_vpr"] / 2.0  # measure_kracht doubles a half hull; this mesh is the full one


def t_bulb_length(tree):
    """A fuller bulb (C_VPR up) adds about that much volume forward of FP. A longer bulb (C_LPR
    up) with the same volume forward of FP (C_VPR kept): the nose moves forward by the change
    times Lpp, the volume forward of FP stays C_VPR x displacement, and the whole mesh equals the
    engine package's composition."""
    ev = sub("evaluator")
    fore = bpy.data.objects["Ship"]
    bare = bpy.data.objects["Bare Hull"]
    L = blender_graph.LPP
    node = tree.nodes["Bulbous Bow"]
    hull = ev.outputs_of(tree, "SAC")["Hull"]
    disp = hull.ship_particulars()["displacement_volume"]
    c_vpr = hull.bulbous_bow().kracht["c_vpr"]
    v0, x0, bare0, fore0 = volume(fore, False), coords(fore)[:, 0].max(), coords(bare), coords(fore).copy()
    fwd0 = forward_volume(fore, L)
    # Below the waterline (the raked stem above it lies forward of FP too, and is not bulb).
    check(abs(fwd0 / (c_vpr * disp) - 1) < 0.05, "volume forward of FP %.2f m3, C_VPR asks %.2f" % (
        fwd0, c_vpr * disp))
    # A fuller bulb first (at the default length: the longer one below, fuller too, leaves the
    # fine forefoot of a hull whose ship holds the particulars and meets it in two curves): C_VPR
    # up by 0.0004 adds 0.0004 x displacement forward of FP.
    node.inputs["C_VPR"].use = True
    node.inputs["C_VPR"].default_value = c_vpr + 0.0004
    ev.flush()
    check(node.fl_state == "OK" and tree.nodes["Ship Output"].fl_state == "OK", node.fl_message)
    fwd2, v2 = forward_volume(fore, L), volume(fore, False)
    check(abs((fwd2 - fwd0) / (0.0004 * disp) - 1) < 0.1, "forward volume grew %.2f m3, expected %.2f" % (
        fwd2 - fwd0, 0.0004 * disp))
    check(v2 > v0, "a fuller bulb did not add volume (%.2f -> %.2f m3)" % (v0, v2))
    results["bulb_volume"] = {"forward_volume_added_m3": round(fwd2 - fwd0, 2), "expected_m3": round(0.0004 * disp, 2)}
    node.inputs["C_VPR"].use = False
    ev.flush()
    check(np.array_equal(coords(fore), fore0), "the default bulb did not come back")
    node.inputs["C_LPR"].use = True
    node.inputs["C_LPR"].default_value = 0.032
    # Deferred: the change queued the tree for a timer; nothing ran inside the callback.
    check(coords(fore)[:, 0].max() == x0, "evaluation ran inside the update callback")
    check(tree.name in ev._pending, "property change did not queue the tree")
    blend_node = tree.nodes["Blend"]
    blend_info0 = blend_node.fl_info
    ev.flush(later=False)  # the timer's first tick: the forebody, not yet the Blend's own surface
    check(coords(fore)[:, 0].max() != x0, "the forebody waited for the Blend node's surface")
    check(blend_node.fl_info == blend_info0 and "Surface" not in ev._cache[(tree.name, "Blend")].outputs,
          "the Blend node's surface was not deferred")
    ev.flush()
    ran = set(ev.last_stats["evaluated"])
    check(ran == {"Bulbous Bow", "Blend", "Compose", "Ship Output"}, "a bulb change re-ran %s" % sorted(ran))
    import fairlines as fl
    bi = blend_node.inputs  # single-precision socket values, as the node passes them
    ref_blend = fl.seam_blend_placement(
        ev.outputs_of(tree, "Refine")["Surface"], ev.outputs_of(tree, "Bulbous Bow")["Surface"],
        clearance_u=bi["Clearance U"].default_value, clearance_v=bi["Clearance V"].default_value,
        bulb_clearance=bi["Bulb Clearance"].default_value,
        tension=bi["Tension"].default_value).blend_surface(samples=bi["Sections"].default_value)
    check(np.array_equal(np.asarray(ev.outputs_of(tree, "Blend")["Surface"].control_points),
                         np.asarray(ref_blend.surface.control_points)), "the Blend node's surface is not fl.seam_blend's")
    check(blend_node.fl_info != blend_info0 and "%.3f deg at hull" % ref_blend.at_a["max_angle_deg"] in blend_node.fl_info,
          "the Blend node's info: %s" % blend_node.fl_info)
    # The Compose node measures its blend's continuity in a deferred job: the package's figures.
    ref_c = fl.compose([ev.outputs_of(tree, "Refine")["Surface"], ev.outputs_of(tree, "Bulbous Bow")["Surface"],
                        ref_blend])
    want = "blend %.3f / %.3f deg" % tuple(d["max_angle_deg"] for d in ref_c.blend_continuity)
    check(want in tree.nodes["Compose"].fl_info, "Compose info %r lacks %r" % (tree.nodes["Compose"].fl_info, want))
    x1 = coords(fore)[:, 0].max()
    check(abs((x1 - x0) / (0.007 * L) - 1) < 0.02, "nose moved %.3f m, expected %.3f" % (x1 - x0, 0.007 * L))
    fwd1 = forward_volume(fore, L)
    check(abs((fwd1 - fwd0) / (c_vpr * disp)) < 0.03, "longer bulb: forward volume %.2f -> %.2f m3 (C_VPR %.2f)" % (
        fwd0, fwd1, c_vpr * disp))
    v1 = volume(fore, False)
    check(v1 != v0, "the volume did not change")
    ref, _ = package_forebody(tree, c_lpr=node.inputs["C_LPR"].default_value)
    check(abs(v1 / (2 * ref.volume) - 1) < 1e-6, "nodes %.4f m3 vs package %.4f m3" % (v1, 2 * ref.volume))
    check(np.array_equal(coords(bare), bare0), "the bare hull changed when only the bulb did")
    results["bulb_length"] = {"nose_dx_m": round(x1 - x0, 4), "forward_volume_m3": [round(fwd0, 2), round(fwd1, 2)],
                              "volume_m3": [round(v0, 2), round(v1, 2)]}
    # The timer works in time slices: with a zero budget it runs one node per tick and asks
    # to be called again until the change has reached the object.
    ev.SLICE_MS = 0.0
    try:
        node.inputs["C_LPR"].default_value = 0.025
        ticks = 1
        while ev._on_timer() is not None:
            ticks += 1
            check(ticks < 50, "timer never finished")
    finally:
        ev.SLICE_MS = 30.0
    # One node per tick, plus possibly one tick that only confirms the rest is up to date, then
    # one per deferred job (after the forebody is in the scene): the Blend node's surface and
    # the Compose node's continuity figures.
    check(ticks in (6, 7), "4 bulb nodes and 2 deferred jobs took %d timer ticks" % ticks)
    check(abs(volume(fore, False) / v0 - 1) < 1e-9, "sliced evaluation did not restore the forebody")
    # A topology change (resolution) rebuilds the mesh.
    n0 = len(fore.data.vertices)
    tree.nodes["Compose"].inputs["Hull Cells U"].default_value = 64
    ev.flush()
    check(len(fore.data.vertices) > n0, "resolution change gave %d vertices (was %d)" % (len(fore.data.vertices), n0))
    check(closed_edges(fore) and abs(volume(fore, False) / v0 - 1) < 0.005, "finer composition changed the volume")
    tree.nodes["Compose"].inputs["Hull Cells U"].default_value = 48
    ev.flush()
    check(abs(volume(fore, False) / v0 - 1) < 1e-9, "default resolution not restored")


def t_mesh_rewrite():
    """A mesh written over one of another topology (what a SAC change does to the composed ship)
    has the new corners exactly, one edge per pair of adjacent vertices and nothing for
    Mesh.validate to mend, in every Blender the checks run (the ".corner_vert" attribute from
    4.0 on, loops' vertex_index before)."""
    scene_io, data = sub("scene_io"), sub("data")
    grid = np.array([[x, y, 0.0] for y in range(4) for x in range(5)], dtype=np.float64)
    quads = np.array([[j * 5 + i, j * 5 + i + 1, j * 5 + i + 6, j * 5 + i + 5] for j in range(3) for i in range(4)],
                     dtype=np.int32)
    split = [quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]], [quads[:, [0, 1, 3]], quads[:, [1, 2, 3]]]
    obj = scene_io.ensure_object("Fairlines Rewrite Check", "MESH", None)
    for halves in split + split:  # the same vertices, the diagonals flipped each time
        tris = np.concatenate(halves)
        scene_io.write_mesh(obj, data.MeshData(grid, tris), True, 0.5)
        me = obj.data
        loops = np.empty(len(me.loops), dtype=np.int64)
        me.loops.foreach_get("vertex_index", loops)
        check(np.array_equal(loops, tris.ravel()), "rewritten corners differ from the faces")
        edges = {tuple(sorted(e)) for t in tris for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
        check(len(me.edges) == len(edges), "rewritten mesh has %d edges, expected %d" % (len(me.edges), len(edges)))
        check(not me.validate(), "Mesh.validate mended the rewritten mesh")
    # moved in place (same topology), shaded smooth (sharp edges marked) or flat: bounds and
    # normals follow the new positions
    moved = grid * [2.0, 3.0, 1.0] + [0.0, 0.0, 5.0]
    normals = np.empty(len(tris) * 3)
    for smooth in (True, False):
        scene_io.write_mesh(obj, data.MeshData(grid, tris), smooth, 0.5)
        bpy.context.view_layer.update()
        check(scene_io.write_mesh(obj, data.MeshData(moved, tris), smooth, 0.5), "not written in place")
        bpy.context.view_layer.update()
        check(np.allclose(obj.dimensions, (8.0, 9.0, 0.0)), "bounds after an in-place move: %s" % (tuple(obj.dimensions),))
        check(np.allclose(coords(obj), moved), "in-place positions differ")
        scene_io.write_mesh(obj, data.MeshData(grid * [1.0, -1.0, 1.0], tris), smooth, 0.5)  # mirrored: faces turn over
        obj.data.polygons.foreach_get("normal", normals)
        check(np.allclose(normals.reshape(-1, 3), [0.0, 0.0, -1.0]), "normals did not follow a mirrored in-place write")
    bpy.data.objects.remove(obj)


def t_rename_output(tree):
    """The Object field names the output object: changing it renames the object in place."""
    ev = sub("evaluator")
    out = tree.nodes["Hull Output"]
    obj = bpy.data.objects["Bare Hull"]
    n_objects = len(bpy.data.objects)
    out.object_name = "Bare Renamed"
    ev.flush()
    check(bpy.data.objects.get("Bare Renamed") == obj and "Bare Hull" not in bpy.data.objects,
          "renaming did not rename the object")
    check(len(bpy.data.objects) == n_objects, "renaming created an object")
    out.object_name = "Bare Hull"
    ev.flush()
    check(bpy.data.objects.get("Bare Hull") == obj, "renaming back failed")
    smooth = np.empty(len(obj.data.polygons), dtype=bool)
    out.smooth = False
    ev.flush()
    obj.data.polygons.foreach_get("use_smooth", smooth)
    check(not smooth.any(), "Smooth off left smooth faces")
    out.smooth = True
    ev.flush()
    obj.data.polygons.foreach_get("use_smooth", smooth)
    check(smooth.all(), "Smooth on left flat faces")
    # A deleted output object is re-created from the cached result, without re-running upstream.
    bpy.data.objects.remove(obj)
    ev.request(tree)
    ev.flush()
    check(ev.last_stats["evaluated"] == ["Hull Output"], "re-creating ran %s" % ev.last_stats["evaluated"])
    check("Bare Hull" in bpy.data.objects and len(bpy.data.objects["Bare Hull"].data.vertices) == 48 * 160,
          "deleted output object not re-created")


def t_watched_object():
    """Editing an input object (Points From Object) re-fits the surface read from it."""
    ev, ids = sub("evaluator"), sub("ids")
    u, v = np.meshgrid(np.linspace(0, 20, 9), np.linspace(0, 5, 6), indexing="ij")
    grid = np.stack([u, v, np.sin(u / 6.0) * np.cos(v / 3.0)], axis=-1)
    obj = blender_graph.points_object(grid, "Test Points")
    tree = bpy.data.node_groups.new("Watched", ids.TREE)
    pts = tree.nodes.new(ids.NODE_POINTS_FROM_OBJECT)
    pts.source, pts.columns = obj, grid.shape[1]
    fit = tree.nodes.new(ids.NODE_FIT_SURFACE)
    fit.name = "Fit"
    te = tree.nodes.new(ids.NODE_TESSELLATE)
    out = tree.nodes.new(ids.NODE_MESH_OUTPUT)
    out.object_name, out.mirror = "Watched Surface", False
    tree.links.new(pts.outputs[0], fit.inputs[0])
    tree.links.new(fit.outputs[0], te.inputs[0])
    tree.links.new(te.outputs[0], out.inputs[0])
    ev.flush()
    surf = bpy.data.objects["Watched Surface"]
    h0 = coords(surf)
    obj.location.z = 1.0
    bpy.context.view_layer.update()  # the depsgraph update the handler listens to
    check(tree.name in ev._pending, "moving the points object did not queue the tree")
    ev.flush()
    check("Fit" in ev.last_stats["evaluated"], "fit did not re-run: %s" % ev.last_stats["evaluated"])
    check(np.allclose(coords(surf)[:, 2] - h0[:, 2], 1.0, atol=1e-3), "surface did not follow the points")
    obj.location.z = 0.0
    bpy.context.view_layer.update()
    ev.flush()
    check(np.allclose(coords(surf), h0, atol=1e-5), "surface did not return")
    for name in ("Watched Surface", "Test Points"):
        bpy.data.objects.remove(bpy.data.objects[name])
    bpy.data.node_groups.remove(tree)


LBT = blender_graph.LPP * blender_graph.BEAM * blender_graph.DRAFT


def _point_attribute(obj, name):
    a = obj.data.attributes[name]
    out = np.empty(len(a.data), dtype=np.float32)
    a.data.foreach_get("value", out)
    return out


def t_deferred_curvature(tree):
    """Curvature attributes are deferred work: a new resolution puts the new mesh in the object
    before them, and the next tick writes the curvature of the surface at the new vertices
    (the engine's, at the tessellation's parameters). A material reading one gets them with
    the mesh."""
    ev, ids = sub("evaluator"), sub("ids")
    hull, tess, out = bpy.data.objects["Bare Hull"], tree.nodes["Tessellate Hull"], tree.nodes["Hull Output"]
    tess.inputs["Resolution V"].default_value = 150
    ev.flush(later=False)
    check(len(hull.data.vertices) == 48 * 150 and hull.data.attributes.get(ids.ATTR_MEAN) is None,
          "curvature written with the mesh")
    ev.flush()
    mesh = ev.outputs_of(tree, "Tessellate Hull")["Mesh"]
    s = ev.outputs_of(tree, "Refine")["Surface"]
    inset = lambda d: (d[0] + 1e-6 * (d[1] - d[0]), d[1] - 1e-6 * (d[1] - d[0]))  # noqa: E731
    _, H = s.curvature(np.clip(mesh.params[:, 0], *inset(s.domain_u)), np.clip(mesh.params[:, 1], *inset(s.domain_v)))
    check(np.array_equal(_point_attribute(hull, ids.ATTR_MEAN), np.asarray(H, dtype=np.float32)),
          "deferred curvature is not the surface's at the new vertices")
    # Shown by a material: written with the mesh.
    mat = bpy.data.materials.new("Reads Curvature")
    mat.use_nodes = True
    mat.node_tree.nodes.new("ShaderNodeAttribute").attribute_name = ids.ATTR_MEAN
    out.material = "keep"
    ev.flush()
    hull.data.materials.clear()
    hull.data.materials.append(mat)
    tess.inputs["Resolution V"].default_value = 160
    ev.flush(later=False)
    check(hull.data.attributes.get(ids.ATTR_MEAN) is not None and len(hull.data.vertices) == 48 * 160,
          "a material reads the curvature but it came later")
    ev.flush()
    out.material = "zebra"
    ev.flush()
    bpy.data.materials.remove(mat)


def t_outputs_tree():
    """The example's second tree (blender_graph.build_outputs): every node OK, or red only for
    an optional package this Blender lacks; its Hydrostatics node shows Hull.hydrostatics()."""
    api = sub("api")
    tree = blender_graph.build_outputs()
    api.evaluate(tree, check=False)
    bad = {k: v[1] for k, v in api.status(tree).items() if v[0] != "OK" and "pip install" not in v[1]}
    check(not bad, "outputs tree: %s" % bad)
    h = api.hydrostatics(tree, "Hydrostatics")
    ref = api.result(tree, "Particulars", "Hull").hydrostatics()
    check(abs(h.volume - ref.volume) < 1e-9 * ref.volume and abs(h.lcb - ref.lcb) < 1e-9 * ref.lcb,
          "Hydrostatics node %r vs Hull.hydrostatics() %r" % ((h.volume, h.lcb), (ref.volume, ref.lcb)))
    check(len(bpy.data.objects["Quad Hull"].data.polygons) > 1000, "no Hull Mesh object")
    bpy.data.node_groups.remove(tree)


def t_hull_nodes(tree):
    """The bare-hull chain: a bigger displaced volume on the SAC node re-runs the hull and
    everything after it, but not the bulb, and the bare hull's integrated volume follows; an
    impossible volume and an impossible draught are red with the engine's message; Fair Skin
    of the Sections with the description's settings is the Bare Hull surface."""
    ev, ids = sub("evaluator"), sub("ids")
    sac, bare = tree.nodes["SAC"], tree.nodes["Bare Hull"]
    fore = bpy.data.objects["Ship"]
    V0 = ev.outputs_of(tree, "Bare Hull")["Volume"]
    # the example's bare hull: its ship, with the bulb, holds Cb L B T (fl.design_hull)
    ref = python_example().hydrostatics().volume
    check(abs(V0 / ref - 1) < 1e-6 and ref < blender_graph.PARTICULARS["cb"] * LBT,
          "bare hull volume %.1f vs the example's %.1f (Cb L B T %.1f with its bulb)" % (
              V0, ref, blender_graph.PARTICULARS["cb"] * LBT))
    area0 = python_example().description.curves["sac"].aliases["volume"]
    f0 = volume(fore, False)
    info0 = bare.fl_info
    sac.inputs["Area"].use = True
    sac.inputs["Area"].default_value = area0 + 500.0
    # The timer's first tick: the meshes are new, the hydrostatics (a deferred job) still old.
    ev.flush(later=False)
    check(volume(fore, False) > f0 + 250.0, "the forebody waited for the deferred hydrostatics")
    check(bare.fl_info == info0 and ev._cache[(tree.name, "Bare Hull")].later is not None,
          "the hydrostatics were not deferred")
    ev.flush()
    check(bare.fl_info != info0 and "V %.6g m3" % ev.outputs_of(tree, "Bare Hull")["Volume"] in bare.fl_info,
          "deferred hydrostatics not shown: %s" % bare.fl_info)
    ran = set(ev.last_stats["evaluated"])
    # The bulb is sized from the hull's midship area and displacement: it follows the SAC.
    check({"SAC", "Bare Hull", "Bulbous Bow", "Compose", "Ship Output", "Sections"} <= ran,
          "a SAC change re-ran %s" % sorted(ran))
    V1 = ev.outputs_of(tree, "Bare Hull")["Volume"]
    check(abs((V1 - V0) / 500.0 - 1) < 0.05, "bare hull volume grew %.1f m3, SAC asks 500" % (V1 - V0))
    f1 = volume(fore, False)
    check(f1 > f0 + 250.0, "forebody volume %.1f -> %.1f m3" % (f0, f1))
    smooth = np.zeros(len(fore.data.polygons), dtype=bool)
    fore.data.polygons.foreach_get("use_smooth", smooth)
    check(smooth.all(), "the re-built forebody mesh has flat faces")
    results["sac_volume_change"] = {"bare_hull_m3": [round(V0, 1), round(V1, 1)], "forebody_m3": [round(f0, 1), round(f1, 1)]}
    # A node reading a deferred output gets it at once, in the same tick.
    reader = tree.nodes.new(ids.NODE_SPHERE)  # a sphere of radius V m: shows what it was given
    reader.name = "Volume Reader"
    tree.links.new(bare.outputs["Volume"], reader.inputs["Radius"])
    ev.flush()
    sac.inputs["Area"].default_value = area0 + 400.0
    ev.flush(later=False)
    entry = ev._cache[(tree.name, "Bare Hull")]
    cp = np.asarray(ev.outputs_of(tree, "Volume Reader")["Surface"].control_points)[..., :3].reshape(-1, 3)
    check(entry.later is None and abs(np.ptp(cp[:, 0]) / (2.0 * entry.outputs["Volume"]) - 1) < 1e-9,
          "a linked deferred output was not computed on read")
    check("V %.6g m3" % entry.outputs["Volume"] in bare.fl_info, "info of a job run on read: %s" % bare.fl_info)
    tree.nodes.remove(reader)
    sac.inputs["Area"].default_value = area0 + 500.0
    ev.flush()
    sac.inputs["Area"].default_value = 1.2 * LBT   # more than the box: Cb > 1
    ev.flush()
    check(sac.fl_state == "ERROR" and "InfeasibleFormParameters" in sac.fl_message, sac.fl_message)
    check(bare.fl_state == "BLOCKED" and tree.nodes["Compose"].fl_state == "BLOCKED", "downstream of the SAC")
    check(abs(volume(fore, False) / f1 - 1) < 1e-12, "a failed SAC changed the forebody")
    results["sac_error_message"] = sac.fl_message
    sac.inputs["Area"].use = False
    ev.flush()
    check(sac.fl_state == "OK" and abs(volume(fore, False) / f0 - 1) < 1e-9, "did not recover the ship")
    dims = tree.nodes["Particulars"]
    dims.inputs["T"].default_value = 20.0
    ev.flush()
    check(dims.fl_state == "ERROR" and "D" in dims.fl_message, "T > D accepted: %s" % dims.fl_message)
    check(tree.nodes["Bulbous Bow"].fl_state == "BLOCKED", "bulb not waiting for the dimensions")
    dims.inputs["T"].default_value = blender_graph.DRAFT
    ev.flush()
    bad = ["%s: %s" % (n.name, n.fl_message) for n in tree.nodes if n.fl_state != "OK"]
    check(not bad and abs(volume(fore, False) / f0 - 1) < 1e-9, "not recovered: %s" % bad)
    skin = tree.nodes.new(ids.NODE_FAIR_SKIN)
    skin.name = "Test Skin"
    skin.start = "parallel"
    skin.inputs["Control Points"].use = True
    skin.inputs["Control Points"].default_value = 32
    tree.links.new(tree.nodes["Sections"].outputs["Sections"], skin.inputs["Sections"])
    ev.flush()
    check(skin.fl_state == "OK", skin.fl_message)
    # The node is a faithful front of fl.fair_skin on the same sections and options (the Bare
    # Hull skins with the description's own fairness weights and junction stations instead).
    a = np.asarray(ev.outputs_of(tree, "Test Skin")["Surface"].control_points)
    import fairlines as fl

    sections = ev.outputs_of(tree, "Sections")["Sections"]
    b = np.asarray(fl.fair_skin(sections, n_control=32, mode="interpolate", start="parallel",
                                end="free").surface.control_points)
    check(a.shape == b.shape and np.allclose(a, b, atol=1e-12), "Fair Skin differs from fl.fair_skin")
    tree.nodes.remove(skin)
    check(len(bpy.data.objects["Sections"].data.splines) == len(ev.outputs_of(tree, "Sections")["Sections"]),
          "sections object")


def t_boolean(tree):
    """Live Boolean composition in the generated Geometry Nodes group: a sphere on the bulb's
    nose united with / cut from the composed forebody."""
    ev, ids = sub("evaluator"), sub("ids")
    fore = bpy.data.objects["Ship"]
    nose = coords(fore)[:, 0].max()
    sph = tree.nodes.new(ids.NODE_SPHERE)
    sph.name = "Test Sphere"
    sph.inputs["Center"].default_value = (nose - 1.0, 0.0, 0.45 * blender_graph.DRAFT)
    sph.inputs["Radius"].default_value = 3.0
    st = tree.nodes.new(ids.NODE_TESSELLATE)
    st.name = "Test Sphere Mesh"
    so = tree.nodes.new(ids.NODE_MESH_OUTPUT)
    so.name = "Test Sphere Output"
    so.object_name, so.mirror = "Test Sphere", False
    tree.links.new(sph.outputs[0], st.inputs[0])
    tree.links.new(st.outputs[0], so.inputs[0])
    ev.flush()
    check(so.fl_state == "OK", "sphere output: %s" % so.fl_message)
    sphere = bpy.data.objects["Test Sphere"]
    coll = bpy.data.collections.new("Subdomains")
    coll.objects.link(sphere)
    fore_out = tree.nodes["Ship Output"]
    vb, vs = volume(fore), volume(sphere)
    fore_out.union = coll
    ev.flush()
    vu = volume(fore)
    check(vb < vu < vb + vs - 1.0, "union volume %.2f not in (%.2f, %.2f)" % (vu, vb, vb + vs))
    fore_out.union = None
    fore_out.cutter = sphere
    ev.flush()
    vd = volume(fore)
    check(vb - vs < vd < vb - 1.0, "difference volume %.2f vs forebody %.2f sphere %.2f" % (vd, vb, vs))
    # Both results see the same overlap O = vb - vd, so the union must be vb + vs - O.
    check(abs(vu - (vb + vs - (vb - vd))) < 0.02 * vs, "union and difference volumes inconsistent")
    fore_out.cutter = None
    ev.flush()
    check(abs(volume(fore) / vb - 1) < 1e-9, "removing the cutter did not restore the forebody")
    results["boolean_union_m3"] = round(vu, 2)
    results["boolean_difference_m3"] = round(vd, 2)
    for name in ("Test Sphere Output", "Test Sphere Mesh", "Test Sphere"):
        tree.nodes.remove(tree.nodes[name])
    bpy.data.objects.remove(sphere)
    bpy.data.collections.remove(coll)


def t_errors(tree):
    ev = sub("evaluator")
    hull = bpy.data.objects["Bare Hull"]
    h0 = coords(hull)
    refine = tree.nodes["Refine"]
    refine.inputs["Parameter"].default_value = 5.0   # outside the knot domain
    ev.flush()
    check(refine.fl_state == "ERROR" and refine.use_custom_color, "bad knot did not turn the node red")
    check(np.allclose(tuple(refine.color)[:3], (0.8, 0.12, 0.12), atol=1e-3), "node colour %r" % (tuple(refine.color),))
    check("InvalidInput" in refine.fl_message, "message: %r" % refine.fl_message)
    results["error_message"] = refine.fl_message
    for name, waits_for in (("Tessellate Hull", "Refine"), ("Blend", "Refine"), ("Compose", "Blend")):
        down = tree.nodes[name]
        check(down.fl_state == "BLOCKED" and waits_for in down.fl_message, "%s: %s %s" % (
            name, down.fl_state, down.fl_message))
    check(np.array_equal(coords(hull), h0), "a failed node changed the output object")
    refine.inputs["Parameter"].default_value = 0.85
    ev.flush()
    check(refine.fl_state == "OK" and not refine.use_custom_color, "node did not recover")
    check(np.array_equal(coords(hull), h0), "recovered hull differs")
    t = tree.nodes["Tessellate Hull"]
    res_v = t.inputs["Resolution V"].default_value
    t.inputs["Resolution V"].default_value = 1
    ev.flush()
    check(t.fl_state == "ERROR" and "Resolution" in t.fl_message, "resolution 1 accepted")
    t.inputs["Resolution V"].default_value = res_v
    # A link between incompatible sockets is reported on the node, not raised.
    link = tree.links.new(tree.nodes["Lines"].outputs["Lines"], t.inputs["Surface"])
    ev.flush()
    check(t.fl_state == "ERROR" and "Cannot connect" in t.fl_message, "bad link: %s" % t.fl_message)
    tree.links.remove(link)
    tree.links.new(tree.nodes["Refine"].outputs["Surface"], t.inputs["Surface"])
    ev.flush()
    check(t.fl_state == "OK", "tessellate did not recover: %s" % t.fl_message)
    check(np.array_equal(coords(hull), h0), "hull differs after relinking")
    # A bulb the Kracht coefficients cannot make: red with the engine's message, the blend and
    # the composition wait, the forebody object keeps its last good geometry.
    fore = bpy.data.objects["Ship"]
    f0 = coords(fore)
    bow = tree.nodes["Bulbous Bow"]
    bow.inputs["C_BB"].use = True
    bow.inputs["C_BB"].default_value = -0.1
    ev.flush()
    check(bow.fl_state == "ERROR" and bow.use_custom_color and bow.fl_message, "negative bulb breadth accepted")
    check(tree.nodes["Compose"].fl_state == "BLOCKED", "compose not waiting for the bulb")
    check(np.array_equal(coords(fore), f0), "a failed bulb changed the forebody")
    results["bulb_error_message"] = bow.fl_message
    bow.inputs["C_BB"].use = False
    ev.flush()
    check(bow.fl_state == "OK" and tree.nodes["Compose"].fl_state == "OK", "bulb did not recover")
    check(np.array_equal(coords(fore), f0), "forebody differs after recovery")


def t_api_headless():
    """The scripting API and the evaluate operator work without a node editor: build a tree,
    evaluate, read results, set a value, see the change, get a TreeError for a bad value."""
    api = importlib.import_module("fairlines_blender.api")
    check(api is sub("api"), "fairlines_blender.api is not the installed add-on's api")
    import fairlines as fl
    tree = api.new_tree("API Ship")
    ship = api.add(tree, "Particulars", "Ship", Cb=0.70, LCB=124.0)
    bare = api.add(tree, "Bare Hull", "Bare")
    api.link(tree, ship, "Hull", bare, "Hull")
    times = api.evaluate(tree)
    check({"Ship", "Bare"} <= set(times), "evaluate ran %s" % times)
    ref = fl.design_hull(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.70, lcb=124.0, bulb=True)
    ok, bad = hydro_equal(api.hydrostatics(tree, "Bare"), ref.hydrostatics())
    check(ok, "API hydrostatics vs fl.design_hull: %s" % bad)
    api.set(tree, "Ship", "Cb", 0.72)
    api.evaluate(tree)
    # the bare hull's Cb: the ship with its bulb holds 0.72 (fl.design_hull matches the composed ship)
    ref = fl.design_hull(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.72, lcb=124.0, bulb=True)
    check(abs(api.result(tree, "Bare", "Cb") - ref.hydrostatics().cb) < 1e-6 and ref.hydrostatics().cb < 0.72,  # single precision
          "bare hull's Cb after set: %.6f, fl.design_hull's %.6f" % (api.result(tree, "Bare", "Cb"), ref.hydrostatics().cb))
    check("ship with its bulb: V" in ship.fl_info and "Cb 0.7200" in ship.fl_info,
          "the Particulars node's ship figures: %r" % ship.fl_info)
    api.set(tree, ship, "Cb", 0.99)  # outside the designer's range
    try:
        api.evaluate(tree)
        raised = None
    except api.TreeError as exc:
        raised = exc
    check(raised is not None and "Ship" in raised.failed and "cb" in raised.failed["Ship"], "bad Cb: %r" % raised)
    check(ship.use_custom_color and "0.45 to 0.9" in ship.fl_message, "red node message: %r" % ship.fl_message)
    results["particulars_error_message"] = ship.fl_message
    api.set(tree, ship, "Cb", 0.70)
    check(bpy.ops.fairlines.evaluate_tree(tree=tree.name) == {"FINISHED"}, "evaluate_tree operator headless")
    check(ship.fl_state == "OK" and bare.fl_state == "OK", "operator did not evaluate: %s" % ship.fl_message)
    # A single screw and a sonar dome switched on: the node's hull is the designer's with them.
    ship.skeg, ship.sonar_dome = True, True
    api.evaluate(tree)
    ref = fl.design_hull(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.70, lcb=124.0, bulb=True, skeg=True,
                         sonar_dome=True)
    ok, bad = hydro_equal(api.hydrostatics(tree, "Bare"), ref.hydrostatics())
    d = api.result(tree, "Ship", "Hull").description
    check(ok and d.skeg is not None and d.dome is not None, "skeg and dome: %s" % bad)
    # ... the dome's nose where the Sonar Dome Nose socket says (the designer's is aft of the blend)
    api.set(tree, ship, "Sonar Dome Nose", 190.0)
    api.evaluate(tree)
    nose = api.result(tree, "Ship", "Hull").description.dome.x_fore
    check(ship.fl_state == "OK" and nose == 190.0, "sonar dome nose %r: %s" % (nose, ship.fl_message))
    api.set(tree, ship, "Sonar Dome Nose", None)
    ship.skeg, ship.sonar_dome = False, False
    # The Flat Bottom socket switched on at 0.3: the designer's hull with a flat of 0.3.
    api.set(tree, ship, "Flat Bottom", 0.3)
    api.evaluate(tree)
    ref = fl.design_hull(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.70, lcb=124.0, bulb=True, flat_bottom=0.3)
    ok, bad = hydro_equal(api.hydrostatics(tree, "Bare"), ref.hydrostatics())
    check(ok and "flat_bottom" in api.result(tree, "Ship", "Hull").description.curves, "flat of bottom: %s" % bad)
    # ... and at 0: none (switched off, the designer's default flat).
    api.set(tree, ship, "Flat Bottom", 0.0)
    api.evaluate(tree)
    check("flat_bottom" not in api.result(tree, "Ship", "Hull").description.curves, "a Flat Bottom of 0 draws none")
    api.set(tree, ship, "Flat Bottom", None)
    # The Transom Rake socket (an angle): the designer's hull with its transom raked so.
    api.set(tree, ship, "Transom Rake", math.radians(15.0))
    api.evaluate(tree)
    ref = fl.design_hull(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.70, lcb=124.0, bulb=True, transom_rake=15.0)
    ok, bad = hydro_equal(api.hydrostatics(tree, "Bare"), ref.hydrostatics())
    rake = api.result(tree, "Ship", "Hull").description.transom_rake
    check(ok and abs(rake - 15.0) < 1e-5, "transom rake %r: %s" % (rake, bad))  # the socket holds a float32
    api.set(tree, ship, "Transom Rake", 0.0)
    # The description JSON through the Hull Description node is the same hull as the designer's.
    desc = api.add(tree, "Hull Description", "Description", text=blender_graph.description_text())
    bare2 = api.add(tree, "Bare Hull", "Bare 2")
    api.link(tree, desc, "Hull", bare2, "Hull")
    api.evaluate(tree)
    ok, bad = hydro_equal(api.hydrostatics(tree, "Bare 2"), python_example().hydrostatics(), rel=1e-12)
    check(ok, "Hull Description node vs Hull.from_json: %s" % bad)
    bpy.data.node_groups.remove(tree)


def t_shading(tree):
    """Smooth shading with sharp edges where the ship's faces meet at a corner (deck edge,
    transom), none on the fair flank; the paint and zebra materials are on their objects."""
    ship = bpy.data.objects["Ship"]
    me = ship.data
    smooth = np.zeros(len(me.polygons), dtype=bool)
    me.polygons.foreach_get("use_smooth", smooth)
    check(smooth.all(), "flat faces on the ship")
    if hasattr(me, "set_sharp_from_angle"):
        attr = me.attributes.get("sharp_edge")
        check(attr is not None and attr.domain == "EDGE", "no sharp_edge attribute")
        sharp = np.zeros(len(me.edges), dtype=bool)
        attr.data.foreach_get("value", sharp)
        ev_ = np.empty(len(me.edges) * 2, dtype=np.int64)
        me.edges.foreach_get("vertices", ev_)
        v = coords(ship)[ev_.reshape(-1, 2)]  # (edges, 2, 3)
        at_deck = np.all(np.abs(v[:, :, 2] - blender_graph.DEPTH) < 1e-3, axis=1)
        deck_edge = at_deck & np.all(np.abs(v[:, :, 1]) > 15.0, axis=1) & np.all(np.abs(v[:, :, 0] - 120) < 20, axis=1)
        flank = np.all((np.abs(v[:, :, 0] - 120) < 20) & (v[:, :, 2] > 3.0) & (v[:, :, 2] < 17.0), axis=1)
        check(deck_edge.any() and sharp[deck_edge].all(), "deck edge not sharp (%d of %d)" % (
            sharp[deck_edge].sum(), deck_edge.sum()))
        check(flank.any() and not sharp[flank].any(), "%d sharp edges on the flank" % sharp[flank].sum())
        results["sharp_edges"] = int(sharp.sum())
    else:
        check(me.use_auto_smooth and abs(me.auto_smooth_angle - np.radians(30)) < 1e-4, "auto smooth off")
    mats = sub("materials")
    check(ship.data.materials[0].name.startswith(sub("ids").MAT_PAINT), "ship not painted")
    check(ship.data.materials[0].get("fairlines_draft") == blender_graph.DRAFT, "paint not split at T")
    check(bpy.data.objects["Bare Hull"].data.materials[0] == mats.zebra(), "bare hull has no zebra material")


def t_form_curve():
    """The form-parameter curve node meets the switched-on parameters (angles given in the
    interface's degrees, curvature in 1/m) and an infeasible request turns it red with the
    engine's diagnosis; switching the offending parameter off recovers."""
    ev, ids = sub("evaluator"), sub("ids")
    import fairlines as fl
    tree = bpy.data.node_groups.new("Form Curve", ids.TREE)
    fc = tree.nodes.new(ids.NODE_FORM_CURVE)
    fc.name = "Form Curve"
    cl = tree.nodes.new(ids.NODE_CURVE_LINES)
    tree.links.new(fc.outputs["Curve"], cl.inputs["Curve"])
    ev.flush()
    check(fc.fl_state == "OK" and cl.fl_state == "OK", "form curve: %s" % fc.fl_message)
    request = {}
    for sock in fc.inputs:
        if getattr(sock, "is_optional", False) and sock.use:
            v = sock.default_value
            request[sock.name] = np.degrees(v) if sock.bl_idname == ids.SOCKET_ANGLE else v
    check(set(request) == {"xB", "yB", "xE", "yE", "alphaB", "alphaE", "CAB", "CAE", "Area"}, sorted(request))
    curve = ev.outputs_of(tree, "Form Curve")["Curve"]
    got = fl.form_parameters_of(curve.degree, np.asarray(curve.control_points))
    for name, want in request.items():
        # Sockets hold single precision: compare with what the engine was given.
        check(abs(got[name] - want) < 1e-5 * max(1.0, abs(want)), "%s = %.8g, requested %.8g" % (name, got[name], want))
    ref = fl.design_curve(request).curve
    check(np.allclose(np.asarray(ref.control_points), np.asarray(curve.control_points), atol=1e-9),
          "node and package curves differ")
    # yC far below the least a non-folding curve with this Area and xC can have.
    fc.inputs["xC"].use = True
    fc.inputs["yC"].use = True
    fc.inputs["yC"].default_value = 0.02
    ev.flush()
    check(fc.fl_state == "ERROR" and fc.use_custom_color, "infeasible request accepted")
    check("InfeasibleFormParameters" in fc.fl_message and "yC" in fc.fl_message, fc.fl_message)
    check(cl.fl_state == "BLOCKED", "downstream of an infeasible curve: %s" % cl.fl_state)
    results["infeasible_message"] = fc.fl_message
    fc.inputs["yC"].use = False
    ev.flush()
    check(fc.fl_state == "OK" and not fc.use_custom_color and cl.fl_state == "OK", "did not recover")
    c2 = ev.outputs_of(tree, "Form Curve")["Curve"]
    got = fl.form_parameters_of(c2.degree, np.asarray(c2.control_points))
    check(abs(got["xC"] - fc.inputs["xC"].default_value) < 1e-5, "xC not met after recovery")
    bpy.data.node_groups.remove(tree)


def t_curve_edit():
    """Curve knot insertion and degree elevation keep the shape; a weight pulls the curve."""
    ev, ids = sub("evaluator"), sub("ids")
    tree = bpy.data.node_groups.new("Curve Edit", ids.TREE)
    circ = tree.nodes.new(ids.NODE_CIRCLE)
    circ.inputs["Radius"].default_value = 2.0
    chain = [circ]
    for idname in (ids.NODE_CURVE_INSERT_KNOT, ids.NODE_CURVE_ELEVATE_DEGREE, ids.NODE_CURVE_SET_WEIGHT):
        n = tree.nodes.new(idname)
        tree.links.new(chain[-1].outputs["Curve"], n.inputs["Curve"])
        chain.append(n)
    chain[1].inputs["Parameter"].default_value = 0.3
    outs = []
    for src in chain:
        cl = tree.nodes.new(ids.NODE_CURVE_LINES)
        cl.inputs["Samples"].default_value = 200
        tree.links.new(src.outputs["Curve"], cl.inputs["Curve"])
        outs.append(cl)
    ev.flush()
    bad = ["%s: %s" % (n.name, n.fl_message) for n in tree.nodes if n.fl_state != "OK"]
    check(not bad, "curve edit nodes: %s" % bad)
    pts = [ev.outputs_of(tree, o.name)["Lines"].polylines[0] for o in outs]
    radius = [np.linalg.norm(p, axis=1) for p in pts]
    for r in radius[:4]:  # circle, knot inserted, degree elevated, weight 1: all the circle
        check(np.allclose(r, 2.0, atol=1e-9), "shape changed: radius %.12g .. %.12g" % (r.min(), r.max()))
    ctrl = ev.outputs_of(tree, chain[2].name)["Curve"].control_points
    chain[3].inputs["Index"].default_value = 3
    chain[3].inputs["Weight"].default_value = 5.0
    ev.flush()
    moved = ev.outputs_of(tree, outs[3].name)["Lines"].polylines[0]
    target = np.asarray(ctrl[3])[:2]
    before = np.min(np.linalg.norm(pts[3][:, :2] - target, axis=1))
    after = np.min(np.linalg.norm(moved[:, :2] - target, axis=1))
    check(after < 0.5 * before, "weight 5 did not pull the curve (%.4f -> %.4f m)" % (before, after))
    ran = set(ev.evaluate(tree))
    check(not ran, "unchanged curve tree re-ran %s" % ran)
    bpy.data.node_groups.remove(tree)


def t_every_node_alone():
    """Every node type, alone and then with its integer inputs at 0 and -1 and its numbers at
    -1e9: each evaluates to OK or to a red node with a message; nothing raises, nothing crashes."""
    ev, ids = sub("evaluator"), sub("ids")
    tree = bpy.data.node_groups.new("Every Node", ids.TREE)
    kinds = [v for k, v in vars(ids).items() if k.startswith("NODE_") and isinstance(v, str)]
    for idname in kinds:
        node = tree.nodes.new(idname)
        for variant in (None, 0, -1, -1e9):
            for sock in node.inputs:
                if variant is None or not hasattr(sock, "default_value"):
                    continue
                if sock.bl_idname == ids.SOCKET_INT and variant in (0, -1):
                    sock.default_value = variant
                elif sock.bl_idname in (ids.SOCKET_LENGTH, ids.SOCKET_FLOAT, ids.SOCKET_ANGLE) and variant == -1e9:
                    sock.default_value = variant
            ev.evaluate(tree)
            check(node.fl_state in ("OK", "ERROR"), "%s: state %r" % (idname, node.fl_state))
            check(node.fl_state == "OK" or node.fl_message, "%s: red without a message" % idname)
        tree.nodes.remove(node)
    for name in [o.name for o in bpy.data.objects if o.name.startswith("Fairlines ")]:
        bpy.data.objects.remove(bpy.data.objects[name])
    bpy.data.node_groups.remove(tree)
    results["node_types"] = len(kinds)


def t_random_properties():
    """Thousands of seeded random, extreme and degenerate property values on every node type
    (random_properties.py): every node stays OK or turns red / blocked with a message."""
    if not args.random_changes:
        return
    u, v = np.meshgrid(np.linspace(0, 20, 9), np.linspace(0, 5, 6), indexing="ij")
    points = blender_graph.points_object(np.stack([u, v, np.sin(u / 6.0) * np.cos(v / 3.0)], axis=-1),
                                         "Random Points")
    files = {"offsets": os.path.join(DATA, "series60_cb080_offsets.csv"), "description": blender_graph.DESCRIPTION}
    results["random_properties"] = random_properties.run(
        sub("api"), sub("ids"), check, os.path.join(args.tmp, "random"), points, files, changes=args.random_changes)


DATA = os.environ.get("FAIRLINES_DATA", os.path.join(os.path.dirname(ROOT), "shared", "data"))


def t_offsets_hydrostatics():
    """Series 60 offsets -> rebuilt surface -> hydrostatics on the node and a hull object."""
    ev, ids = sub("evaluator"), sub("ids")
    import fairlines as fl
    from fairlines import offsets, preprocess
    path = os.path.join(DATA, "series60_cb080_offsets.csv")
    check(os.path.exists(path), "reference data missing: %s (set FAIRLINES_DATA)" % path)
    tree = bpy.data.node_groups.new("Series 60", ids.TREE)
    imp = tree.nodes.new(ids.NODE_OFFSETS_IMPORT)
    imp.name = "Import"
    imp.filepath = path
    for name, value in (("Lpp", 121.92), ("Beam", 18.757), ("Draft", 7.503)):
        imp.inputs[name].default_value = value
    rb = tree.nodes.new(ids.NODE_REBUILD)
    rb.name = "Rebuild"
    hy = tree.nodes.new(ids.NODE_HYDROSTATICS)
    hy.name = "Hydrostatics"
    for name, value in (("Lpp", 121.92), ("Beam", 18.757), ("Draft", 7.503)):
        hy.inputs[name].default_value = value
    te = tree.nodes.new(ids.NODE_TESSELLATE)
    out = tree.nodes.new(ids.NODE_MESH_OUTPUT)
    out.object_name = "Series 60"
    tree.links.new(imp.outputs[0], rb.inputs["Hull Data"])
    tree.links.new(rb.outputs[0], hy.inputs["Surface"])
    tree.links.new(rb.outputs[0], te.inputs["Surface"])
    tree.links.new(te.outputs[0], out.inputs["Mesh"])
    ev.flush()
    bad = ["%s: %s" % (n.name, n.fl_message) for n in tree.nodes if n.fl_state != "OK"]
    check(not bad, "Series 60 graph: %s" % bad)
    data = offsets.read_hull_data(path, 121.92, 18.757, 7.503)
    surface = preprocess.rebuild(data, deviation=False).surfaces[0]
    ref = fl.hydrostatics(surface, 7.503, length=121.92, breadth=18.757, midship_x=121.92 / 2)
    got = ev.outputs_of(tree, "Hydrostatics")
    # Equal up to the single precision in which Blender stores the Lpp / B / T sockets.
    ok, bad = hydro_equal(sub("api").hydrostatics(tree, "Hydrostatics"), ref)
    check(ok, "node hydrostatics differ from fl.hydrostatics: %s" % bad)
    check(0.95 < ref.cm <= 1.0 and 0.75 < ref.cp < 0.85, "Series 60 Cm %.4f Cp %.4f" % (ref.cm, ref.cp))
    check(abs(got["Cb"] - 0.80) < 0.005, "Series 60 Cb %.4f" % got["Cb"])
    check("Cb %.4f" % got["Cb"] in hy.fl_info and "deviation max" in rb.fl_info, hy.fl_info + rb.fl_info)
    results["series60"] = {"volume_m3": round(got["Volume"], 1), "Cb": round(got["Cb"], 4),
                           "hydrostatics_ms": round(hy.fl_time_ms, 2), "info": hy.fl_info}
    hy.inputs["Draft"].default_value = 6.0
    ev.flush()
    check(ev.last_stats["evaluated"] == ["Hydrostatics"], "a draft change re-ran %s" % ev.last_stats["evaluated"])
    check(ev.outputs_of(tree, "Hydrostatics")["Volume"] < 0.85 * got["Volume"], "volume did not drop with the draft")
    check(len(bpy.data.objects["Series 60"].data.vertices) == 64 * 32, "Series 60 mesh")
    imp.filepath = os.path.join(DATA, "no_such_offsets.csv")
    ev.flush()
    check(imp.fl_state == "ERROR" and "does not exist" in imp.fl_message, "bad path: %s" % imp.fl_message)
    check(rb.fl_state == "BLOCKED" and hy.fl_state == "BLOCKED", "downstream of a bad import")
    bpy.data.objects.remove(bpy.data.objects["Series 60"])
    bpy.data.node_groups.remove(tree)


def t_export(tree):
    ev, ids = sub("evaluator"), sub("ids")
    exp = tree.nodes.new(ids.NODE_EXPORT_OBJ)
    exp.name = "Export"
    path = os.path.join(args.tmp, "hull.obj")
    exp.filepath = path
    tree.links.new(tree.nodes["Curvature"].outputs["Mesh"], exp.inputs["Mesh"])
    # The package's tessellation keeps S_u x S_v; compare with the node's unflipped winding.
    tess = tree.nodes["Tessellate Hull"]
    tess.orientation = "native"
    ev.flush()
    check(not os.path.exists(path), "export wrote before being asked")
    check(bpy.ops.fairlines.export_node(tree=tree.name, node="Export") == {"FINISHED"}, "export failed")
    lines = open(path).read().splitlines()
    check(sum(l.startswith("v ") for l in lines) == 48 * 160, "OBJ vertex count")
    check(sum(l.startswith("f ") for l in lines) == 2 * 47 * 159, "OBJ triangle count")
    # The same surface through the engine package alone gives the same file.
    import fairlines.io
    surf = ev.outputs_of(tree, "Refine")["Surface"]
    verts, faces = fairlines.io.tessellate(surf, tess.inputs["Resolution U"].default_value,
                                           tess.inputs["Resolution V"].default_value)
    ref = os.path.join(args.tmp, "ref.obj")
    fairlines.io.write_obj(ref, verts, faces)
    ref_lines = open(ref).read().splitlines()
    check(sorted(l for l in lines if l.startswith("f ")) == sorted(l for l in ref_lines if l.startswith("f ")),
          "OBJ faces differ from fairlines.io.tessellate")
    check([l for l in lines if l.startswith("v ")] == [l for l in ref_lines if l.startswith("v ")],
          "OBJ vertices differ from fairlines.io.tessellate")
    tess.orientation = "outward"
    tree.nodes.remove(exp)
    ev.flush()


def t_save_reload(tree):
    ev = sub("evaluator")
    saved = {n: coords(bpy.data.objects[n]) for n in ("Ship", "Bare Hull")}
    path = os.path.join(args.tmp, "graph.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    check(not ev._cache, "cache survived the file load")
    ev.flush()
    tree = bpy.data.node_groups[blender_graph.TREE_NAME]
    check(len(ev.last_stats["evaluated"]) > 0, "nothing evaluated after load")
    bad = ["%s: %s" % (n.name, n.fl_message) for n in tree.nodes if n.fl_state not in ("OK",)]
    check(not bad, "nodes not OK after reload: %s" % bad)
    for name, before in saved.items():
        after = coords(bpy.data.objects[name])
        check(after.shape == before.shape and np.array_equal(after, before),
              "%s differs after save and reload" % name)
    return tree


def t_unregister():
    ids, ev, tree_mod = sub("ids"), sub("evaluator"), sub("tree")
    disable()
    left = [v for k, v in vars(ids).items() if k.startswith(("NODE_", "SOCKET_", "TREE"))
            and isinstance(v, str) and registered(v) is not None]
    check(not left, "still registered after disabling: %s" % left)
    for handlers, fn in tree_mod.HANDLERS:
        check(fn not in handlers, "handler %s left behind" % fn.__name__)
    check(not bpy.app.timers.is_registered(ev._on_timer), "timer left behind")


def t_no_engine():
    """The add-on registers without the engine and says why on the nodes."""
    import addon_utils
    saved = {k: v for k, v in sys.modules.items() if k == "fairlines" or k.startswith("fairlines.")}
    for k in [k for k in sys.modules if k == MODULE or k.startswith(MODULE + ".") or k in saved]:
        del sys.modules[k]
    sys.modules["fairlines"] = None  # makes `import fairlines` fail like a broken install
    try:
        addon_utils.enable(MODULE, default_set=True, handle_error=_raise)
        eng, ids, ev = sub("engine"), sub("ids"), sub("evaluator")
        check(not eng.available() and "engine unavailable" in eng.IMPORT_ERROR, eng.IMPORT_ERROR)
        tree = bpy.data.node_groups.new("No Engine", ids.TREE)
        node = tree.nodes.new(ids.NODE_SPHERE)
        ev.evaluate(tree)
        check(node.fl_state == "ERROR" and "engine unavailable" in node.fl_message, node.fl_message)
        results["no_engine_message"] = node.fl_message
        disable()
    finally:
        del sys.modules["fairlines"]
        sys.modules.update(saved)


def bench(tree, n):
    """Median wall time from a property change to the updated mesh in the object."""
    ev = sub("evaluator")
    out = {}
    api = sub("api")
    cases = [("bulb_length", "Ship", lambda k: api.set(tree, "Bulbous Bow", "C_LPR", 0.025 + 0.0002 * (k % 50))),
             ("hull_knot", "Bare Hull", lambda k: tree.nodes["Refine"].inputs["Parameter"].__setattr__(
                 "default_value", 0.80 + 0.001 * (k % 50))),
             ("sac_volume", "Ship", lambda k: api.set(tree, "SAC", "Area", 56448.8 + 10.0 * (k % 50)))]
    for label, obj_name, change in cases:
        obj = bpy.data.objects[obj_name]
        to_mesh, to_eval, to_all, cpu = [], [], [], []
        for k in range(n):
            before = coords(obj)[0].copy() if k == 0 else None
            t0, c0 = time.perf_counter(), time.process_time()
            change(k + 1)
            # What the add-on's timer does in its first tick, after which Blender draws the
            # new meshes; deferred jobs (the bare hull's hydrostatics) follow in the next tick.
            ev.flush(later=False)
            t1 = time.perf_counter()
            cpu.append((time.process_time() - c0) * 1e3)  # the add-on is single-threaded: idle wall time
            bpy.context.evaluated_depsgraph_get()  # includes the Geometry Nodes modifier
            t2 = time.perf_counter()
            ev.flush()
            t3 = time.perf_counter()
            check(not ev._deferred, "deferred jobs left after flush")
            to_mesh.append((t1 - t0) * 1e3)
            to_eval.append((t2 - t0) * 1e3)
            to_all.append((t1 - t0 + t3 - t2) * 1e3)
            if k == 0:
                check(not np.array_equal(before, coords(obj)[0]) or label == "hull_knot",
                      "bench change did not reach the mesh")
        nodes_ms = {name: round(tree.nodes[name].fl_time_ms, 2) for name in ev.last_stats["evaluated"]}
        out[label] = {"median_ms_to_mesh": round(statistics.median(to_mesh), 2), "last_run_nodes_ms": nodes_ms,
                      "median_ms_including_geometry_nodes": round(statistics.median(to_eval), 2),
                      "median_ms_including_deferred": round(statistics.median(to_all), 2),
                      "median_cpu_ms_to_mesh": round(statistics.median(cpu), 2),
                      "vertices": len(obj.data.vertices), "runs": n}
    results["bench"] = out


def main():
    steps = []
    try:
        t_register()
        steps.append("register")
        tree = t_build()
        steps.append("build")
        if args.bench:
            bench(tree, args.bench)
        else:
            t_shading(tree)
            steps.append("shading")
            t_api_headless()
            steps.append("api headless")
            t_bulb_length(tree)
            steps.append("bulb length")
            t_mesh_rewrite()
            steps.append("mesh rewrite")
            t_rename_output(tree)
            steps.append("rename output")
            t_watched_object()
            steps.append("watched object")
            t_deferred_curvature(tree)
            steps.append("deferred curvature")
            t_outputs_tree()
            steps.append("outputs tree")
            t_hull_nodes(tree)
            steps.append("hull nodes")
            t_boolean(tree)
            steps.append("boolean")
            t_errors(tree)
            steps.append("errors")
            t_form_curve()
            steps.append("form curve")
            t_curve_edit()
            steps.append("curve edit")
            t_every_node_alone()
            steps.append("every node alone")
            t_random_properties()
            steps.append("random properties")
            t_offsets_hydrostatics()
            steps.append("offsets and hydrostatics")
            t_export(tree)
            steps.append("export")
            t_save_reload(tree)
            steps.append("save/reload")
            t_unregister()
            steps.append("unregister")
            t_no_engine()
            steps.append("no engine")
    except Exception:
        results["failed_after"] = steps
        results["error"] = traceback.format_exc()
        print("FAIRLINES-CHECKS " + json.dumps(results))
        sys.stdout.flush()
        os._exit(1)  # bpy module: sys.exit inside Blender's atexit machinery is unreliable
    results["passed"] = steps
    print("FAIRLINES-CHECKS " + json.dumps(results))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    sys.stdout.flush()


main()
