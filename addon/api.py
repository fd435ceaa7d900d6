"""Scripting Fairlines trees without the interface (``blender -b``, the ``bpy`` module) or from
Blender's Python console. Import it as ``fairlines_blender.api`` (the add-on registers that
name whichever way it was installed):

    from fairlines_blender import api
    tree = api.new_tree("Ship")
    ship = api.add(tree, "Particulars", Cb=0.7, LCB=120.0)
    bare = api.add(tree, "Bare Hull")
    api.link(tree, ship, "Hull", bare, "Hull")
    api.evaluate(tree)                       # raises api.TreeError naming the failed nodes
    h = api.hydrostatics(tree, bare)         # the engine's fl.Hydrostatics
    api.set(tree, ship, "Cb", 0.72)          # a socket value (switched on if optional) or a property
    api.evaluate(tree)
    cad = api.add(tree, "Export CAD")        # file nodes write only when their button is pressed:
    cad.filepath = "/tmp/ship.step"
    api.link(tree, ship, "Hull", cad, "Hull")
    api.export(tree, cad)                    # -> "/tmp/ship.step"

Node types are given by their menu label ("Particulars") or bl_idname (ids.NODE_*); nodes by
object or name. Every function raises KeyError for an unknown tree, node, type or socket.
"""

import bpy

from . import evaluator, ids
from .nodes.base import HYDROSTATICS, NODE_CLASSES


class TreeError(RuntimeError):
    """Some nodes failed; ``.failed`` maps node name -> message."""

    def __init__(self, failed):
        self.failed = failed
        super().__init__("; ".join("%s: %s" % kv for kv in failed.items()))


def _tree(tree):
    if isinstance(tree, str):
        found = bpy.data.node_groups.get(tree)
        if found is None or found.bl_idname != ids.TREE:
            raise KeyError("no Fairlines tree named %r" % tree)
        return found
    return tree


def _node(tree, node):
    if isinstance(node, str):
        found = _tree(tree).nodes.get(node)
        if found is None:
            raise KeyError("tree %r has no node %r" % (_tree(tree).name, node))
        return found
    return node


def node_types():
    """{menu label: bl_idname} of every Fairlines node."""
    return {cls.bl_label: cls.bl_idname for cls in NODE_CLASSES}


def new_tree(name="Fairlines", replace=True):
    """A Fairlines node tree called `name` (an existing one is removed first when replace)."""
    old = bpy.data.node_groups.get(name)
    if old is not None:
        if not replace:
            return old
        bpy.data.node_groups.remove(old)
    return bpy.data.node_groups.new(name, ids.TREE)


def add(tree, node_type, name=None, location=(0.0, 0.0), **values):
    """Add a node (by label or bl_idname), name it, and set values as :func:`set` does; socket
    names with spaces are given with underscores (``Resolution_U=96``)."""
    tree = _tree(tree)
    idname = node_types().get(node_type, node_type)
    if idname not in node_types().values():
        raise KeyError("node type %r; expected one of %s" % (node_type, sorted(node_types())))
    n = tree.nodes.new(idname)
    if name:
        n.name = n.label = name
    n.location = location
    for key, value in values.items():
        set(tree, n, key.replace("_", " ") if key.replace("_", " ") in n.inputs else key, value)
    return n


def link(tree, from_node, from_socket, to_node, to_socket):
    """Link an output socket to an input socket (by name)."""
    tree = _tree(tree)
    a, b = _node(tree, from_node), _node(tree, to_node)
    if from_socket not in a.outputs:
        raise KeyError("%s has no output %r; it has %s" % (a.name, from_socket, [s.name for s in a.outputs]))
    if to_socket not in b.inputs:
        raise KeyError("%s has no input %r; it has %s" % (b.name, to_socket, [s.name for s in b.inputs]))
    return tree.links.new(a.outputs[from_socket], b.inputs[to_socket])


def set(tree, node, name, value):
    """Set an input socket's value (an optional socket is switched on; value None switches it
    off) or a node property. The tree is queued for evaluation, as a slider change is."""
    n = _node(tree, node)
    sock = n.inputs.get(name)
    if sock is not None:
        if value is None:
            if not getattr(sock, "is_optional", False):
                raise KeyError("input %r of %s is not optional" % (name, n.name))
            sock.use = False
            return
        if getattr(sock, "is_optional", False) and not sock.use:
            sock.use = True
        sock.default_value = value
        return
    if name not in getattr(n, "params", ()) and name not in n.bl_rna.properties:
        raise KeyError("%s has no input or property %r" % (n.name, name))
    setattr(n, name, value)


def evaluate(tree=None, check=True):
    """Evaluate now (every queued tree, or `tree`) including deferred work; with check, raise
    TreeError when a node is red or blocked. Returns {node name: milliseconds} of what ran."""
    if tree is not None:
        tree = _tree(tree)
        evaluator.request(tree)
    evaluator.flush()
    if tree is None:
        return {}
    if check:
        failed = {n.name: n.fl_message for n in tree.nodes if getattr(n, "fl_state", "OK") in ("ERROR", "BLOCKED")}
        if failed:
            raise TreeError(failed)
    return {n.name: n.fl_time_ms for n in tree.nodes if getattr(n, "fl_time_ms", -1.0) >= 0.0}


def status(tree):
    """{node name: (state, message, info)}: state "OK", "ERROR", "BLOCKED" or "" (not run)."""
    return {n.name: (n.fl_state, n.fl_message, n.fl_info) for n in _tree(tree).nodes if hasattr(n, "fl_state")}


def result(tree, node, output):
    """The value of a node's output (engine object, number, MeshData ...); runs the node's
    deferred work if the output comes from it. KeyError when the node has not produced it."""
    tree = _tree(tree)
    n = _node(tree, node)
    outs = evaluator.outputs_of(tree, n.name)
    if outs is None or output not in outs:
        raise KeyError("%s has no result %r (state %s: %s)" % (n.name, output, n.fl_state, n.fl_message))
    return outs[output]


def export(tree, node):
    """Press a file node's Export (or Run Sweep) button: write its file now. Returns the path
    written; raises TreeError when the node is red (a missing package names its pip line)."""
    tree = _tree(tree)
    n = _node(tree, node)
    if not hasattr(n, "export_count"):
        raise KeyError("%s writes no file; file nodes are %s" % (n.name, sorted(
            cls.bl_label for cls in NODE_CLASSES if "export_count" in getattr(cls, "__annotations__", {}))))
    evaluator.flush()
    try:
        bpy.ops.fairlines.export_node(tree=tree.name, node=n.name)
    except RuntimeError:
        pass  # the operator reported the node's error; it is raised below with the node named
    evaluator.flush()
    if n.fl_state != "OK":
        raise TreeError({n.name: n.fl_message or "waiting for its inputs"})
    return getattr(n, "written_path", "") or bpy.path.abspath(n.filepath)


def hydrostatics(tree, node):
    """The fl.Hydrostatics a node shows (Bare Hull, Hydrostatics)."""
    return result(tree, node, HYDROSTATICS)
