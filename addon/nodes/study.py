"""The sweep face: a small design study of the connected hull (fairlines.sweep), its variants
laid out side by side in the scene, each labelled with its varied values and displacement."""

import json
import math
import os
import sys

import bpy

from .. import engine, ids, progress, props
from .base import FairlinesNode, NodeError, register
from .files import FileWriter, require_packages

SEA_WATER = 1.025  # t/m^3: displacement of the labels
# Varied description fields: (node property, dotted path, label, unit, relative).
VARIED = (("vary_volume", "basic_curves.sac.volume", "V", "m3", True),
          ("vary_lcb", "basic_curves.sac.lcb", "LCB", "m", False),
          ("vary_bulb", "bulb.kracht.c_lpr", "C_LPR", "", False))
MAX_VARIANTS = 27
MAX_COLUMNS = 9  # variants side by side before a new row starts aft of them
LABEL_BELOW, LABEL_SIZE = 0.08, 0.16  # label aft of its hull (fraction of Lpp); text height (of B)
GAP = 0.4  # free space between neighbours, as a fraction of the hull's breadth / length
_SCHEDULERS = [("serial", "Serial", "One variant after the other in Blender's process"),
               ("local", "Local Dask", "A local Dask cluster of worker processes (all cores)")]


def base_value(doc, path):
    for key in path.split("."):
        if not isinstance(doc, dict) or key not in doc:
            raise NodeError("The hull description has no %s to vary" % path)
        doc = doc[key]
    return float(doc)


@register
class FLNodeSweep(FileWriter, FairlinesNode, bpy.types.Node):
    """Run a small study of the connected hull (fairlines.sweep, full factorial): SAC volume
    +- a percentage, LCB +- metres, bulb length coefficient +- a step (0 leaves one fixed).
    Run writes the Parquet table and lays the variants out side by side in the collection
    "Fairlines Sweep", labelled with the varied values and displacement; a failed variant is a
    text object with its message"""
    bl_idname = ids.NODE_SWEEP
    bl_label = "Sweep"
    category = "Output"
    button = "Run Sweep"
    suffixes = (".parquet",)
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {})]
    params = ("filepath", "vary_volume", "vary_lcb", "vary_bulb", "levels", "scheduler")
    filepath: props.text("Table", "//sweep.parquet", subtype="FILE_PATH")
    vary_volume: props.number("Volume +-%", 2.0, 0.0, 30.0, "SAC volume varied by this percentage either way")
    vary_lcb: props.number("LCB +-", 0.0, 0.0, 50.0, "LCB varied by this many metres either way")
    vary_bulb: props.number("C_LPR +-", 0.003, 0.0, 0.02, "Bulb length coefficient varied by this much either way")
    levels: props.integer("Levels", 2, 2, 5, description="Values per varied parameter")
    scheduler: props.enum("Run", _SCHEDULERS, "serial")

    def packages(self, suffix):
        return ("pyarrow",) + (("dask", "distributed") if self.scheduler == "local" else ())

    def source(self, inputs, fl):
        hull = inputs["Hull"]
        if not isinstance(hull, fl.Hull):
            raise NodeError("Connect a hull (Particulars or Hull Description)")
        doc = json.loads(hull.to_json())
        params = []
        for prop, path, _, _, relative in VARIED:
            step = float(getattr(self, prop))
            if not math.isfinite(step) or step < 0.0:
                raise NodeError("%s is %s; expected a step >= 0" % (prop, step))
            if step > 0.0:
                v = base_value(doc, path)
                d = abs(v) * step / 100.0 if relative else step
                params.append({"path": path, "low": v - d, "high": v + d})
        if not params:
            raise NodeError("Every step is 0; vary at least one value")
        if self.levels ** len(params) > MAX_VARIANTS:
            raise NodeError("%d variants; expected at most %d (fewer levels or parameters)" % (
                self.levels ** len(params), MAX_VARIANTS))
        return doc, params

    def write(self, value, path, suffix, fl):
        doc, params = value
        study = {"name": "blender sweep", "base": {"description": doc},
                 "sampling": {"method": "factorial", "levels": int(self.levels)}, "parameters": params,
                 "measure": {"fairness": False, "compose": False, "displacement": False}}
        with progress.Progress("sweep", self.levels ** len(params)) as bar:
            if self.scheduler == "serial":
                table = fl.sweep(study, scheduler="serial", table=path, resume=False,
                                 progress=lambda done, total, row: bar.update(done, "variants", total))
            else:
                table = run_in_child(study, path, bar)
            rows = table.to_pylist()
            show_variants(fl, doc, [p["path"] for p in params], rows, bar)
        failed = sum(r["status"] != "ok" for r in rows)
        return "%d variants, %d failed" % (len(rows), failed)


# A local Dask cluster's worker processes re-import the parent's main module, which inside
# Blender is Blender itself: the study runs in a child Python (Blender's own interpreter, the
# engine on its path) that starts the cluster and reports progress line by line.
_CHILD = """import json, sys
from fairlines.sweep import sweep
def tell(done, total, row):
    print("PROGRESS", done, total, flush=True)
sweep(json.load(open(sys.argv[1])), table=sys.argv[2], resume=False, progress=tell)
"""


def run_in_child(study, path, bar):
    """fl.sweep on a local Dask cluster in a child process; the table it wrote."""
    import subprocess
    import pyarrow.parquet as pq
    spec = path + ".study.json"
    with open(spec, "w") as f:
        json.dump(study, f)
    env = dict(os.environ)
    engine_dir = os.path.dirname(engine.SOURCE)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (engine_dir, env.get("PYTHONPATH", "")) if p)
    proc = subprocess.Popen([sys.executable, "-c", _CHILD, spec, path], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env)
    for line in proc.stdout:
        parts = line.split()
        if len(parts) == 3 and parts[0] == "PROGRESS":
            bar.update(int(parts[1]), "variants on Dask", int(parts[2]))
    err = proc.stderr.read()
    if proc.wait() != 0:
        last = [ln for ln in err.strip().splitlines() if ln.strip()][-1:] or ["exit code %d" % proc.returncode]
        raise NodeError("The local Dask sweep failed: %s" % last[0])
    os.remove(spec)
    return pq.read_table(path)


def _label_text(row, paths):
    parts = []
    for _, path, label, unit, _ in VARIED:
        if path in paths:
            parts.append("%s %.5g%s" % (label, row[path], (" " + unit) if unit else ""))
    head = ", ".join(parts)
    if row["status"] != "ok":
        return "%s\nFAILED (%s): %s" % (head, row.get("error_stage") or "?", row.get("error") or "")
    return "%s\ndisplacement %.0f t" % (head, SEA_WATER * row["hydro.volume"])


def _collection():
    coll = bpy.data.collections.get(ids.SWEEP_COLLECTION)
    if coll is None:
        coll = bpy.data.collections.new(ids.SWEEP_COLLECTION)
    if coll.name not in bpy.context.scene.collection.children:
        bpy.context.scene.collection.children.link(coll)
    for obj in list(coll.objects):  # the previous run's variants
        data = obj.data
        bpy.data.objects.remove(obj)
        if data is not None and data.users == 0:
            (bpy.data.meshes if isinstance(data, bpy.types.Mesh) else bpy.data.curves).remove(data)
    return coll


def _hull_mesh(fl, np, surface, name, coll, offset):
    """The full hull (both sides) of a bare-hull surface as a mesh object at offset."""
    from .mesh import grid_quads
    nu, nv = 24, 64
    pts = surface.evaluate_grid(np.linspace(*surface.domain_u, nu), np.linspace(*surface.domain_v, nv)).reshape(-1, 3)
    quads = grid_quads(nu, nv)
    mirrored = pts * np.array([1.0, -1.0, 1.0])
    verts = np.concatenate([pts, mirrored]) + np.asarray(offset)
    faces = np.concatenate([quads[:, ::-1], quads + len(pts)])  # outward on both sides
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts.tolist(), [], faces.tolist())
    me.polygons.foreach_set("use_smooth", [True] * len(faces))
    me.update()
    obj = bpy.data.objects.new(name, me)
    coll.objects.link(obj)
    return obj


def _label(name, text, coll, location, size):
    cu = bpy.data.curves.new(name, "FONT")
    cu.body = text
    cu.size = size
    cu.align_x = "CENTER"
    obj = bpy.data.objects.new(name, cu)
    obj.location = location
    obj.rotation_euler = (0.0, 0.0, -0.5 * math.pi)  # seen from above with the bows up, it reads across
    coll.objects.link(obj)
    return obj


def show_variants(fl, doc, paths, rows, bar=None):
    """Each row's hull (rebuilt from the description with its varied values) in a grid of
    columns, and its label above it; failed rows get only the label."""
    from fairlines.sweep_variant import apply_parameters
    np = engine.np
    p = doc["principal"]
    lpp, beam, depth = float(p["Lpp"]), float(p["B"]), float(p["D"])
    cols = min(len(rows), MAX_COLUMNS)
    coll = _collection()
    for k, row in enumerate(rows):
        offset = ((k // cols) * lpp * (1.0 + GAP), (k % cols) * beam * (2.0 + GAP), 0.0)
        name = "Variant %02d" % row["variant"]
        if row["status"] == "ok":
            hull = fl.Hull.from_json(apply_parameters(doc, {q: row[q] for q in paths}))
            _hull_mesh(fl, np, hull.bare_hull_surface(), name, coll, offset)
        _label(name + " label", _label_text(row, paths), coll,
               (offset[0] - LABEL_BELOW * lpp, offset[1], depth), LABEL_SIZE * beam)
        if bar is not None:
            bar.update(k + 1, "laid out", len(rows))
    return coll
