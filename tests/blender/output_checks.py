"""Checks of the output nodes (Hull Mesh, Surface Grid, Export Mesh, Export CAD, Lines Plan,
Curves of Form) and the sweep face, inside a real Blender, driven through fairlines_blender.api.

    python  output_checks.py --zip dist/...-extension.zip --tmp DIR            (bpy, with the extras)
    blender -b --factory-startup --python output_checks.py -- --zip dist/...-legacy.zip --tmp DIR

Each file a node writes is compared with what the fairlines package's own function writes or
computes in the same process, and with an independent truth where one exists (OpenCASCADE's
volume of the STEP solid, meshio's reading of the mesh). Where an optional package is missing
(Debian's Blender has none of them) the node must be red with the pip line instead; the check
also blocks each package in the bpy module to see that message there.
"""

import argparse
import filecmp
import importlib
import json
import os
import sys
import traceback

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "examples"))
import blender_graph  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
ap = argparse.ArgumentParser()
ap.add_argument("--zip", required=True)
ap.add_argument("--tmp", required=True)
args = ap.parse_args(argv)
os.makedirs(args.tmp, exist_ok=True)
results = {"blender": bpy.app.version_string, "python": sys.version.split()[0]}

SHIP = dict(Lpp=244.8, B=32.25, T=11.0, D=19.0, Cb=0.65, LCB=118.73)
MESH_SIZE = 8.0  # m: a coarse hull mesh keeps the checks quick
MESH_VOLUME_TOLERANCE = 0.01  # relative: a coarse mesh's volume against the composition's triangles
# m: Blender stores the 0.2 m spacings in single precision (0.2 + 3e-9), which moves the points
GRID_TOLERANCE = 1e-6
CAD_VOLUME_TOLERANCE = 5e-4
CAD_POINT_TOLERANCE = 1e-7  # m: a surface read back from a file against ours  # relative: OpenCASCADE's solid volume against the hull's quadrature
EXTRAS = ("meshio", "OCP", "rhino3dm", "matplotlib", "ezdxf", "pyarrow")


class CheckFailed(AssertionError):
    pass


def check(cond, message):
    if not cond:
        raise CheckFailed(message)


def has(module):
    try:
        importlib.import_module(module)
        return True
    except ImportError:
        return False


def out(name):
    return os.path.join(args.tmp, name)


def ship_tree(api):
    tree = api.new_tree("Outputs")
    api.add(tree, "Particulars", name="Ship", **SHIP)
    api.evaluate(tree)
    return tree, api.result(tree, "Ship", "Hull")


def file_node(api, tree, label, name, path, source="Hull", from_node="Ship", from_socket="Hull", **values):
    n = api.add(tree, label, name=name, **values)
    n.filepath = path
    api.link(tree, from_node, from_socket, n, source)
    api.evaluate(tree, check=False)  # a missing package turns it red; api.export raises then
    check(not os.path.exists(path), "%s wrote %s before Export was pressed" % (name, path))
    return n


def t_hull_mesh(api, tree, hull, fl):
    """Hull Mesh into the scene: the package's mesh, quality per face, faces out of the body."""
    api.add(tree, "Hull Mesh", name="Hull Mesh", Size=MESH_SIZE)
    api.link(tree, "Ship", "Hull", "Hull Mesh", "Hull")
    api.add(tree, "Mesh Output", name="Quad Out", object_name="Quad Hull", mirror=False)
    api.link(tree, "Hull Mesh", "Mesh", "Quad Out", "Mesh")
    api.evaluate(tree)
    ref = fl.mesh_hull(hull.composed_hull(), size=MESH_SIZE)
    me = bpy.data.objects["Quad Hull"].data
    check(len(me.vertices) == len(ref.vertices) and len(me.polygons) == len(ref.faces),
          "Hull Mesh object %d/%d vs fl.mesh_hull %d/%d" % (len(me.vertices), len(me.polygons), len(ref.vertices),
                                                            len(ref.faces)))
    sizes = np.zeros(len(me.polygons), dtype=np.int32)
    me.polygons.foreach_get("loop_total", sizes)
    check(np.array_equal(sizes, np.where(ref.faces[:, 3] >= 0, 4, 3)), "quad / triangle pattern differs")
    attr = me.attributes.get("scaled_jacobian")
    check(attr is not None and attr.domain == "FACE", "no scaled_jacobian face attribute")
    q = np.zeros(len(me.polygons), dtype=np.float32)
    attr.data.foreach_get("value", q)
    check(np.allclose(q, fl._native.scaled_jacobians(ref.vertices, ref.faces), atol=1e-6), "quality attribute differs")
    vol = blender_volume(me)
    half = hull.composed_hull().volume  # the closed starboard half, centre plane included
    check(vol > 0 and abs(vol - half) < MESH_VOLUME_TOLERANCE * half,
          "mesh volume %.1f vs the composed hull's %.1f" % (vol, half))
    api.set(tree, "Hull Mesh", "Draft", SHIP["T"])
    api.evaluate(tree)
    wet = api.result(tree, "Hull Mesh", "Mesh").solver
    ref_wet = fl.mesh_hull(hull.composed_hull(), size=MESH_SIZE, draft=SHIP["T"])
    check(np.array_equal(wet.faces, ref_wet.faces), "wetted mesh differs from fl.mesh_hull(draft=T)")
    check(wet.vertices[:, 2].max() <= SHIP["T"] + 1e-9, "wetted mesh above the draft")
    results["hull_mesh"] = {"faces": len(ref.faces), "quads": float(ref.quality()["quad_fraction"]),
                            "volume_half": round(vol, 1), "wetted_faces": len(wet.faces)}


def t_hull_mesh_without_bulb(api, tree, hull, fl):
    """A ship without a bulb meshes too: its bare hull closed by deck, transom and centre plane
    (Hull Mesh once turned red: 'bulb is missing')."""
    plain = api.new_tree("Plain ship")
    api.add(plain, "Particulars", name="Plain", bulb=False, **SHIP)
    api.add(plain, "Hull Mesh", name="Plain Mesh", Size=MESH_SIZE)
    api.link(plain, "Plain", "Hull", "Plain Mesh", "Hull")
    api.evaluate(plain)  # raises TreeError when a node is red
    solver = api.result(plain, "Plain Mesh", "Mesh").solver
    ref = fl.mesh_hull(api.result(plain, "Plain", "Hull").composed_hull(), size=MESH_SIZE)
    check(np.array_equal(solver.faces, ref.faces), "bulb-less Hull Mesh differs from fl.mesh_hull of the closed bare hull")
    results["hull_mesh_without_bulb"] = {"faces": len(ref.faces)}


def blender_volume(me):
    """Signed volume of a closed Blender mesh (divergence theorem over its triangulated faces)."""
    co = np.zeros(len(me.vertices) * 3)
    me.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    vol = 0.0
    for poly in me.polygons:
        idx = list(poly.vertices)
        for k in range(1, len(idx) - 1):
            a, b, c = co[idx[0]], co[idx[k]], co[idx[k + 1]]
            vol += np.dot(a, np.cross(b, c)) / 6.0
    return vol


def t_surface_grid(api, tree, hull, fl):
    api.add(tree, "Bare Hull", name="Bare")
    api.link(tree, "Ship", "Hull", "Bare", "Hull")
    g = api.add(tree, "Surface Grid", name="Grid", Points_U=9, Points_V=17)
    g.spacing_v = "tanh_two_sided"
    api.link(tree, "Bare", "Surface", "Grid", "Surface")
    api.evaluate(tree)
    mesh = api.result(tree, "Grid", "Mesh")
    ref = fl.grids.surface_grid(hull.bare_hull_surface(), u=fl.grids.distribution("uniform", 9),
                                v=fl.grids.distribution("tanh_two_sided", 17, first=0.2, last=0.2))
    got, want = np.asarray(mesh.vertices), ref.points.reshape(-1, 3)
    check(got.shape == want.shape and np.abs(got - want).max() < GRID_TOLERANCE,
          "grid points differ from fl.grids.surface_grid: %s vs %s, %s" % (
              got.shape, want.shape, np.abs(got - want).max() if got.shape == want.shape else ""))
    # the boundary lines carry the distribution (the interior is interpolated between them)
    first = [np.linalg.norm(got.reshape(9, 17, 3)[i, 1] - got.reshape(9, 17, 3)[i, 0]) for i in (0, -1)]
    check(all(abs(f - 0.2) < 0.01 * 0.2 for f in first), "first spacings %s m, asked 0.2 m" % first)


def t_export_mesh(api, tree, hull, fl):
    if not has("meshio"):
        return missing(api, tree, "Export Mesh", "Mesh", "meshio", source="Mesh", from_node="Hull Mesh",
                       from_socket="Mesh")
    import meshio
    api.set(tree, "Hull Mesh", "Draft", None)
    n = file_node(api, tree, "Export Mesh", "Export Mesh", out("hull.msh"), source="Mesh", from_node="Hull Mesh",
                  from_socket="Mesh")
    path = api.export(tree, n)
    m = meshio.read(path)
    ref = fl.mesh_hull(hull.composed_hull(), size=MESH_SIZE)
    check(np.allclose(m.points, ref.vertices), "msh points differ from fl.mesh_hull")
    check(sum(len(c.data) for c in m.cells) == len(ref.faces), "msh element count")
    api.set(tree, "Hull Mesh", "Draft", SHIP["T"])
    n.filepath = out("hull.gdf")
    path = api.export(tree, n)
    fl.write_gdf(fl.mesh_hull(hull.composed_hull(), size=MESH_SIZE, draft=SHIP["T"]), out("ref.gdf"))
    check(filecmp.cmp(path, out("ref.gdf"), shallow=False), "gdf differs from fl.write_gdf")
    results["export_mesh"] = ["msh", "gdf"]


def t_export_cad(api, tree, hull, fl):
    if not has("OCP"):
        return missing(api, tree, "Export CAD", "CAD", "cadquery-ocp-novtk")
    from fairlines import cad
    n = file_node(api, tree, "Export CAD", "CAD", out("hull.step"))
    v = cad.verify(cad.read_cad(api.export(tree, n)))
    s, c = hull.bare_hull_surface(), hull.composed_hull()
    expected = fl.hydrostatics(s, SHIP["D"]).volume / 2 + c.volume - fl.compose([s]).volume
    check(v["valid"] and v["closed"], "STEP solid not valid and closed: %s" % v)
    check(abs(v["volume"] - expected) < CAD_VOLUME_TOLERANCE * expected,
          "STEP volume %.2f vs quadrature %.2f" % (v["volume"], expected))
    results["export_cad"] = {"step_volume": round(v["volume"], 2), "expected": round(expected, 2)}
    if has("rhino3dm"):
        n.filepath = out("hull.3dm")
        got = cad.read_3dm(api.export(tree, n))
        mine = [t[0] for t in c.trimmed_surfaces]
        check(len(got) == len(mine), "3dm holds %d surfaces; the composed hull has %d" % (len(got), len(mine)))
        for g, m in zip(got, mine):
            us, vs = np.linspace(*m.domain_u, 7), np.linspace(*m.domain_v, 7)
            dev = np.abs(g.evaluate_grid(us, vs) - m.evaluate_grid(us, vs)).max()
            check(dev < CAD_POINT_TOLERANCE, "3dm surface off by %.3g m" % dev)
        results["export_cad"]["3dm_surfaces"] = len(got)


def t_lines_plan(api, tree, hull, fl):
    if not has("matplotlib"):
        return missing(api, tree, "Lines Plan", "Lines", "matplotlib")
    from fairlines.lines_plan import lines_plan
    n = file_node(api, tree, "Lines Plan", "Lines", out("lines.png"))
    path = api.export(tree, n)
    img = bpy.data.images.get("Fairlines Lines Plan")
    check(img is not None and tuple(img.size)[0] > 1000, "lines plan PNG not shown as an image")
    p = hull.description.principal
    plan = lines_plan(hull.composed_hull(), lpp=p.lpp, beam=p.breadth, draft=p.draft, depth=p.depth,
                      name=hull.description.name)
    check(os.path.getsize(path) > 10000, "lines plan PNG is tiny")
    if has("ezdxf"):
        import ezdxf
        n.filepath = out("lines.dxf")
        path = api.export(tree, n)
        plan.save(out("ref.dxf"))
        got, ref = ezdxf.readfile(path), ezdxf.readfile(out("ref.dxf"))
        census = lambda d: sorted((e.dxftype(), e.dxf.layer) for e in d.modelspace())  # noqa: E731
        check(census(got) == census(ref), "DXF entities differ from the package's lines plan")
        results["lines_plan"] = {"png": list(img.size), "dxf_entities": len(census(got))}


def t_curves_of_form(api, tree, hull, fl):
    if not has("matplotlib"):
        return missing(api, tree, "Curves of Form", "Curves", "matplotlib")
    from fairlines.curves_of_form import curves_of_form, highest_draft
    n = file_node(api, tree, "Curves of Form", "Curves", out("cof.csv"), Drafts=5)
    path = api.export(tree, n)
    s = hull.bare_hull_surface()
    ship = hull.composed_hull() if hull.description.bulb is not None else s  # the ship, with its bulb
    p = hull.description.principal  # the sockets' single-precision values the hull was designed with
    drafts = np.linspace(0.1 * p.draft, highest_draft(s, p.depth, p.lpp), 5)
    ref = curves_of_form(ship, drafts, lpp=p.lpp, beam=p.breadth, depth=p.depth, design_draft=p.draft)
    ref.write_csv(out("ref.csv"))
    check(filecmp.cmp(path, out("ref.csv"), shallow=False), "CSV differs from fl curves_of_form")
    check(os.path.exists(out("cof.png")), "no curves-of-form plot")
    at_t = curves_of_form(ship, [p.draft], lpp=p.lpp, beam=p.breadth).rows[0]
    want = hull.ship_hydrostatics()["volume"]
    check(abs(at_t["volume"] - want) < 1e-6 * at_t["volume"],
          "curves of form at T %.3f vs Hull.ship_hydrostatics %.3f" % (at_t["volume"], want))


def t_sweep(api, tree, hull, fl):
    if not has("pyarrow"):
        return missing(api, tree, "Sweep", "Sweep", "pyarrow")
    n = file_node(api, tree, "Sweep", "Sweep", out("sweep.parquet"))
    n.vary_volume, n.vary_bulb, n.levels = 2.0, 0.003, 2
    api.export(tree, n)
    coll = bpy.data.collections["Fairlines Sweep"]
    hulls = sorted(o.name for o in coll.objects if o.type == "MESH")
    labels = {o.name: o.data.body for o in coll.objects if o.type == "FONT"}
    check(len(labels) == 4, "expected 4 variant labels, got %s" % sorted(labels))
    base = json.loads(hull.to_json())
    vol = base["basic_curves"]["sac"]["volume"]
    study = {"name": "x", "base": {"description": base}, "sampling": {"method": "factorial", "levels": 2},
             "parameters": [{"path": "basic_curves.sac.volume", "low": vol * 0.98, "high": vol * 1.02},
                            {"path": "bulb.kracht.c_lpr", "low": 0.022, "high": 0.028}],
             "measure": {"fairness": False, "compose": False, "displacement": False}}
    ref = fl.sweep(study, scheduler="serial", table=out("ref.parquet"), resume=False).to_pylist()
    for row in ref:
        text = labels["Variant %02d label" % row["variant"]]
        if row["status"] == "ok":
            check("displacement %.0f t" % (1.025 * row["hydro.volume"]) in text, "label %r vs row %s" % (text, row))
            check("Variant %02d" % row["variant"] in hulls, "no hull for variant %d" % row["variant"])
        else:
            check("FAILED" in text, "failed variant without its message: %r" % text)
    xs = sorted({round(bpy.data.objects[h].data.vertices[0].co.x, 3) for h in hulls})
    check(len(hulls) < 2 or len(xs) + len({round(bpy.data.objects[h].data.vertices[0].co.y, 3) for h in hulls}) > 2,
          "variants are not laid out side by side")
    results["sweep"] = {"variants": len(ref), "failed": sum(r["status"] != "ok" for r in ref),
                        "labels": [labels["Variant %02d label" % r["variant"]] for r in ref]}
    if has("distributed"):  # the same study on a local Dask cluster (run from a child process)
        n.scheduler = "local"
        api.export(tree, n)
        dask_labels = {o.name: o.data.body for o in coll.objects if o.type == "FONT"}
        check(dask_labels == labels, "local Dask sweep labels differ from the serial run's")
        results["sweep"]["dask_same_as_serial"] = True


def missing(api, tree, label, name, pip, **kw):
    """A missing optional package: the node is red naming the package and the pip line."""
    n = file_node(api, tree, label, name, out("missing_" + name.lower() + {"CAD": ".step", "Lines": ".svg", "Curves": ".csv",
                                                             "Sweep": ".parquet"}.get(name, ".msh")), **kw)
    check(n.fl_state == "ERROR" and "pip install" in n.fl_message and pip in n.fl_message,
          "%s without %s: %s %r" % (label, pip, n.fl_state, n.fl_message))
    results.setdefault("missing_messages", {})[label] = n.fl_message
    tree.nodes.remove(n)


def t_blocked_packages(api, tree):
    """With each extra blocked in sys.modules, its nodes turn red with the pip line."""
    saved = {m: sys.modules.get(m) for m in EXTRAS}
    try:
        for m in EXTRAS:
            sys.modules[m] = None
        for label, name, pip, kw in (("Export Mesh", "Mesh", "meshio", dict(source="Mesh", from_node="Hull Mesh",
                                                                             from_socket="Mesh")),
                                     ("Export CAD", "CAD", "cadquery-ocp-novtk", {}),
                                     ("Lines Plan", "Lines", "matplotlib", {}),
                                     ("Curves of Form", "Curves", "matplotlib", {}),
                                     ("Sweep", "Sweep", "pyarrow", {})):
            if label in [n.bl_label for n in tree.nodes]:
                tree.nodes.remove(next(n for n in tree.nodes if n.bl_label == label))
            missing(api, tree, label, name, pip, **kw)
    finally:
        for m, mod in saved.items():
            if mod is None:
                sys.modules.pop(m, None)
            else:
                sys.modules[m] = mod


def main():
    steps = []
    try:
        module = blender_graph.enable_addon(args.zip)
        api = importlib.import_module(module + ".api")
        import fairlines as fl
        tree, hull = ship_tree(api)
        for step in (t_hull_mesh, t_hull_mesh_without_bulb, t_surface_grid, t_export_mesh, t_export_cad, t_lines_plan, t_curves_of_form,
                     t_sweep):
            step(api, tree, hull, fl)
            steps.append(step.__name__)
        t_blocked_packages(api, tree)
        steps.append("t_blocked_packages")
    except Exception:
        results["failed_after"] = steps
        results["error"] = traceback.format_exc()
        print("FAIRLINES-CHECKS " + json.dumps(results))
        sys.stdout.flush()
        os._exit(1)
    results["passed"] = steps
    print("FAIRLINES-CHECKS " + json.dumps(results))
    sys.stdout.flush()


main()
