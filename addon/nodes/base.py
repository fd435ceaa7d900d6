"""Base class of every Fairlines node, and the registry the node classes join.

A node class declares its sockets (``inputs_spec`` / ``outputs_spec``), the names of its own
properties to draw (``params``), and ``compute(inputs) -> outputs``, a function of its input
values that calls the engine. Everything else (caching, timing, error display, re-evaluation)
is done here and in evaluator.py, so a new engine operator is one small class:

    @register
    class FLNodeThing(FairlinesNode, bpy.types.Node):
        bl_idname = ids.NODE_THING
        bl_label = "Thing"
        category = "Surfaces"
        inputs_spec = [(ids.SOCKET_SURFACE, "Surface", {})]
        outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]
        def compute(self, inputs):
            return {"Surface": engine_call(inputs["Surface"])}

Besides its outputs, compute() may return "__info__" (text shown on the node) and "__later__":
a job returning more outputs (and "__info__" to add) that the evaluator runs only once they
are needed or the meshes are in the scene (evaluator.py, "Deferred work").
"""

import bpy

from .. import ids

# Registered node classes, in menu order. Categories are menu names.
NODE_CLASSES = []
CATEGORIES = []

ERROR_COLOUR = (0.8, 0.12, 0.12)
# Output key (no socket) under which a node keeps the fl.Hydrostatics it shows; the sidebar's
# hydrostatics table reads it from the active node.
HYDROSTATICS = "__hydrostatics__"


def register(cls):
    NODE_CLASSES.append(cls)
    if cls.category not in CATEGORIES:
        CATEGORIES.append(cls.category)
    return cls


class NodeError(Exception):
    """A message for the user, shown on the node (bad or missing input)."""


class FairlinesNode:
    bl_width_default = 200
    category = "Misc"
    inputs_spec = []
    outputs_spec = []
    params = ()
    # Output nodes write into the scene; they run again when their target went missing.
    is_output = False

    # Status written by the evaluator and drawn on the node; not part of the signature
    # (only the names in `params` are), so showing a result never re-runs the node.
    fl_state: bpy.props.StringProperty(default="")  # "", "OK", "ERROR", "BLOCKED"
    fl_message: bpy.props.StringProperty(default="")
    fl_info: bpy.props.StringProperty(default="")
    fl_time_ms: bpy.props.FloatProperty(default=-1.0)

    @classmethod
    def poll(cls, ntree):
        return ntree.bl_idname == ids.TREE

    def init(self, context):
        for idname, name, opts in self.inputs_spec:
            sock = self.inputs.new(idname, name)
            if "default" in opts:
                sock.default_value = opts["default"]
            if opts.get("optional"):
                sock.is_optional = True
                sock.use = opts.get("use", True)
            if opts.get("hide_value"):
                sock.hide_value = True
        for idname, name in self.outputs_spec:
            self.outputs.new(idname, name)

    # ---- evaluation hooks ----------------------------------------------------------------
    def compute(self, inputs):
        raise NodeError("node %s has no compute()" % self.bl_idname)

    def signature(self):
        """Values of this node's own properties; a change re-runs the node."""
        out = []
        for name in self.params:
            v = getattr(self, name)
            if isinstance(v, bpy.types.ID):
                v = ("ID", v.name)
            elif v is not None and hasattr(v, "__len__") and not isinstance(v, str):
                v = tuple(v)
            out.append(v)
        return tuple(out)

    def needs_run(self):
        return False

    # ---- drawing -------------------------------------------------------------------------
    def draw_params(self, context, layout):
        for name in self.params:
            layout.prop(self, name)

    def draw_buttons(self, context, layout):
        self.draw_params(context, layout)
        if self.fl_state == "ERROR":
            col = layout.column(align=True)
            col.alert = True
            for k, line in enumerate(_wrap(self.fl_message)):
                col.label(text=line, icon="ERROR" if k == 0 else "NONE")
        elif self.fl_state == "BLOCKED":
            layout.label(text=self.fl_message, icon="INFO")
        if self.fl_info:
            for line in self.fl_info.split("\n"):
                layout.label(text=line)
        if self.fl_time_ms >= 0.0:
            layout.label(text="%.2f ms" % self.fl_time_ms, icon="TIME")

    def draw_buttons_ext(self, context, layout):
        self.draw_buttons(context, layout)

    def draw_label(self):
        return self.bl_label


_WRAP_CACHE = {}


def _wrap(message, width=34):
    """Node bodies are narrow: break a long engine message into lines (cached per message so
    the draw callback, run on every redraw, stays cheap)."""
    got = _WRAP_CACHE.get(message)
    if got is not None:
        return got
    lines, line = [], ""
    for word in message.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = (line + " " + word) if line else word
    lines.append(line)
    if len(_WRAP_CACHE) > 256:
        _WRAP_CACHE.clear()
    _WRAP_CACHE[message] = lines
    return lines
