"""Every bl_idname of the add-on, in one place.

Blender stores these strings in saved .blend files (tree, node and socket types), so they are
part of the file format: renaming one breaks files saved before. Keep them here and nowhere
else, so a grep shows the whole public surface and tests can check that nothing is duplicated.
"""

# Node tree and its editor.
TREE = "FairlinesTreeType"

# Sockets: data (engine objects passed between nodes) and numbers with units.
SOCKET_CURVE = "FLSocketCurve"
SOCKET_SURFACE = "FLSocketSurface"
SOCKET_MESH = "FLSocketMesh"
SOCKET_LINES = "FLSocketLines"
SOCKET_HULL_DATA = "FLSocketHullData"
SOCKET_LENGTH = "FLSocketLength"
SOCKET_ANGLE = "FLSocketAngle"
SOCKET_FLOAT = "FLSocketFloat"
SOCKET_INT = "FLSocketInt"
SOCKET_VECTOR = "FLSocketVector"

# Nodes: one per engine operator (plus values and outputs).
NODE_VALUE_LENGTH = "FLNodeValueLength"
NODE_VALUE_ANGLE = "FLNodeValueAngle"
NODE_VALUE_FLOAT = "FLNodeValueFloat"
NODE_CIRCLE = "FLNodeCircle"
NODE_ARC = "FLNodeArc"
NODE_ELLIPSE = "FLNodeEllipse"
NODE_POINTS_FROM_OBJECT = "FLNodePointsFromObject"
NODE_OFFSETS_IMPORT = "FLNodeOffsetsImport"
NODE_REBUILD = "FLNodeRebuildSurface"
NODE_HYDROSTATICS = "FLNodeHydrostatics"
NODE_FIT_CURVE = "FLNodeFitCurve"
NODE_TRIM_CURVE = "FLNodeTrimCurve"
NODE_CURVE_INSERT_KNOT = "FLNodeCurveInsertKnot"
NODE_CURVE_ELEVATE_DEGREE = "FLNodeCurveElevateDegree"
NODE_CURVE_SET_WEIGHT = "FLNodeCurveSetWeight"
NODE_FIT_SURFACE = "FLNodeFitSurface"
NODE_REVOLVE = "FLNodeRevolve"
NODE_CYLINDER = "FLNodeCylinder"
NODE_SPHERE = "FLNodeSphere"
NODE_INSERT_KNOT = "FLNodeInsertKnot"
NODE_ELEVATE_DEGREE = "FLNodeElevateDegree"
NODE_SET_WEIGHT = "FLNodeSetWeight"
NODE_MOVE_CONTROL_POINT = "FLNodeMoveControlPoint"
NODE_TESSELLATE = "FLNodeTessellate"
NODE_CURVATURE = "FLNodeCurvature"
NODE_ISO_LINES = "FLNodeIsoLines"
NODE_CURVE_LINES = "FLNodeCurveLines"
NODE_MESH_OUTPUT = "FLNodeMeshOutput"
NODE_LINES_OUTPUT = "FLNodeLinesOutput"
NODE_EXPORT_OBJ = "FLNodeExportOBJ"

# Operators, menus, panels.
OP_EVALUATE = "fairlines.evaluate_tree"
OP_EXPORT = "fairlines.export_node"
MENU_ADD_PREFIX = "NODE_MT_fairlines_add_"
PANEL_STATUS = "NODE_PT_fairlines_status"

# Data written into the scene.
GN_GROUP = "Fairlines Output"
GN_MODIFIER = "Fairlines"
ATTR_GAUSSIAN = "gaussian_curvature"
ATTR_MEAN = "mean_curvature"
MESH_TOPOLOGY_KEY = "fairlines_topology"
