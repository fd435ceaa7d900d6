"""Number nodes: one value with a unit, to drive several inputs from one slider."""

import bpy

from .. import ids, props
from .base import FairlinesNode, register


@register
class FLNodeValueLength(FairlinesNode, bpy.types.Node):
    """A length in metres"""
    bl_idname = ids.NODE_VALUE_LENGTH
    bl_label = "Length"
    category = "Values"
    bl_width_default = 160
    outputs_spec = [(ids.SOCKET_LENGTH, "Length")]
    params = ("value",)
    value: props.length("Length", 1.0)

    def compute(self, inputs):
        return {"Length": self.value}


@register
class FLNodeValueAngle(FairlinesNode, bpy.types.Node):
    """An angle"""
    bl_idname = ids.NODE_VALUE_ANGLE
    bl_label = "Angle"
    category = "Values"
    bl_width_default = 160
    outputs_spec = [(ids.SOCKET_ANGLE, "Angle")]
    params = ("value",)
    value: props.angle("Angle", 0.0)

    def compute(self, inputs):
        return {"Angle": self.value}


@register
class FLNodeValueFloat(FairlinesNode, bpy.types.Node):
    """A dimensionless number (coefficients, ratios)"""
    bl_idname = ids.NODE_VALUE_FLOAT
    bl_label = "Value"
    category = "Values"
    bl_width_default = 160
    outputs_spec = [(ids.SOCKET_FLOAT, "Value")]
    params = ("value",)
    value: props.number("Value", 0.0)

    def compute(self, inputs):
        return {"Value": self.value}
