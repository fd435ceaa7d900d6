"""Curve nodes: exact conics and fitting, all computed by the engine."""

import bpy

from .. import engine, ids, props
from ..data import LinesData
from .base import FairlinesNode, NodeError, register

_PARAMETERIZATION = [("chord", "Chord length", "Chord-length parameters"),
                     ("centripetal", "Centripetal", "Square root of chord lengths"),
                     ("uniform", "Uniform", "Equally spaced parameters")]


@register
class FLNodeCircle(FairlinesNode, bpy.types.Node):
    """Exact full circle (rational quadratic)"""
    bl_idname = ids.NODE_CIRCLE
    bl_label = "Circle"
    category = "Curves"
    inputs_spec = [(ids.SOCKET_VECTOR, "Center", {}),
                   (ids.SOCKET_LENGTH, "Radius", {"default": 1.0}),
                   (ids.SOCKET_VECTOR, "Normal", {"default": (0.0, 0.0, 1.0)})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]

    def compute(self, inputs):
        fl, _ = engine.require()
        return {"Curve": fl.circle(inputs["Center"], inputs["Radius"], inputs["Normal"])}


@register
class FLNodeArc(FairlinesNode, bpy.types.Node):
    """Exact circular arc"""
    bl_idname = ids.NODE_ARC
    bl_label = "Arc"
    category = "Curves"
    inputs_spec = [(ids.SOCKET_VECTOR, "Center", {}),
                   (ids.SOCKET_LENGTH, "Radius", {"default": 1.0}),
                   (ids.SOCKET_ANGLE, "Start", {"default": 0.0}),
                   (ids.SOCKET_ANGLE, "End", {"default": 1.5707963267948966}),
                   (ids.SOCKET_VECTOR, "Normal", {"default": (0.0, 0.0, 1.0)})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]

    def compute(self, inputs):
        fl, _ = engine.require()
        return {"Curve": fl.arc(inputs["Center"], inputs["Radius"], inputs["Start"], inputs["End"],
                                inputs["Normal"])}


@register
class FLNodeEllipse(FairlinesNode, bpy.types.Node):
    """Exact ellipse from its centre and two semi-axis vectors"""
    bl_idname = ids.NODE_ELLIPSE
    bl_label = "Ellipse"
    category = "Curves"
    inputs_spec = [(ids.SOCKET_VECTOR, "Center", {}),
                   (ids.SOCKET_VECTOR, "Semi-axis A", {"default": (2.0, 0.0, 0.0)}),
                   (ids.SOCKET_VECTOR, "Semi-axis B", {"default": (0.0, 0.0, 1.0)})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]

    def compute(self, inputs):
        fl, _ = engine.require()
        return {"Curve": fl.ellipse(inputs["Center"], inputs["Semi-axis A"], inputs["Semi-axis B"])}


@register
class FLNodeFitCurve(FairlinesNode, bpy.types.Node):
    """Interpolate or least-squares fit the first polyline of the input"""
    bl_idname = ids.NODE_FIT_CURVE
    bl_label = "Fit Curve"
    category = "Curves"
    inputs_spec = [(ids.SOCKET_LINES, "Points", {}),
                   (ids.SOCKET_INT, "Degree", {"default": 3}),
                   (ids.SOCKET_INT, "Control Points", {"default": 8, "optional": True, "use": False})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]
    params = ("parameterization",)
    parameterization: props.enum("Parameters", _PARAMETERIZATION, "chord")

    def compute(self, inputs):
        fl, np = engine.require()
        lines = inputs["Points"]
        if lines is None or not lines.polylines:
            raise NodeError("Connect points to fit (e.g. Lines From Object)")
        fit = fl.fit_curve(np.asarray(lines.polylines[0]), degree=inputs["Degree"],
                           n_control=inputs["Control Points"], parameterization=self.parameterization)
        return {"Curve": fit.curve,
                "__info__": "max dev %.4g m, rms %.4g m" % (fit.max_deviation, fit.rms_deviation)}


@register
class FLNodeTrimCurve(FairlinesNode, bpy.types.Node):
    """The piece of a curve between two parameters, as a clamped curve (engine split)"""
    bl_idname = ids.NODE_TRIM_CURVE
    bl_label = "Trim Curve"
    category = "Curves"
    inputs_spec = [(ids.SOCKET_CURVE, "Curve", {}),
                   (ids.SOCKET_FLOAT, "Start", {"default": 0.0}),
                   (ids.SOCKET_FLOAT, "End", {"default": 0.5})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]

    def compute(self, inputs):
        engine.require()
        curve = inputs["Curve"]
        if curve is None:
            raise NodeError("Connect a curve")
        out = curve.split(inputs["Start"], inputs["End"])
        return {"Curve": out, "__info__": "domain %.3g .. %.3g" % tuple(curve.domain)}


def _curve(inputs):
    c = inputs.get("Curve")
    if c is None:
        raise NodeError("Connect a curve")
    return c


@register
class FLNodeCurveInsertKnot(FairlinesNode, bpy.types.Node):
    """Insert a knot into a curve (same shape, more control points)"""
    bl_idname = ids.NODE_CURVE_INSERT_KNOT
    bl_label = "Curve Insert Knot"
    category = "Edit"
    inputs_spec = [(ids.SOCKET_CURVE, "Curve", {}),
                   (ids.SOCKET_FLOAT, "Parameter", {"default": 0.5}),
                   (ids.SOCKET_INT, "Times", {"default": 1})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]

    def compute(self, inputs):
        out = _curve(inputs).insert_knot(inputs["Parameter"], inputs["Times"])
        return {"Curve": out, "__info__": "%d control points" % out.n_control}


@register
class FLNodeCurveElevateDegree(FairlinesNode, bpy.types.Node):
    """Raise the degree of a curve (same shape)"""
    bl_idname = ids.NODE_CURVE_ELEVATE_DEGREE
    bl_label = "Curve Elevate Degree"
    category = "Edit"
    inputs_spec = [(ids.SOCKET_CURVE, "Curve", {}),
                   (ids.SOCKET_INT, "Times", {"default": 1})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]

    def compute(self, inputs):
        out = _curve(inputs).elevate_degree(inputs["Times"])
        return {"Curve": out, "__info__": "degree %d" % out.degree}


@register
class FLNodeCurveSetWeight(FairlinesNode, bpy.types.Node):
    """Set the weight of one control point of a curve: up pulls the curve toward it"""
    bl_idname = ids.NODE_CURVE_SET_WEIGHT
    bl_label = "Curve Set Weight"
    category = "Edit"
    inputs_spec = [(ids.SOCKET_CURVE, "Curve", {}),
                   (ids.SOCKET_INT, "Index", {"default": 0}),
                   (ids.SOCKET_FLOAT, "Weight", {"default": 1.0})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]

    def compute(self, inputs):
        out = _curve(inputs).copy()  # the input is a shared cached value: never edit it
        out.set_weight(inputs["Index"], inputs["Weight"])
        return {"Curve": out}


@register
class FLNodeCurveLines(FairlinesNode, bpy.types.Node):
    """Sample a curve into a polyline (to show it as a curve object)"""
    bl_idname = ids.NODE_CURVE_LINES
    bl_label = "Curve to Lines"
    category = "Lines"
    inputs_spec = [(ids.SOCKET_CURVE, "Curve", {}),
                   (ids.SOCKET_INT, "Samples", {"default": 64})]
    outputs_spec = [(ids.SOCKET_LINES, "Lines")]

    def compute(self, inputs):
        fl, np = engine.require()
        curve, n = inputs["Curve"], inputs["Samples"]
        if curve is None:
            raise NodeError("Connect a curve")
        if n < 2:
            raise NodeError("Samples is %d; expected at least 2" % n)
        t0, t1 = curve.domain
        pts = np.asarray(curve.evaluate(np.linspace(t0, t1, n)), dtype=np.float64)
        if pts.shape[1] == 2:  # a 2-D curve lies in the scene's xy plane
            pts = np.column_stack([pts, np.zeros(len(pts))])
        return {"Lines": LinesData([pts])}
