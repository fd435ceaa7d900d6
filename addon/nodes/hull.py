"""Bare-hull nodes (fairlines.Hull): principal dimensions, hull description, basic curves,
sections, fair skin and the bare hull surface. The Hull object travels between nodes; a node
that changes it builds a new one from a copy of the description (cached values are shared by
every downstream node and are never edited)."""

import copy
import json
import math
import os

import bpy

from .. import engine, ids, props
from ..data import LinesData
from .base import FairlinesNode, NodeError, register


@register
class FLNodePrincipalDimensions(FairlinesNode, bpy.types.Node):
    """Lpp, moulded breadth B, design draught T and depth D, checked together (T < D), to
    drive the hull description and the bulbous bow from one place"""
    bl_idname = ids.NODE_PRINCIPAL_DIMENSIONS
    bl_label = "Principal Dimensions"
    category = "Hull"
    inputs_spec = [(ids.SOCKET_LENGTH, "Lpp", {"default": 244.8}),
                   (ids.SOCKET_LENGTH, "B", {"default": 32.25}),
                   (ids.SOCKET_LENGTH, "T", {"default": 11.0}),
                   (ids.SOCKET_LENGTH, "D", {"default": 19.0})]
    outputs_spec = [(ids.SOCKET_LENGTH, "Lpp"), (ids.SOCKET_LENGTH, "B"), (ids.SOCKET_LENGTH, "T"),
                    (ids.SOCKET_LENGTH, "D")]

    def compute(self, inputs):
        fl, _ = engine.require()
        # The engine's own check (all > 0, T < D), so the message is the one a JSON file gets.
        pd = fl.PrincipalDimensions.from_dict({k: inputs[k] for k in ("Lpp", "B", "T", "D")})
        return {"Lpp": pd.lpp, "B": pd.breadth, "T": pd.draft, "D": pd.depth,
                "__info__": "L/B %.2f, B/T %.2f" % (pd.lpp / pd.breadth, pd.breadth / pd.draft)}


@register
class FLNodeHullDescription(FairlinesNode, bpy.types.Node):
    """A hull description (JSON: principal dimensions, modelled range, stations, basic curves,
    section and skinning settings) from a text block in the .blend or a file; switched-on
    inputs override its principal dimensions"""
    bl_idname = ids.NODE_HULL_DESCRIPTION
    bl_label = "Hull Description"
    category = "Hull"
    bl_width_default = 260
    inputs_spec = [(ids.SOCKET_LENGTH, name, {"default": value, "optional": True, "use": False})
                   for name, value in (("Lpp", 244.8), ("B", 32.25), ("T", 11.0), ("D", 19.0))]
    outputs_spec = [(ids.SOCKET_HULL, "Hull")]
    params = ("text", "filepath")
    text: props.pointer("Text", bpy.types.Text, "Text block holding the JSON (used when set)")
    filepath: props.text("File", "", subtype="FILE_PATH", description="JSON file (when no text block is set)")

    def signature(self):
        # The description's content belongs to the key: editing the text or saving the file
        # re-runs the node.
        if self.text is not None:
            stamp = hash(self.text.as_string())
        else:
            try:
                st = os.stat(bpy.path.abspath(self.filepath))
                stamp = (st.st_mtime_ns, st.st_size)
            except OSError:
                stamp = None
        return super().signature() + (stamp,)

    def _read(self):
        if self.text is not None:
            source, name = self.text.as_string(), "text block '%s'" % self.text.name
        elif self.filepath:
            path = bpy.path.abspath(self.filepath)
            if not os.path.isfile(path):
                raise NodeError("File %s does not exist" % path)
            with open(path, encoding="utf-8") as f:
                source, name = f.read(), os.path.basename(path)
        else:
            raise NodeError("Choose a text block or a JSON file with the hull description")
        try:
            return json.loads(source)
        except json.JSONDecodeError as exc:
            raise NodeError("%s is not valid JSON: %s" % (name, exc))

    def compute(self, inputs):
        fl, _ = engine.require()
        data = self._read()
        if isinstance(data, dict) and isinstance(data.get("principal"), dict):
            for key in ("Lpp", "B", "T", "D"):
                if inputs[key] is not None:
                    data["principal"][key] = float(inputs[key])
        hull = fl.Hull.from_json(data)
        d = hull.description
        pr = d.principal
        info = "%s\nLpp %.2f B %.2f T %.2f D %.2f m\nx %.1f .. %.1f m, %d stations" % (
            d.name[:40], pr.lpp, pr.breadth, pr.draft, pr.depth, d.x_start, d.x_end, len(d.stations))
        return {"Hull": hull, "__info__": info}


def _hull(inputs):
    hull = inputs.get("Hull")
    if hull is None:
        raise NodeError("Connect a hull (Hull Description)")
    return hull


_BASIC = [("sac", "Sectional Area (SAC)", "Sectional area below the DWL, both sides (m^2)"),
          ("dwl", "Design Waterline", "Half-breadth of the design waterline (m)"),
          ("deck", "Deck Line", "Half-breadth of the deck line (m)"),
          ("profile", "Centre Profile", "Keel / forefoot height (m)"),
          ("fos", "Flat of Side", "Height of the lower end of the flat side (m)"),
          ("fob", "Flat of Bottom", "Half-breadth of the flat bottom (m)"),
          ("deck_angle", "Deck Angle", "Section tangent angle at the deck (deg; < 0 flare)"),
          ("bottom_angle", "Bottom Angle", "Section tangent angle at the keel (deg)")]
_UNITS = {"sac": "m^2", "deck_angle": "deg", "bottom_angle": "deg"}
# Socket -> the description's parameter name. Area and xC are the curve's integral and its
# centroid (for the SAC: displaced volume and LCB).
_BASIC_PARAMS = (("Flat To", "flat_to"), ("Value", "value"), ("x End", "x_end"), ("yB", "yB"), ("yE", "yE"),
                 ("alphaB", "alphaB"), ("alphaE", "alphaE"), ("Area", "Area"), ("xC", "xC"))


@register
class FLNodeBasicCurve(FairlinesNode, bpy.types.Node):
    """One basic curve of the hull (SAC, waterline, deck, profile, flats, angles): switched-on
    form parameters replace the description's, the curve is solved (fairest B-spline meeting
    them) and the changed hull goes on. Values are in the curve's unit (shown below)"""
    bl_idname = ids.NODE_BASIC_CURVE
    bl_label = "Basic Curve"
    category = "Hull"
    bl_width_default = 250
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {}),
                   (ids.SOCKET_LENGTH, "Flat To", {"default": 130.0, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "Value", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_LENGTH, "x End", {"default": 244.8, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "yB", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "yE", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_ANGLE, "alphaB", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_ANGLE, "alphaE", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "Area", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_LENGTH, "xC", {"default": 166.5, "optional": True, "use": False})]
    outputs_spec = [(ids.SOCKET_HULL, "Hull"), (ids.SOCKET_CURVE, "Curve")]
    params = ("curve",)
    curve: props.enum("Curve", _BASIC, "sac")

    def draw_params(self, context, layout):
        layout.prop(self, "curve", text="")
        layout.label(text="f in %s, Area in %s.m" % (_UNITS.get(self.curve, "m"), _UNITS.get(self.curve, "m")))

    def compute(self, inputs):
        fl, _ = engine.require()
        src = _hull(inputs)
        if self.curve not in src.description.curves:
            raise NodeError("The description has no '%s' curve" % self.curve)
        from fairlines.hull import _ALIASES
        # A new description that shares everything with the upstream one except the curve this
        # node edits (Hull.set and the alias clean-up below touch only that curve's spec). A
        # deep copy of the whole description took longer than solving the curve.
        desc = copy.copy(src.description)
        desc.curves = dict(desc.curves)
        spec = desc.curves[self.curve] = copy.deepcopy(desc.curves[self.curve])
        hull = fl.Hull(desc)
        for sock, key in _BASIC_PARAMS:
            value = inputs[sock]
            if value is None:
                continue
            # A description may give the same condition by its alias (the SAC's volume is its
            # Area, lcb its xC): the socket replaces it rather than conflicting with it.
            for alias, (target, _) in _ALIASES.get(self.curve, {}).items():
                if target == key:
                    spec.aliases.pop(alias, None)
            hull.set(self.curve, key, math.degrees(value) if key in ("alphaB", "alphaE") else value)
        bc = hull.basic_curves[self.curve]  # solved here, so an infeasible request is red here
        fp = bc.form_parameters()
        info = ", ".join("%s %.4g" % (k, v) for k, v in fp.items() if k in ("Area", "xC", "yB", "yE"))
        if bc.curve is None:
            return {"Hull": hull, "__info__": "constant %g" % bc.value}
        return {"Hull": hull, "Curve": bc.curve, "__info__": info}


@register
class FLNodeSections(FairlinesNode, bpy.types.Node):
    """The hull's section curves (form-parameter curves from deck to keel at every station,
    read off the basic curves), as curves for Fair Skin and as lines to show"""
    bl_idname = ids.NODE_SECTIONS
    bl_label = "Sections"
    category = "Hull"
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {}),
                   (ids.SOCKET_INT, "Samples", {"default": 48})]
    outputs_spec = [(ids.SOCKET_CURVES, "Sections"), (ids.SOCKET_LINES, "Lines")]

    def compute(self, inputs):
        _, np = engine.require()
        n = inputs["Samples"]
        if n < 2:
            raise NodeError("Samples is %d; expected at least 2" % n)
        sections = list(_hull(inputs).sections)
        # The sections share their parameter domain: one sample vector for all (np.linspace per
        # section cost as much as evaluating the curves).
        params = {}
        lines = []
        for c in sections:
            dom = tuple(c.domain)
            t = params.get(dom)
            if t is None:
                t = params[dom] = np.linspace(dom[0], dom[1], n)
            lines.append(np.asarray(c.evaluate(t), dtype=np.float64))
        return {"Sections": sections, "Lines": LinesData(lines), "__info__": "%d sections" % len(sections)}


_SKIN_MODE = [("interpolate", "Interpolate", "Longitudinals pass through every section (least E2)"),
              ("approximate", "Approximate", "Longitudinals approximate the sections, smoothed")]
_SKIN_END = [("free", "Free", "Natural end"),
             ("parallel", "Parallel", "dy/dv = dz/dv = 0: joins a parallel middle body with C1")]


@register
class FLNodeFairSkin(FairlinesNode, bpy.types.Node):
    """Fair skinning of section curves into one B-spline surface (common section knots,
    longitudinals of least bending energy)"""
    bl_idname = ids.NODE_FAIR_SKIN
    bl_label = "Fair Skin"
    category = "Surfaces"
    bl_width_default = 230
    inputs_spec = [(ids.SOCKET_CURVES, "Sections", {}),
                   (ids.SOCKET_INT, "Control Points", {"default": 32, "optional": True, "use": False})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface")]
    params = ("mode", "start", "end")
    mode: props.enum("Mode", _SKIN_MODE, "interpolate")
    start: props.enum("Start", _SKIN_END, "free")
    end: props.enum("End", _SKIN_END, "free")

    def compute(self, inputs):
        fl, _ = engine.require()
        sections = inputs["Sections"]
        if not sections:
            raise NodeError("Connect sections (Sections node)")
        skin = fl.fair_skin(sections, n_control=inputs["Control Points"], mode=self.mode, start=self.start,
                            end=self.end)
        return {"Surface": skin.surface,
                "__info__": "section fit max %.3g m\nlongitudinal max %.2g m" % (
                    skin.section_fit_max, skin.longitudinal_max)}


@register
class FLNodeBareHull(FairlinesNode, bpy.types.Node):
    """The fair-skinned bare hull of a hull description (sections skinned with the
    description's settings): the half hull y >= 0, with its hydrostatics at the design draught"""
    bl_idname = ids.NODE_BARE_HULL
    bl_label = "Bare Hull"
    category = "Hull"
    bl_width_default = 240
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface"), (ids.SOCKET_VOLUME, "Volume"), (ids.SOCKET_LENGTH, "LCB"),
                    (ids.SOCKET_FLOAT, "Cb")]
    params = ("hydrostatics",)
    hydrostatics: props.boolean("Hydrostatics", True, "Integrate volume, LCB and Cb at the design draught")

    def compute(self, inputs):
        engine.require()
        hull = _hull(inputs)
        surface = hull.bare_hull_surface()
        skin = hull.skin()
        info = "%d x %d control points\nsection fit max %.3g m" % (
            surface.control_points.shape[0], surface.control_points.shape[1], skin.section_fit_max)
        out = {"Surface": surface, "__info__": info}
        if self.hydrostatics:
            # The node shows volume, LCB and Cb, not the SAC: no SAC stations, and 4 Gauss points
            # per span (on the Panamax forebody the same volume and LCB as 8 to 1e-11, in a
            # sixth of the time: this runs on every hull change). Nothing on the way to the
            # meshes needs them, so they are a deferred job (evaluator.py): done when a node
            # reads Volume / LCB / Cb, else right after the meshes are in the scene.
            def hydrostatics():
                h = hull.hydrostatics(gauss=4, sac_stations=2)
                return {"Volume": float(h.volume), "LCB": float(h.lcb), "Cb": float(h.cb),
                        "__info__": "\nV %.6g m3, LCB %.4g m, Cb %.4f" % (h.volume, h.lcb, h.cb)}
            out["__later__"] = hydrostatics
        return out
