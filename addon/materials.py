"""Materials the Mesh Output node can put on its object: hull paint split at the design
waterline (antifouling below, a boot-top band above, topsides higher up) and zebra stripes
(reflection lines, the way fairness is judged in a CAD viewer: a fair surface gives smooth
stripes, a dent or a curvature jump bends or breaks them). Built from shader nodes that exist
from Blender 3.4 to 5.x; coordinates are object space, which is the hull's metres."""

import bpy

from . import ids

ANTIFOULING = (0.42, 0.05, 0.04, 1.0)
BOOT_TOP = (0.02, 0.02, 0.02, 1.0)
TOPSIDES = (0.05, 0.09, 0.16, 1.0)
BOOT_TOP_HEIGHT = 1.2      # m above the design waterline
ZEBRA_STRIPES = 14.0       # stripes per unit of the reflection vector's z component
PAINT_TOP = 100.0          # m: the ramp's range (heights above are topsides)


def _fresh(name):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    if bpy.app.version < (5, 0, 0):  # always node-based from 5.0 on
        mat.use_nodes = True
    mat.node_tree.nodes.clear()
    return mat


def _ramp(nodes, stops):
    ramp = nodes.new("ShaderNodeValToRGB")
    cr = ramp.color_ramp
    cr.interpolation = "CONSTANT"
    while len(cr.elements) < len(stops):
        cr.elements.new(0.5)
    for el, (pos, colour) in zip(cr.elements, stops):
        el.position, el.color = pos, colour
    return ramp


def hull_paint(name, draft):
    """Principled paint: antifouling below z = draft, boot-top band, topsides above."""
    mat = bpy.data.materials.get(name)
    if mat is not None and mat.get("fairlines_draft") == round(float(draft), 6):
        return mat
    mat = _fresh(name)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    tex = nodes.new("ShaderNodeTexCoord")
    sep = nodes.new("ShaderNodeSeparateXYZ")
    div = nodes.new("ShaderNodeMath")
    div.operation = "DIVIDE"
    div.inputs[1].default_value = PAINT_TOP
    ramp = _ramp(nodes, [(0.0, ANTIFOULING), (draft / PAINT_TOP, BOOT_TOP),
                         ((draft + BOOT_TOP_HEIGHT) / PAINT_TOP, TOPSIDES)])
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.inputs["Roughness"].default_value = 0.45
    out = nodes.new("ShaderNodeOutputMaterial")
    links.new(tex.outputs["Object"], sep.inputs[0])
    links.new(sep.outputs["Z"], div.inputs[0])
    links.new(div.outputs[0], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(bsdf.outputs[0], out.inputs["Surface"])
    mat.diffuse_color = TOPSIDES  # solid viewport colour
    mat["fairlines_draft"] = round(float(draft), 6)
    return mat


def zebra(name=ids.MAT_ZEBRA):
    """Black and white stripes of the reflection vector's height, emitted (no lighting)."""
    mat = bpy.data.materials.get(name)
    if mat is not None and mat.get("fairlines_zebra"):
        return mat
    mat = _fresh(name)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    tex = nodes.new("ShaderNodeTexCoord")
    sep = nodes.new("ShaderNodeSeparateXYZ")
    mul = nodes.new("ShaderNodeMath")
    mul.operation = "MULTIPLY"
    mul.inputs[1].default_value = ZEBRA_STRIPES * 3.141592653589793
    sine = nodes.new("ShaderNodeMath")
    sine.operation = "SINE"
    ramp = _ramp(nodes, [(0.0, (0.0, 0.0, 0.0, 1.0)), (0.5, (1.0, 1.0, 1.0, 1.0))])
    scale = nodes.new("ShaderNodeMath")  # sine -1..1 -> 0..1 for the ramp
    scale.operation = "MULTIPLY_ADD"
    scale.inputs[1].default_value = 0.5
    scale.inputs[2].default_value = 0.5
    emit = nodes.new("ShaderNodeEmission")
    out = nodes.new("ShaderNodeOutputMaterial")
    links.new(tex.outputs["Reflection"], sep.inputs[0])
    links.new(sep.outputs["Z"], mul.inputs[0])
    links.new(mul.outputs[0], sine.inputs[0])
    links.new(sine.outputs[0], scale.inputs[0])
    links.new(scale.outputs[0], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], emit.inputs["Color"])
    links.new(emit.outputs[0], out.inputs["Surface"])
    mat["fairlines_zebra"] = True
    return mat


def assign(obj, mat):
    """Make mat the object's first material (only when it is not already)."""
    mats = obj.data.materials
    if len(mats) == 0:
        mats.append(mat)
    elif mats[0] != mat:
        mats[0] = mat
