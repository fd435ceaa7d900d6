"""The hull description: a whole ship (or part of one) as principal dimensions and basic curves.

Format (JSON; ``docs/hull_description.schema.json`` is its JSON Schema)::

    {
      "name": "...", "notes": "...",
      "principal": {"Lpp": 244.8, "B": 32.25, "T": 11.0, "D": 19.0},      # metres
      "ends": {"aft": -5.0, "fore": 247.0},       # x of the hull's aft end (transom / stern) and
                                                  # forward end (stem head); default 0 and Lpp;
                                                  # "aft_post" / "fore_post": true, that end is a
                                                  # vertical post of zero width (default false);
                                                  # "transom_rake": the transom's plane from the
                                                  # vertical, deg, top aft when positive (default 0;
                                                  # its lower edge stays at "aft")
      "stations": {"count": 61} | {"x": [...]},    # default {"count": 61}, clustered at the ends
      "sections": {"n_control": 20,                # control points of every section
                   "given": [{"x": 12.0, "points": [[y, z], ...]}, ...]},   # optional shapes
      "basic_curves": {"profile": ..., "dwl": ..., "deck": ..., "sac": ...,
                       "top_corner": ..., "deadrise": ..., "character": ...},
      "skinning": {"e2": 1.0, "e3": 0.0,         # fairness of the rows along the hull
                   "station_mean": 0.375},        # each section the mean of the family's at x +- 0.375
                                                  # of the station spacing (0: as designed)
      "bulb": {...},                              # optional bulbous bow (Kracht coefficients)
      "skeg": {"x_aft": 13.0, "x_fore": 42.0, "half_thickness": 0.8},  # optional skeg under the run
      "dome": {"x_aft": 104.0, "x_fore": 120.0, "depth": 2.0, "half_breadth": 1.4}  # optional sonar dome
    }

Basic curves (each a fairest spline function of x, fairlines.spline_design):

==============  ==============================================================  ================
name            f(x)                                                            range
==============  ==============================================================  ================
profile         centre-line contour: keel, counter or stern, forefoot and stem   ends
                height (m); below T it bounds the immersed body
dwl             design-waterline half-breadth (m)                               where profile < T
deck            deck-at-side half-breadth (m) at the deck edge                  ends
sheer           (optional) deck-at-side height (m above base); default the      ends
                depth D everywhere (no sheer); it stays above T
sac             sectional area below T, both sides (m^2), designed through the  as dwl
                section fullness SAC / (2 y_dwl (T - z_keel))
top_corner      (optional) where the sections' top turns, as a fraction of the  ends
                freeboard above T: small values turn it near the waterline, large
                ones near the deck (more flare at the deck); default 0.5
deadrise        (optional) rise of the bottom at the bilge, deg; default 0       ends
character       (optional) where the bilge heads as the sections fine, as a      ends
                fraction of the chord from the waterline point to the keel: 0.5
                a symmetric V, smaller the side leans in first; default 0.5
corner_breadth  (optional, with corner_height) the bilge corner of each section's  ends
                arc below T given directly: its half-breadth as a fraction of the
                waterline's (0 .. 1]; the SAC's area then sets only the arc's
                weight (deadrise and character no longer place the corner)
corner_height   (optional, with corner_breadth) the bilge corner's height above  ends
                the keel as a fraction of the immersed depth [0 .. 1): (1, 0.5)
                holds a parabolic (Wigley) section, a corner inside the chord from
                the waterline point to the keel a hollow one
flat_bottom     (optional) flat of bottom: the half-breadth of the straight      its own
                floor from the keel point as a fraction of the waterline         x_start ..
                half-breadth [0 .. 0.9], rising at the deadrise; none outside    x_end
                its range; the bilge arc starts from its end, the corner rounded;
                a section too fine to hold all of it narrows it
==============  ==============================================================  ================

**Given sections** (``sections.given``, optional): auxiliary sections where the template family
cannot hold the ship's shape (a skeg, a stern bulb, hollow or S-shaped sections, a dome): each
``{"x": x, "points": [[y, z], ...]}``, half-breadths and heights (m) from the deck edge down to
the keel on the centre plane, at increasing x inside the ends. A station between two given
sections blends their shapes; outside the first and last, the template family holds. Each
shape is mapped onto its station's deck, waterline and keel points (heights stretched between
them, half-breadths scaled to the waterline's and the deck's), so it follows edits of the
basic curves, and its half-breadths are shifted smoothly until it holds the SAC's area. A
measured shape may add ``"offsets": {"deck": [dy, dz], "waterline": dy, "keel": dz}`` (m, default 0):
its deck edge, waterline point and keel point lie that far from the basic curves at its x, and it is mapped onto the
curves moved by them (blended linearly in x between given sections), so the shape keeps its
measured points where a fair curve passes a few mm off them and still follows the curves' edits.
``sections.given_smoothing`` (optional, >= 0; default the engine's, 1e-6: near-interpolation)
is the bending penalty of each given shape's fit against its points; the importer writes
0.1 for measured shapes (docs/import.md).

A basic curve is ``{"value": v}`` (constant) or a spline with any of: ``x_start``, ``x_end``
(inside its range above), ``flat_from`` / ``flat_to`` / ``value`` (a part where f = value exactly,
left with G2; flat_from defaults to the start), ``yB`` / ``yE`` (end values), ``alphaB`` /
``alphaE`` (end slope angles, deg) or ``slopeB`` / ``slopeE`` (df/dx), ``CAB`` / ``CAE`` (end
curvatures, 1/m, with the slope at that end), ``Area`` and ``xC`` (integral of f over the range
and its centroid), ``points`` ([[x, f], ...] passed through), ``slopes`` ([[x, df/dx], ...]: interior tangents), ``fit`` ([[x, f], ...] passed near,
weight ``fit_weight``), ``lower`` / ``upper`` (bounds), ``convex`` / ``concave`` ([[x_from,
x_to, k], ...]: f'' <= -k / f'' >= k there, k >= 0 a least curvature in 1/m: a waterline that
bulges out, or a hollow; on the sac they hold the section fullness, which it is designed as),
sac ``convex_where_met`` (the same, held where the volume and LCB allow it and dropped where they
do not), ``monotone`` (true: f moves away from its
flat value monotonically on both sides of the flat part), ``e3`` (weight of the change of
curvature, h^2 int f'''^2 dx with h the mean knot span, beside int f''^2 dx in the fairness the
curve is made least in; default 0), ``spans`` (default 12) and ``breaks``
(extra knot positions, m, where the curve must turn quickly: a sternpost). Aliases: sac
``volume`` (Area, m^3) and ``lcb`` (xC, m from the AP), and ``fullness_fit`` ([[x, s], ...]: the
section fullness the SAC stays near while meeting its volume and LCB exactly); dwl ``waterplane_area`` (both sides,
m^2), ``lcf``, ``entrance_angle`` (half angle at the fore end, deg) and ``run_angle`` (at the aft
end, deg). Unknown keys anywhere are refused with the nearest valid one.
"""

from __future__ import annotations

import copy
import json
import os
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from . import _native
from .station_mean import STATION_MEAN
from .validation import bad, integer, keyed_object, number, text_value

__all__ = [
    "BASIC_CURVES",
    "FORM_ALIASES",
    "BasicCurveSpec",
    "BulbSpec",
    "HullDescription",
    "PrincipalDimensions",
    "load_description",
]

REQUIRED_CURVES = ("profile", "dwl", "deck", "sac")
OPTIONAL_CURVES = ("top_corner", "deadrise", "character", "corner_breadth", "corner_height", "sheer", "flat_bottom")
#: Curves that are given together or not at all (the bilge corner given directly).
PAIRED_CURVES = (("corner_breadth", "corner_height"),)
#: ``ends.transom_rake``: the transom's plane from the vertical (deg; positive: its top aft of its
#: lower edge). Beyond 45 deg a transom is more deck than end; a reverse rake past 30 deg is a
#: yacht's.
TRANSOM_RAKE_RANGE = (-30.0, 45.0)
#: ``ends`` keys that make an end a vertical post of zero width.
POST_KEYS = {"aft": "aft_post", "fore": "fore_post"}
BASIC_CURVES = REQUIRED_CURVES + OPTIONAL_CURVES
FORM_KEYS = ("yB", "yE", "alphaB", "alphaE", "slopeB", "slopeE", "CAB", "CAE", "Area", "xC")
#: Public aliases of form parameters per curve: alias -> (form parameter, factor).
FORM_ALIASES = {
    "sac": {"volume": ("Area", 1.0), "lcb": ("xC", 1.0)},
    "dwl": {"waterplane_area": ("Area", 0.5), "lcf": ("xC", 1.0), "entrance_angle": ("alphaE", -1.0),
            "run_angle": ("alphaB", 1.0)},
}
CURVE_KEYS = ("x_start", "x_end", "flat_from", "flat_to", "value", "points", "slopes", "fit", "fit_weight", "lower", "upper",
              "monotone", "spans", "n_control", "breaks", "convex", "concave", "e3") + FORM_KEYS
# sac only: the section fullness SAC / (2 y_dwl (T - z_keel)) it stays near ([[x, s], ...]).
FULLNESS_KEY = "fullness_fit"
# sac only: convex ranges of the fullness held where the volume and LCB allow them, else dropped.
CONVEX_WHERE_MET_KEY = "convex_where_met"

# Limits on sizes a description may ask for (refused beyond, before any work is done).
MAX_E3 = 1e4  # a basic curve's e3: far past where the third derivative's term alone decides
MAX_STATIONS = 1000
MAX_SPANS = 200
SECTION_CONTROLS = (8, 64)
# A skeg tapers into the keel over this fraction of its length aft of its forward end.
SKEG_FORE_TAPER = 0.3
# A sonar dome is widest and deepest at this fraction of its length from its aft end, and its
# neck (where it meets the hull body) is this fraction of its half-breadth.
DOME_WIDEST = 0.65
DOME_NECK = 0.55
# Least number of points of a given section, and the most given sections and points per section.
GIVEN_POINTS = (3, 2000)
MAX_GIVEN_SECTIONS = 1000
# Largest bending penalty of a given shape's fit (sections.given_smoothing): beyond it the fit
# is the straight line the penalty asks for, not the shape.
MAX_GIVEN_SMOOTHING = 100.0
# Plausible ship sizes: a length outside this range is a unit mistake far more often than a ship.
LENGTH_RANGE = (1.0, 600.0)


def _flag(path: str, value: Any) -> bool:
    if not isinstance(value, bool):
        raise bad(path, value, "true or false")
    return value


def _pairs(path: str, value: Any) -> list[tuple[float, float]]:
    if not isinstance(value, (list, tuple)):
        raise bad(path, value, "a list of [x, value] pairs")
    out = []
    for i, p in enumerate(value):
        if not isinstance(p, (list, tuple)) or len(p) != 2:
            raise bad(f"{path}[{i}]", p, "an [x, value] pair")
        out.append((number(f"{path}[{i}][0]", p[0]), number(f"{path}[{i}][1]", p[1])))
    return out


@dataclass
class PrincipalDimensions:
    """Lpp, B (moulded breadth), T (design draught), D (depth to the deck), metres; B_max, the
    largest breadth where the sides flare beyond B above the waterline (default B)."""

    lpp: float
    breadth: float
    draft: float
    depth: float
    max_breadth: float | None = None

    @property
    def half_breadth_limit(self) -> float:
        """The sections' half-breadth bound (m): B_max / 2, or B / 2."""
        return (self.max_breadth or self.breadth) / 2

    @classmethod
    def from_dict(cls, d: Any, path: str = "principal") -> PrincipalDimensions:
        """The principal dimensions of ``d`` (keys Lpp, B, T, D, optional B_max). Raises
        InvalidInput naming a missing or unknown key or a length out of range."""
        d = keyed_object(path, d, ("Lpp", "B", "T", "D", "B_max"))
        vals = {}
        for key in ("Lpp", "B", "T", "D"):
            if key not in d:
                raise _native.InvalidInput(f"{path}.{key} is missing; expected a length in metres")
            vals[key] = number(f"{path}.{key}", d[key], positive=True)
        lo, hi = LENGTH_RANGE
        if not lo <= vals["Lpp"] <= hi:
            hint = " (millimetres? divide by 1000)" if vals["Lpp"] > 1000 * lo else ""
            raise _native.InvalidInput(f"{path}.Lpp is {vals['Lpp']}; expected a ship length from {lo} to {hi} m{hint}")
        for key in ("B", "T", "D"):
            if not vals[key] < vals["Lpp"]:
                raise _native.InvalidInput(f"{path}.{key} is {vals[key]}; expected less than Lpp = {vals['Lpp']} m (same unit: metres)")
        if not vals["T"] < vals["D"]:
            raise _native.InvalidInput(f"{path}.T is {vals['T']}; expected a draught below the depth D = {vals['D']} m")
        b_max = None
        if d.get("B_max") is not None:
            b_max = number(f"{path}.B_max", d["B_max"], positive=True)
            if not vals["B"] <= b_max < vals["Lpp"]:
                raise _native.InvalidInput(f"{path}.B_max is {b_max}; expected the largest breadth, from B = {vals['B']} m "
                                           f"to less than Lpp = {vals['Lpp']} m")
        return cls(vals["Lpp"], vals["B"], vals["T"], vals["D"], b_max)

    def to_dict(self) -> dict:
        d = {"Lpp": self.lpp, "B": self.breadth, "T": self.draft, "D": self.depth}
        if self.max_breadth is not None:
            d["B_max"] = self.max_breadth
        return d


@dataclass
class BasicCurveSpec:
    """One basic curve as described (see the module docstring for the fields)."""

    x_start: float | None = None
    x_end: float | None = None
    flat_from: float | None = None
    flat_to: float | None = None
    value: float | None = None
    params: dict[str, float] = field(default_factory=dict)
    aliases: dict[str, float] = field(default_factory=dict)
    points: list[tuple[float, float]] = field(default_factory=list)
    slopes: list[tuple[float, float]] = field(default_factory=list)
    fit: list[tuple[float, float]] = field(default_factory=list)
    fit_weight: float = 1.0
    e3: float = 0.0  # weight of h^2 int f'''^2 dx beside int f''^2 dx in the fairness
    lower: float | None = None
    upper: float | None = None
    monotone: bool = False
    spans: int = 12
    breaks: list[float] = field(default_factory=list)
    fullness_fit: list[tuple[float, float]] = field(default_factory=list)
    convex: list[tuple[float, float, float]] = field(default_factory=list)   # f'' <= -k on [x0, x1]
    concave: list[tuple[float, float, float]] = field(default_factory=list)  # f'' >= k on [x0, x1]
    convex_where_met: list[tuple[float, float, float]] = field(default_factory=list)  # sac: convex unless infeasible

    def copy(self) -> BasicCurveSpec:
        """A copy whose fields, dicts and lists can be changed without changing this one (the
        lists' items, numbers or pairs that nothing changes in place, are shared): what a
        Blender slider edits, at a tenth of copy.deepcopy's cost."""
        out = copy.copy(self)
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, (list, dict)):
                setattr(out, f.name, type(value)(value))
        return out

    @classmethod
    def from_dict(cls, name: str, d: Any, path: str) -> BasicCurveSpec:
        """The spec of basic curve ``name`` from ``d``. Raises InvalidInput naming a missing,
        unknown or malformed key."""
        extra = (FULLNESS_KEY, CONVEX_WHERE_MET_KEY) if name == "sac" else ()
        d = keyed_object(path, d, CURVE_KEYS + tuple(FORM_ALIASES.get(name, {})) + extra)
        spec = cls()
        for key in ("x_start", "x_end", "flat_from", "flat_to", "value", "lower", "upper"):
            if d.get(key) is not None:
                setattr(spec, key, number(f"{path}.{key}", d[key]))
        if "spans" in d and "n_control" in d:
            raise _native.InvalidInput(f"{path}.spans and {path}.n_control are both given; expected one of them")
        if "spans" in d:
            spec.spans = integer(f"{path}.spans", d["spans"], 1, MAX_SPANS)
        elif "n_control" in d:
            spec.spans = integer(f"{path}.n_control", d["n_control"], 4, MAX_SPANS + 3) - 3
        for key in FORM_KEYS:
            if d.get(key) is not None:
                spec.params[key] = number(f"{path}.{key}", d[key])
        for key in FORM_ALIASES.get(name, {}):
            if d.get(key) is not None:
                spec.aliases[key] = number(f"{path}.{key}", d[key])
        for key in ("alphaB", "alphaE"):
            if key in spec.params and not -90 < spec.params[key] < 90:
                raise bad(f"{path}.{key}", spec.params[key], "an angle between -90 and 90 degrees")
        spec.points = _pairs(f"{path}.points", d.get("points", []))
        spec.slopes = _pairs(f"{path}.slopes", d.get("slopes", []))
        spec.fit = _pairs(f"{path}.fit", d.get("fit", []))
        if "breaks" in d:
            if not isinstance(d["breaks"], (list, tuple)) or len(d["breaks"]) > MAX_SPANS:
                raise bad(f"{path}.breaks", d["breaks"], f"a list of at most {MAX_SPANS} knot positions (m)")
            spec.breaks = sorted(number(f"{path}.breaks[{i}]", v) for i, v in enumerate(d["breaks"]))
        for key in ("convex", "concave", CONVEX_WHERE_MET_KEY):
            ranges = d.get(key, [])
            if not isinstance(ranges, (list, tuple)):
                raise bad(f"{path}.{key}", ranges, "a list of [x_from, x_to, least curvature] triples")
            for i, r in enumerate(ranges):
                if not isinstance(r, (list, tuple)) or len(r) != 3:
                    raise bad(f"{path}.{key}[{i}]", r, "an [x_from, x_to, least curvature (1/m, >= 0)] triple")
                a, b, k = (number(f"{path}.{key}[{i}][{j}]", v) for j, v in enumerate(r))
                if not a < b or k < 0:
                    raise bad(f"{path}.{key}[{i}]", list(r), "x_from < x_to and a least curvature >= 0")
                getattr(spec, key).append((a, b, k))
        if FULLNESS_KEY in d:
            spec.fullness_fit = _pairs(f"{path}.{FULLNESS_KEY}", d[FULLNESS_KEY])
            for i, (_, v) in enumerate(spec.fullness_fit):
                if not 0 < v <= 1:
                    raise bad(f"{path}.{FULLNESS_KEY}[{i}][1]", v, "a section fullness between 0 and 1")
        if "fit_weight" in d:
            spec.fit_weight = number(f"{path}.fit_weight", d["fit_weight"], positive=True)
        if "e3" in d:
            spec.e3 = number(f"{path}.e3", d["e3"])
            if not 0 <= spec.e3 <= MAX_E3:
                raise bad(f"{path}.e3", spec.e3, f"a weight from 0 to {MAX_E3:g} (0: the curvature's square alone)")
        if "monotone" in d:
            if not isinstance(d["monotone"], bool):
                raise bad(f"{path}.monotone", d["monotone"], "true or false")
            spec.monotone = d["monotone"]
        if (spec.flat_to is not None or spec.flat_from is not None) and spec.value is None:
            raise _native.InvalidInput(f"{path}.value is missing; expected the constant value of the flat part")
        for a, b in (("flat_from", "flat_to"), ("x_start", "x_end"), ("lower", "upper")):
            va, vb = getattr(spec, a), getattr(spec, b)
            if va is not None and vb is not None and not va <= vb:
                raise _native.InvalidInput(f"{path}.{a} is {va}; expected at most {path}.{b} = {vb}")
        return spec

    @property
    def constant(self) -> bool:
        """Only a value: the curve is that constant over its range."""
        return (self.value is not None and self.flat_to is None and self.flat_from is None and not self.params
                and not self.aliases and not self.points and not self.slopes and not self.fit)

    def to_dict(self) -> dict:
        d: dict[str, Any] = {}
        for key in ("x_start", "x_end", "flat_from", "flat_to", "value", "lower", "upper"):
            if getattr(self, key) is not None:
                d[key] = getattr(self, key)
        d.update(self.params)
        d.update(self.aliases)
        if self.points:
            d["points"] = [list(p) for p in self.points]
        if self.slopes:
            d["slopes"] = [list(p) for p in self.slopes]
        if self.fit:
            d["fit"] = [list(p) for p in self.fit]
            d["fit_weight"] = self.fit_weight
        if self.monotone:
            d["monotone"] = True
        if self.e3:
            d["e3"] = self.e3
        if self.breaks:
            d["breaks"] = list(self.breaks)
        for key in ("convex", "concave", CONVEX_WHERE_MET_KEY):
            if getattr(self, key):
                d[key] = [list(r) for r in getattr(self, key)]
        if self.fullness_fit:
            d[FULLNESS_KEY] = [list(p) for p in self.fullness_fit]
        if not self.constant:
            d["spans"] = self.spans
        return d


KRACHT = ("c_lpr", "c_bb", "c_zb", "c_abt", "c_abl", "c_vpr")
BULB_SHAPE_NUMBERS = ("aft_length", "nose_height_shift")
BULB_SHAPE_INTEGERS = {"sections": (8, 200), "section_points": (8, 400), "control_u": (4, 100), "control_v": (4, 100)}


@dataclass
class BulbSpec:
    """The optional ``"bulb"`` section: Kracht coefficients, shape controls and (for a hull
    that models only part of the ship) the ship's displacement volume."""

    kracht: dict[str, float] = field(default_factory=dict)
    shape: dict[str, float] = field(default_factory=dict)
    displacement_volume: float | None = None

    @classmethod
    def from_dict(cls, d: Any, path: str = "bulb") -> BulbSpec:
        """The bulb section of a description. Raises InvalidInput naming an unknown key or a
        value out of range."""
        d = keyed_object(path, d, ("kracht", "shape", "displacement_volume"))
        spec = cls()
        for key, val in keyed_object(f"{path}.kracht", d.get("kracht", {}), KRACHT).items():
            spec.kracht[key] = number(f"{path}.kracht.{key}", val, positive=True)
        shape_keys = BULB_SHAPE_NUMBERS + tuple(BULB_SHAPE_INTEGERS)
        for key, val in keyed_object(f"{path}.shape", d.get("shape", {}), shape_keys).items():
            if key in BULB_SHAPE_NUMBERS:
                v = number(f"{path}.shape.{key}", val)
                if key == "aft_length" and v < 0:
                    raise bad(f"{path}.shape.{key}", v, "a length >= 0 m (0: the default 2 (L_PR + B_B))")
                spec.shape[key] = v
            else:
                spec.shape[key] = integer(f"{path}.shape.{key}", val, *BULB_SHAPE_INTEGERS[key])
        if d.get("displacement_volume") is not None:
            spec.displacement_volume = number(f"{path}.displacement_volume", d["displacement_volume"], positive=True)
        return spec

    def to_dict(self) -> dict:
        d: dict[str, Any] = {"kracht": dict(self.kracht), "shape": dict(self.shape)}
        if self.displacement_volume is not None:
            d["displacement_volume"] = self.displacement_volume
        return d


TOP_KEYS = ("name", "notes", "principal", "ends", "stations", "sections", "basic_curves", "skinning", "bulb", "skeg", "dome",
            "design")


@dataclass
class SkegSpec:
    """A skeg under the run (metres): from the sternpost x_aft forward to x_fore, its bottom at
    `bottom` above base, its sides half_thickness off the centre plane, joined to the hull body
    by a hollow fillet of about `fillet`; over `end_length` forward of the sternpost its bottom
    rises to the body (a raked aft edge)."""

    x_aft: float
    x_fore: float
    half_thickness: float
    fillet: float
    bottom: float = 0.0
    end_length: float = 0.0

    KEYS = ("x_aft", "x_fore", "half_thickness", "fillet", "bottom", "end_length")

    @classmethod
    def from_dict(cls, d: Any, path: str, x_aft: float, x_fore: float) -> SkegSpec:
        """The skeg of ``d`` on a hull from x_aft to x_fore (m). Raises InvalidInput naming a
        missing or unknown key, or a value out of range."""
        d = keyed_object(path, d, cls.KEYS)
        for key in ("x_aft", "x_fore", "half_thickness"):
            if key not in d:
                raise _native.InvalidInput(f"{path}.{key} is missing; expected a length in metres")
        v = {k: number(f"{path}.{k}", d[k]) for k in cls.KEYS if k in d}
        v.setdefault("fillet", 2.0 * v["half_thickness"])
        if not x_aft <= v["x_aft"] < v["x_fore"] <= x_fore:
            raise _native.InvalidInput(f"{path}.x_aft / x_fore are {v['x_aft']} / {v['x_fore']} m; expected x_aft < x_fore "
                                       f"on the hull ({x_aft} to {x_fore} m)")
        for key, lo in (("half_thickness", "> 0"), ("fillet", ">= 0"), ("end_length", ">= 0")):
            if key in v and not (v[key] > 0 if lo == "> 0" else v[key] >= 0):
                raise _native.InvalidInput(f"{path}.{key} is {v[key]} m; expected {lo}")
        if v.get("end_length", 0.0) > v["x_fore"] - v["x_aft"]:
            raise _native.InvalidInput(f"{path}.end_length is {v['end_length']} m; expected at most the skeg's length "
                                       f"{v['x_fore'] - v['x_aft']} m")
        return cls(**v)

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.KEYS}

    def at(self, x: np.ndarray, body: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The skeg's bottom (NaN outside it) and how far it is developed (0 .. 1) at x: over
        end_length forward of the sternpost the bottom rises smoothly to the body's bottom `body`
        and the skeg tapers (a fine aft edge ahead of the propeller); over SKEG_FORE_TAPER of its
        length aft of x_fore it tapers into the keel."""
        out = np.full(x.shape, np.nan)
        inside = (x >= self.x_aft) & (x <= self.x_fore)
        r = np.ones(x.shape) if self.end_length <= 0 else np.clip((x - self.x_aft) / self.end_length, 0.0, 1.0)
        rise = r * r * (3.0 - 2.0 * r)  # 0 at the sternpost, 1 end_length forward of it
        out[inside] = (body + rise * (self.bottom - body))[inside]
        q = np.clip((self.x_fore - x) / (SKEG_FORE_TAPER * (self.x_fore - self.x_aft)), 0.0, 1.0)
        return out, rise * q * q * (3.0 - 2.0 * q)


@dataclass
class DomeSpec:
    """A sonar dome under the keel (metres): from x_aft to x_fore, hanging `depth` below the
    hull body's bottom where it is deepest, `half_breadth` wide there; in plan and profile a
    teardrop (a rounded nose, a tail tapering aft), joined to the body by a neck of DOME_NECK of
    its half-breadth."""

    x_aft: float
    x_fore: float
    depth: float
    half_breadth: float

    KEYS = ("x_aft", "x_fore", "depth", "half_breadth")

    @classmethod
    def from_dict(cls, d: Any, path: str, x_aft: float, x_fore: float) -> DomeSpec:
        """The dome of ``d`` on a hull from x_aft to x_fore (m). Raises InvalidInput naming a
        missing or unknown key, or a value out of range."""
        d = keyed_object(path, d, cls.KEYS)
        for key in cls.KEYS:
            if key not in d:
                raise _native.InvalidInput(f"{path}.{key} is missing; expected a length in metres")
        v = {k: number(f"{path}.{k}", d[k]) for k in cls.KEYS}
        if not x_aft <= v["x_aft"] < v["x_fore"] <= x_fore:
            raise _native.InvalidInput(f"{path}.x_aft / x_fore are {v['x_aft']} / {v['x_fore']} m; expected x_aft < x_fore "
                                       f"on the hull ({x_aft} to {x_fore} m)")
        for key in ("depth", "half_breadth"):
            if not v[key] > 0:
                raise _native.InvalidInput(f"{path}.{key} is {v[key]} m; expected > 0")
        return cls(**v)

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.KEYS}

    def at(self, x: np.ndarray, body: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The dome's bottom (NaN outside it) and half-breadth at x under the body's bottom
        `body`: the teardrop's size r rises from its tail (aft) to 1 at DOME_WIDEST of its
        length (a smoothstep) and falls to 0 at its nose as (1 - s^2)^2, both ends meeting the
        keel tangentially (a blunt end would change the sections abruptly between stations)."""
        xi = (x - self.x_aft) / (self.x_fore - self.x_aft)
        inside = (xi > 0) & (xi < 1)
        tail = np.clip(xi / DOME_WIDEST, 0.0, 1.0)
        nose = np.clip((xi - DOME_WIDEST) / (1 - DOME_WIDEST), 0.0, 1.0)
        r = np.where(xi < DOME_WIDEST, tail * tail * (3 - 2 * tail), np.maximum(1 - nose * nose, 0.0) ** 2)
        bottom = np.where(inside & (r > 0), body - self.depth * r, np.nan)
        return bottom, self.half_breadth * r


#: The skin's end conditions at the aft end (fl.fair_skin's start): "free", the natural end (no
#: curvature along the hull at the end station), or "not_a_knot", the two end spans one cubic
#: (the end keeps the curvature its stations' trend gives it: a transom's waterline ends curved).
SKIN_ENDS = ("free", "not_a_knot")


@dataclass
class HullDescription:
    """A hull: principal dimensions, its x range, stations, section options, basic curves."""

    name: str
    principal: PrincipalDimensions
    x_aft: float
    x_fore: float
    curves: dict[str, BasicCurveSpec]
    station_count: int | None = 61
    station_x: list[float] | None = None
    section_n_control: int = 20
    skin_e2: float = 1.0
    skin_e3: float = 0.0
    skin_station_mean: float = STATION_MEAN
    skin_ruled_aft_of: float | None = None  # x (m): the skin straight between its stations aft of here
    skin_knuckles: list = field(default_factory=list)  # x (m) of stations where the skin is only C0
    skin_aft_end: str = "free"  # the skin's end condition at the aft end: "free" or "not_a_knot"
    notes: str = ""
    bulb: BulbSpec | None = None
    design: dict | None = None  # the particulars a designer built it from (kept, not used)
    posts: tuple = ()  # ends ("aft", "fore") that are vertical posts of zero width
    transom_rake: float = 0.0  # the transom's plane from the vertical (deg), its top aft when positive
    given_sections: list = field(default_factory=list)  # [(x, (m, 2) array of (y, z))], increasing x
    given_offsets: list = field(default_factory=list)  # per given section (deck dy, deck dz, waterline dy, keel dz), m
    given_smoothing: float | None = None  # the given shapes' fit's bending penalty (None: the engine's default)
    skeg: SkegSpec | None = None
    dome: DomeSpec | None = None

    @classmethod
    def from_dict(cls, d: Any) -> HullDescription:
        """A hull description from its JSON object (docs/hull_description.schema.json). Raises
        InvalidInput naming the first missing, unknown or out-of-range key."""
        d = keyed_object("description", d, TOP_KEYS)
        principal = PrincipalDimensions.from_dict(d.get("principal"), "principal")
        ends = keyed_object("ends", d.get("ends", {}), ("aft", "fore", "transom_rake", *POST_KEYS.values()))
        posts = tuple(end for end, key in POST_KEYS.items() if _flag(f"ends.{key}", ends.get(key, False)))
        x_aft = number("ends.aft", ends.get("aft", 0.0))
        x_fore = number("ends.fore", ends.get("fore", principal.lpp))
        lpp = principal.lpp
        if not x_aft < x_fore:
            raise _native.InvalidInput(f"ends.fore is {x_fore}; expected more than ends.aft = {x_aft}")
        if x_aft < -0.25 * lpp or x_fore > 1.25 * lpp:
            raise _native.InvalidInput(f"ends are {x_aft} .. {x_fore} m; expected the hull within -0.25 Lpp .. 1.25 Lpp of the AP")
        desc = cls(name=text_value("name", d.get("name", "hull")), principal=principal, x_aft=x_aft, x_fore=x_fore,
                   curves={}, notes=text_value("notes", d.get("notes", "")), posts=posts)
        desc.transom_rake = number("ends.transom_rake", ends.get("transom_rake", 0.0))
        if not TRANSOM_RAKE_RANGE[0] <= desc.transom_rake <= TRANSOM_RAKE_RANGE[1]:
            raise _native.InvalidInput(f"ends.transom_rake is {desc.transom_rake:g} deg; expected {TRANSOM_RAKE_RANGE[0]:g} to "
                                       f"{TRANSOM_RAKE_RANGE[1]:g} deg from the vertical (positive: the top aft)")
        if desc.transom_rake and "aft" in posts:
            raise _native.InvalidInput(f"ends.transom_rake is {desc.transom_rake:g} deg with ends.aft_post; expected 0 "
                                       "(a post of zero width has no transom to rake)")
        desc._parse_stations(d.get("stations", {"count": 61}))
        sec = keyed_object("sections", d.get("sections", {}), ("n_control", "given", "given_smoothing"))
        desc.section_n_control = integer("sections.n_control", sec.get("n_control", 20), *SECTION_CONTROLS)
        desc._parse_given(sec.get("given", []))
        if "given_smoothing" in sec:
            gs = number("sections.given_smoothing", sec["given_smoothing"])
            if not 0 <= gs <= MAX_GIVEN_SMOOTHING:
                raise bad("sections.given_smoothing", gs, f"a bending penalty from 0 to {MAX_GIVEN_SMOOTHING:g}")
            desc.given_smoothing = gs
        bc = keyed_object("basic_curves", d.get("basic_curves"), BASIC_CURVES)
        for name in REQUIRED_CURVES:
            if name not in bc:
                raise _native.InvalidInput(f"basic_curves.{name} is missing; expected the {name} basic curve")
        desc.curves = {name: BasicCurveSpec.from_dict(name, spec, f"basic_curves.{name}") for name, spec in bc.items()}
        for pair in PAIRED_CURVES:
            if sum(name in bc for name in pair) == 1:
                given, missing = pair if pair[0] in bc else pair[::-1]
                raise _native.InvalidInput(f"basic_curves.{missing} is missing; expected it with basic_curves.{given} "
                                           "(the bilge corner's breadth and height are given together)")
        sk = keyed_object("skinning", d.get("skinning", {}), ("e2", "e3", "station_mean", "ruled_aft_of", "knuckles", "aft_end"))
        desc.skin_e2 = number("skinning.e2", sk.get("e2", 1.0))
        desc.skin_e3 = number("skinning.e3", sk.get("e3", 0.0))
        if desc.skin_e2 < 0 or desc.skin_e3 < 0 or desc.skin_e2 + desc.skin_e3 <= 0:
            raise _native.InvalidInput(f"skinning.e2 / e3 are {desc.skin_e2} / {desc.skin_e3}; expected weights >= 0, not both 0")
        desc.skin_station_mean = number("skinning.station_mean", sk.get("station_mean", STATION_MEAN))
        if not 0.0 <= desc.skin_station_mean < 1.0:
            raise _native.InvalidInput(f"skinning.station_mean is {desc.skin_station_mean}; expected a fraction of the "
                                       "station spacing in [0, 1) (0: the sections as designed)")
        desc._parse_skin_continuity(sk)
        if d.get("bulb") is not None:
            desc.bulb = BulbSpec.from_dict(d["bulb"], "bulb")
        if d.get("skeg") is not None:
            desc.skeg = SkegSpec.from_dict(d["skeg"], "skeg", x_aft, x_fore)
        if d.get("dome") is not None:
            desc.dome = DomeSpec.from_dict(d["dome"], "dome", x_aft, x_fore)
        if d.get("design") is not None:
            if not isinstance(d["design"], dict):
                raise bad("design", d["design"], "an object (the particulars the hull was designed from)")
            desc.design = copy.deepcopy(d["design"])
        if desc.bulb is not None and desc.bulb.displacement_volume is None and not (x_aft <= 0.0 and x_fore >= lpp):
            raise _native.InvalidInput(
                f"bulb.displacement_volume is missing; the hull models only x = {x_aft} .. {x_fore} m of the ship, so the "
                "ship's displacement volume (m^3) for C_VPR must be given")
        return desc

    def _parse_skin_continuity(self, sk: dict) -> None:
        """skinning.aft_end (SKIN_ENDS), skinning.ruled_aft_of and skinning.knuckles (x, m, within
        the hull's ends)."""
        inside = f"within the hull's ends {self.x_aft:g} .. {self.x_fore:g} m"
        self.skin_aft_end = sk.get("aft_end", HullDescription.skin_aft_end)
        if self.skin_aft_end not in SKIN_ENDS:
            raise bad("skinning.aft_end", self.skin_aft_end, " or ".join(map(repr, SKIN_ENDS)))
        if sk.get("ruled_aft_of") is not None:
            self.skin_ruled_aft_of = number("skinning.ruled_aft_of", sk["ruled_aft_of"])
            if not self.x_aft <= self.skin_ruled_aft_of <= self.x_fore:
                raise bad("skinning.ruled_aft_of", self.skin_ruled_aft_of, f"an x (m) {inside}")
        knuckles = sk.get("knuckles", [])
        if not isinstance(knuckles, (list, tuple)):
            raise bad("skinning.knuckles", knuckles, "a list of x (m) of stations where the skin is only C0")
        self.skin_knuckles = [number(f"skinning.knuckles[{i}]", v) for i, v in enumerate(knuckles)]
        for i, v in enumerate(self.skin_knuckles):
            if not self.x_aft < v < self.x_fore:
                raise bad(f"skinning.knuckles[{i}]", v, f"an x (m) strictly {inside}")

    def _parse_stations(self, st: Any) -> None:
        st = keyed_object("stations", st, ("count", "x"))
        if "count" in st and "x" in st:
            raise _native.InvalidInput("stations.count and stations.x are both given; expected one of them")
        if "x" in st:
            xs = st["x"]
            if not isinstance(xs, (list, tuple)) or not 4 <= len(xs) <= MAX_STATIONS:
                raise bad("stations.x", xs, f"a list of 4 to {MAX_STATIONS} station positions (m)")
            vals = [number(f"stations.x[{i}]", v) for i, v in enumerate(xs)]
            tol = 1e-9 * self.principal.lpp
            for i, xs_ in enumerate(vals):
                if xs_ < self.x_aft - tol or xs_ > self.x_fore + tol:
                    raise _native.InvalidInput(f"stations.x[{i}] is {xs_}; expected a station on the hull ({self.x_aft} to {self.x_fore} m)")
                if i and not xs_ > vals[i - 1]:
                    raise _native.InvalidInput(f"stations.x[{i}] is {xs_}; expected increasing x (previous {vals[i - 1]})")
            self.station_x, self.station_count = vals, None
        else:
            self.station_count, self.station_x = integer("stations.count", st.get("count", 61), 5, MAX_STATIONS), None

    def _parse_given(self, given: Any) -> None:
        """sections.given: shapes at increasing x inside the ends, points deck edge -> keel."""
        if not isinstance(given, (list, tuple)) or len(given) > MAX_GIVEN_SECTIONS:
            raise bad("sections.given", given, f"a list of at most {MAX_GIVEN_SECTIONS} sections {{x, points}}")
        tol = 1e-9 * self.principal.lpp
        out, offsets = [], []
        for i, g in enumerate(given):
            path = f"sections.given[{i}]"
            g = keyed_object(path, g, ("x", "points", "offsets"))
            x = number(f"{path}.x", g.get("x"))
            if x < self.x_aft - tol or x > self.x_fore + tol:
                raise _native.InvalidInput(f"{path}.x is {x}; expected a station on the hull ({self.x_aft} to {self.x_fore} m)")
            if out and not x > out[-1][0]:
                raise _native.InvalidInput(f"{path}.x is {x}; expected increasing x (previous {out[-1][0]})")
            out.append((x, _given_points(f"{path}.points", g.get("points"))))
            offsets.append(_given_offsets(f"{path}.offsets", g.get("offsets", {})))
        self.given_sections, self.given_offsets = out, offsets

    def to_dict(self) -> dict:
        d = {
            "name": self.name,
            "notes": self.notes,
            "principal": self.principal.to_dict(),
            "ends": {"aft": self.x_aft, "fore": self.x_fore, **{POST_KEYS[end]: True for end in self.posts},
                     **({"transom_rake": self.transom_rake} if self.transom_rake else {})},
            "stations": {"x": list(map(float, self.station_x))} if self.station_x else {"count": self.station_count},
            "sections": {"n_control": self.section_n_control},
            "basic_curves": {k: v.to_dict() for k, v in self.curves.items()},
            "skinning": {"e2": self.skin_e2, "e3": self.skin_e3, "station_mean": self.skin_station_mean,
                         "aft_end": self.skin_aft_end},
        }
        if self.skin_ruled_aft_of is not None:
            d["skinning"]["ruled_aft_of"] = self.skin_ruled_aft_of
        if self.skin_knuckles:
            d["skinning"]["knuckles"] = list(self.skin_knuckles)
        if self.given_smoothing is not None:
            d["sections"]["given_smoothing"] = self.given_smoothing
        if self.given_sections:
            d["sections"]["given"] = [{"x": float(x), "points": p.tolist()} for x, p in self.given_sections]
            for g, off in zip(d["sections"]["given"], self.given_offsets):
                if any(off):
                    g["offsets"] = {"deck": [off[0], off[1]], "waterline": off[2], "keel": off[3]}
        if self.bulb is not None:
            d["bulb"] = self.bulb.to_dict()
        if self.skeg is not None:
            d["skeg"] = self.skeg.to_dict()
        if self.dome is not None:
            d["dome"] = self.dome.to_dict()
        if self.design is not None:
            d["design"] = copy.deepcopy(self.design)
        return d


def _given_points(path: str, points: Any):
    """A given section's points as an (m, 2) float array: finite pairs (y >= 0, z), the first
    (the deck edge) above the last (the keel point). Raises InvalidInput naming the value."""
    lo, hi = GIVEN_POINTS
    if not isinstance(points, (list, tuple)) or not lo <= len(points) <= hi:
        raise bad(path, points if not isinstance(points, (list, tuple)) else f"a list of {len(points)}",
                  f"{lo} to {hi} points [y, z] (m) from the deck edge down to the keel")
    rows = []
    for j, p in enumerate(points):
        if not isinstance(p, (list, tuple)) or len(p) != 2:
            raise bad(f"{path}[{j}]", p, "a point [y, z] (m)")
        y, z = number(f"{path}[{j}][0]", p[0]), number(f"{path}[{j}][1]", p[1])
        if y < 0:
            raise bad(f"{path}[{j}][0]", y, "a half-breadth >= 0 (m)")
        rows.append((y, z))
    a = np.array(rows, dtype=float)
    if not a[0, 1] > a[-1, 1]:
        raise _native.InvalidInput(f"{path} runs from z = {a[0, 1]} to z = {a[-1, 1]} m; expected the deck edge first "
                                   "and the keel point, lower, last")
    return a


def _given_offsets(path: str, offsets: Any) -> tuple[float, float, float, float]:
    """A given section's offsets {"deck": [dy, dz], "waterline": dy, "keel": dz} (m, each default
    0) as (deck dy, deck dz, waterline dy, keel dz). Raises InvalidInput naming the value."""
    offsets = keyed_object(path, offsets, ("deck", "waterline", "keel"))
    deck = offsets.get("deck", [0.0, 0.0])
    if not isinstance(deck, (list, tuple)) or len(deck) != 2:
        raise bad(f"{path}.deck", deck, "a pair [dy, dz] (m): the deck edge's offset from the basic curves")
    dy, dz = (number(f"{path}.deck[{j}]", v) for j, v in enumerate(deck))
    return (dy, dz, number(f"{path}.waterline", offsets.get("waterline", 0.0)),
            number(f"{path}.keel", offsets.get("keel", 0.0)))


def load_description(path_or_text_or_dict: Any) -> dict:
    """A description as a dict, from a dict (copied), JSON text or a path to a JSON file.
    Raises InvalidInput for an unreadable file, text that is not JSON, or anything else."""
    src = path_or_text_or_dict
    if isinstance(src, dict):
        return copy.deepcopy(src)
    if isinstance(src, (str, os.PathLike)):
        text = str(src)
        if isinstance(src, os.PathLike) or not text.lstrip().startswith(("{", "[")):
            try:
                with open(src, encoding="utf-8") as fh:
                    text = fh.read()
            except OSError as e:
                raise _native.InvalidInput(f"description file {text!r} cannot be read: {e.strerror}") from None
        try:
            data = json.loads(text)
        except json.JSONDecodeError as e:
            raise _native.InvalidInput(f"description is not valid JSON: {e}") from None
        if not isinstance(data, dict):
            raise bad("description", type(data).__name__, "a JSON object")
        return data
    raise bad("description", type(src).__name__, "a path, JSON text or a dict")
