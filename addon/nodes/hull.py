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
from .. import report
from ..data import LinesData
from .base import HYDROSTATICS, FairlinesNode, NodeError, register


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


_STERNS = [("transom", "Transom", "Flat transom aft of the AP"),
           ("cruiser", "Cruiser", "Cruiser stern rising to the deck")]
# Optional particulars: socket, Particulars field, socket type, default shown when switched on.
_OPTIONAL = (("Cm", "cm", ids.SOCKET_FLOAT, 0.98), ("Cwp", "cwp", ids.SOCKET_FLOAT, 0.82),
             ("LCF", "lcf", ids.SOCKET_LENGTH, 115.06), ("Parallel Length", "parallel_length", ids.SOCKET_LENGTH, 17.0),
             ("Transom Immersion", "transom_immersion", ids.SOCKET_LENGTH, -0.55),
             ("Propeller Diameter", "propeller_diameter", ids.SOCKET_LENGTH, 7.7),
             ("Sonar Dome Nose", "sonar_dome_nose", ids.SOCKET_LENGTH, 190.0),
             ("Flat Bottom", "flat_bottom", ids.SOCKET_FLOAT, 0.15))


@register
class FLNodeParticulars(FairlinesNode, bpy.types.Node):
    """A whole ship designed from its principal particulars (fl.design_hull): Lpp, B, T, D, Cb
    and LCB (from the AP), optionally Cm, Cwp, LCF, the parallel middle body, the transom
    immersion, (with a skeg) the propeller diameter, (with a sonar dome) its nose (from the AP;
    switched off, where the keel's flat ends, or aft of a bulb's blend) and a flat of bottom (fraction of the
    waterline's half-breadth over the parallel body; switched off, the designer's 0.15, left
    out on fine ships whose sections would narrow it; switched on, drawn as given, narrowing
    where it must; 0: none); the stern type, the stem rake, the transom's rake (from the
    vertical, the top aft), a bulbous
    bow, a single screw's skeg and propeller aperture, a sonar dome. The ship meets Cb and LCB
    (with a bulb the composed ship: bare hull, bulb and blend) and Cwp; the node shows the
    ship's figures; out of the designer's range the node is red with the range named"""
    bl_idname = ids.NODE_PARTICULARS
    bl_label = "Particulars"
    category = "Hull"
    bl_width_default = 260
    inputs_spec = [(ids.SOCKET_LENGTH, "Lpp", {"default": 244.8}),
                   (ids.SOCKET_LENGTH, "B", {"default": 32.25}),
                   (ids.SOCKET_LENGTH, "T", {"default": 11.0}),
                   (ids.SOCKET_LENGTH, "D", {"default": 19.0}),
                   (ids.SOCKET_FLOAT, "Cb", {"default": 0.65}),
                   (ids.SOCKET_LENGTH, "LCB", {"default": 118.73})] + [
                  (idname, name, {"default": value, "optional": True, "use": False})
                  for name, _, idname, value in _OPTIONAL] + [
                  (ids.SOCKET_ANGLE, "Stem Rake", {"default": math.radians(20.0)}),
                  (ids.SOCKET_ANGLE, "Transom Rake", {"default": 0.0})]
    outputs_spec = [(ids.SOCKET_HULL, "Hull"), (ids.SOCKET_LENGTH, "Lpp"), (ids.SOCKET_LENGTH, "B"),
                    (ids.SOCKET_LENGTH, "T"), (ids.SOCKET_LENGTH, "D")]
    params = ("stern", "bulb", "skeg", "sonar_dome", "ship_name")
    stern: props.enum("Stern", _STERNS, "transom")
    bulb: props.boolean("Bulbous Bow", True, "Give the description a bulbous bow (Kracht's default coefficients)")
    skeg: props.boolean("Skeg", False, "A single screw: a skeg under the run and a propeller aperture aft of it")
    sonar_dome: props.boolean("Sonar Dome", False, "A sonar dome under the keel's forward end")
    ship_name: props.text("Name", "designed hull")

    def compute(self, inputs):
        fl, _ = engine.require()
        kw = {k: float(inputs[s]) for s, k in (("Lpp", "lpp"), ("B", "breadth"), ("T", "draft"), ("D", "depth"),
                                                ("Cb", "cb"), ("LCB", "lcb"))}
        for name, key, _, _ in _OPTIONAL:
            if inputs.get(name) is not None:  # .get: nodes saved before a socket was added lack it
                kw[key] = float(inputs[name])
        p = fl.Particulars(stern=self.stern, bulb=bool(self.bulb), skeg=bool(self.skeg), sonar_dome=bool(self.sonar_dome),
                           stem_rake=math.degrees(inputs["Stem Rake"]),
                           transom_rake=math.degrees(inputs.get("Transom Rake") or 0.0),  # not on nodes saved before it
                           name=self.ship_name, **kw)
        hull = fl.design_hull(p)
        d = hull.description
        notes = d.notes.split("designed from particulars: ")[-1].replace(", parallel", "\nparallel")
        info = "x %.2f .. %.2f m\n%s" % (d.x_aft, d.x_fore, notes)

        def later():
            # the ship's figures (with a bulb its composition, which the designer kept): nothing drawn needs them
            h = hull.ship_hydrostatics()
            return {"__info__": "\nship%s: V %.6g m3, Cb %.4f, LCB %.3f m" % (
                " with its bulb" if d.bulb is not None else "", h["volume"], h["cb"], h["lcb"])}
        return {"Hull": hull, "Lpp": p.lpp, "B": p.breadth, "T": p.draft, "D": p.depth, "__info__": info,
                "__later__": later}


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
        info = "%s\nLpp %.2f B %.2f T %.2f D %.2f m\nx %.2f .. %.2f m, %d stations%s" % (
            d.name[:40], pr.lpp, pr.breadth, pr.draft, pr.depth, d.x_aft, d.x_fore, len(hull.stations()),
            ", bulb" if d.bulb is not None else "")
        return {"Hull": hull, "__info__": info}


def _hull(inputs):
    hull = inputs.get("Hull")
    if hull is None:
        raise NodeError("Connect a hull (Hull Description)")
    return hull


_BASIC = [("sac", "Sectional Area (SAC)", "Sectional area below the DWL, both sides (m^2); Area is the "
           "displaced volume, xC the LCB"),
          ("dwl", "Design Waterline", "Half-breadth of the design waterline (m); Area is half the waterplane "
           "area, xC the LCF"),
          ("deck", "Deck Line", "Half-breadth of the deck line (m)"),
          ("profile", "Centre Profile", "Keel / stem / transom height (m)"),
          ("top_corner", "Top Corner", "Where the section's upper corner sits (fraction)"),
          ("deadrise", "Deadrise", "Rise of floor (deg)"),
          ("character", "Character", "Section character, V (low) to U (high)")]
_UNITS = {"sac": "m^2", "deadrise": "deg", "top_corner": "-", "character": "-"}
# Socket -> the description's parameter name. Area and xC are the curve's integral and its
# centroid (for the SAC: displaced volume and LCB).
_BASIC_PARAMS = (("Flat To", "flat_to"), ("Value", "value"), ("x End", "x_end"), ("yB", "yB"), ("yE", "yE"),
                 ("alphaB", "alphaB"), ("alphaE", "alphaE"), ("Area", "Area"), ("xC", "xC"))


@register
class FLNodeBasicCurve(FairlinesNode, bpy.types.Node):
    """One basic curve of the hull (SAC, waterline, deck, profile, shape curves): switched-on
    form parameters replace the description's, the curve is solved (fairest B-spline meeting
    them) and the changed hull goes on. Values are in the curve's unit (shown below)"""
    bl_idname = ids.NODE_BASIC_CURVE
    bl_label = "Basic Curve"
    category = "Hull"
    bl_width_default = 250
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {}),
                   (ids.SOCKET_LENGTH, "Flat To", {"default": 125.36, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "Value", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_LENGTH, "x End", {"default": 244.8, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "yB", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "yE", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_ANGLE, "alphaB", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_ANGLE, "alphaE", {"default": 0.0, "optional": True, "use": False}),
                   (ids.SOCKET_FLOAT, "Area", {"default": 56448.8, "optional": True, "use": False}),
                   (ids.SOCKET_LENGTH, "xC", {"default": 118.73, "optional": True, "use": False})]
    outputs_spec = [(ids.SOCKET_HULL, "Hull"), (ids.SOCKET_CURVE, "Curve")]
    params = ("curve",)
    curve: props.enum("Curve", _BASIC, "sac")

    def draw_params(self, context, layout):
        layout.prop(self, "curve", text="")
        unit = _UNITS.get(self.curve, "m")
        layout.label(text="f in %s, Area in %s.m" % (unit, unit))

    def compute(self, inputs):
        fl, _ = engine.require()
        from fairlines.description import FORM_ALIASES
        src = _hull(inputs)
        if self.curve not in src.description.curves:
            raise NodeError("The description has no '%s' curve" % self.curve)
        # A new description that shares everything with the upstream one except the curve this
        # node edits (Hull.set and the alias clean-up below touch only that curve's spec). A
        # deep copy of the whole description took longer than solving the curve.
        desc = copy.copy(src.description)
        desc.curves = dict(desc.curves)
        spec = desc.curves[self.curve] = desc.curves[self.curve].copy()
        hull = fl.Hull(desc)
        for sock, key in _BASIC_PARAMS:
            value = inputs[sock]
            if value is None:
                continue
            # The description may give the same condition by its public alias (the SAC's
            # volume is its Area, lcb its xC): the socket replaces it rather than conflicting.
            for alias, (target, _) in FORM_ALIASES.get(self.curve, {}).items():
                if target == key:
                    spec.aliases.pop(alias, None)
            hull.set(self.curve, key, math.degrees(value) if key in ("alphaB", "alphaE") else value)
        bc = hull.basic_curves[self.curve]  # solved here, so an infeasible request is red here
        if bc.curve is None and bc.value is not None:
            return {"Hull": hull, "__info__": "constant %g" % bc.value}

        def info():  # integrals of the solved curve, only shown: a deferred job (evaluator.py)
            fp = bc.form_parameters()
            return {"__info__": ", ".join("%s %.6g" % (k, v) for k, v in fp.items()
                                          if k in ("Area", "xC", "yB", "yE") and v is not None)}
        return {"Hull": hull, "Curve": bc.curve, "__later__": info}


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
    """The fair-skinned bare hull of a hull description: the half hull y >= 0, with the hull's
    hydrostatics at the design draught (Hull.hydrostatics: on Lpp and B, midship at Lpp / 2)"""
    bl_idname = ids.NODE_BARE_HULL
    bl_label = "Bare Hull"
    category = "Hull"
    bl_width_default = 270
    inputs_spec = [(ids.SOCKET_HULL, "Hull", {})]
    outputs_spec = [(ids.SOCKET_SURFACE, "Surface"), (ids.SOCKET_VOLUME, "Volume"), (ids.SOCKET_LENGTH, "LCB"),
                    (ids.SOCKET_FLOAT, "Cb")]
    params = ("hydrostatics",)
    hydrostatics: props.boolean("Hydrostatics", True, "Integrate the hydrostatics at the design draught")

    def compute(self, inputs):
        engine.require()
        hull = _hull(inputs)
        surface = hull.bare_hull_surface()
        info = "%d x %d control points" % tuple(surface.control_points.shape[:2])
        out = {"Surface": surface, "__info__": info}
        if self.hydrostatics:
            # Nothing on the way to the meshes needs them, so they are a deferred job
            # (evaluator.py): done when a node reads Volume / LCB / Cb, else right after the
            # meshes are in the scene. Exactly Hull.hydrostatics(), so the figures are the
            # engine's wherever they are shown.
            def hydrostatics():
                h = hull.hydrostatics()
                return {"Volume": float(h.volume), "LCB": float(h.lcb), "Cb": float(h.cb), HYDROSTATICS: h,
                        "__info__": "\n" + report.compact(h)}
            out["__later__"] = hydrostatics
        return out
