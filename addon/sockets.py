"""Typed sockets of the Fairlines tree.

Data sockets carry engine objects (curve, surface) or engine results (mesh, lines) between
nodes; they have no editable value. Number sockets carry a value with a unit (Blender shows
and edits it in the scene's unit system; the engine always receives metres / radians). A number
socket can be *optional*: it then has an on/off switch and passes None when off, which is how
form-parameter inputs are dropped from a design request.
"""

import bpy

from . import ids, props

# Colours only help the eye match sockets; compatible links are decided by bl_idname.
_COLOURS = {
    ids.SOCKET_CURVE: (0.25, 0.75, 0.95, 1.0),
    ids.SOCKET_SURFACE: (0.95, 0.55, 0.15, 1.0),
    ids.SOCKET_MESH: (0.0, 0.85, 0.6, 1.0),
    ids.SOCKET_LINES: (0.7, 0.6, 0.95, 1.0),
    ids.SOCKET_HULL_DATA: (0.9, 0.85, 0.3, 1.0),
    ids.SOCKET_LENGTH: (0.63, 0.63, 0.63, 1.0),
    ids.SOCKET_ANGLE: (0.63, 0.63, 0.75, 1.0),
    ids.SOCKET_FLOAT: (0.63, 0.63, 0.63, 1.0),
    ids.SOCKET_INT: (0.35, 0.55, 0.36, 1.0),
    ids.SOCKET_VECTOR: (0.39, 0.39, 0.78, 1.0),
    ids.SOCKET_AREA: (0.55, 0.63, 0.63, 1.0),
    ids.SOCKET_VOLUME: (0.5, 0.6, 0.6, 1.0),
    ids.SOCKET_CURVATURE: (0.7, 0.6, 0.6, 1.0),
    ids.SOCKET_BLEND: (0.95, 0.4, 0.55, 1.0),
    ids.SOCKET_HULL: (0.2, 0.45, 0.95, 1.0),
    ids.SOCKET_CURVES: (0.25, 0.6, 0.8, 1.0),
}

# Number sockets that may feed one another (a Length into a Float input and so on).
NUMERIC = {ids.SOCKET_LENGTH, ids.SOCKET_ANGLE, ids.SOCKET_FLOAT, ids.SOCKET_INT, ids.SOCKET_AREA,
           ids.SOCKET_VOLUME, ids.SOCKET_CURVATURE}


class _DataSocket:
    def draw(self, context, layout, node, text):
        layout.label(text=text)

    def draw_color(self, context, node):
        return _COLOURS[self.bl_idname]

    def value(self):
        return None


class _ValueSocket:
    is_optional: bpy.props.BoolProperty(default=False)
    use: props.boolean("Use", True, "Pass this parameter to the engine; off drops it")
    # Shown after the name for units Blender's unit system has no name for (1/m).
    unit_suffix = ""

    def draw(self, context, layout, node, text):
        if self.unit_suffix:
            text = "%s (%s)" % (text, self.unit_suffix)
        if self.is_output or self.is_linked:
            layout.label(text=text)
            return
        row = layout.row(align=True)
        if self.is_optional:
            row.prop(self, "use", text="")
            sub = row.row(align=True)
            sub.active = self.use
            sub.prop(self, "default_value", text=text)
        else:
            row.prop(self, "default_value", text=text)

    def draw_color(self, context, node):
        return _COLOURS[self.bl_idname]

    def value(self):
        if self.is_optional and not self.use:
            return None
        v = self.default_value
        return tuple(v) if hasattr(v, "__len__") else v


class FLSocketCurve(_DataSocket, bpy.types.NodeSocket):
    """A NURBS curve (metres)"""
    bl_idname = ids.SOCKET_CURVE
    bl_label = "Curve"


class FLSocketSurface(_DataSocket, bpy.types.NodeSocket):
    """A NURBS surface (metres)"""
    bl_idname = ids.SOCKET_SURFACE
    bl_label = "Surface"


class FLSocketMesh(_DataSocket, bpy.types.NodeSocket):
    """A polygon mesh with optional point attributes"""
    bl_idname = ids.SOCKET_MESH
    bl_label = "Mesh"


class FLSocketLines(_DataSocket, bpy.types.NodeSocket):
    """Polylines (waterlines, buttocks, frames, iso-lines)"""
    bl_idname = ids.SOCKET_LINES
    bl_label = "Lines"


class FLSocketHullData(_DataSocket, bpy.types.NodeSocket):
    """Imported hull data (offsets, sections or grids with Lpp, B, T), metres, x from the AP"""
    bl_idname = ids.SOCKET_HULL_DATA
    bl_label = "Hull Data"


class FLSocketLength(_ValueSocket, bpy.types.NodeSocket):
    """A length in metres"""
    bl_idname = ids.SOCKET_LENGTH
    bl_label = "Length"
    default_value: props.length("Value", 1.0)


class FLSocketArea(_ValueSocket, bpy.types.NodeSocket):
    """An area in square metres"""
    bl_idname = ids.SOCKET_AREA
    bl_label = "Area"
    default_value: props.area("Value", 1.0, min=-1e9)


class FLSocketVolume(_ValueSocket, bpy.types.NodeSocket):
    """A volume in cubic metres"""
    bl_idname = ids.SOCKET_VOLUME
    bl_label = "Volume"
    default_value: props.volume("Value", 1.0, min=-1e12)


class FLSocketCurvature(_ValueSocket, bpy.types.NodeSocket):
    """A curvature in 1/m (signed: positive turns left along the curve)"""
    bl_idname = ids.SOCKET_CURVATURE
    bl_label = "Curvature"
    unit_suffix = "1/m"
    default_value: bpy.props.FloatProperty(name="Value", default=0.0, min=-1e6, max=1e6, precision=5,
                                           description="Curvature (1/m)", update=props.changed)


class FLSocketBlend(_DataSocket, bpy.types.NodeSocket):
    """A blending surface with the boundaries it was built on (hull and bulb), metres"""
    bl_idname = ids.SOCKET_BLEND
    bl_label = "Blend"


class FLSocketHull(_DataSocket, bpy.types.NodeSocket):
    """A hull description with its solved basic curves, sections and bare hull (fairlines.Hull)"""
    bl_idname = ids.SOCKET_HULL
    bl_label = "Hull"


class FLSocketCurves(_DataSocket, bpy.types.NodeSocket):
    """An ordered list of curves (hull sections, metres)"""
    bl_idname = ids.SOCKET_CURVES
    bl_label = "Curves"


class FLSocketAngle(_ValueSocket, bpy.types.NodeSocket):
    """An angle (radians inside, degrees on screen by default)"""
    bl_idname = ids.SOCKET_ANGLE
    bl_label = "Angle"
    default_value: props.angle("Value", 0.0)


class FLSocketFloat(_ValueSocket, bpy.types.NodeSocket):
    """A dimensionless number"""
    bl_idname = ids.SOCKET_FLOAT
    bl_label = "Float"
    default_value: props.number("Value", 0.0)


class FLSocketInt(_ValueSocket, bpy.types.NodeSocket):
    """An integer"""
    bl_idname = ids.SOCKET_INT
    bl_label = "Integer"
    default_value: props.integer("Value", 0)


class FLSocketVector(_ValueSocket, bpy.types.NodeSocket):
    """A point or offset in metres"""
    bl_idname = ids.SOCKET_VECTOR
    bl_label = "Vector"
    default_value: props.vector("Value")


CLASSES = (FLSocketCurve, FLSocketSurface, FLSocketMesh, FLSocketLines, FLSocketHullData, FLSocketLength,
           FLSocketAngle, FLSocketFloat, FLSocketInt, FLSocketVector, FLSocketArea, FLSocketVolume,
           FLSocketCurvature, FLSocketBlend, FLSocketHull, FLSocketCurves)


def compatible(from_idname, to_idname):
    return from_idname == to_idname or (from_idname in NUMERIC and to_idname in NUMERIC)
