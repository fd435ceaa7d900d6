"""Output nodes: write results into the scene (mesh object with the Geometry Nodes modifier,
curve object) or to a file."""

import os

import bpy

from .. import engine, geonodes, ids, materials, props, scene_io
from .base import FairlinesNode, NodeError, register


class _ObjectOutput:
    is_output = True
    target: bpy.props.PointerProperty(type=bpy.types.Object)

    def needs_run(self):
        # Runs again (from cached inputs) when its object was deleted or renamed away.
        obj = self.target
        try:
            return obj is None or obj.users == 0 or not obj.users_collection
        except ReferenceError:
            return True


_MATERIALS = [("keep", "Keep", "Leave the object's materials alone"),
              ("paint", "Hull Paint", "Antifouling below the Waterline, a boot-top band, topsides above"),
              ("zebra", "Zebra", "Reflection-line stripes to judge fairness")]


@register
class FLNodeMeshOutput(_ObjectOutput, FairlinesNode, bpy.types.Node):
    """Write the mesh into an object, with the generated Geometry Nodes modifier (mirror to the
    full hull, Boolean union with a collection, difference with a cutter object)"""
    bl_idname = ids.NODE_MESH_OUTPUT
    bl_label = "Mesh Output"
    category = "Output"
    bl_width_default = 220
    inputs_spec = [(ids.SOCKET_MESH, "Mesh", {}),
                   (ids.SOCKET_LENGTH, "Waterline", {"default": 11.0})]
    params = ("object_name", "mirror", "union", "cutter", "smooth", "sharp_angle", "material")
    object_name: props.text("Object", "Fairlines Hull")
    mirror: props.boolean("Mirror", True, "Join the mirror image about y = 0 (full hull)")
    union: props.pointer("Union", bpy.types.Collection)
    cutter: props.pointer("Cutter", bpy.types.Object)
    smooth: props.boolean("Smooth", True, "Smooth shading, sharp where faces meet at more than Sharp Angle")
    sharp_angle: bpy.props.FloatProperty(name="Sharp Angle", default=0.5235988, min=0.0, max=3.1415927,
                                         subtype="ANGLE", update=props.changed,
                                         description="Edges whose faces meet at more than this shade as corners")
    material: props.enum("Material", _MATERIALS, "keep")

    def compute(self, inputs):
        engine.require()
        mesh = inputs["Mesh"]
        if mesh is None:
            raise NodeError("Connect a mesh")
        if not self.object_name.strip():
            raise NodeError("Give the object a name")
        waterline = inputs.get("Waterline")
        if self.material == "paint" and not (waterline is not None and waterline > 0):
            raise NodeError("Waterline is %s m; the hull paint needs the design draught > 0" % waterline)
        obj = scene_io.ensure_object(self.object_name, "MESH", self.target)
        if self.target != obj:
            self.target = obj
        in_place = scene_io.write_mesh(obj, mesh, self.smooth, self.sharp_angle)
        geonodes.apply_modifier(obj, self.mirror, self.union, self.cutter)
        if self.material == "paint":
            materials.assign(obj, materials.hull_paint("%s (%s)" % (ids.MAT_PAINT, obj.name), waterline))
        elif self.material == "zebra":
            materials.assign(obj, materials.zebra())
        out = {"__info__": "%s: %d vertices%s" % (obj.name, len(mesh.vertices), " (in place)" if in_place else "")}
        pending = mesh.pending_names()
        if pending and scene_io.reads_attribute(obj, pending):
            scene_io.write_point_attributes(obj, mesh.lazy.values())  # shown: needed now
        elif pending:
            out["__later__"] = lambda: _write_later(obj, mesh)
        return out


def _write_later(obj, mesh):
    """Deferred job of Mesh Output: the lazy attributes nothing showed, once the mesh is drawn."""
    try:
        same = len(obj.data.vertices) == len(mesh.vertices)
    except (ReferenceError, AttributeError):
        same = False  # the object or its mesh went away meanwhile
    if same:
        scene_io.write_point_attributes(obj, mesh.lazy.values())
    return {}


@register
class FLNodeLinesOutput(_ObjectOutput, FairlinesNode, bpy.types.Node):
    """Write polylines into a curve object"""
    bl_idname = ids.NODE_LINES_OUTPUT
    bl_label = "Lines Output"
    category = "Output"
    inputs_spec = [(ids.SOCKET_LINES, "Lines", {})]
    params = ("object_name",)
    object_name: props.text("Object", "Fairlines Lines")

    def compute(self, inputs):
        engine.require()
        lines = inputs["Lines"]
        if lines is None:
            raise NodeError("Connect lines")
        if not self.object_name.strip():
            raise NodeError("Give the object a name")
        obj = scene_io.ensure_object(self.object_name, "CURVE", self.target)
        if self.target != obj:
            self.target = obj
        scene_io.write_lines(obj, lines)
        return {"__info__": "%s: %d lines" % (obj.name, len(lines.polylines))}


def write_obj(path, mesh):
    """The engine package's OBJ writer (triangles). Quads are split along the same diagonal
    as fairlines.io.tessellate, so the file equals the package's own tessellation."""
    np = engine.np
    import fairlines.io
    faces = mesh.faces
    if faces.shape[1] == 4:
        quads, tris = faces[faces[:, 3] >= 0], faces[faces[:, 3] < 0, :3]  # -1 pads a mixed mesh's triangles
        faces = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]], tris])
    elif faces.shape[1] != 3:
        raise NodeError("OBJ export takes triangles or quads; got %d-gons" % faces.shape[1])
    fairlines.io.write_obj(path, mesh.vertices, faces)


@register
class FLNodeExportOBJ(FairlinesNode, bpy.types.Node):
    """Write the mesh to a Wavefront OBJ file (on every change when Auto is on, else with the
    Export button)"""
    bl_idname = ids.NODE_EXPORT_OBJ
    bl_label = "Export OBJ"
    category = "Output"
    is_output = True
    bl_width_default = 240
    inputs_spec = [(ids.SOCKET_MESH, "Mesh", {})]
    params = ("filepath", "auto")
    filepath: props.text("File", "//hull.obj", subtype="FILE_PATH")
    auto: props.boolean("Auto", False, "Write the file on every change")
    export_count: bpy.props.IntProperty(default=0)

    def signature(self):
        return super().signature() + (self.export_count,)

    def draw_params(self, context, layout):
        layout.prop(self, "filepath", text="")
        row = layout.row(align=True)
        row.prop(self, "auto")
        op = row.operator(ids.OP_EXPORT, text="Export", icon="EXPORT")
        op.tree = self.id_data.name
        op.node = self.name

    def compute(self, inputs):
        engine.require()
        mesh = inputs["Mesh"]
        if mesh is None:
            raise NodeError("Connect a mesh")
        if not (self.auto or self.export_count):
            return {"__info__": "not written yet"}
        path = bpy.path.abspath(self.filepath)
        if not path or os.path.isdir(path):
            raise NodeError("Choose a file name")
        parent = os.path.dirname(path)
        if parent and not os.path.isdir(parent):
            raise NodeError("Folder %s does not exist" % parent)
        write_obj(path, mesh)
        return {"__info__": "wrote %s" % os.path.basename(path)}
