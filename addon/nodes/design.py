"""Hull design nodes: form-parameter curves, bulbous bow (Kracht coefficients), blending
surface and Boolean composition. Each is a thin call into the engine package (fairlines);
the node only maps sockets to arguments and units (Blender angles are radians, the form-curve
engine takes degrees)."""

import math

import bpy

from .. import engine, ids, props
from ..data import MeshData
from .base import FairlinesNode, NodeError, register

# The test request of Kim, Shin & Kim (2002), Table 3, with the centroid switched off: a
# feasible request out of the box that shows every kind of parameter.
_FORM_DEFAULTS = [
    ("xB", ids.SOCKET_LENGTH, 0.0, True), ("yB", ids.SOCKET_LENGTH, 0.569026, True),
    ("xE", ids.SOCKET_LENGTH, 1.0, True), ("yE", ids.SOCKET_LENGTH, 0.0, True),
    ("alphaB", ids.SOCKET_ANGLE, math.radians(-31.0), True), ("alphaE", ids.SOCKET_ANGLE, math.radians(-58.0), True),
    ("CAB", ids.SOCKET_CURVATURE, -1.5, True), ("CAE", ids.SOCKET_CURVATURE, -4.41, True),
    ("Area", ids.SOCKET_AREA, 0.1925, True),
    ("xC", ids.SOCKET_LENGTH, 0.28489, False), ("yC", ids.SOCKET_LENGTH, 0.16952, False),
]
_ANGLES = {"alphaB", "alphaE"}

_FAIRNESS = [("e2", "Bending (E2)", "Least integral of |C''|^2: the usual fairness"),
             ("e1", "Length (E1)", "Least integral of |C'|^2"),
             ("e3", "Jerk (E3)", "Least integral of |C'''|^2: smoothest curvature")]


@register
class FLNodeFormCurve(FairlinesNode, bpy.types.Node):
    """The fairest B-spline meeting the switched-on form parameters exactly (positions,
    end tangent angles, end curvatures, area under the curve and its centroid); an infeasible
    request turns the node red with the engine's diagnosis"""
    bl_idname = ids.NODE_FORM_CURVE
    bl_label = "Form Parameter Curve"
    category = "Curves"
    bl_width_default = 250
    inputs_spec = [(idname, name, {"default": value, "optional": True, "use": use})
                   for name, idname, value, use in _FORM_DEFAULTS] + [
                   (ids.SOCKET_INT, "Control Points", {"default": 8}),
                   (ids.SOCKET_INT, "Degree", {"default": 3})]
    outputs_spec = [(ids.SOCKET_CURVE, "Curve")]
    params = ("fairness", "section_bounds")
    fairness: props.enum("Fairness", _FAIRNESS, "e2")
    section_bounds: props.boolean("Section Bounds", True,
                                  "Keep x monotone and y >= 0 on the control polygon (a section or "
                                  "waterline stays one)")

    def compute(self, inputs):
        fl, _ = engine.require()
        request = {}
        for name, _, _, _ in _FORM_DEFAULTS:
            value = inputs.get(name)
            if value is not None:
                request[name] = math.degrees(value) if name in _ANGLES else float(value)
        result = fl.design_curve(request, n_control=inputs["Control Points"], degree=inputs["Degree"],
                                 fairness={self.fairness: 1.0}, bounds=None if self.section_bounds else False)
        worst = result.max_residual()
        info = "%d parameters, max residual %.2g\nE2 %.4g, %d iterations%s" % (
            len(request), worst, result.fairness["E2"], result.iterations,
            "" if result.converged else " (not fully converged)")
        return {"Curve": result.curve, "__info__": info}


@register
class FLNodeBulbousBow(FairlinesNode, bpy.types.Node):
    """Bulbous bow from the six Kracht coefficients and the ship's particulars: fair-skinned
    superelliptic sections forward of FP, running aft into the hull (surface y >= 0)"""
    bl_idname = ids.NODE_BULBOUS_BOW
    bl_label = "Bulbous Bow"
    category = "Surfaces"
    bl_width_default = 260
    # Panamax container ship: Am = 0.985 B T, displacement 0.65 Lpp B T (as in
    # examples/compose_ship.py), the engine's default Kracht coefficients.
    inputs_spec = [(ids.SOCKET_LENGTH, "Lpp", {"default": 244.8}),
                   (ids.SOCKET_LENGTH, "Beam", {"default": 32.25}),
                   (ids.SOCKET_LENGTH, "Draft FP", {"default": 11.0}),
                   (ids.SOCKET_AREA, "Midship Area", {"default": 349.4}),
                   (ids.SOCKET_VOLUME, "Displacement", {"default": 56447.0}),
                   (ids.SOCKET_FLOAT, "C_LPR", {"default": 0.025}),
                   (ids.SOCKET_FLOAT, "C_BB", {"default": 0.18}),
                   (ids.SOCKET_FLOAT, "C_ZB", {"default": 0.45}),
                   (ids.SOCKET_FLOAT, "C_ABT", {"default": 0.10}),
                   (ids.SOCKET_FLOAT, "C_ABL", {"default": 0.10}),
                   (ids.SOCKET_FLOAT, "C_VPR", {"default": 0.0022}),
                   (ids.SOCKET_LENGTH, "x FP", {"default": 244.8, "optional": True, "use": False}),
                   (ids.SOCKET_LENGTH, "Aft Length", {"default": 12.0, "optional": True, "use": False}),
                   (ids.SOCKET_LENGTH, "Nose Height Shift", {"default": 0.0})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface"), (ids.SOCKET_LENGTH, "Protrusion")]

    def compute(self, inputs):
        fl, _ = engine.require()
        kw = dict(lpp=inputs["Lpp"], beam=inputs["Beam"], draft_fp=inputs["Draft FP"],
                  midship_area=inputs["Midship Area"], displacement_volume=inputs["Displacement"],
                  nose_height_shift=inputs["Nose Height Shift"])
        for name in ("C_LPR", "C_BB", "C_ZB", "C_ABT", "C_ABL", "C_VPR"):
            kw[name.lower()] = inputs[name]
        if inputs["x FP"] is not None:
            kw["x_fp"] = inputs["x FP"]
        if inputs["Aft Length"] is not None:
            kw["aft_length"] = inputs["Aft Length"]
        return _bulb_outputs(fl.BulbousBow(**kw))


def _bulb_outputs(bulb):
    s = bulb.shape
    info = "L_PR %.3f m, B_B %.3f m, Z_B %.3f m\nH %.3f m, n %.3f, m %.3f\nfit deviation %.2g m" % (
        s["length"], s["breadth"], s["nose_height"], s["height"], s["section_fullness"], s["nose_shape"],
        bulb.max_fit_deviation)
    return {"Surface": bulb.surface, "Protrusion": float(s["length"]), "__info__": info}


_KRACHT = (("C_LPR", 0.025), ("C_BB", 0.18), ("C_ZB", 0.45), ("C_ABT", 0.10), ("C_ABL", 0.10), ("C_VPR", 0.0022))


@register
class FLNodeHullBulb(FairlinesNode, bpy.types.Node):
    """The hull's own bulbous bow (Hull.bulbous_bow): sized from the hull's Lpp, B, T, midship
    area and displacement, with the description's Kracht coefficients; switched-on inputs
    override them"""
    bl_idname = ids.NODE_HULL_BULB
    bl_label = "Hull Bulb"
    category = "Hull"
    bl_width_default = 230
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {})] + [
        (ids.SOCKET_FLOAT, name, {"default": value, "optional": True, "use": False}) for name, value in _KRACHT]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface"), (ids.SOCKET_LENGTH, "Protrusion")]

    def compute(self, inputs):
        engine.require()
        hull = inputs["Hull"]
        if hull is None:
            raise NodeError("Connect a hull (Particulars or Hull Description)")
        overrides = {name.lower(): float(inputs[name]) for name, _ in _KRACHT if inputs[name] is not None}
        return _bulb_outputs(hull.bulbous_bow(**overrides))


@register
class FLNodeBlendSurface(FairlinesNode, bpy.types.Node):
    """Blending surface between the bare hull and the bulb, curvature-continuous (G2) with both: on the hull
    around the seam the bulb makes, on the bulb just ahead of it (clearances in the surfaces'
    parameters, which run 0 .. 1; see fairlines.seam_blend_placement)"""
    bl_idname = ids.NODE_BLEND
    bl_label = "Blend Surface"
    category = "Surfaces"
    bl_width_default = 240
    inputs_spec = [(ids.SOCKET_SURFACE, "Hull", {}),
                   (ids.SOCKET_SURFACE, "Bulb", {}),
                   (ids.SOCKET_FLOAT, "Clearance U", {"default": 0.05}),
                   (ids.SOCKET_FLOAT, "Clearance V", {"default": 0.01}),
                   (ids.SOCKET_FLOAT, "Bulb Clearance", {"default": 0.01}),
                   (ids.SOCKET_FLOAT, "Tension", {"default": 0.6}),
                   (ids.SOCKET_INT, "Sections", {"default": 61})]
    outputs_spec = [(ids.SOCKET_BLEND, "Blend"), (ids.SOCKET_SURFACE, "Surface")]

    def compute(self, inputs):
        fl, _ = engine.require()
        hull, bulb = inputs["Hull"], inputs["Bulb"]
        if hull is None or bulb is None:
            raise NodeError("Connect the bare hull and the bulb surfaces")
        samples = inputs["Sections"]
        if samples < 4:
            raise NodeError("Sections is %d; expected at least 4" % samples)
        # Where the blend goes is all Compose needs (it skins the blend at its mesh resolution
        # itself): that goes on at once. This node's own surface and its measured continuity
        # (fl.seam_blend_placement(...).blend_surface()) are a deferred job (evaluator.py), run when
        # something reads Surface or else once the meshes are in the scene.
        placement = fl.seam_blend_placement(hull, bulb, clearance_u=inputs["Clearance U"],
                                            clearance_v=inputs["Clearance V"],
                                            bulb_clearance=inputs["Bulb Clearance"], tension=inputs["Tension"])

        def surface():
            blend = placement.blend_surface(samples=samples)
            info = "max normal angle %.3f deg at hull, %.3f deg at bulb\nmax gap %.2g m" % (
                blend.at_a["max_angle_deg"], blend.at_b["max_angle_deg"],
                max(blend.at_a["max_gap"], blend.at_b["max_gap"]))
            return {"Surface": blend.surface, "__info__": info}
        return {"Blend": placement, "__later__": surface}


_COMPOSE_OUTPUT = [("full", "Full Hull", "Mirrored about y = 0 and welded by the engine (set Mirror off "
                    "on Mesh Output)"),
                   ("half", "Half Hull", "The closed starboard half, centre plane included")]


@register
class FLNodeCompose(FairlinesNode, bpy.types.Node):
    """Boolean union of the hull subdomains (bare hull, bulb, blending surface) into one
    watertight, outward-oriented hull closed by the centre plane, deck and aft cut"""
    bl_idname = ids.NODE_COMPOSE
    bl_label = "Compose (Union)"
    category = "Mesh"
    bl_width_default = 240
    inputs_spec = [(ids.SOCKET_SURFACE, "Hull", {}),
                   (ids.SOCKET_SURFACE, "Bulb", {}),
                   (ids.SOCKET_BLEND, "Blend", {}),
                   (ids.SOCKET_INT, "Hull Cells U", {"default": 48}),
                   (ids.SOCKET_INT, "Hull Cells V", {"default": 20}),
                   (ids.SOCKET_INT, "Bulb Cells U", {"default": 24}),
                   (ids.SOCKET_INT, "Bulb Cells V", {"default": 32})]
    outputs_spec = [(ids.SOCKET_MESH, "Mesh"), (ids.SOCKET_VOLUME, "Volume")]
    params = ("output",)
    output: props.enum("Output", _COMPOSE_OUTPUT, "full")

    def compute(self, inputs):
        fl, np = engine.require()
        hull, bulb, blend = inputs["Hull"], inputs["Bulb"], inputs["Blend"]
        if hull is None:
            raise NodeError("Connect the bare hull surface")
        if blend is not None and bulb is None:
            raise NodeError("A blend needs the bulb it was built on: connect Bulb")
        cells = [inputs[n] for n in ("Hull Cells U", "Hull Cells V", "Bulb Cells U", "Bulb Cells V")]
        if min(cells) < 2 or cells[0] * cells[1] + cells[2] * cells[3] > 2_000_000:
            raise NodeError("Cells must each be >= 2 (at most 2M in all)")
        subdomains = [hull] + ([bulb] if bulb is not None else []) + ([blend] if blend is not None else [])
        # The blend's continuity (shown on the node) is 400 projections onto hull and bulb and
        # changes nothing in the mesh: the engine measures 2 points here and the 200 per
        # boundary it measures by default are a deferred job below (same figures).
        composed = fl.compose(subdomains, hull_u=cells[0], hull_v=cells[1], bulb_u=cells[2], bulb_v=cells[3],
                              blend_check_samples=2)
        full = self.output == "full"
        mesh = composed.full_mesh() if full else composed.mesh
        data = MeshData(np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, dtype=np.int32))
        info = "%d vertices, %d triangles" % (len(data.vertices), len(data.faces))
        if composed.intersection_curves:
            info += "\nseam gap %.2g m" % max(c["max_gap"] for c in composed.intersection_curves)
        surface_b = bulb.surface if isinstance(bulb, fl.BulbousBow) else bulb

        def later():
            # Volume and the blend's continuity change nothing in the mesh: a deferred job.
            volume = composed.volume * (2.0 if full else 1.0)
            more = "\nvolume %.6g m3 (%s)" % (volume, "both sides" if full else "half")
            if composed.blend is not None:
                at_hull = fl.boundary_continuity(composed.blend, False, composed.trimmed_surfaces[0][0], 200)
                at_bulb = fl.boundary_continuity(composed.blend, True, surface_b, 200)
                more += "\nblend %.3f / %.3f deg" % (at_hull["max_angle_deg"], at_bulb["max_angle_deg"])
            return {"Volume": float(volume), "__info__": more}
        return {"Mesh": data, "__info__": info, "__later__": later}
