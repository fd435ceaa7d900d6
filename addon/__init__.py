"""Fairlines for Blender: the engine's operators as a node tree, live.

Installs as a Blender extension (4.2 LTS and newer, blender_manifest.toml, engine wheel in
wheels/) or as a legacy add-on (3.4 .. 4.1, engine wheel in wheels/, unpacked on first use), on Python 3.11.
Registration never depends on the compiled engine: when it cannot be imported the tree, nodes
and menus still register and every node shows why it cannot run.
"""

bl_info = {
    "name": "Fairlines",
    "author": "Fairlines",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Node Editor > Fairlines",
    "description": "Fair parametric hull design: NURBS engine operators as live nodes",
    "category": "Node",
}

import sys  # noqa: E402

import bpy  # noqa: E402

from . import api, engine, evaluator, queue, sockets, tree  # noqa: E402,F401  (api: fairlines_blender.api)
from .nodes import NODE_CLASSES  # noqa: E402


def _all_classes():
    return sockets.CLASSES + tuple(NODE_CLASSES) + tree.CLASSES


def _merge_annotations(cls):
    """Blender registers the properties found in a class's own __annotations__; properties
    declared on plain-Python mixins (node status, socket switches) are copied in here."""
    merged = {}
    for base in reversed(cls.__mro__):
        if base.__module__.startswith("bpy") or base is object:
            continue
        merged.update(base.__dict__.get("__annotations__", {}))
    cls.__annotations__ = merged


_registered = []
ALIAS = "fairlines_blender"


def register():
    for cls in _all_classes():
        _merge_annotations(cls)
        bpy.utils.register_class(cls)
        _registered.append(cls)
    bpy.types.NODE_MT_add.append(tree.draw_add_menu)
    for handlers, fn in tree.HANDLERS:
        if fn not in handlers:
            handlers.append(fn)
    if not engine.available():
        print("Fairlines: registered without the engine. " + engine.IMPORT_ERROR)
    # Scripts import the API as fairlines_blender.api whichever way the add-on was installed
    # (an extension's package is bl_ext.<repository>.fairlines).
    if __package__ != ALIAS and ALIAS not in sys.modules:
        sys.modules[ALIAS] = sys.modules[__package__]
        sys.modules[ALIAS + ".api"] = api


def unregister():
    if __package__ != ALIAS and sys.modules.get(ALIAS) is sys.modules.get(__package__):
        sys.modules.pop(ALIAS, None)
        sys.modules.pop(ALIAS + ".api", None)
    for handlers, fn in tree.HANDLERS:
        while fn in handlers:
            handlers.remove(fn)
    try:
        bpy.types.NODE_MT_add.remove(tree.draw_add_menu)
    except ValueError:
        pass
    evaluator.drop_timer()
    queue.pending.clear()
    evaluator.clear()
    while _registered:
        bpy.utils.unregister_class(_registered.pop())
