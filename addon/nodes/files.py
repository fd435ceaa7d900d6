"""File outputs: solver meshes (meshio formats, WAMIT .gdf, Nemoh .mar), CAD (STEP, IGES,
Rhino .3dm), the lines plan (SVG, PDF, PNG, DXF) and the curves of form (CSV and plot), each
through the fairlines package's own writer. A file is written only by the node's Export button
(api.export in scripts), never on a slider move. Optional packages the writer needs are checked
first: when one is missing from Blender's Python the node is red with the pip line to install it."""

import importlib.util
import os
import sys

import bpy

from .. import engine, ids, props
from .base import FairlinesNode, NodeError, register

# Import name -> pip name of the optional packages the writers use.
PIP_NAMES = {"meshio": "meshio", "OCP": "cadquery-ocp-novtk", "rhino3dm": "rhino3dm", "matplotlib": "matplotlib",
             "ezdxf": "ezdxf", "dask": "dask[distributed]", "distributed": "dask[distributed]", "pyarrow": "pyarrow",
             "scipy": "scipy"}


def _importable(module):
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):  # ValueError: blocked in sys.modules (None)
        return False


def require_packages(*modules):
    """Raise NodeError naming the missing packages and the pip line for Blender's own Python."""
    missing = [m for m in modules if not _importable(m)]
    if missing:
        pip = " ".join(sorted({PIP_NAMES.get(m, m) for m in missing}))
        raise NodeError("Needs %s, missing in Blender's Python. Install with: \"%s\" -m pip install %s" % (
            ", ".join(missing), sys.executable, pip))


def target_path(filepath, suffixes):
    """The absolute path of a File property, checked: a file name with one of the suffixes in a
    folder that exists."""
    path = bpy.path.abspath(filepath)
    if not path or os.path.isdir(path):
        raise NodeError("Choose a file name")
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in suffixes:
        raise NodeError("File ends in %r; expected one of %s" % (suffix, ", ".join(sorted(suffixes))))
    parent = os.path.dirname(path)
    if parent and not os.path.isdir(parent):
        raise NodeError("Folder %s does not exist" % parent)
    return path, suffix


def _hull(value, fl):
    if not isinstance(value, fl.Hull):
        raise NodeError("Connect a hull (Particulars or Hull Description)")
    return value


def particulars(hull):
    p = hull.description.principal
    return dict(lpp=float(p.lpp), beam=float(p.breadth), draft=float(p.draft), depth=float(p.depth))


class FileWriter:
    """A node that writes a file when its Export button is pressed: export_count counts the
    presses (part of the node's cache key, so a press re-runs it) and written_count the presses
    served, so a change upstream re-runs the checks without writing."""
    is_output = True
    bl_width_default = 250
    suffixes = ()
    button = "Export"
    export_count: bpy.props.IntProperty(default=0)
    written_count: bpy.props.IntProperty(default=0)
    written_path: bpy.props.StringProperty(default="")

    def signature(self):
        return super().signature() + (self.export_count,)

    def draw_params(self, context, layout):
        layout.prop(self, "filepath", text="")
        for name in self.params:
            if name != "filepath":
                layout.prop(self, name)
        op = layout.operator(ids.OP_EXPORT, text=self.button, icon="EXPORT")
        op.tree = self.id_data.name
        op.node = self.name

    def packages(self, suffix):
        """Import names of the optional packages writing `suffix` needs."""
        return ()

    def compute(self, inputs):
        fl, _ = engine.require()
        path, suffix = target_path(self.filepath, self.suffixes)
        require_packages(*self.packages(suffix))
        value = self.source(inputs, fl)
        if self.export_count <= self.written_count:
            return {"__info__": "press Export to write %s" % os.path.basename(path)}
        info = self.write(value, path, suffix, fl) or ""
        self.written_count = self.export_count
        self.written_path = path
        return {"__info__": "wrote %s%s" % (path, "\n" + info if info else "")}


_MESH_SUFFIXES = (".msh", ".vtu", ".vtk", ".stl", ".obj", ".med", ".ply", ".off", ".gdf", ".mar")


@register
class FLNodeExportMesh(FileWriter, FairlinesNode, bpy.types.Node):
    """Write a mesh for a solver: meshio formats (.msh, .vtu, .stl, .obj, .med ...) or the
    wetted panels of a Hull Mesh with Draft as WAMIT .gdf / Nemoh .mar"""
    bl_idname = ids.NODE_EXPORT_MESH
    bl_label = "Export Mesh"
    category = "Output"
    suffixes = _MESH_SUFFIXES
    inputs_spec = [(ids.SOCKET_MESH, "Mesh", {})]
    params = ("filepath",)
    filepath: props.text("File", "//hull.msh", subtype="FILE_PATH")

    def packages(self, suffix):
        return () if suffix in (".gdf", ".mar") else ("meshio",)

    def source(self, inputs, fl):
        mesh = inputs["Mesh"]
        if mesh is None:
            raise NodeError("Connect a mesh")
        if mesh.solver is not None:
            return mesh.solver
        np = engine.np
        faces = np.asarray(mesh.faces, dtype=np.int64)
        if faces.shape[1] == 3:
            faces = np.column_stack([faces, np.full(len(faces), -1)])
        elif faces.shape[1] != 4:
            raise NodeError("Mesh has %d-gons; expected triangles or quads" % faces.shape[1])
        return fl.SurfaceMesh(np.asarray(mesh.vertices), faces, np.zeros(len(faces), dtype=np.int64), ("mesh",))

    def write(self, solver, path, suffix, fl):
        if suffix in (".gdf", ".mar"):
            if solver.draft is None:
                raise NodeError("Panel files hold the wetted part: use Hull Mesh with Draft on")
            (fl.write_gdf if suffix == ".gdf" else fl.write_mar)(solver, path)
        else:
            fl.write_mesh(solver, path)
        return "%d elements" % len(solver.faces)


_CAD_WHAT = [("solid", "Solid", "Trimmed faces sewn into one closed shell"),
             ("surfaces", "Surfaces", "Each NURBS surface whole")]
_SCHEMAS = [("AP214", "AP214", "STEP AP214"), ("AP242", "AP242", "STEP AP242")]


@register
class FLNodeExportCAD(FileWriter, FairlinesNode, bpy.types.Node):
    """Write the composed hull's exact NURBS geometry as STEP / IGES (OpenCASCADE) or Rhino
    .3dm (rhino3dm), through fairlines.cad.export_cad"""
    bl_idname = ids.NODE_EXPORT_CAD
    bl_label = "Export CAD"
    category = "Output"
    suffixes = (".step", ".stp", ".iges", ".igs", ".3dm")
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {})]
    params = ("filepath", "what", "full", "schema")
    filepath: props.text("File", "//hull.step", subtype="FILE_PATH")
    what: props.enum("What", _CAD_WHAT, "solid")
    full: props.boolean("Full Ship", False, "The mirrored full ship instead of the half (y >= 0)")
    schema: props.enum("Schema", _SCHEMAS, "AP214")

    def packages(self, suffix):
        return ("rhino3dm",) if suffix == ".3dm" else ("OCP",)

    def source(self, inputs, fl):
        return _hull(inputs["Hull"], fl)

    def write(self, hull, path, suffix, fl):
        from fairlines import cad
        cad.export_cad(hull.composed_hull(), path, what=self.what, full=self.full, schema=self.schema)
        return ""


_ENDS = [("none", "Whole Ship", "The whole lines plan"), ("bow", "Bow", "Close-up of the bow"),
         ("stern", "Stern", "Close-up of the stern")]


@register
class FLNodeLinesPlan(FileWriter, FairlinesNode, bpy.types.Node):
    """Lines plan of the composed hull (fairlines.lines_plan): profile, half-breadth and body
    plans with stations, waterlines, buttocks, diagonals and a title block, as SVG, PDF, PNG
    (shown in Blender's image editor as "Fairlines Lines Plan") or DXF"""
    bl_idname = ids.NODE_LINES_PLAN
    bl_label = "Lines Plan"
    category = "Output"
    suffixes = (".svg", ".pdf", ".png", ".dxf")
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {})]
    params = ("filepath", "closeup")
    filepath: props.text("File", "//lines.png", subtype="FILE_PATH")
    closeup: props.enum("View", _ENDS, "none")

    def packages(self, suffix):
        return ("ezdxf",) if suffix == ".dxf" else ("matplotlib",)

    def source(self, inputs, fl):
        return _hull(inputs["Hull"], fl)

    def write(self, hull, path, suffix, fl):
        from fairlines.lines_plan import closeup, lines_plan
        kw = dict(particulars(hull), name=hull.description.name)
        composed = hull.composed_hull()
        plan = lines_plan(composed, **kw) if self.closeup == "none" else closeup(composed, self.closeup, **kw)
        plan.save(path)
        if suffix == ".png":
            show_image(path)
        return "scale 1:%g" % plan.scale


def show_image(path):
    """Load (or reload) the PNG as the image "Fairlines Lines Plan"."""
    img = bpy.data.images.get(ids.IMAGE_LINES_PLAN)
    if img is not None and bpy.path.abspath(img.filepath) == path:
        img.reload()
        return img
    if img is not None:
        bpy.data.images.remove(img)
    img = bpy.data.images.load(path)
    img.name = ids.IMAGE_LINES_PLAN
    return img


@register
class FLNodeCurvesOfForm(FileWriter, FairlinesNode, bpy.types.Node):
    """Hydrostatics of the ship over drafts (fairlines.curves_of_form: the bare hull, with a bulb
    the composed ship) as a CSV table, and the curves-of-form plot beside it (same name, .png)
    when Plot is on"""
    bl_idname = ids.NODE_CURVES_OF_FORM
    bl_label = "Curves of Form"
    category = "Output"
    suffixes = (".csv",)
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {}),
                   (ids.SOCKET_INT, "Drafts", {"default": 19})]
    params = ("filepath", "plot")
    filepath: props.text("File", "//curves_of_form.csv", subtype="FILE_PATH")
    plot: props.boolean("Plot", True, "Also write the plot (PNG beside the table)")

    def packages(self, suffix):
        return ("matplotlib",) if self.plot else ()

    def source(self, inputs, fl):
        hull = _hull(inputs["Hull"], fl)
        n = inputs["Drafts"]
        if not 2 <= n <= 500:
            raise NodeError("Drafts is %d; expected 2 .. 500" % n)
        return hull, n

    def write(self, value, path, suffix, fl):
        from fairlines.curves_of_form import curves_of_form, highest_draft
        hull, n = value
        p, surface = particulars(hull), hull.bare_hull_surface()
        top = highest_draft(surface, p["depth"], p["lpp"])
        drafts = engine.np.linspace(0.1 * p["draft"], top, n)
        ship = hull.composed_hull() if hull.description.bulb is not None else surface  # as fairlines hydrostatics
        cof = curves_of_form(ship, drafts, lpp=p["lpp"], beam=p["beam"], depth=p["depth"], design_draft=p["draft"])
        cof.write_csv(path)
        if self.plot:
            cof.plot(os.path.splitext(path)[0] + ".png", hull.description.name)
        return "%d drafts %.3g .. %.3g m" % (n, drafts[0], drafts[-1])
