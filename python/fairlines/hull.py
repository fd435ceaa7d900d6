"""Bare hull from principal dimensions and basic curves (seed 000 steps 2-3; SPEC §2, §5, §6).

A hull description holds the principal dimensions, the modelled x range (a forebody, an
afterbody or the whole ship), the stations, and the basic curves of SPEC §2 -- each a
form-parameter curve f(x) along the ship:

==============  =====================================================  ===========================
name            meaning of f(x)                                        form-parameter aliases
==============  =====================================================  ===========================
sac             sectional area below the DWL, both sides (m^2)         volume -> Area, lcb -> xC
dwl             design waterline half-breadth (m)                      waterplane_area (both sides)
                                                                       -> Area = Awp / 2, lcf -> xC,
                                                                       entrance_angle (half angle,
                                                                       deg) -> alphaE = -angle
deck            deck-line half-breadth at z = D (m)
profile         centre profile: keel / forefoot height (m); the stem
                is vertical at the end of the modelled range
fos             flat of side: height of the flat side's lower end (m);
                end it at the deck (yE = D, alphaE = 0, CAE = 0): past
                x_end its straight continuation runs above the deck
fob             flat of bottom: half-breadth of the flat bottom (m);
                end it on the centre line (yE = 0, alphaE = 0, CAE = 0)
deck_angle      section tangent angle at the deck (deg from the
                downward vertical toward +y; 0 vertical, < 0 flare);
                0 wherever there is a flat of side
bottom_angle    section tangent angle at the keel (same convention;
                -90 horizontal); -90 wherever there is a flat bottom
section_zc      (optional) height of each section's area centroid (m)
==============  =====================================================  ===========================

Every basic curve is ``{"flat_to": x, "value": v}`` (constant v from the start of the range to
x -- the parallel middle body part), then a fairest B-spline from there to ``x_end`` (default:
the end of the range) meeting the form parameters given: ``yB``/``yE`` (end values), ``alphaB``/
``alphaE`` (end tangent angles, degrees) or ``slopeB``/``slopeE`` (dy/dx), ``CAB``/``CAE`` (end
curvatures, 1/m; a nonzero one needs the slope at that end), ``Area`` (integral of f over the
whole range, the flat part included) and ``xC`` (its centroid x), ``points`` ([[x, f], ...] to
pass through), ``n_control`` (default 8). After a flat part the curve starts at v with zero
slope and zero curvature (G2), so nothing on the hull jumps in curvature where a flat ends.
Constant curves need only ``value``.

Each section is then a form-parameter curve in the (y, z) plane (fairlines/sections.hpp), all
on one knot vector (fl.section_knot_vector): a straight top zone from the deck point (the flat
of side down to the fos curve, or a few centimetres along the deck tangent), a curved part --
the fairest curve through the DWL point with half the SAC value as its area below the DWL,
leaving the zones with G2 continuity where they are flats -- and a straight bottom zone into
the keel point (the flat of bottom, or a short leg along the bottom tangent). Where the design
waterline leaves the flat of side (the DWL's flat_to, where the fos curve crosses the DWL) the
sections aft of it blend their departure from the flat toward the DWL's own rate
(Hull.flat_departure), so the DWL is met exactly without a jump. The sections' control points
are the skin's rows as they are (no refit): fair_skin interpolates each row along the hull,
holding it exactly where it is constant over three or more stations (the parallel middle body,
the flats), so flats and the parallel body are exact on the surface. ``skinning`` holds the
longitudinal options: ``start`` / ``end`` ("free" / "parallel"), the fairness weights ``e2`` /
``e3`` (default 1 / 0, seed 000's E2) and ``junctions`` (default false): move the station nearest
each basic-curve junction (end of a flat part or of a curve) onto it, so the flats end exactly
where the basic curves say. ``sections.n_control`` (default 16) is the number of control points
of each section's curved part (each section has six more).

Optional ``"bulb"`` section (issue 5; SPEC §7): a bulbous bow added to the bare hull by
:meth:`Hull.bulbous_bow` / :meth:`Hull.composed_hull`::

    "bulb": {
      "kracht": {"c_lpr": 0.025, "c_bb": 0.18, "c_zb": 0.45, "c_abt": 0.10, "c_abl": 0.10, "c_vpr": 0.0022},
      "shape": {"aft_length": 12.0, "nose_height_shift": 0.0},
      "displacement_volume": 56490.0
    }

``kracht``: the six Kracht (1978) coefficients (each > 0; any left out takes the default of
fairlines.BulbousBow): c_lpr = L_PR / Lpp (protrusion beyond FP), c_bb = B_B / B (bulb
breadth at FP), c_zb = Z_B / T (height of the nose), c_abt = A_BT / A_MS (bulb section area at
FP, both sides), c_abl = A_BL / A_MS (lateral area forward of FP), c_vpr = V_PR / displacement
volume (bulb volume forward of FP, both sides). ``shape``: ``aft_length`` (m, >= 0; how far
the bulb runs on behind FP into the hull; 0: the default 2 (L_PR + B_B)), ``nose_height_shift``
(m), ``sections``, ``section_points``, ``control_u``, ``control_v`` (integers; the bulb's
skinning resolution). The ship particulars come from the hull itself: Lpp, B, T (draught at FP)
from ``principal``, FP at x = Lpp, A_MS from the hull's hydrostatics (section area at Lpp / 2,
both sides). The displacement volume is the hull's own hydrostatic volume when the range
covers the whole ship (0 .. Lpp); a forebody or afterbody must give the ship's displacement
volume (m^3) as ``displacement_volume`` (the hull alone is only part of it).
"""

from __future__ import annotations

import copy
import json
import math
import os
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from . import _native
from .inflections import classify_cut
from .skinning import fair_skin

__all__ = [
    "BASIC_CURVES",
    "BasicCurve",
    "BasicCurveSpec",
    "Hull",
    "HullDescription",
    "PrincipalDimensions",
    "BulbSpec",
    "AuxiliarySection",
    "fairness_report",
]

BASIC_CURVES = ("sac", "dwl", "deck", "profile", "fos", "fob", "deck_angle", "bottom_angle")
OPTIONAL_CURVES = ("section_zc",)
_FORM_KEYS = ("yB", "yE", "alphaB", "alphaE", "slopeB", "slopeE", "CAB", "CAE", "Area", "xC")
_ALIASES = {
    "sac": {"volume": ("Area", 1.0), "lcb": ("xC", 1.0)},
    "dwl": {"waterplane_area": ("Area", 0.5), "lcf": ("xC", 1.0), "entrance_angle": ("alphaE", -1.0)},
}


def _bad(path: str, value: Any, expected: str) -> ValueError:
    return _native.InvalidInput(f"{path} is {value!r}; expected {expected}")


def _number(path: str, value: Any, *, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise _bad(path, value, "a number")
    v = float(value)
    if not math.isfinite(v):
        raise _bad(path, v, "a finite number")
    if positive and not v > 0:
        raise _bad(path, v, "a number > 0")
    return v


def _flag(path: str, value: Any) -> bool:
    if not isinstance(value, bool):
        raise _bad(path, value, "true or false")
    return value


def _integer(path: str, value: Any, lo: int | None) -> int:
    """value as an int, or InvalidInput naming `path`; lo None leaves the range to the engine."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or (lo is not None and int(value) < lo):
        raise _bad(path, value, "an integer" if lo is None else f"an integer >= {lo}")
    return int(value)


@dataclass
class PrincipalDimensions:
    """Lpp, B (moulded breadth), T (design draught), D (depth to the deck), in metres."""

    lpp: float
    breadth: float
    draft: float
    depth: float

    @classmethod
    def from_dict(cls, d: Any, path: str = "principal") -> PrincipalDimensions:
        if not isinstance(d, dict):
            raise _bad(path, d, "an object with Lpp, B, T, D")
        vals = {}
        for key in ("Lpp", "B", "T", "D"):
            if key not in d:
                raise _native.InvalidInput(f"{path}.{key} is missing; expected a length in metres")
            vals[key] = _number(f"{path}.{key}", d[key], positive=True)
        if not vals["T"] < vals["D"]:
            raise _native.InvalidInput(f"{path}.T is {vals['T']}; expected a draught below the depth D = {vals['D']} m")
        return cls(vals["Lpp"], vals["B"], vals["T"], vals["D"])

    def to_dict(self) -> dict:
        return {"Lpp": self.lpp, "B": self.breadth, "T": self.draft, "D": self.depth}


@dataclass
class BasicCurveSpec:
    """One basic curve as described (see the module docstring for the fields)."""

    flat_to: float | None = None
    value: float | None = None
    x_end: float | None = None
    params: dict[str, float] = field(default_factory=dict)
    points: list[tuple[float, float]] = field(default_factory=list)
    n_control: int = 8
    aliases: dict[str, float] = field(default_factory=dict)

    @classmethod
    def from_dict(cls, name: str, d: Any, path: str) -> BasicCurveSpec:
        if not isinstance(d, dict):
            raise _bad(path, d, "an object of form parameters")
        known = {"flat_to", "value", "x_end", "points", "n_control", *_FORM_KEYS, *_ALIASES.get(name, {})}
        for key in d:
            if key not in known:
                raise _native.InvalidInput(f"{path}.{key} is not a form parameter of this curve; expected one of {sorted(known)}")
        spec = cls()
        for key in ("flat_to", "value", "x_end"):
            if d.get(key) is not None:
                setattr(spec, key, _number(f"{path}.{key}", d[key]))
        if "n_control" in d:
            spec.n_control = _integer(f"{path}.n_control", d["n_control"], 4)
        for key in _FORM_KEYS:
            if d.get(key) is not None:
                spec.params[key] = _number(f"{path}.{key}", d[key])
        for key in _ALIASES.get(name, {}):
            if d.get(key) is not None:
                spec.aliases[key] = _number(f"{path}.{key}", d[key])
        pts = d.get("points", [])
        if not isinstance(pts, (list, tuple)):
            raise _bad(f"{path}.points", pts, "a list of [x, value] pairs")
        for i, p in enumerate(pts):
            if not isinstance(p, (list, tuple)) or len(p) != 2:
                raise _bad(f"{path}.points[{i}]", p, "an [x, value] pair")
            spec.points.append((_number(f"{path}.points[{i}][0]", p[0]), _number(f"{path}.points[{i}][1]", p[1])))
        if spec.flat_to is not None and spec.value is None:
            raise _native.InvalidInput(f"{path}.value is missing; expected the constant value up to flat_to = {spec.flat_to}")
        return spec

    def to_dict(self) -> dict:
        d: dict[str, Any] = {}
        for key in ("flat_to", "value", "x_end"):
            if getattr(self, key) is not None:
                d[key] = getattr(self, key)
        d.update(self.params)
        d.update(self.aliases)
        if self.points:
            d["points"] = [list(p) for p in self.points]
        d["n_control"] = self.n_control
        return d


@dataclass
class AuxiliarySection:
    """An extra section given by offsets: station x and [[y, z], ...] from deck to keel."""

    x: float
    offsets: list[tuple[float, float]]


_KRACHT = ("c_lpr", "c_bb", "c_zb", "c_abt", "c_abl", "c_vpr")
_BULB_SHAPE_NUMBERS = ("aft_length", "nose_height_shift")
_BULB_SHAPE_INTEGERS = {"sections": 8, "section_points": 8, "control_u": 4, "control_v": 4}


@dataclass
class BulbSpec:
    """The optional ``"bulb"`` section: Kracht coefficients, shape controls and (for a hull
    that models only part of the ship) the ship's displacement volume."""

    kracht: dict[str, float] = field(default_factory=dict)
    shape: dict[str, float] = field(default_factory=dict)
    displacement_volume: float | None = None

    @classmethod
    def from_dict(cls, d: Any, path: str = "bulb") -> BulbSpec:
        if not isinstance(d, dict):
            raise _bad(path, d, "an object with kracht, shape and displacement_volume")
        for key in d:
            if key not in ("kracht", "shape", "displacement_volume"):
                raise _native.InvalidInput(f"{path}.{key} is not a bulb field; expected kracht, shape, displacement_volume")
        spec = cls()
        kr = d.get("kracht", {})
        if not isinstance(kr, dict):
            raise _bad(f"{path}.kracht", kr, "an object of Kracht coefficients " + ", ".join(_KRACHT))
        for key, val in kr.items():
            if key not in _KRACHT:
                raise _native.InvalidInput(f"{path}.kracht.{key} is not a Kracht coefficient; expected one of {list(_KRACHT)}")
            spec.kracht[key] = _number(f"{path}.kracht.{key}", val, positive=True)
        sh = d.get("shape", {})
        if not isinstance(sh, dict):
            raise _bad(f"{path}.shape", sh, "an object of bulb shape controls")
        for key, val in sh.items():
            if key in _BULB_SHAPE_NUMBERS:
                v = _number(f"{path}.shape.{key}", val)
                if key == "aft_length" and v < 0:
                    raise _bad(f"{path}.shape.{key}", v, "a length >= 0 m (0: the default 2 (L_PR + B_B))")
                spec.shape[key] = v
            elif key in _BULB_SHAPE_INTEGERS:
                spec.shape[key] = _integer(f"{path}.shape.{key}", val, _BULB_SHAPE_INTEGERS[key])
            else:
                raise _native.InvalidInput(f"{path}.shape.{key} is not a bulb shape control; expected one of "
                                           f"{list(_BULB_SHAPE_NUMBERS) + list(_BULB_SHAPE_INTEGERS)}")
        if d.get("displacement_volume") is not None:
            spec.displacement_volume = _number(f"{path}.displacement_volume", d["displacement_volume"], positive=True)
        return spec

    def to_dict(self) -> dict:
        d: dict[str, Any] = {"kracht": dict(self.kracht), "shape": dict(self.shape)}
        if self.displacement_volume is not None:
            d["displacement_volume"] = self.displacement_volume
        return d


@dataclass
class HullDescription:
    """A bare hull: principal dimensions, modelled x range, stations and basic curves."""

    name: str
    principal: PrincipalDimensions
    x_start: float
    x_end: float
    stations: list[float]
    curves: dict[str, BasicCurveSpec]
    auxiliary_sections: list[AuxiliarySection] = field(default_factory=list)
    section_n_control: int = 16
    skin_start: str = "free"
    skin_end: str = "free"
    skin_e2: float = 1.0
    skin_e3: float = 0.0
    skin_junctions: bool = False
    notes: str = ""
    bulb: BulbSpec | None = None

    @classmethod
    def from_dict(cls, d: Any) -> HullDescription:
        if not isinstance(d, dict):
            raise _bad("description", type(d).__name__, "a JSON object")
        principal = PrincipalDimensions.from_dict(d.get("principal"), "principal")
        rng = d.get("range", {"x_start": 0.0, "x_end": principal.lpp})
        if not isinstance(rng, dict):
            raise _bad("range", rng, "an object with x_start and x_end")
        x0 = _number("range.x_start", rng.get("x_start", 0.0))
        x1 = _number("range.x_end", rng.get("x_end", principal.lpp))
        if not x0 < x1:
            raise _native.InvalidInput(f"range.x_end is {x1}; expected more than range.x_start = {x0}")
        if "stations" not in d:
            raise _native.InvalidInput("stations is missing; expected {\"count\": n} or {\"x\": [...]}")
        st = d["stations"]
        if isinstance(st, dict) and "count" in st:
            n = _integer("stations.count", st["count"], 4)
            stations = list(np.linspace(x0, x1, n))
        elif isinstance(st, dict) and "x" in st:
            if not isinstance(st["x"], (list, tuple)) or len(st["x"]) < 4:
                raise _bad("stations.x", st["x"], "a list of at least 4 station positions (m)")
            stations = [_number(f"stations.x[{i}]", v) for i, v in enumerate(st["x"])]
        else:
            raise _bad("stations", st, "{\"count\": n} or {\"x\": [...]}")
        tol = 1e-9 * principal.lpp
        for i, xs in enumerate(stations):
            if xs < x0 - tol or xs > x1 + tol:
                raise _native.InvalidInput(f"stations[{i}] is {xs}; expected a station inside the hull (x from {x0} to {x1} m)")
            if i and not xs > stations[i - 1]:
                raise _native.InvalidInput(f"stations[{i}] is {xs}; expected stations in increasing x (previous {stations[i - 1]})")
        bc = d.get("basic_curves")
        if not isinstance(bc, dict):
            raise _bad("basic_curves", bc, "an object holding " + ", ".join(BASIC_CURVES))
        curves = {}
        for name in BASIC_CURVES:
            if name not in bc:
                raise _native.InvalidInput(f"basic_curves.{name} is missing; expected the {name} basic curve")
        for name in bc:
            if name not in BASIC_CURVES + OPTIONAL_CURVES:
                raise _native.InvalidInput(f"basic_curves.{name} is not a basic curve; expected one of {list(BASIC_CURVES + OPTIONAL_CURVES)}")
            curves[name] = BasicCurveSpec.from_dict(name, bc[name], f"basic_curves.{name}")
        aux = []
        for i, a in enumerate(d.get("auxiliary_sections", [])):
            path = f"auxiliary_sections[{i}]"
            if not isinstance(a, dict) or "x" not in a or "offsets" not in a:
                raise _bad(path, a, "an object with x and offsets [[y, z], ...]")
            xa = _number(f"{path}.x", a["x"])
            if not x0 < xa < x1:
                raise _native.InvalidInput(f"{path}.x is {xa}; expected a station inside the hull ({x0} < x < {x1} m)")
            offs = a["offsets"]
            if not isinstance(offs, (list, tuple)) or len(offs) < 4:
                raise _bad(f"{path}.offsets", offs, "at least 4 [y, z] points from deck to keel")
            pts = [(_number(f"{path}.offsets[{k}][0]", p[0]), _number(f"{path}.offsets[{k}][1]", p[1])) for k, p in enumerate(offs)]
            aux.append(AuxiliarySection(xa, pts))
        sk = d.get("skinning", {})
        desc = cls(
            name=str(d.get("name", "hull")),
            principal=principal,
            x_start=x0,
            x_end=x1,
            stations=stations,
            curves=curves,
            auxiliary_sections=aux,
            section_n_control=_integer("sections.n_control", d.get("sections", {}).get("n_control", 16), 8),
            skin_start=str(sk.get("start", "free")),
            skin_end=str(sk.get("end", "free")),
            skin_e2=_number("skinning.e2", sk.get("e2", 1.0)),
            skin_e3=_number("skinning.e3", sk.get("e3", 0.0)),
            skin_junctions=_flag("skinning.junctions", sk.get("junctions", False)),
            notes=str(d.get("notes", "")),
            bulb=BulbSpec.from_dict(d["bulb"], "bulb") if d.get("bulb") is not None else None,
        )
        if desc.bulb is not None and desc.bulb.displacement_volume is None and not (x0 <= 0.0 and x1 >= principal.lpp):
            raise _native.InvalidInput(
                f"bulb.displacement_volume is missing; the hull models only x = {x0} .. {x1} m of the ship, so the "
                "ship's displacement volume (m^3) for C_VPR must be given")
        return desc

    def to_dict(self) -> dict:
        return {
            "name": self.name,
            "notes": self.notes,
            "principal": self.principal.to_dict(),
            "range": {"x_start": self.x_start, "x_end": self.x_end},
            "stations": {"x": list(map(float, self.stations))},
            "basic_curves": {k: v.to_dict() for k, v in self.curves.items()},
            "auxiliary_sections": [{"x": a.x, "offsets": [list(p) for p in a.offsets]} for a in self.auxiliary_sections],
            "sections": {"n_control": self.section_n_control},
            "skinning": {"start": self.skin_start, "end": self.skin_end, "e2": self.skin_e2, "e3": self.skin_e3,
                         "junctions": self.skin_junctions},
            **({"bulb": self.bulb.to_dict()} if self.bulb is not None else {}),
        }


@dataclass
class BasicCurve:
    """A solved basic curve: constant ``value`` on [x_start, flat_to], then ``curve`` (a 2-D
    NurbsCurve (x, f) whose x is linear in its parameter) up to ``x_end``; absent beyond."""

    name: str
    x_start: float
    flat_to: float
    x_end: float
    value: float | None
    curve: _native.NurbsCurve | None

    def __call__(self, x: Any, outside: float = math.nan) -> np.ndarray:
        """f at x (array); ``outside`` beyond x_end."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = np.full(x.shape, outside, dtype=float)
        tol = 1e-9 * max(1.0, abs(self.x_end))
        flat = x <= self.flat_to + tol
        if self.value is not None:
            out[flat & (x >= self.x_start - tol)] = self.value
        if self.curve is not None:
            on = (x > self.flat_to + tol) & (x <= self.x_end + tol)
            if np.any(on):
                t = np.clip((x[on] - self.flat_to) / (self.x_end - self.flat_to), 0.0, 1.0)
                out[on] = self.curve.evaluate(t)[:, 1]
        return out

    def extended(self, x: Any) -> np.ndarray:
        """f at x (array), continued beyond x_end along the end tangent (a straight line), so a
        flat-of-side / flat-of-bottom curve that ends at the deck / centre line passes on
        beyond it smoothly (fairlines.sections: the zone then shrinks to its floor)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = self(x)
        beyond = x > self.x_end + 1e-9 * max(1.0, abs(self.x_end))
        if np.any(beyond):
            out[beyond] = self(self.x_end)[0] + self.derivative(self.x_end, 1) * (x[beyond] - self.x_end)
        return out

    def derivative(self, x: float, order: int) -> float:
        """d^order f / dx^order just after x (the curve part; 0 on the flat part)."""
        if self.curve is None or x < self.flat_to:
            return 0.0
        t = min(max((x - self.flat_to) / (self.x_end - self.flat_to), 0.0), 1.0)
        # x is linear in t, so d/dx = (1 / (x_end - flat_to)) d/dt.
        return float(self.curve.derivatives(t, order)[order][1] / (self.x_end - self.flat_to) ** order)

    def form_parameters(self) -> dict[str, float]:
        """Area and centroid of f over its whole extent (flat part included), by quadrature."""
        xs = np.linspace(self.x_start, self.x_end, 4001)
        f = self(xs)
        area = np.trapezoid(f, xs) if hasattr(np, "trapezoid") else np.trapz(f, xs)
        mom = np.trapezoid(f * xs, xs) if hasattr(np, "trapezoid") else np.trapz(f * xs, xs)
        return {"Area": float(area), "xC": float(mom / area) if area else math.nan}


def _solve_basic_curve(name: str, spec: BasicCurveSpec, x0: float, x_range_end: float,
                       bounds: tuple[float | None, float | None] = (None, None)) -> BasicCurve:
    path = f"basic_curves.{name}"
    x_end = spec.x_end if spec.x_end is not None else x_range_end
    if not x0 < x_end <= x_range_end + 1e-9 * abs(x_range_end):
        raise _native.InvalidInput(f"{path}.x_end is {x_end}; expected x_start < x_end <= {x_range_end} m")
    params = dict(spec.params)
    for alias, val in spec.aliases.items():
        key, factor = _ALIASES[name][alias]
        if key in params:
            raise _native.InvalidInput(f"{path}.{alias} and {path}.{key} are both given; expected one of them")
        params[key] = factor * val
    for side in ("B", "E"):
        if f"alpha{side}" in params and f"slope{side}" in params:
            raise _native.InvalidInput(f"{path}.alpha{side} and {path}.slope{side} are both given; expected one of them")
        if f"alpha{side}" in params:
            a = params.pop(f"alpha{side}")
            if not -90 < a < 90:
                raise _native.InvalidInput(f"{path}.alpha{side} is {a}; expected an angle between -90 and 90 degrees")
            params[f"slope{side}"] = math.tan(math.radians(a))
    flat_to = spec.flat_to if spec.flat_to is not None else x0
    if spec.flat_to is not None and not x0 <= flat_to <= x_end:
        raise _native.InvalidInput(f"{path}.flat_to is {flat_to}; expected {x0} <= flat_to <= {x_end} m")
    value = spec.value
    curve_needed = flat_to < x_end - 1e-12 * abs(x_end)
    if not curve_needed:
        if value is None:
            raise _native.InvalidInput(f"{path}.value is missing; expected a constant value")
        return BasicCurve(name, x0, x_end, x_end, value, None)
    yB = params.get("yB")
    slopeB = params.get("slopeB")
    curvB = params.get("CAB")
    fixed: list[tuple[int, float]] = []
    if spec.flat_to is not None and spec.flat_to > x0:
        if yB is not None and abs(yB - value) > 1e-9 * (1 + abs(value)):
            raise _native.InvalidInput(f"{path}.yB is {yB}; after a flat part it must equal value = {value}")
        if (slopeB is not None and slopeB != 0) or (curvB is not None and curvB != 0):
            raise _native.InvalidInput(f"{path}.{'alphaB' if slopeB else 'CAB'} is given after a flat part; "
                                       "the curve leaves it with zero slope and zero curvature (G2)")
        # G2 exit: with the uniform Greville abscissae y' = 0 fixes y_1 = y_0 and y'' = 0 y_2 = y_1.
        yB, slopeB, curvB = value, None, None
        fixed = [(1, value), (2, value)]
    elif value is not None and yB is None:
        yB = value
    area, xc = params.get("Area"), params.get("xC")
    flat_len = flat_to - x0
    if area is not None and value is not None and flat_len > 0:
        flat_area = value * flat_len
        curve_area = area - flat_area
        if xc is not None:
            xc = (area * xc - flat_area * (x0 + flat_to) / 2) / curve_area if curve_area != 0 else math.nan
        area = curve_area
    elif xc is not None and value is not None and flat_len > 0:
        raise _native.InvalidInput(f"{path}.xC is given without Area; expected both (the centroid includes the flat part)")
    n = spec.n_control
    gre = _native.greville_abscissae(_native.clamped_uniform_knots(n, 3), 3)
    absc = flat_to + (x_end - flat_to) * np.asarray(gre)
    pts = np.array(spec.points, dtype=float).reshape(-1, 2) if spec.points else None
    if pts is not None:
        for i, (px, _) in enumerate(spec.points):
            if not x0 <= px <= x_end:
                raise _native.InvalidInput(f"{path}.points[{i}] x = {px}; expected a point within {x0} .. {x_end} m")
        pts = pts[pts[:, 0] > flat_to] if flat_to > x0 else pts
        if len(pts) == 0:
            pts = None
    try:
        curve = _native._linear_form_curve(path, absc, 3, yB, params.get("yE"), slopeB, params.get("slopeE"), area, xc, None, pts,
                                           bounds[0], bounds[1], curvB, params.get("CAE"), fixed)
    except _native.InvalidInput as e:
        raise type(e)(str(e)) from None
    return BasicCurve(name, x0, flat_to, x_end, value, curve)


def _fit_on_section_knots(a: AuxiliarySection, n_control: int, path: str) -> _native.NurbsCurve:
    """An auxiliary section's offsets (deck to keel) as a cubic on the designed sections' knot
    vector: ends interpolated, the rest by least squares at chord-length parameters."""
    pts = np.array([[a.x, y, z] for y, z in a.offsets], dtype=float)
    knots = np.asarray(_native.section_knot_vector(n_control))
    n = n_control + 6
    if len(pts) < n:
        raise _native.InvalidInput(f"{path}.offsets has {len(pts)} points; expected at least {n} "
                                   f"(the sections' control points, sections.n_control + 6)")
    chord = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))]
    if not chord[-1] > 0 or np.any(np.diff(chord) <= 0):
        raise _native.InvalidInput(f"{path}.offsets repeat a point; expected distinct points from deck to keel")
    t = chord / chord[-1]
    N = _native.basis_functions(knots, 3, t)[:, 0, :]
    # The zones' interior rows stay at 1/3 and 2/3 of their zone (fl.section_straight_groups),
    # as on the designed sections: M maps the free rows to all rows.
    interior = {}
    for first, last in _native.section_straight_groups(n_control):
        for i in range(first + 1, last):
            interior[i] = (first, last, (i - first) / (last - first))
    free = [i for i in range(n) if i not in interior]
    M = np.zeros((n, len(free)))
    for k, i in enumerate(free):
        M[i, k] = 1.0
    for i, (first, last, s) in interior.items():
        M[i, free.index(first)] += 1.0 - s
        M[i, free.index(last)] += s
    A = N @ M
    # ends interpolated: the first and last free rows are the first and last offsets
    rhs = pts - np.outer(A[:, 0], pts[0]) - np.outer(A[:, -1], pts[-1])
    inner = np.linalg.lstsq(A[1:-1, 1:-1], rhs[1:-1], rcond=None)[0]
    ctrl = M @ np.vstack([pts[0], inner, pts[-1]])
    ctrl[:, 0] = a.x
    return _native.NurbsCurve(3, knots, ctrl)


class Hull:
    """A bare hull built from a HullDescription: basic curves, sections, skinned surface.

    Build steps are cached; :meth:`set` changes one form parameter and invalidates what depends
    on it, so a slider move costs one rebuild of the basic curve, the sections and the skin.
    """

    def __init__(self, description: HullDescription):
        self.description = description
        self._basic: dict[str, BasicCurve] | None = None
        self._sections: list | None = None
        self._skin = None

    # ---- construction -------------------------------------------------------------------
    @classmethod
    def from_json(cls, path_or_dict: Any) -> Hull:
        """From a JSON file path, a JSON string, or an already parsed dict."""
        if isinstance(path_or_dict, dict):
            data = copy.deepcopy(path_or_dict)
        elif isinstance(path_or_dict, (str, os.PathLike)):
            text = str(path_or_dict)
            if isinstance(path_or_dict, os.PathLike) or not text.lstrip().startswith("{"):
                with open(path_or_dict, encoding="utf-8") as fh:
                    text = fh.read()
            try:
                data = json.loads(text)
            except json.JSONDecodeError as e:
                raise _native.InvalidInput(f"description is not valid JSON: {e}") from None
        else:
            raise _bad("path_or_dict", type(path_or_dict).__name__, "a path, a JSON string or a dict")
        hull = cls(HullDescription.from_dict(data))
        hull._check_dimensions()
        return hull

    def to_json(self) -> str:
        return json.dumps(self.description.to_dict(), indent=2)

    def _check_dimensions(self) -> None:
        """Checks that need the principal dimensions together with the SAC."""
        d = self.description
        pr = d.principal
        sac = d.curves["sac"]
        am = sac.value if sac.value is not None else sac.params.get("yB")
        if am is not None and am > pr.breadth * pr.draft:
            raise _native.InfeasibleFormParameters(
                f"basic_curves.sac.value is {am} m^2; a section area cannot exceed B x T = {pr.breadth * pr.draft:.6g} m^2 (Cm <= 1)")
        vol = sac.aliases.get("volume", sac.params.get("Area"))
        length = d.x_end - d.x_start
        if vol is not None:
            if vol <= 0:
                raise _native.InfeasibleFormParameters(f"basic_curves.sac.volume is {vol} m^3; expected a volume > 0")
            cap = pr.breadth * pr.draft * length
            if vol > cap:
                raise _native.InfeasibleFormParameters(
                    f"basic_curves.sac.volume is {vol} m^3; it exceeds B x T x length = {cap:.6g} m^3 (Cb <= 1)")
            if am is not None and vol > am * length:
                raise _native.InfeasibleFormParameters(
                    f"basic_curves.sac.volume is {vol} m^3; it exceeds Am x length = {am * length:.6g} m^3 (Cp <= 1)")
        lcb = sac.aliases.get("lcb", sac.params.get("xC"))
        if lcb is not None and not d.x_start < lcb < d.x_end:
            raise _native.InfeasibleFormParameters(
                f"basic_curves.sac.lcb is {lcb} m; expected a centroid inside the hull ({d.x_start} to {d.x_end} m)")

    # ---- editing ------------------------------------------------------------------------
    def set(self, curve: str, parameter: str, value: float) -> None:
        """Change one form parameter of one basic curve (e.g. ``set("sac", "volume", 27000)``)
        and invalidate the build; the next access rebuilds."""
        if curve not in self.description.curves:
            raise _native.InvalidInput(f"curve is {curve!r}; expected one of {sorted(self.description.curves)}")
        spec = self.description.curves[curve]
        path = f"basic_curves.{curve}.{parameter}"
        v = _number(path, value)
        if parameter in ("flat_to", "value", "x_end"):
            setattr(spec, parameter, v)
        elif parameter in _ALIASES.get(curve, {}):
            spec.aliases[parameter] = v
        elif parameter in _FORM_KEYS:
            spec.params[parameter] = v
        else:
            raise _native.InvalidInput(f"{path} is not a form parameter of this curve")
        self._check_dimensions()
        self._basic = None
        self._sections = None
        self._skin = None

    # ---- build steps --------------------------------------------------------------------
    @property
    def basic_curves(self) -> dict[str, BasicCurve]:
        if self._basic is None:
            d = self.description
            pr = d.principal
            # Physical bounds keep the fairest curves inside the hull's box (SAC <= B T,
            # half-breadths <= B/2, all >= 0); a request that needs more is infeasible.
            bounds = {"sac": (0.0, pr.breadth * pr.draft), "dwl": (0.0, pr.breadth / 2), "deck": (0.0, pr.breadth / 2),
                      "fob": (0.0, pr.breadth / 2), "profile": (0.0, None)}
            self._basic = {name: _solve_basic_curve(name, spec, d.x_start, d.x_end, bounds.get(name, (None, None)))
                           for name, spec in d.curves.items()}
            self._check_basic_curves(self._basic)
        return self._basic

    def _check_basic_curves(self, bc: dict[str, BasicCurve]) -> None:
        d = self.description
        pr = d.principal
        xs = np.linspace(d.x_start, d.x_end, 801)
        sac = bc["sac"](xs)
        tol = 1e-9 * pr.breadth * pr.draft
        if np.any(sac < -tol):
            i = int(np.argmin(sac))
            raise _native.InfeasibleFormParameters(
                f"basic_curves.sac: the requested volume / lcb give a negative sectional area {sac[i]:.4g} m^2 at x = {xs[i]:.4g} m; "
                "expected a SAC >= 0 (move lcb toward the middle of the range or change the volume)")
        if np.any(sac > pr.breadth * pr.draft * (1 + 1e-9)):
            i = int(np.argmax(sac))
            raise _native.InfeasibleFormParameters(
                f"basic_curves.sac: the requested volume / lcb give a sectional area {sac[i]:.6g} m^2 at x = {xs[i]:.4g} m, "
                f"above B x T = {pr.breadth * pr.draft:.6g} m^2")
        for name, limit in (("dwl", pr.breadth / 2), ("deck", pr.breadth / 2)):
            f = bc[name](xs)
            if np.any(f < -1e-9 * limit) or np.any(f > limit * (1 + 1e-9)):
                i = int(np.argmax(np.maximum(f - limit, -f)))
                raise _native.InfeasibleFormParameters(
                    f"basic_curves.{name}: the curve reaches {f[i]:.6g} m at x = {xs[i]:.4g} m; expected 0 <= y <= B/2 = {limit} m")
        prof = bc["profile"](xs)
        if np.any(prof >= pr.draft) or np.any(prof < -1e-9 * pr.draft):
            i = int(np.argmax(np.abs(prof - pr.draft / 2)))
            raise _native.InfeasibleFormParameters(
                f"basic_curves.profile: keel height {prof[i]:.6g} m at x = {xs[i]:.4g} m; expected 0 <= z < T = {pr.draft} m")

    def junctions(self) -> list[float]:
        """x strictly inside the range where a basic curve leaves its flat part or ends: a flat
        of side, bottom or parallel body ends there, and a station on it makes that end exact
        on the surface (fair_skin holds the rows constant up to it)."""
        d = self.description
        tol = 1e-9 * d.principal.lpp
        out = set()
        for bc in self.basic_curves.values():
            for xj in (bc.flat_to, bc.x_end):
                if d.x_start + tol < xj < d.x_end - tol:
                    out.add(round(float(xj), 9))
        return sorted(out)

    def stations(self) -> np.ndarray:
        """Stations of the designed sections: the description's, except that with
        ``skinning.junctions`` the station nearest each basic-curve junction (not an end one)
        moves onto it, so flats and the parallel body end exactly where the basic curves say."""
        d = self.description
        x = np.asarray(d.stations, dtype=float).copy()
        if d.skin_junctions:
            for xj in self.junctions():
                k = int(np.argmin(np.abs(x - xj)))
                if 0 < k < len(x) - 1 and x[k - 1] < xj < x[k + 1]:
                    x[k] = xj
        return x

    def flat_departure(self) -> float:
        """Rate K (1/m^2) at which the design waterline leaves the flat of side, where the
        flat's lower end (the fos curve) crosses the DWL at x_T (the DWL's flat_to): the DWL's
        deficit from B/2 grows as c dx^3 (it leaves its flat part with zero curvature) while
        the fos curve rises with slope s, so a section leaving the flat with zero curvature
        loses K d^3 at depth d below it, K = c / s^3. NaN when the fos curve does not cross the
        DWL at the end of the DWL's flat part (fairlines.sections: SectionSpec.flat_departure)."""
        d = self.description
        bc = self.basic_curves
        dwl, fos = bc["dwl"], bc["fos"]
        x_t = dwl.flat_to
        tol = 1e-6 * d.principal.depth
        if dwl.curve is None or not d.x_start < x_t < d.x_end or fos.curve is None or not fos.flat_to < x_t < fos.x_end:
            return math.nan
        if abs(float(fos(x_t)[0]) - d.principal.draft) > tol:
            return math.nan
        c = -dwl.derivative(x_t, 3) / 6.0
        slope = fos.derivative(x_t, 1)
        return max(c, 0.0) / slope**3 if slope > 0 else math.nan

    def section_parameters(self, x: Any = None) -> dict[str, np.ndarray]:
        """Section parameters read off the basic curves (SectionSpec fields) at the stations,
        or at the given x (m). The flat-of-side and flat-of-bottom curves are continued
        straight beyond their ends (the flat then ends smoothly where the continuation passes
        the deck / the centre line)."""
        d = self.description
        pr = d.principal
        bc = self.basic_curves
        if x is None:
            x = self.stations()
        else:
            x = np.atleast_1d(np.asarray(x, dtype=float))
            tol = 1e-9 * pr.lpp
            for i, xi in enumerate(x):
                if not (d.x_start - tol <= xi <= d.x_end + tol):
                    raise _native.InvalidInput(f"x[{i}] is {xi}; expected a station inside the hull ({d.x_start} to {d.x_end} m)")
        ones = np.ones_like(x)
        zc = bc["section_zc"](x) if "section_zc" in bc else np.full_like(x, math.nan)
        return {
            "x": x,
            "z_deck": pr.depth * ones,
            "y_deck": np.clip(bc["deck"](x), 0.0, None),
            "draft": pr.draft * ones,
            "y_dwl": np.clip(bc["dwl"](x), 0.0, None),
            "z_keel": bc["profile"](x),
            "half_area": np.clip(bc["sac"](x), 0.0, None) / 2,
            "z_centroid": zc,
            "z_fos": self._flat_end(bc["fos"], x, pr.depth),
            "y_fob": self._flat_end(bc["fob"], x, 0.0),
            "alpha_deck": bc["deck_angle"](x),
            "alpha_bottom": bc["bottom_angle"](x),
            "flat_departure": np.full_like(x, self.flat_departure()),
        }

    def _flat_end(self, curve: BasicCurve, x: np.ndarray, end: float) -> np.ndarray:
        """The flat-of-side / flat-of-bottom curve at x. One that ends on the deck / the centre
        line (yE = D / 0) is continued straight beyond its end, so the flat ends smoothly (the
        section's zone shrinks to its floor through a soft maximum); one that ends elsewhere
        stops there (NaN / 0 beyond: the flat ends abruptly, as described)."""
        if curve.curve is None or abs(curve(curve.x_end)[0] - end) <= 1e-6 * self.description.principal.depth:
            return curve.extended(x)
        return curve(x, outside=math.nan if end > 0 else 0.0)

    @property
    def sections(self) -> list:
        """Section curves (3-D NurbsCurves, deck to keel), auxiliary sections included, in x
        order, all on one knot vector (fl.section_knot_vector(sections.n_control))."""
        if self._sections is None:
            d = self.description
            fields_ = self.section_parameters()
            secs = list(_native._design_sections(fields_, d.section_n_control, 3, d.principal.breadth / 2))
            self._sections = self._with_auxiliary(secs, fields_["x"])
        return self._sections

    def _with_auxiliary(self, secs: list, xs: np.ndarray) -> list:
        """Designed sections at xs with the auxiliary sections put in place (replacing a section
        at the same x, else inserted in x order), fitted on the shared knot vector."""
        d = self.description
        xl = list(xs)
        for i, a in enumerate(d.auxiliary_sections):
            c = _fit_on_section_knots(a, d.section_n_control, f"auxiliary_sections[{i}]")
            k = int(np.searchsorted(xl, a.x))
            if k < len(xl) and abs(xl[k] - a.x) < 1e-9 * d.principal.lpp:
                secs[k] = c
            else:
                xl.insert(k, a.x)
                secs.insert(k, c)
        return secs

    def sections_at(self, x: Any) -> list:
        """The designed sections at any x (m): what the basic curves define between the
        stations too (the form-parameter family the skinned surface approximates)."""
        d = self.description
        return list(_native._design_sections(self.section_parameters(x), d.section_n_control, 3, d.principal.breadth / 2))

    def design_family(self, per_interval: int = 4) -> list:
        """Designed sections at the stations and ``per_interval - 1`` more between each pair,
        auxiliary sections in place: the designed shape at that density, for judging the
        skinned surface's inflections (fairness_report)."""
        per_interval = _integer("per_interval", per_interval, 1)
        xs = self.stations()
        dense = np.concatenate([np.linspace(a, b, per_interval + 1)[:-1] for a, b in zip(xs[:-1], xs[1:])] + [xs[-1:]])
        return self._with_auxiliary(self.sections_at(dense), dense)

    def skin(self):
        """The SkinResult of the fair skinning (cached): the sections share one knot vector, so
        their control points are the surface's rows exactly; constant runs (the parallel body,
        flats) are held exactly along the hull (fair_skin hold_runs, straight_groups)."""
        if self._skin is None:
            d = self.description
            self._skin = fair_skin(self.sections, start=d.skin_start, end=d.skin_end, params="station",
                                   e2=d.skin_e2, e3=d.skin_e3, hold_runs=True,
                                   straight_groups=_native.section_straight_groups(d.section_n_control))
        return self._skin

    def bare_hull_surface(self) -> _native.NurbsSurface:
        """The fair-skinned bare hull: the half hull y >= 0, u from deck to keel, v from the
        first station (v = 0) to the last (v = 1), v proportional to x."""
        return self.skin().surface

    def hydrostatics(self, draft: float | None = None, **options) -> _native.Hydrostatics:
        """fl.hydrostatics of the bare hull surface at `draft` (default T), both sides, with
        length = the modelled range, breadth = B and Am at x = Lpp/2 (or the middle of the
        range when Lpp/2 is outside it) unless given."""
        d = self.description
        options.setdefault("length", d.x_end - d.x_start)
        options.setdefault("breadth", d.principal.breadth)
        mid = d.principal.lpp / 2
        options.setdefault("midship_x", mid if d.x_start <= mid <= d.x_end else (d.x_start + d.x_end) / 2)
        return _native.hydrostatics(self.bare_hull_surface(), d.principal.draft if draft is None else draft, **options)

    # ---- bulbous bow (issue 5) ----------------------------------------------------------
    def ship_particulars(self) -> dict[str, float]:
        """The particulars a bulbous bow is sized from (fairlines.BulbousBow): Lpp, B, T at
        FP (the design draught), FP at x = Lpp, A_MS (both sides) from the hull's
        hydrostatics at Lpp / 2, and the ship's displacement volume: the bulb section's
        ``displacement_volume`` or, for a hull modelling the whole ship, its own volume."""
        d = self.description
        pr = d.principal
        cached = getattr(self, "_ship", None)
        if cached is not None and cached[0] is self.skin() and cached[1] == (d.bulb.to_dict() if d.bulb else None):
            return dict(cached[2])
        h = self.hydrostatics()
        vol = d.bulb.displacement_volume if d.bulb is not None else None
        if vol is None:
            if not (d.x_start <= 0.0 and d.x_end >= pr.lpp):
                raise _native.InvalidInput(
                    f"bulb.displacement_volume is missing; the hull models only x = {d.x_start} .. {d.x_end} m")
            vol = float(h.volume)
        ship = dict(lpp=pr.lpp, beam=pr.breadth, draft_fp=pr.draft, midship_area=float(h.midship_area),
                    displacement_volume=float(vol), x_fp=pr.lpp)
        self._ship = (self.skin(), d.bulb.to_dict() if d.bulb else None, ship)  # until the skin is rebuilt
        return dict(ship)

    def bulbous_bow(self, **overrides):
        """The BulbousBow of the ``"bulb"`` section sized from :meth:`ship_particulars`;
        keyword overrides (Kracht coefficients or shape controls) replace the section's."""
        from .compose import BulbousBow

        d = self.description
        if d.bulb is None and not overrides:
            raise _native.InvalidInput("bulb is missing; expected a \"bulb\" section in the hull description "
                                       "(kracht, shape, displacement_volume)")
        spec = d.bulb if d.bulb is not None else BulbSpec()
        kw = {**spec.kracht, **spec.shape, **overrides}
        return BulbousBow(**self.ship_particulars(), **kw)

    def composed_hull(self, blend: bool = True, bulb=None, **compose_options):
        """Bare hull + bulbous bow (+ a C1 blending surface between them when ``blend``)
        composed into one watertight half hull (fairlines.ComposedHull). ``bulb``: a
        BulbousBow to use instead of :meth:`bulbous_bow`. Raises ValueError ("bulb cannot
        meet the hull ...") when the bulb does not cross the hull in one seam."""
        from .compose import compose_with_blend

        b = self.bulbous_bow() if bulb is None else bulb
        return compose_with_blend(self.bare_hull_surface(), b, blend=blend, **compose_options)

    def fairness_report(self, family_density: int = 4, **kwargs) -> dict:
        """fairness_report of the bare hull, every inflection judged against the designed shape
        (fairlines.inflections): real (the shape calls for it, and why) or false. The designed
        shape is the family of sections the basic curves define, taken at ``family_density``
        sections per station interval (design_family): a feature shorter than two station
        spacings is still the design's, and the skinned surface must not add any other."""
        d = self.description
        if "sections" not in kwargs:
            kwargs["sections"] = self.design_family(family_density)
        kwargs.setdefault("dz", d.principal.depth / (d.section_n_control - 1))
        return fairness_report(self.bare_hull_surface(), draft=d.principal.draft, **kwargs)


def fairness_report(surface, draft: float, n_waterlines: int = 8, n_buttocks: int = 6, n_frames: int = 12,
                    samples: int = 401, sections=None, dz: float | None = None) -> dict:
    """Waterlines, buttocks and frames cut from the surface (fl.plane_cut), each with its E2, its
    bending energy int k^2 ds and its number of curvature sign changes with their positions.

    Waterlines at equally spaced heights strictly between the lowest point and the draft plus
    half the freeboard-free margin (up to 1.2 T, clipped to the surface); buttocks at fractions
    of the largest half-breadth; frames at equally spaced x strictly inside the surface.

    With the designed `sections` (3-D curves in x order) every inflection is also classified
    (fairlines.inflections.classify_cut; `dz` the frames' height tolerance, default a tenth of
    the sections' height): "classified" lists {point, real, reason} and "false_inflections" /
    "real_inflections" count them.
    """
    us = np.linspace(*surface.domain_u(), 41) if callable(surface.domain_u) else np.linspace(*surface.domain_u, 41)
    vs = np.linspace(*surface.domain_v(), 41) if callable(surface.domain_v) else np.linspace(*surface.domain_v, 41)
    grid = surface.evaluate_grid(us, vs).reshape(-1, 3)
    lo, hi = grid.min(axis=0), grid.max(axis=0)
    z_top = min(1.2 * draft, hi[2])
    report: dict[str, list] = {"waterline": [], "buttock": [], "frame": []}
    if sections is not None:
        station_x = np.array([float(np.asarray(c.control_points)[0, 0]) for c in sections])
        zs = np.concatenate([np.asarray(c.control_points)[:, 2] for c in sections])
        dz_ = dz if dz is not None else (zs.max() - zs.min()) / 10
    plan = {
        "waterline": (2, np.linspace(lo[2], z_top, n_waterlines + 2)[1:-1]),
        "buttock": (1, np.linspace(0.0, hi[1], n_buttocks + 2)[1:-1]),
        "frame": (0, np.linspace(lo[0], hi[0], n_frames + 2)[1:-1]),
    }
    for kind, (axis, values) in plan.items():
        for val in values:
            cut = _native.plane_cut(surface, axis, float(val), samples)
            if len(cut.points) == 0:
                continue
            report[kind].append({
                "value": float(val),
                "points": int(len(cut.points)),
                "e2": float(cut.e2),
                "bending_energy": float(cut.bending_energy),
                "sign_changes": int(cut.sign_changes),
                "inflections": cut.inflections.tolist(),
                "max_abs_curvature": float(np.max(np.abs(cut.curvature))),
            })
            if sections is not None:
                judged = classify_cut(kind, float(val), cut.inflections, sections, station_x, dz_)
                report[kind][-1]["classified"] = judged
                report[kind][-1]["real_inflections"] = sum(1 for j in judged if j["real"])
                report[kind][-1]["false_inflections"] = sum(1 for j in judged if not j["real"])
    return report
