"""The Fairlines node tree, its Add menu, operators, status panel and handlers."""

import bpy
from bpy.app.handlers import persistent

from . import engine, evaluator, ids, progress, report
from .nodes.base import HYDROSTATICS
from .nodes import CATEGORIES, NODE_CLASSES


class FairlinesTree(bpy.types.NodeTree):
    """Fair hull design: engine operators as nodes"""
    bl_idname = ids.TREE
    bl_label = "Fairlines"
    bl_icon = "NODETREE"

    def update(self):
        # Links or nodes changed: the evaluator re-runs only the nodes whose inputs changed.
        evaluator.request(self)


class FL_OT_evaluate(bpy.types.Operator):
    """Re-evaluate the Fairlines tree (from scratch when Full is on): the one in the node
    editor, or the one named by Tree, or every Fairlines tree (works headless too)"""
    bl_idname = ids.OP_EVALUATE
    bl_label = "Evaluate Fairlines Tree"
    bl_options = {"REGISTER"}

    full: bpy.props.BoolProperty(name="Full", default=False)
    tree: bpy.props.StringProperty(name="Tree", default="", description="Tree name; empty: the edited tree or all")

    def execute(self, context):
        space = getattr(context, "space_data", None)
        if self.tree:
            trees = [bpy.data.node_groups.get(self.tree)]
            if not evaluator.is_fairlines_tree(trees[0]):
                self.report({"ERROR"}, "No Fairlines tree named %r" % self.tree)
                return {"CANCELLED"}
        elif space is not None and getattr(space, "tree_type", "") == ids.TREE and space.edit_tree is not None:
            trees = [space.edit_tree]
        else:
            trees = [t for t in bpy.data.node_groups if evaluator.is_fairlines_tree(t)]
        for tree in trees:
            if self.full:
                evaluator.clear(tree.name)
            evaluator.request(tree)
        evaluator.flush()
        return {"FINISHED"}


class FL_OT_export(bpy.types.Operator):
    """Write the file now"""
    bl_idname = ids.OP_EXPORT
    bl_label = "Export"
    bl_options = {"REGISTER", "UNDO"}

    tree: bpy.props.StringProperty()
    node: bpy.props.StringProperty()

    def execute(self, context):
        tree = bpy.data.node_groups.get(self.tree)
        node = tree.nodes.get(self.node) if tree is not None else None
        if node is None or not hasattr(node, "export_count"):
            self.report({"ERROR"}, "Export node %s not found" % self.node)
            return {"CANCELLED"}
        node.export_count += 1
        with progress.Progress("%s: %s" % (node.name, getattr(node, "button", "Export").lower())):
            evaluator.evaluate(tree)
        if node.fl_state == "ERROR":
            self.report({"ERROR"}, node.fl_message)
            return {"CANCELLED"}
        return {"FINISHED"}


def _menu_class(category):
    def draw(self, context):
        for cls in NODE_CLASSES:
            if cls.category == category:
                op = self.layout.operator("node.add_node", text=cls.bl_label)
                op.type = cls.bl_idname
                op.use_transform = True
    return type(ids.MENU_ADD_PREFIX + category.lower(), (bpy.types.Menu,),
                {"bl_idname": ids.MENU_ADD_PREFIX + category.lower(), "bl_label": category,
                 "draw": draw})


MENUS = [_menu_class(c) for c in CATEGORIES]


def draw_add_menu(self, context):
    space = context.space_data
    if space is None or getattr(space, "tree_type", "") != ids.TREE:
        return
    layout = self.layout
    if not engine.available():
        layout.label(text=engine.IMPORT_ERROR, icon="ERROR")
    for menu in MENUS:
        layout.menu(menu.bl_idname)


def _fairlines_editor(context):
    """The node editor showing a Fairlines tree, or None."""
    space = context.space_data
    return space if space is not None and getattr(space, "tree_type", "") == ids.TREE else None


class FL_PT_status(bpy.types.Panel):
    """Engine status and tree evaluation time"""
    bl_idname = ids.PANEL_STATUS
    bl_label = "Fairlines"
    bl_space_type = "NODE_EDITOR"
    bl_region_type = "UI"
    bl_category = "Fairlines"

    @classmethod
    def poll(cls, context):
        return _fairlines_editor(context) is not None

    def draw(self, context):
        layout = self.layout
        if engine.available():
            layout.label(text="Engine %s" % getattr(engine.fl, "__version__", "?"), icon="CHECKMARK")
        else:
            col = layout.column()
            col.alert = True
            col.label(text="Engine not loaded", icon="ERROR")
            col.label(text=engine.IMPORT_ERROR)
        stats = evaluator.last_stats
        if stats["tree"]:
            layout.label(text="Last run: %d nodes, %.1f ms" % (len(stats["evaluated"]), stats["ms"]))
        layout.operator(ids.OP_EVALUATE, text="Re-evaluate").full = True


class FL_PT_hydrostatics(bpy.types.Panel):
    """The active node's hydrostatics (Bare Hull, Hydrostatics), as the engine computed them"""
    bl_idname = ids.PANEL_HYDROSTATICS
    bl_label = "Hydrostatics"
    bl_space_type = "NODE_EDITOR"
    bl_region_type = "UI"
    bl_category = "Fairlines"

    @classmethod
    def poll(cls, context):
        space = _fairlines_editor(context)
        return space is not None and space.edit_tree is not None

    def draw(self, context):
        tree = context.space_data.edit_tree
        node = tree.nodes.active
        entry = evaluator.peek(tree, node.name) if node is not None else None
        h = entry.outputs.get(HYDROSTATICS) if entry is not None else None
        if h is None:
            self.layout.label(text="Select a Bare Hull or Hydrostatics node" if entry is None or entry.later is None
                              else "Computing ...")
            return
        self.layout.label(text="%s, T %.3f m" % (node.name, h.draft))
        grid = self.layout.grid_flow(columns=2, even_columns=False, align=True)
        for label, value in report.rows(h):
            grid.label(text=label)
            grid.label(text=value)


# ---- handlers -------------------------------------------------------------------------------
@persistent
def _on_load(*_args):
    # A reopened file has no cache: evaluate every tree so objects match the saved graph.
    evaluator.clear()
    for tree in bpy.data.node_groups:
        evaluator.request(tree)


@persistent
def _on_undo(*_args):
    # Undo restores node properties and object data; outputs must be rewritten from the
    # restored graph even where their own key looks unchanged.
    evaluator.clear(outputs_only=True)
    for tree in bpy.data.node_groups:
        evaluator.request(tree)


@persistent
def _on_depsgraph(scene, depsgraph=None):
    # An edited input object (Points From Object) re-runs the nodes reading it.
    if depsgraph is None:
        depsgraph = bpy.context.evaluated_depsgraph_get()
    changed = {u.id.original.name for u in depsgraph.updates
               if isinstance(u.id, bpy.types.Object) and u.is_updated_geometry or
               isinstance(u.id, bpy.types.Object) and u.is_updated_transform}
    if not changed:
        return
    for tree in bpy.data.node_groups:
        if not evaluator.is_fairlines_tree(tree):
            continue
        for node in tree.nodes:
            watched = getattr(node, "watched_objects", None)
            if watched is not None and watched() & changed:
                evaluator.request(tree)
                break


HANDLERS = ((bpy.app.handlers.load_post, _on_load), (bpy.app.handlers.undo_post, _on_undo),
            (bpy.app.handlers.redo_post, _on_undo),
            (bpy.app.handlers.depsgraph_update_post, _on_depsgraph))

CLASSES = (FairlinesTree, FL_OT_evaluate, FL_OT_export, FL_PT_status, FL_PT_hydrostatics) + tuple(MENUS)


class FairlinesPreferences(bpy.types.AddonPreferences):
    """Shows whether the engine loaded, and why not (Preferences > Add-ons > Fairlines)."""
    # The add-on's module name: "fairlines_blender" (legacy) or "bl_ext.<repo>.fairlines".
    bl_idname = __package__

    def draw(self, context):
        layout = self.layout
        if engine.available():
            layout.label(text="Engine %s from %s" % (getattr(engine.fl, "__version__", "?"), engine.SOURCE),
                         icon="CHECKMARK")
        else:
            col = layout.column()
            col.alert = True
            col.label(text=engine.IMPORT_ERROR, icon="ERROR")


CLASSES = CLASSES + (FairlinesPreferences,)
