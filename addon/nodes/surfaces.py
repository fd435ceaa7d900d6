"""Surface nodes: primitives, revolution, fitting and the shape-control operators (knot
insertion, degree elevation, weights, control points), all computed by the engine."""

import math

import bpy

from .. import engine, ids, props
from ..data import LinesData
from .base import FairlinesNode, NodeError, register

_DIRECTIONS = [("u", "U", "First parametric direction"), ("v", "V", "Second parametric direction")]


def _surface(inputs, name="Surface"):
    s = inputs.get(name)
    if s is None:
        raise NodeError("Connect a surface to '%s'" % name)
    return s


@register
class FLNodeLinesFromObject(FairlinesNode, bpy.types.Node):
    """Points of a mesh object, in vertex order, cut into rows of equal length: offsets or a
    point grid drawn in Blender (fit them with Fit Curve / Fit Surface)"""
    bl_idname = ids.NODE_POINTS_FROM_OBJECT
    bl_label = "Points From Object"
    category = "Input"
    outputs_spec = [(ids.SOCKET_LINES, "Points")]
    params = ("source", "columns")
    source: props.pointer("Object", bpy.types.Object)
    columns: props.integer("Columns", 0, min=0, description="Points per row; 0 = one row")

    def watched_objects(self):
        return {self.source.name} if self.source is not None else set()

    def signature(self):
        # The object's vertices belong to the key so that editing it re-runs the fit.
        base = super().signature()
        pts = self._points()
        return base + ((pts.shape, hash(pts.tobytes())) if pts is not None else (None,))

    def _points(self):
        if engine.np is None or self.source is None or self.source.type != "MESH":
            return None
        mesh = self.source.data
        np = engine.np
        pts = np.empty(len(mesh.vertices) * 3, dtype=np.float64)
        mesh.vertices.foreach_get("co", pts)
        pts = pts.reshape(-1, 3)
        mw = np.array(self.source.matrix_world, dtype=np.float64)
        return pts @ mw[:3, :3].T + mw[:3, 3]

    def compute(self, inputs):
        engine.require()
        if self.source is None:
            raise NodeError("Choose a mesh object")
        pts = self._points()
        if pts is None:
            raise NodeError("'%s' is not a mesh object" % self.source.name)
        cols = self.columns or len(pts)
        if cols == 0 or len(pts) % cols:
            raise NodeError("%d points do not split into rows of %d" % (len(pts), cols))
        rows = pts.reshape(-1, cols, 3)
        return {"Points": LinesData(list(rows)), "__info__": "%d x %d points" % rows.shape[:2]}


@register
class FLNodeFitSurface(FairlinesNode, bpy.types.Node):
    """Interpolate or least-squares fit a grid of points (rows run in u)"""
    bl_idname = ids.NODE_FIT_SURFACE
    bl_label = "Fit Surface"
    category = "Surfaces"
    inputs_spec = [(ids.SOCKET_LINES, "Points", {}),
                   (ids.SOCKET_INT, "Degree U", {"default": 3}),
                   (ids.SOCKET_INT, "Degree V", {"default": 3}),
                   (ids.SOCKET_INT, "Control Points U", {"default": 8, "optional": True, "use": False}),
                   (ids.SOCKET_INT, "Control Points V", {"default": 8, "optional": True, "use": False})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]
    params = ("parameterization",)
    parameterization: props.enum("Parameters", [("chord", "Chord length", ""),
                                                ("centripetal", "Centripetal", ""),
                                                ("uniform", "Uniform", "")], "chord")

    def compute(self, inputs):
        fl, np = engine.require()
        lines = inputs["Points"]
        if lines is None or not lines.polylines:
            raise NodeError("Connect a point grid (e.g. Points From Object)")
        lengths = {len(p) for p in lines.polylines}
        if len(lengths) != 1:
            raise NodeError("Rows have different lengths %s; a grid needs equal rows" % sorted(lengths))
        grid = np.stack(lines.polylines)
        fit = fl.fit_surface(grid, degree_u=inputs["Degree U"], degree_v=inputs["Degree V"],
                             n_control_u=inputs["Control Points U"], n_control_v=inputs["Control Points V"],
                             parameterization=self.parameterization)
        return {"Surface": fit.surface,
                "__info__": "max dev %.4g m, rms %.4g m" % (fit.max_deviation, fit.rms_deviation)}


@register
class FLNodeRevolve(FairlinesNode, bpy.types.Node):
    """Surface of revolution of a profile curve about an axis"""
    bl_idname = ids.NODE_REVOLVE
    bl_label = "Revolve"
    category = "Surfaces"
    inputs_spec = [(ids.SOCKET_CURVE, "Profile", {}),
                   (ids.SOCKET_VECTOR, "Axis Point", {}),
                   (ids.SOCKET_VECTOR, "Axis Direction", {"default": (1.0, 0.0, 0.0)}),
                   (ids.SOCKET_ANGLE, "Angle", {"default": 6.283185307179586})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]

    def compute(self, inputs):
        fl, _ = engine.require()
        profile = inputs["Profile"]
        if profile is None:
            raise NodeError("Connect a profile curve")
        if profile.dim == 2:
            raise NodeError("Profile is a 2-D curve; revolve needs a 3-D curve (give 3-D centre and axes)")
        angle = inputs["Angle"]
        # Blender stores the socket in single precision: 360 degrees reads back as 2 pi plus
        # 1.7e-7, which the engine rightly rejects as more than a full turn.
        if 0.0 < angle - 2.0 * math.pi < 1e-6:
            angle = 2.0 * math.pi
        return {"Surface": fl.revolve(profile, inputs["Axis Point"], inputs["Axis Direction"], angle)}


@register
class FLNodeCylinder(FairlinesNode, bpy.types.Node):
    """Exact cylinder"""
    bl_idname = ids.NODE_CYLINDER
    bl_label = "Cylinder"
    category = "Surfaces"
    inputs_spec = [(ids.SOCKET_VECTOR, "Base", {}),
                   (ids.SOCKET_VECTOR, "Axis", {"default": (0.0, 1.0, 0.0)}),
                   (ids.SOCKET_LENGTH, "Radius", {"default": 1.0}),
                   (ids.SOCKET_LENGTH, "Height", {"default": 2.0})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]

    def compute(self, inputs):
        fl, _ = engine.require()
        return {"Surface": fl.cylinder(inputs["Base"], inputs["Axis"], inputs["Radius"], inputs["Height"])}


@register
class FLNodeSphere(FairlinesNode, bpy.types.Node):
    """Exact sphere"""
    bl_idname = ids.NODE_SPHERE
    bl_label = "Sphere"
    category = "Surfaces"
    inputs_spec = [(ids.SOCKET_VECTOR, "Center", {}),
                   (ids.SOCKET_LENGTH, "Radius", {"default": 1.0})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]

    def compute(self, inputs):
        fl, _ = engine.require()
        return {"Surface": fl.sphere(inputs["Center"], inputs["Radius"])}


@register
class FLNodeInsertKnot(FairlinesNode, bpy.types.Node):
    """Insert a knot (same shape, more control points)"""
    bl_idname = ids.NODE_INSERT_KNOT
    bl_label = "Insert Knot"
    category = "Edit"
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_FLOAT, "Parameter", {"default": 0.5}),
                   (ids.SOCKET_INT, "Times", {"default": 1})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]
    params = ("direction",)
    direction: props.enum("Direction", _DIRECTIONS, "u")

    def compute(self, inputs):
        s = _surface(inputs)
        out = s.insert_knot(self.direction, inputs["Parameter"], inputs["Times"])
        return {"Surface": out, "__info__": "control net %d x %d" % tuple(out.shape)}


@register
class FLNodeElevateDegree(FairlinesNode, bpy.types.Node):
    """Raise the degree in one direction (same shape)"""
    bl_idname = ids.NODE_ELEVATE_DEGREE
    bl_label = "Elevate Degree"
    category = "Edit"
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_INT, "Times", {"default": 1})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]
    params = ("direction",)
    direction: props.enum("Direction", _DIRECTIONS, "u")

    def compute(self, inputs):
        s = _surface(inputs)
        out = s.elevate_degree(self.direction, inputs["Times"])
        return {"Surface": out, "__info__": "degrees %d, %d" % (out.degree_u, out.degree_v)}


@register
class FLNodeSetWeight(FairlinesNode, bpy.types.Node):
    """Set the weight of control point (i, j): up pulls the surface toward it"""
    bl_idname = ids.NODE_SET_WEIGHT
    bl_label = "Set Weight"
    category = "Edit"
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_INT, "I", {"default": 0}),
                   (ids.SOCKET_INT, "J", {"default": 0}),
                   (ids.SOCKET_FLOAT, "Weight", {"default": 1.0})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]

    def compute(self, inputs):
        out = _surface(inputs).copy()  # the input is a shared cached value: never edit it
        out.set_weight(inputs["I"], inputs["J"], inputs["Weight"])
        return {"Surface": out}


@register
class FLNodeMoveControlPoint(FairlinesNode, bpy.types.Node):
    """Move control point (i, j) by an offset"""
    bl_idname = ids.NODE_MOVE_CONTROL_POINT
    bl_label = "Move Control Point"
    category = "Edit"
    inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {}),
                   (ids.SOCKET_INT, "I", {"default": 0}),
                   (ids.SOCKET_INT, "J", {"default": 0}),
                   (ids.SOCKET_VECTOR, "Offset", {})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]

    def compute(self, inputs):
        _, np = engine.require()
        s = _surface(inputs)
        i, j = inputs["I"], inputs["J"]
        nu, nv = s.shape
        if not (0 <= i < nu and 0 <= j < nv):
            raise NodeError("Control point (%d, %d) is outside the %d x %d net" % (i, j, nu, nv))
        out = s.copy()
        out.set_control_point(i, j, np.asarray(s.control_points[i, j]) + np.asarray(inputs["Offset"]))
        return {"Surface": out}
