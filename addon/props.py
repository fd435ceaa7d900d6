"""Property constructors shared by nodes and sockets: every user-editable value queues its
tree for a (deferred) re-evaluation when it changes (queue.py; the evaluator drains it)."""

import bpy

from . import queue


def changed(self, context):
    """The update callback of every Fairlines property: queues its tree for re-evaluation."""
    queue.push(self.id_data)


def length(name, default=1.0, min=-1e6, max=1e6, soft_min=None, soft_max=None, description=""):
    return bpy.props.FloatProperty(
        name=name, default=default, min=min, max=max,
        soft_min=min if soft_min is None else soft_min, soft_max=max if soft_max is None else soft_max,
        subtype="DISTANCE", unit="LENGTH", precision=3, description=description or name + " (m)",
        update=changed)


def area(name, default=1.0, min=0.0, max=1e9, description=""):
    return bpy.props.FloatProperty(name=name, default=default, min=min, max=max, subtype="NONE", unit="AREA",
                                   precision=2, description=description or name + " (m^2)", update=changed)


def volume(name, default=1.0, min=0.0, max=1e12, description=""):
    return bpy.props.FloatProperty(name=name, default=default, min=min, max=max, subtype="NONE", unit="VOLUME",
                                   precision=1, description=description or name + " (m^3)", update=changed)


def angle(name, default=0.0, description=""):
    return bpy.props.FloatProperty(name=name, default=default, subtype="ANGLE", unit="ROTATION",
                                   description=description or name, update=changed)


def number(name, default=0.0, min=-1e9, max=1e9, description=""):
    return bpy.props.FloatProperty(name=name, default=default, min=min, max=max,
                                   description=description or name, update=changed)


def integer(name, default=0, min=-1000000, max=1000000, soft_max=None, description=""):
    return bpy.props.IntProperty(name=name, default=default, min=min, max=max,
                                 soft_max=max if soft_max is None else soft_max,
                                 description=description or name, update=changed)


def vector(name, default=(0.0, 0.0, 0.0), description="", unit="LENGTH"):
    return bpy.props.FloatVectorProperty(name=name, default=default, size=3,
                                         subtype="TRANSLATION" if unit == "LENGTH" else "XYZ",
                                         unit=unit if unit == "LENGTH" else "NONE",
                                         description=description or name, update=changed)


def boolean(name, default=False, description=""):
    return bpy.props.BoolProperty(name=name, default=default, description=description or name,
                                  update=changed)


def enum(name, items, default, description=""):
    return bpy.props.EnumProperty(name=name, items=items, default=default,
                                  description=description or name, update=changed)


def _blend_relative_option():
    # Blender 4.5+ warns whenever a "//" (blend-relative) path is set on a path property that
    # does not declare the option; older releases refuse the option when the class registers.
    return {"PATH_SUPPORTS_BLEND_RELATIVE"} if bpy.app.version >= (4, 5, 0) else set()


def text(name, default="", subtype="NONE", description=""):
    extra = {}
    if subtype == "FILE_PATH":
        extra["options"] = {"ANIMATABLE"} | _blend_relative_option()
    return bpy.props.StringProperty(name=name, default=default, subtype=subtype,
                                    description=description or name, update=changed, **extra)


def pointer(name, type, description=""):
    return bpy.props.PointerProperty(name=name, type=type, description=description or name,
                                     update=changed)
