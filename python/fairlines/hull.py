"""A hull built from its description: basic curves -> sections -> fair-skinned surface.

``fl.Hull.from_json(path | text | dict)`` reads a description (fairlines.description documents
the format); ``fl.design_hull(...)`` (fairlines.designer) writes one from principal particulars.
Every build step is cached and :meth:`Hull.set` invalidates what an edit touches, so a slider
costs one rebuild of the curves, the sections and the skin.

Each section (``fl.design_section``) is built from its deck point, keel point, waterline point
and the area the SAC asks below the waterline: a guide polygon with rounded corners (flat of
side and bottom where the bilge is tight, a V where the section is fine, flare above the
waterline where the deck is wider) sampled on one knot vector shared by every section, so the
sections are the surface's rows and change smoothly along the hull. Each section the skin
interpolates is the mean of the family's a little either side of its station
(``fairlines.station_mean``), so detail shorter than a station spacing is not sampled into
wobbles. ``fl.fair_skin`` interpolates each row along the hull (v proportional to x), holding
runs that stay constant (the parallel middle body) exactly. The surface is the half hull y >= 0, u from the deck (0) to
the keel (1), v from the aft end (0) to the forward end (1).
"""

from __future__ import annotations

import json
import math
import threading
from dataclasses import replace
from typing import Any

import numpy as np

from . import _native
from . import basic_curves as _basic_curves
from . import dry_ends, station_mean, transom_run
from .basic_curves import (CORNER_FULLNESS_BOUNDS, FULLNESS_BOUNDS, BasicCurve, BuildCache, clip, immersed_range, solve_curve, solve_sac,
                           solve_sac_area)
from .description import DOME_NECK, FORM_ALIASES, FORM_KEYS, BasicCurveSpec, HullDescription, load_description
from .hydrostatics_surface import hydrostatics
from .skinning import fair_skin
from .transom_rake import raked

__all__ = ["Hull", "station_positions"]

# Stations cluster toward both ends: spacing 1 - c cos(2 pi s) over the hull (ratio
# (1 + c) / (1 - c) between the middle and the ends), where sections change fastest.
STATION_CLUSTERING = 0.6
# A station this close (fraction of the mean spacing) to a junction of the basic curves moves
# onto it, so flat parts and the waterline's ends are exact at a station.
SNAP_FRACTION = 0.5
# The SAC keeps each station's fullness inside what the section family holds there, shrunk by
# these fractions of the band's width (the family's extremes are a straight V and the tightest
# bilge the knots allow).
BAND_MARGIN = (0.05, 0.002)
# Where no SAC fits the bands so shrunk (a built design's volume cut by 10 % with its DWL kept
# asks near-V sections at the ends), these margins are tried before the request is refused.
RELAXED_BAND_MARGIN = (0.01, 0.0005)
# Stations whose immersed box is within this many end bands (fairlines.sections kEndBand) of
# vanishing get no band: their area fades out there anyway.
BAND_FREE = 2.0
# ... by depth over an immersed transom, this many: a section's area is asked in full from one end
# band of depth, and a transom 0.12 T deep (the designer's default for fine ships) left band-free
# took a SAC whose fullness fell below what the family holds there (0.45 asked, 0.64 the least).
BAND_FREE_DEPTH = 1.0
# ... and where the keel rises out of the water aft (a dry transom, a cruiser stern), this many,
# the stations there holding their band's lower side DRY_END_MARGIN of its width in (not
# BAND_MARGIN's) out to BAND_FREE end bands. Band-free, the SAC asked the last stations before
# the fade for less than the family's V holds (bench_hull's hull 65: fullness 0.512 against 0.515
# at 0.106 T deep), the section held its V instead and the buttocks crossing T there took a hollow
# lobe of 0.1-1.6 deg. The full margin held the sections near the end fuller than the V, and the
# waterlines just under T rounded at their aft ends. bench_fairness_space's hulls 0-99 / 100-199
# / 200-299 / 300-399, every mark 38 / 41 / 37 / 31 -> 41 / 44 / 37 / 34, buttocks over two sign
# changes 27 / 29 / 28 / 35 -> 23 / 25 / 27 / 31, waterlines 48 / 47 / 52 / 46 -> 49 / 46 / 52 / 46.
# Depth 1.0: 39 / 44; margin 0.01 / 0.03: 40 / 42, 37 / 42; 0.05 (BAND_MARGIN's): 36 / 39 at 1.0.
BAND_FREE_DRY_DEPTH = 0.75
DRY_END_MARGIN = 0.02
# The station mean's samples (fairlines.station_mean) stay this fraction of the way to a
# neighbouring station at most (stations added over an overhang or a dome, or halving the spans
# inside a closed end, lie closer).
MEAN_REACH = 0.45
# Gauss points per span of the hydrostatics a bulb is sized from (volume, midship area): 1e-11
# of the 8-point figures at half the time.
SIZING_GAUSS = 4
# Shape curves: default value and bounds.
SHAPE_CURVES = {"top_corner": (0.5, 0.05, 0.95), "deadrise": (0.0, 0.0, 40.0), "character": (0.5, 0.05, 0.95)}
# The bilge corner given directly (optional, together): bounds of its breadth and height fractions.
CORNER_CURVES = {"corner_breadth": ("corner_y", 0.02, 1.0), "corner_height": ("corner_z", 0.0, 0.95)}
# The flat of bottom (optional): bounds of its half-breadth, a fraction of the waterline's (the
# bilge arc beyond it keeps at least a tenth of the breadth). Outside its own x_start .. x_end
# there is none (the designer's starts on the rising keel aft and ends at the forefoot).
FLAT_BOTTOM_BOUNDS = (0.0, 0.9)
# A post end: the deck line's and waterline's half-breadth there at most this fraction of B/2.
POST_TOL = 1e-6
#: A skinning knuckle (skinning.knuckles) within this fraction of Lpp of a station is at it.
STATION_MATCH_TOL = 1e-6
# Points along the waterline's range where the deck line must clear the waterline.
DECK_CHECKS = 81
# Where the waterline runs at the half-breadth limit the deck is asked to clear it less this
# fraction of the limit: held at the limit from both sides (the waterline rounds past it by
# 1e-15 m), the deck's design found no solution on a waterline widened by 10 %.
DECK_CLEARANCE_TOL = 1e-9
# Between its checks the deck line is looked at on DECK_DENSE points, and around the DECK_LOOKS
# nearest contacts there (local minima of its clearance under DECK_NEAR of the limit) on
# DECK_LOCAL more; where it is inside the waterline a check is added and the deck designed again,
# at most DECK_REFINES times.
DECK_DENSE, DECK_NEAR, DECK_LOOKS, DECK_LOCAL, DECK_REFINES = 641, 1e-3, 8, 33, 8
# The sheer (deck-at-side height) stays above T by this fraction of T, and below this multiple of D.
SHEER_CLEARANCE = 0.01
SHEER_LIMIT = 2.0
# A skeg with a square aft edge (no end_length): the station before it lies this fraction of
# Lpp aft of it (the sternpost is the surface's turn between the two).
STERNPOST_GAP = 0.002
# ... with a raked aft end: stations this many to its rake (18 let the skin follow the skeg's
# quickly changing sections, but showed the body's own topside ripple of 2-3 mm along x between
# them: docs/sections.md); a sonar dome: stations this many along it (closer toward its nose).
SKEG_END_STATIONS = 6
DOME_STATIONS = 16
# Stations off the hull named in the error (the rest are counted).
OFF_HULL_SHOWN = 5
# Stations between a waterline's end and the point where the hull closes beyond it at the deck
# (a stem head; a cruiser stern; fairlines.dry_ends), closer toward that point, where the skin's
# rows meet: with none the skin's one span there made lobes of its own. Measured on the first 100
# hulls of bench_hull's sample (waterlines above T clean as a lines plan): 1 or 2 at even
# spacing 120 / 121 of 300, 2 closer toward the head 127 (closer still 127; 3 at even spacing no
# better on 40 of them); at 1 the example's bare-hull mesh scored a mean scaled Jacobian 0.04 %
# under gmsh's.
OVERHANG_STATIONS = 2
# Station spans inside such an end halved: there the forefoot (the counter) rises to T and the
# waterlines above T turn from the body's convex line into the overhang's hollow tip, and at the
# clustered spacing the skin rang (measured: docs/sections.md) ...
CLOSED_END_HALVED_SPANS = 2
# ... but a span shorter than this share of the clustered spacing there (a dome's, a skeg end's)
# is dense already and kept.
HALVED_LEAST_SHARE = 0.5
# Least slope (dz/dx) of the profile used for the arrival angle of above-water sections.
MIN_STEM_SLOPE = 0.05
# Beyond a dry transom's waterline end a section's lower angle leans less by this (deg) times
# (distance from the end / T)^2: ahead of the end the side leans less as the knob leaves the V,
# from zero with zero slope, and the dry sections mirror that to second order. Without it the
# waterlines above T over the transom turned hollow, then convex (container 13 / 15 / 17 m: 3 / 5 /
# 6 sign changes; 1 / 3 / 4 with it and kVeeExcessFade). At a stem it raised the fine ferry's
# waterline sign changes (26 -> 28), so it applies at a dry transom only. Now 0: since the transom's
# run (fairlines.transom_run) fairs the topside lines there, the bend's only mark left is on the
# buttocks near the keel, whose height over it goes as y / tan(lower angle): 10 deg (h / T)^2
# bent the 0.1 B/2 buttocks over the transom (bench_fairness_space, hulls 0-99 with
# designer.MAX_RUN_ANGLE: a buttock over two 48 -> 46 hulls, every mark 31 -> 34; held-out 100-199
# 42 -> 41, 37 -> 38; upper waterlines clean 275 -> 274 of 300; -5 reads as 0).
DRY_TRANSOM_LEAN_BEND = 0.0
# The dry sections' arrival angle is the immersed chord's limit, the ratio of the waterline's and
# the keel's slopes where the waterline ends; it is capped only short of the sections' own limit
# (kMaxLowerAngle, 89 deg). Capped at 75 deg, a full ship whose keel crosses T flatter than that
# met its immersed sections with a step (19-20 cm in the buttocks of a Cb 0.80 ship; 17 of the
# 73 dry transoms of bench_hull's first 100 hulls were over 75 deg).
MAX_LOWER_ANGLE = 88.0
# Recent hulls whose solved shape curves and fullness bands are kept (see basic_curves.BuildCache).
BUILD_CACHE_SIZE = 8
_shape_cache = BuildCache(BUILD_CACHE_SIZE)
_band_cache = BuildCache(BUILD_CACHE_SIZE)


def _clear_build_caches() -> None:
    """Forget every cached build step (tests compare cold and warm builds)."""
    _shape_cache.clear()
    _band_cache.clear()
    _basic_curves.clear_curve_cache()


def _with_stations(stations: np.ndarray, extra: np.ndarray) -> np.ndarray:
    """The stations with those of `extra` that do not lie within a quarter of their own spacing
    of one already there."""
    gap = 0.25 * float(np.min(np.diff(extra))) if len(extra) > 1 else 0.0
    return np.union1d(stations, [x for x in extra if np.min(np.abs(stations - x)) > gap])


def _halved_inside(stations: np.ndarray, x_end: float, x_tip: float, spans: int, tol: float, least: float) -> np.ndarray:
    """The stations with the last `spans` spans up to x_end (m; up to the first station beyond
    it where x_end is none), on the side away from x_tip, halved; spans shorter than `least` (m)
    kept; a station within tol (m) of x_end is x_end's."""
    sign = 1.0 if x_tip > x_end else -1.0  # the aft end mirrored: inside is below x_end
    s = np.sort(sign * np.asarray(stations, dtype=float))
    last = int(np.searchsorted(s, sign * x_end - tol))  # the first station at or beyond x_end
    if last >= len(s):
        return stations
    run = s[max(last - spans, 0):last + 1]
    mids = [0.5 * (a + b) for a, b in zip(run[:-1], run[1:]) if b - a >= least]
    return np.union1d(stations, sign * np.asarray(mids, dtype=float))


def _clustered(s: np.ndarray, x_aft: float, x_fore: float) -> np.ndarray:
    """x (m) at station parameters s in [0, 1]: spacing 1 - c cos(2 pi s), c = STATION_CLUSTERING."""
    return x_aft + (x_fore - x_aft) * (s - STATION_CLUSTERING * np.sin(2 * np.pi * s) / (2 * np.pi))


def station_spacing(x: np.ndarray, x_aft: float, x_fore: float, count: int) -> np.ndarray:
    """The spacing (m) of station_positions' clustered stations about each x (before junctions
    move them): (x_fore - x_aft) / (count - 1) (1 - c cos(2 pi s)), s the station parameter at x."""
    s = np.linspace(0.0, 1.0, 4 * count)
    sx = np.interp(x, _clustered(s, x_aft, x_fore), s)
    return (x_fore - x_aft) / (count - 1) * (1 - STATION_CLUSTERING * np.cos(2 * np.pi * sx))


def station_positions(x_aft: float, x_fore: float, count: int, junctions: list[float] = ()) -> np.ndarray:
    """`count` stations on [x_aft, x_fore] clustered toward both ends, with the station nearest
    each junction (inside the range) moved onto it."""
    x = _clustered(np.linspace(0.0, 1.0, count), x_aft, x_fore)
    mean = (x_fore - x_aft) / (count - 1)
    for xj in sorted(junctions):
        if not x_aft + 1e-9 * mean < xj < x_fore - 1e-9 * mean:
            continue
        k = int(np.argmin(np.abs(x - xj)))
        if 0 < k < count - 1 and abs(x[k] - xj) < SNAP_FRACTION * mean and x[k - 1] < xj < x[k + 1]:
            x[k] = xj
    return x


class Hull:
    """A hull built from a HullDescription (see the module docstring)."""

    def __init__(self, description: HullDescription):
        self.description = description
        self._invalidate()

    def _invalidate(self) -> None:
        self._curves: dict[str, BasicCurve] | None = None
        self._designs: list | None = None
        self._specs: list | None = None  # the stations' SectionSpecs the designs were made from
        self._sections: list | None = None
        self._skin = None
        self._raked = None  # (skin, its surface with the transom raked)
        self._ship = None
        self._stations: np.ndarray | None = None
        self._dry_ends: dict = {}  # x_e -> (end waterlines, end contour) of the dry sections beyond it
        self._closed_ends: list | None = None  # _closed_dry_ends, asked by every section_specs
        self._transom_run: list | None = None  # [fairlines.transom_run.TransomRun], or [] without a transom run
        self._hydro: dict = {}  # (draft, options) -> Hydrostatics of the current surface
        self._bow = None  # (key, BulbousBow) of the description's bulb, no overrides
        self._placement = None  # (surface, bow, BlendPlacement) of the default blend
        self._composed = None  # ((surface, bow, placement), ComposedHull) of the default composition
        self._closed = None  # (surface, ComposedHull): the bare hull closed, default meshing

    # ---- construction ---------------------------------------------------------------
    @classmethod
    def from_json(cls, source: Any) -> Hull:
        """From a JSON file path, JSON text or a parsed dict. Raises InvalidInput naming the field."""
        return cls(HullDescription.from_dict(load_description(source)))

    def to_dict(self) -> dict:
        return self.description.to_dict()

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2)

    # ---- editing --------------------------------------------------------------------
    def set(self, curve: str, parameter: str, value: float) -> None:
        """Change one form parameter of one basic curve (``set("sac", "volume", 27000)``); the
        next access rebuilds. Raises InvalidInput naming an unknown curve or parameter."""
        d = self.description
        if curve not in d.curves:
            raise _native.InvalidInput(f"curve is {curve!r}; expected one of {sorted(d.curves)}")
        spec = d.curves[curve]
        path = f"basic_curves.{curve}.{parameter}"
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) or not math.isfinite(value):
            raise _native.InvalidInput(f"{path} is {value!r}; expected a finite number")
        value = float(value)
        if parameter in ("flat_from", "flat_to", "value", "x_start", "x_end", "lower", "upper"):
            setattr(spec, parameter, value)
        elif parameter in FORM_ALIASES.get(curve, {}):
            spec.aliases[parameter] = value
        elif parameter in FORM_KEYS:
            spec.params[parameter] = value
        else:
            known = ["flat_from", "flat_to", "value", "x_start", "x_end", *FORM_KEYS, *FORM_ALIASES.get(curve, {})]
            raise _native.InvalidInput(f"{path} is not a form parameter of this curve; expected one of {known}")
        self._invalidate()

    # ---- basic curves ---------------------------------------------------------------
    @property
    def basic_curves(self) -> dict[str, BasicCurve]:
        """Solved basic curves: profile, dwl, deck, sac, fullness (None where the SAC of given sections is
        designed as area) and the shape curves.
        Raises InfeasibleFormParameters (an InvalidInput) when a curve's conditions cannot be met."""
        if self._curves is None:
            d = self.description
            pr = d.principal
            # Everything the shape curves read; the SAC is solved below.
            shape_key = (pr.lpp, pr.breadth, pr.draft, pr.depth, d.x_aft, d.x_fore, d.posts,
                         tuple((name, repr(spec)) for name, spec in sorted(d.curves.items()) if name != "sac"))
            curves = dict(_shape_cache.get(shape_key, self._shape_curves))
            self._curves = curves  # the bands below read them
            try:
                if d.given_sections:  # given sections hold their own areas: the SAC is designed as area
                    curves["sac"] = solve_sac_area(d.curves["sac"], curves["dwl"], curves["profile"], pr.draft)
                    curves["fullness"] = None
                else:
                    band_key = (shape_key, self.stations().tobytes(), d.section_n_control)
                    curves["sac"], curves["fullness"] = self._solve_sac(_band_cache.get(band_key, self._fullness_ranges))
            except BaseException:
                self._curves = None
                raise
        return self._curves

    def _shape_curves(self) -> dict[str, BasicCurve]:
        """Every basic curve but the SAC (which is designed within what these let sections hold)."""
        d = self.description
        pr = d.principal
        c = d.curves
        x0, x1 = d.x_aft, d.x_fore
        half_b = pr.breadth / 2
        out = {}
        if "sheer" in c:  # the deck edge's height, above the waterline
            out["sheer"] = solve_curve("sheer", c["sheer"], x0, x1, lower=pr.draft * (1 + SHEER_CLEARANCE), upper=SHEER_LIMIT * pr.depth,
                                       maximum=False)
        top = float(np.max(out["sheer"](np.linspace(x0, x1, DECK_CHECKS)))) if "sheer" in out else pr.depth
        out["profile"] = solve_curve("profile", c["profile"], x0, x1, lower=-pr.draft, upper=top, maximum=False)
        xa, xf = immersed_range(out["profile"], pr.draft)
        out["dwl"] = solve_curve("dwl", c["dwl"], xa, xf, lower=0.0, upper=half_b)
        # The deck stays outside the waterline (no tumblehome), so sections flare or stay wall-sided.
        out["deck"] = self._deck_clear_of(out["dwl"], c["deck"], xa, xf)
        for name, (default, lo, hi) in SHAPE_CURVES.items():
            out[name] = solve_curve(name, c.get(name, BasicCurveSpec(value=default)), x0, x1, lower=lo, upper=hi, maximum=False)
        for name, (_, lo, hi) in CORNER_CURVES.items():
            if name in c:
                out[name] = solve_curve(name, c[name], x0, x1, lower=lo, upper=hi, maximum=False)
        if "flat_bottom" in c:
            lo, hi = FLAT_BOTTOM_BOUNDS
            out["flat_bottom"] = solve_curve("flat_bottom", c["flat_bottom"], x0, x1, lower=lo, upper=hi, maximum=False)
        self._check_posts(out)
        return out

    def _deck_clear_of(self, dwl: BasicCurve, spec: BasicCurveSpec, xa: float, xf: float) -> BasicCurve:
        """The deck line designed to clear the waterline `dwl` (on xa..xf) at DECK_CHECKS points,
        and again with a point added where a close look (DECK_DENSE, then DECK_LOCAL about each
        of the DECK_LOOKS nearest contacts) finds it inside between them (a spline between its
        checks dipped up to 5 mm on a 56 m beam), DECK_REFINES times at most."""
        pr = self.description.principal
        limit = pr.half_breadth_limit
        floor = limit * (1.0 - DECK_CLEARANCE_TOL)
        checks, dense = np.linspace(xa, xf, DECK_CHECKS), np.linspace(xa, xf, DECK_DENSE)

        def gap(deck, x):
            return np.ravel(deck(x)) - np.minimum(np.ravel(dwl(x)), floor)

        for _ in range(DECK_REFINES):
            clear = [(float(x), min(float(y), floor), "deck >= design waterline") for x, y in zip(checks, np.ravel(dwl(checks)))]
            deck = solve_curve("deck", spec, self.description.x_aft, self.description.x_fore, lower=0.0, upper=limit,
                               at_least=clear)
            g = gap(deck, dense)
            # near contacts (local minima of the gap under DECK_NEAR of the limit), each looked at closely
            k = 1 + np.flatnonzero((g[1:-1] <= g[:-2]) & (g[1:-1] <= g[2:]) & (g[1:-1] < DECK_NEAR * limit))
            if not len(k):
                break
            k = k[np.argsort(g[k], kind="stable")[:DECK_LOOKS]]  # the closest (a flat of side touches all along)
            local = np.linspace(dense[k - 1], dense[k + 1], DECK_LOCAL, axis=1)  # (minima, DECK_LOCAL)
            gl = gap(deck, local.ravel()).reshape(local.shape)
            j = np.argmin(gl, axis=1)
            inside = local[np.arange(len(k)), j][gl[np.arange(len(k)), j] < -DECK_CLEARANCE_TOL * limit]
            if not len(inside):
                break
            checks = np.union1d(checks, inside)
        return deck

    def _check_posts(self, curves: dict) -> None:
        """A post end (ends.aft_post / fore_post) needs the waterline to reach that end, and the
        deck line and waterline to close on the centre plane there. Raises InvalidInput."""
        d = self.description
        tol = POST_TOL * d.principal.breadth / 2
        for end in d.posts:
            x = d.x_aft if end == "aft" else d.x_fore
            dwl = curves["dwl"]
            reach = dwl.x_start if end == "aft" else dwl.x_end
            deck, wl = float(curves["deck"](x)[0]), float(dwl(reach)[0])
            if abs(reach - x) > 1e-9 * d.principal.lpp or deck > tol or wl > tol:
                raise _native.InvalidInput(
                    f"ends.{end}_post is true; expected the profile below T at the {end} end (x = {x} m; the waterline "
                    f"ends at {reach:.6g} m) and the deck line and waterline at 0 there (deck {deck:.6g} m, waterline {wl:.6g} m)")

    def _solve_sac(self, ranges: list) -> tuple[BasicCurve, BasicCurve]:
        """The SAC and its fullness within the stations' fullness `ranges` (x, least keeping the
        whole flat of bottom, least narrowing it, largest, near a dry end) shrunk by BAND_MARGIN
        (the lower side by at most DRY_END_MARGIN near a dry end): first with the
        whole flat kept, then (when no SAC fits those) narrowing it, then by RELAXED_BAND_MARGIN
        (the refusal then names what that holds). The SAC's convex_where_met ranges are held in
        the first two, and where neither meets the volume and LCB with them, the two again without."""
        d, curves = self.description, self._curves
        free = tuple(d.x_aft if end == "aft" else d.x_fore for end in d.posts)
        limits = FULLNESS_BOUNDS
        if "corner_breadth" in d.curves:
            free, limits = self.immersed_range(), CORNER_FULLNESS_BOUNDS

        def within(margin, narrow, spec):
            bands = []
            for x, held, narrowed, hi, dry_end in ranges:
                lo = narrowed if narrow else held
                below = min(margin[0], DRY_END_MARGIN) if dry_end else margin[0]
                if hi > lo:  # a station that cannot keep its whole flat at all is left free in the first pass
                    bands.append((x, lo + below * (hi - lo), hi - margin[1] * (hi - lo)))
            return solve_sac(spec, curves["dwl"], curves["profile"], d.principal.draft, fullness=limits, bands=bands,
                             free_ends=free)

        sac = d.curves["sac"]
        specs = [sac]
        if sac.convex_where_met:
            specs.insert(0, replace(sac, convex=sac.convex + sac.convex_where_met, convex_where_met=[]))
        tries = [(BAND_MARGIN, False)] + ([(BAND_MARGIN, True)] if "flat_bottom" in d.curves else [])
        for spec in specs:
            for margin, narrow in tries:
                try:
                    with _basic_curves.terse_errors():
                        return within(margin, narrow, spec)
                except _native.InfeasibleFormParameters:
                    pass
        return within(RELAXED_BAND_MARGIN, True, specs[-1])

    def _fullness_ranges(self) -> list[tuple[float, float, float, float, bool]]:
        """(x, least keeping the whole flat of bottom, least narrowing it, largest) fullness the
        section family holds at each station inside the waterline's range, and whether the
        station lies within BAND_FREE end bands of depth of where the keel rises out of the water
        aft (see BAND_FREE_DRY_DEPTH)."""
        xa, xf = self.immersed_range()
        xs = self.stations()
        xs = xs[(xs > xa) & (xs < xf)]
        out = []
        pr = self.description.principal
        transom = float(self._curves["dwl"](xa)[0]) > 1e-9 * pr.breadth  # the waterline ends on an immersed transom
        for x, spec in zip(xs, self.section_specs(xs, with_area=False)):
            aft = x < 0.5 * (xa + xf)
            dry = aft and not transom  # the keel rises out of the water aft
            depth = (spec.draft - spec.z_keel) / pr.draft / _native.END_BAND  # in end bands
            depth_free = BAND_FREE_DRY_DEPTH if dry else BAND_FREE_DEPTH if aft else BAND_FREE
            if spec.y_dwl / (pr.breadth / 2) < BAND_FREE * _native.END_BAND or depth < depth_free:
                continue  # where the waterline ends the area fades out: no band
            held, lo, hi = _native.section_fullness_bounds(spec)
            if np.isfinite(lo) and np.isfinite(hi) and hi > lo:
                out.append((float(x), float(held), float(lo), float(hi), dry and depth < BAND_FREE))
        return out

    def immersed_range(self) -> tuple[float, float]:
        """x range of the design waterline (where the centre profile is below T), m."""
        dwl = self._curves["dwl"] if self._curves is not None else self.basic_curves["dwl"]
        return dwl.x_start, dwl.x_end

    def junctions(self) -> list[float]:
        """x where a basic curve has a flat part's end, the waterline ends or a skeg ends."""
        out = set(self.immersed_range())
        if (sk := self.description.skeg) is not None:
            out.update((sk.x_aft, sk.x_aft + sk.end_length, sk.x_fore))
        if (dm := self.description.dome) is not None:
            out.update((dm.x_aft, dm.x_fore))
        for spec in self.description.curves.values():
            for x in (spec.flat_from, spec.flat_to):
                if x is not None:
                    out.add(float(x))
        return sorted(out)

    def stations(self) -> np.ndarray:
        """Stations of the designed sections (m): the description's list, or its count clustered
        toward the ends with stations on the junctions, plus more where the sections change
        quickly (a skeg's aft end, a dome, a stem's or a counter's overhang and the two spans
        inside it)."""
        if self._stations is None:  # asked by the band cache's key and by every section step
            d = self.description
            if d.station_x is not None:
                self._stations = np.asarray(d.station_x, dtype=float)
            else:
                self._stations = station_positions(d.x_aft, d.x_fore, d.station_count, self.junctions())
                sk = d.skeg
                if sk is not None and sk.end_length <= 0 and sk.x_aft - d.x_aft > 2 * STERNPOST_GAP * d.principal.lpp:
                    # a station just aft of a square sternpost: the skeg ends within this gap
                    self._stations = np.union1d(self._stations, [sk.x_aft - STERNPOST_GAP * d.principal.lpp])
                elif sk is not None:  # the skeg's raked aft end: its sections change quickly
                    self._stations = _with_stations(self._stations, np.linspace(sk.x_aft, sk.x_aft + sk.end_length,
                                                                                SKEG_END_STATIONS + 1))
                if (dm := d.dome) is not None:  # the dome's sections change quickly, most at its nose
                    u = np.sin(0.5 * np.pi * np.linspace(0.0, 1.0, DOME_STATIONS + 1))
                    self._stations = _with_stations(self._stations, dm.x_aft + (dm.x_fore - dm.x_aft) * u)
                self._stations = self._closed_end_stations(self._stations)
        return self._stations.copy()

    def _closed_end_stations(self, st: np.ndarray) -> np.ndarray:
        """`st` with OVERHANG_STATIONS over each closed end's overhang (one span is too few) and the
        CLOSED_END_HALVED_SPANS spans inside it halved (where the skin rang)."""
        d = self.description
        u = np.arange(1, OVERHANG_STATIONS + 1) / (OVERHANG_STATIONS + 1)
        for x_end, x_tip in self._closed_dry_ends():
            st = _with_stations(st, x_end + (x_tip - x_end) * (1 - (1 - u) ** 2))
            least = HALVED_LEAST_SHARE * float(station_spacing(np.array([x_end]), d.x_aft, d.x_fore, d.station_count)[0])
            st = _halved_inside(st, x_end, x_tip, CLOSED_END_HALVED_SPANS, STATION_MATCH_TOL * d.principal.lpp, least)
        return st

    # ---- sections ---------------------------------------------------------------------
    def _lower_angles(self, xs: np.ndarray) -> np.ndarray:
        """Arrival angle (deg) at the keel point of sections above the water beyond the
        waterline's ends: the angle of the line from the keel point to the virtual waterline
        point (b_v, T), b_v the waterline's cubic continued past its end (negative there), so a
        dry section continues the immersed ones' chord K -> Q, whose lean is b / (T - z_keel);
        beyond a dry transom less by DRY_TRANSOM_LEAN_BEND (h / T)^2, h the distance from the end."""
        bc = self._curves
        dwl, prof = bc["dwl"], bc["profile"]
        draft = self.description.principal.draft
        out = np.full(xs.shape, np.nan)
        for side, x_end in (("fore", dwl.x_end), ("aft", dwl.x_start)):
            if dwl(x_end)[0] > 1e-9 * self.description.principal.breadth:
                continue  # an immersed transom: no sections beyond the waterline's end
            taylor = [dwl.derivative(x_end, k) / math.factorial(k) for k in (1, 2, 3)]
            bend = DRY_TRANSOM_LEAN_BEND if side == "aft" else 0.0
            beyond = np.flatnonzero(xs >= x_end if side == "fore" else xs <= x_end)
            keel = prof(xs[beyond]).tolist() if beyond.size else []
            for k, z_keel in zip(beyond, keel):
                h = float(xs[k]) - x_end
                b_v = sum(c * h ** (j + 1) for j, c in enumerate(taylor))
                d_v = draft - z_keel
                if d_v < 0 and b_v < 0:
                    lean = b_v / d_v
                else:  # at the end itself: the limit of the lean, the end slopes' ratio
                    lean = abs(taylor[0]) / max(abs(prof.derivative(float(xs[k]), 1)), MIN_STEM_SLOPE)
                # (never past vertical: the bend grows as h^2 and an overhang of several T would)
                out[k] = min(max(math.degrees(math.atan(lean)) - bend * (h / draft) ** 2, 0.0), MAX_LOWER_ANGLE)
        for end in self.description.posts:  # a vertical post: the end section is the line deck -> keel
            x_end = self.description.x_aft if end == "aft" else self.description.x_fore
            out[np.abs(xs - x_end) <= 1e-9 * self.description.principal.lpp] = 0.0
        return out

    def _given_shapes(self, xs: np.ndarray) -> list:
        """(given, given_fore, mix) of each x from the description's given sections: the shape at
        a given station, the two about a station between them blended linearly in x, None
        outside the first and last."""
        g = self.description.given_sections
        out = [None] * len(xs)
        if not g:
            return out
        gx = np.array([x for x, _ in g])
        tol = 1e-9 * self.description.principal.lpp
        for i, x in enumerate(xs):
            if x < gx[0] - tol or x > gx[-1] + tol:
                continue
            j = int(np.clip(np.searchsorted(gx, x, side="right") - 1, 0, len(gx) - 1))
            if abs(x - gx[j]) <= tol or j == len(gx) - 1:
                out[i] = (g[j][1], None, 0.0)
            else:
                out[i] = (g[j][1], g[j + 1][1], float((x - gx[j]) / (gx[j + 1] - gx[j])))
        return out

    def curve_points(self, xs: np.ndarray, curves: dict | None = None) -> tuple:
        """What the basic curves give a section at each x (m), before the given sections'
        offsets: the deck edge's half-breadth (within [0, B_max / 2]) and height (the sheer, or D),
        the waterline's half-breadth (NaN off its range) and the keel's height, each len(xs).
        `curves`: the solved basic curves (default) or any dict holding these curves."""
        bc = self.basic_curves if curves is None else curves
        pr = self.description.principal
        deck = clip(bc["deck"](xs), 0.0, pr.half_breadth_limit)
        z_deck = bc["sheer"](xs) if "sheer" in bc else np.full(len(xs), pr.depth)
        return deck, z_deck, bc["dwl"](xs, outside=math.nan), bc["profile"](xs)

    def _given_offsets(self, xs: np.ndarray) -> np.ndarray:
        """(deck dy, deck dz, waterline dy, keel dz) of each x (m), len(xs) by 4: the given
        sections' offsets from the basic curves, linear in x between them, zero outside the first
        and last."""
        d = self.description
        out = np.zeros((len(xs), 4))
        if not d.given_sections or not any(map(any, d.given_offsets)):
            return out
        gx = np.array([x for x, _ in d.given_sections])
        off = np.asarray(d.given_offsets, dtype=float)
        tol = 1e-9 * d.principal.lpp
        inside = (xs >= gx[0] - tol) & (xs <= gx[-1] + tol)
        for k in range(4):
            out[inside, k] = np.interp(xs[inside], gx, off[:, k])
        return out

    def section_specs(self, x: Any = None, with_area: bool = True) -> list:
        """fl.SectionSpec of each station (or of the given x, m), read off the basic curves
        (without the SAC's area when `with_area` is false). Raises InvalidInput for an x off the
        hull."""
        d = self.description
        pr = d.principal
        bc = self.basic_curves if with_area else self._curves
        xs = self.stations() if x is None else np.atleast_1d(np.asarray(x, dtype=float))
        tol = 1e-9 * pr.lpp
        off = xs[(xs < d.x_aft - tol) | (xs > d.x_fore + tol)]
        if off.size:  # name the stations off the hull, not every one asked
            shown = ", ".join(f"{v:g}" for v in off[:OFF_HULL_SHOWN]) + (", ..." if off.size > OFF_HULL_SHOWN else "")
            raise _native.InvalidInput(f"x is {shown} m ({off.size} of {xs.size} stations off the hull); expected "
                                       f"stations on the hull, {d.x_aft:g} to {d.x_fore:g} m")
        half_b, limit = pr.breadth / 2, pr.half_breadth_limit
        deck, z_deck, dwl, prof = self.curve_points(xs, bc)
        sac = bc["sac"](xs, outside=math.nan) if with_area else None
        # a spline fitted to a bound may overshoot it by round-off (a deadrise of -4e-13 deg)
        shape = {name: clip(bc[name](xs), lo, hi) for name, (_, lo, hi) in SHAPE_CURVES.items()}
        optional = {field: clip(bc[name](xs), lo, hi) for name, (field, lo, hi) in CORNER_CURVES.items() if name in bc}
        if "flat_bottom" in bc:
            optional["flat_bottom"] = clip(bc["flat_bottom"](xs, outside=0.0), *FLAT_BOTTOM_BOUNDS)
        lower = self._lower_angles(xs)
        given = self._given_shapes(xs)
        offsets = self._given_offsets(xs)
        deck, z_deck = clip(deck + offsets[:, 0], 0.0, limit), z_deck + offsets[:, 1]
        dwl = np.where(dwl > 0, dwl + offsets[:, 2], dwl)
        prof = prof + offsets[:, 3]
        skeg, share = d.skeg.at(xs, np.minimum(prof, z_deck)) if d.skeg is not None else (np.full(len(xs), np.nan), None)
        dome, dome_b = d.dome.at(xs, np.minimum(prof, z_deck)) if d.dome is not None else (np.full(len(xs), np.nan), None)
        # Python floats once (per-element numpy scalars cost most of this loop)
        xl, deck, z_deck, prof, dwl, lower = (np.asarray(a, dtype=float).tolist() for a in (xs, deck, z_deck, prof, dwl, lower))
        sac = sac.tolist() if with_area else None
        shapes = list(zip(*(shape[k].tolist() for k in SHAPE_CURVES)))
        optional = {field: values.tolist() for field, values in optional.items()}
        skeg, dome = skeg.tolist(), dome.tolist()
        specs = []
        for i, xi in enumerate(xl):
            s = _native.SectionSpec()
            if given[i] is not None:
                s.given, s.given_fore, s.given_mix = given[i]
                if d.given_smoothing is not None:
                    s.given_smoothing = d.given_smoothing
            if math.isfinite(skeg[i]) and share[i] > 0:
                s.skeg_bottom, s.skeg_share = skeg[i], float(share[i])
                s.skeg_half_thickness, s.skeg_fillet = d.skeg.half_thickness, d.skeg.fillet
            if math.isfinite(dome[i]) and dome_b[i] > 0:
                s.dome_bottom, s.dome_half_breadth = dome[i], float(dome_b[i])
                s.dome_neck = float(DOME_NECK * dome_b[i])
            s.x, s.y_max, s.n_control = xi, limit, d.section_n_control
            s.y_deck = deck[i]
            s.z_deck = z_deck[i]
            s.z_keel = min(prof[i], z_deck[i])
            s.top_corner, s.deadrise, s.character = shapes[i]
            for field, values in optional.items():
                setattr(s, field, values[i])
            if math.isfinite(lower[i]):
                s.lower_angle = lower[i]
                s.draft = pr.draft  # where the dry section's virtual waterline point lies
            if math.isfinite(dwl[i]) and dwl[i] > 0 and s.z_keel < pr.draft:
                s.draft, s.y_dwl = pr.draft, min(dwl[i], half_b)
                if with_area and math.isfinite(sac[i]):
                    s.half_area = max(sac[i], 0.0) / 2
            specs.append(s)
        if with_area:
            self._read_dry_ends(specs, given)
        return specs

    def _closed_dry_ends(self) -> list:
        """(x_e, x_tip) (m) of each waterline end beyond which the hull runs on above the water
        and closes in a point at the deck: a raked stem, a cruiser stern (not a transom, nor a post)."""
        if self._closed_ends is not None:
            return self._closed_ends
        d, dwl = self.description, self._curves["dwl"]
        pr = d.principal
        out = []
        for side, x_end, x_tip in (("fore", dwl.x_end, d.x_fore), ("aft", dwl.x_start, d.x_aft)):
            if side in d.posts or dwl(x_end)[0] > 1e-9 * pr.breadth or abs(x_tip - x_end) <= 1e-9 * pr.lpp:
                continue
            if side == "aft" and self.curve_points(np.array([x_tip]), self._curves)[0][0] > 1e-6 * pr.breadth:
                continue  # a transom: the waterlines above T end on it, not on the centre plane
            out.append((x_end, x_tip))
        self._closed_ends = out
        return out

    def _read_dry_ends(self, specs: list, given: list) -> None:
        """The dry sections beyond a closed end (_closed_dry_ends) without a given shape or an
        appendage take the shape read off the waterlines (fairlines.dry_ends)."""
        d = self.description
        for x_end, x_tip in self._closed_dry_ends():
            beyond = (lambda x: x > x_end) if x_tip > x_end else (lambda x: x < x_end)
            dry = [s for s, g in zip(specs, given) if g is None and beyond(s.x) and math.isnan(s.skeg_bottom)
                   and math.isnan(s.dome_bottom)]
            if not dry:
                continue
            if x_end not in self._dry_ends:
                step = math.copysign(dry_ends.END_SLOPE_BASE * d.principal.lpp, x_tip - x_end)  # toward the end
                inside = self.section_specs([x_end - 2 * step, x_end - step, x_end])
                self._dry_ends[x_end] = (dry_ends.end_waterlines(inside, d.principal.lpp, d.principal.draft),
                                         dry_ends.end_contour(self._curves["profile"], x_end, x_tip))
            for s in dry:
                shape = dry_ends.dry_section(s, x_end, *self._dry_ends[x_end])
                if shape is not None:
                    s.given = shape

    def _transom_run_fairing(self):
        """The TransomRun of a transom (wet, or dry: the keel leaves the water forward of it) with
        no given section in the run, else None (cached)."""
        if self._transom_run is None:
            self._transom_run = []  # also what the template's own specs see while the run is built
            d, dwl = self.description, self._curves["dwl"]
            pr = d.principal
            x_r = dwl.x_start + transom_run.RUN_LENGTH * pr.lpp
            transom = self.curve_points(np.array([d.x_aft]), self._curves)[0][0] > 1e-6 * pr.breadth
            given_in_run = any(g is not None for g in self._given_shapes(np.linspace(d.x_aft, x_r, 9)))
            wet = dwl.x_start - d.x_aft <= 1e-6 * pr.lpp
            if (transom and "aft" not in d.posts and dwl.x_start - d.x_aft > -1e-6 * pr.lpp
                    and x_r + 2 * transom_run.END_SLOPE_BASE * pr.lpp < d.x_fore and not given_in_run):
                self._transom_run = [transom_run.TransomRun(d.x_aft, dwl.x_start, pr.lpp, pr.draft, self.section_specs,
                                                            wet=wet)]
        return self._transom_run[0] if self._transom_run else None

    def _section_curves(self, specs: list, designs: list) -> list:
        """The designed sections' curves, a transom's run faired (fairlines.transom_run)."""
        curves = [d.curve for d in designs]
        run = self._transom_run_fairing()
        if run is None:
            return curves
        # a skeg's sections too (their topside is the body's own, held when the engine puts them
        # through Q): left as designed, the skegged container ship's topside stepped 1-2 cm where
        # its skeg starts inside the run (x 9.7 m, the run to 11 m)
        return [run.corrected(c, s) if run.covers(s.x) and s.given.size == 0 and math.isnan(s.dome_bottom) else c
                for c, s in zip(curves, specs)]

    @property
    def section_designs(self) -> list:
        """fl.SectionDesign of every station (cached): the curve, the shape knob, the fullness."""
        if self._designs is None:
            self._specs = self.section_specs()
            self._designs = list(_native.design_sections(self._specs))
        return self._designs

    @property
    def section_curves(self) -> list:
        """The curves of section_designs, a transom's run faired (fairlines.transom_run): the
        stations' designed sections before the station mean (3-D NurbsCurves, deck to keel)."""
        designs = self.section_designs
        return self._section_curves(self._specs, designs)

    @property
    def sections(self) -> list:
        """Section curves the skin interpolates (3-D NurbsCurves, deck to keel, x order), all on
        one knot vector: the designed sections, each the mean of the family's a little either side
        of its station (fairlines.station_mean; skinning.station_mean) where
        _station_mean_offsets does not keep it as designed (cached)."""
        if self._sections is None:
            xs = self.stations()
            designed = self.section_curves
            x, averaged = station_mean.window(xs, self._station_mean_offsets(xs, self._specs))
            samples = []
            if len(x):
                specs = self.section_specs(x)
                samples = self._section_curves(specs, _native.design_sections(specs))
            pr = self.description.principal
            hold = station_mean.keel_hold_share(np.array([self._specs[i].z_keel for i in averaged]) / pr.draft,
                                                xs[averaged] > pr.lpp / 2)
            self._sections = station_mean.mean_sections(designed, samples, averaged, hold)
        return self._sections

    def _station_mean_offsets(self, xs: np.ndarray, specs: list) -> np.ndarray:
        """(len(xs),) offsets d (m) of the station mean (fairlines.station_mean): the fraction
        skinning.station_mean of the clustered spacing at the station (of its smaller spacing with
        listed stations), at most MEAN_REACH of the way to a neighbour; 0 where a station is kept
        as designed: the hull's ends, the given sections, the appendages' stations (read off the
        stations' SectionSpecs `specs`), the SAC's flat part and where the waterline is at B/2 (a
        mean there would dip below the flat or the peak)."""
        d = self.description
        near = np.minimum(np.diff(xs, prepend=-np.inf), np.diff(xs, append=np.inf))
        spacing = near if d.station_x is not None else station_spacing(xs, d.x_aft, d.x_fore, d.station_count)
        out = np.minimum(d.skin_station_mean * spacing, MEAN_REACH * near)
        keep = np.array([g is not None for g in self._given_shapes(xs)], dtype=bool)
        keep |= [math.isfinite(s.skeg_bottom) or math.isfinite(s.dome_bottom) for s in specs]
        tol = 1e-9 * d.principal.lpp
        for name in ("sac", "dwl"):  # a mean would dip below a flat part or a peak
            spec = d.curves[name]
            if spec.flat_from is not None and spec.flat_to is not None:
                keep |= (xs >= spec.flat_from - tol) & (xs <= spec.flat_to + tol)
        keep |= self.basic_curves["dwl"](xs, outside=0.0) >= d.principal.breadth / 2 - tol
        out[keep] = 0.0
        out[[0, -1]] = 0.0
        return out

    def sections_at(self, x: Any) -> list:
        """The designed sections at any x (m), between the stations too."""
        specs = self.section_specs(x)
        return self._section_curves(specs, _native.design_sections(specs))

    # ---- surface --------------------------------------------------------------------
    def skin(self):
        """The SkinResult of skinning the sections (cached). Raises InvalidInput for a
        skinning.knuckles x that is not a station's, or a not-a-knot aft end next to a C0 station."""
        if self._skin is None:
            d = self.description
            c0 = self._c0_sections(self.stations())
            if d.skin_aft_end != "free" and 1 in c0:
                raise _native.InvalidInput(f"skinning.aft_end is {d.skin_aft_end!r} but the skin is only C0 at the station "
                                           "next to the aft end (skinning.ruled_aft_of or knuckles); expected 'free'")
            self._skin = fair_skin(self.sections, params="station", e2=d.skin_e2, e3=d.skin_e3, hold_runs=True, y_nonnegative=True,
                                   c0_sections=c0, start=d.skin_aft_end)
        return self._skin

    def _c0_sections(self, xs: np.ndarray) -> list:
        """Interior station indices where the skin is only C0: those at skinning.knuckles, and
        every one aft of skinning.ruled_aft_of up to the first at or forward of it (the skin
        straight between them). Raises InvalidInput for a knuckle that is not at a station."""
        d = self.description
        tol = STATION_MATCH_TOL * d.principal.lpp
        out = set()
        for i, k in enumerate(d.skin_knuckles):
            j = int(np.argmin(np.abs(xs - k)))
            if abs(xs[j] - k) > tol:
                raise _native.InvalidInput(f"skinning.knuckles[{i}] is {k:g} m; expected the x of a station "
                                           f"(the nearest is {xs[j]:g} m)")
            out.add(j)
        if d.skin_ruled_aft_of is not None:
            last = int(np.searchsorted(xs, d.skin_ruled_aft_of - tol))
            out.update(range(1, last + 1))
        return sorted(j for j in out if 0 < j < len(xs) - 1)

    def bare_hull_surface(self) -> _native.NurbsSurface:
        """The half hull y >= 0: u from the deck to the keel, v from the aft to the forward end
        (its transom raked by ends.transom_rake: fairlines.transom_rake)."""
        skin = self.skin()
        if self._raked is None or self._raked[0] is not skin:
            d = self.description
            z_edge = float(self.basic_curves["profile"](d.x_aft)[0])
            self._raked = (skin, raked(skin.surface, d.x_aft, z_edge, d.transom_rake, d.x_fore - d.x_aft))
        return self._raked[1]

    def hydrostatics(self, draft: float | None = None, **options) -> _native.Hydrostatics:
        """fl.hydrostatics of the bare hull at `draft` (default T), both sides, coefficients on
        Lpp and B with the midship section at Lpp / 2 (options override). Raises InvalidInput
        for a draft outside the hull."""
        pr = self.description.principal
        options.setdefault("length", pr.lpp)
        options.setdefault("breadth", pr.breadth)
        options.setdefault("midship_x", pr.lpp / 2)
        draft = pr.draft if draft is None else draft
        key = (float(draft), tuple(sorted(options.items())))
        if key not in self._hydro:  # several nodes and the bulb ask for the same figures
            self._hydro[key] = hydrostatics(self.bare_hull_surface(), draft, **options)
        return self._hydro[key]

    def ship_hydrostatics(self, draft: float | None = None) -> dict:
        """The whole ship's hydrostatics at `draft` (default T) as a dict (the keys of
        fl.Hydrostatics.as_dict() a hydrostatic table shows, and ``source``): the bare hull's
        without a bulb; with one the composed ship's -- bare hull, bulb and blend
        (fairlines.hydrostatics_composed) -- which the designer matches to the particulars.
        Raises InvalidInput for a draft outside the hull or a bulb that does not meet it."""
        pr = self.description.principal
        draft = pr.draft if draft is None else draft
        if self.description.bulb is None:
            return {**self.hydrostatics(draft).as_dict(), "source": "NURBS quadrature"}
        from .hydrostatics_composed import composed_hydrostatics

        composed, closed = self.ship_meshes()
        return composed_hydrostatics(composed, draft, lpp=pr.lpp, beam=pr.breadth, bare_mesh=closed)

    # ---- bulbous bow ----------------------------------------------------------------
    def ship_particulars(self) -> dict[str, float]:
        """What a bulbous bow is sized from (fairlines.BulbousBow): Lpp, B, T at the FP, the FP
        at x = Lpp, A_MS (both sides) at Lpp / 2 and the ship's displacement volume (the bulb
        section's ``displacement_volume``, or the hull's own when it is the whole ship).
        Raises InvalidInput when the hull is not the whole ship and the bulb section gives no
        displacement_volume."""
        d = self.description
        pr = d.principal
        key = (id(self.skin()), repr(d.bulb.to_dict() if d.bulb else None))
        if self._ship is not None and self._ship[0] == key:
            return dict(self._ship[1])
        plain = {"length": pr.lpp, "breadth": pr.breadth, "midship_x": pr.lpp / 2}
        known = [h for (t, opts), h in self._hydro.items()
                 if t == pr.draft and {k: v for k, v in opts if k not in ("gauss", "sac_stations")} == plain]
        h = known[0] if known else self.hydrostatics(gauss=SIZING_GAUSS, sac_stations=2)  # volume, midship area
        vol = d.bulb.displacement_volume if d.bulb is not None else None
        if vol is None:
            if not (d.x_aft <= 0.0 and d.x_fore >= pr.lpp):
                raise _native.InvalidInput(f"bulb.displacement_volume is missing; the hull models only x = {d.x_aft} .. {d.x_fore} m")
            vol = float(h.volume)
        ship = dict(lpp=pr.lpp, beam=pr.breadth, draft_fp=pr.draft, midship_area=float(h.midship_area),
                    displacement_volume=float(vol), x_fp=pr.lpp)
        self._ship = (key, ship)
        return dict(ship)

    def bulbous_bow(self, **overrides):
        """The BulbousBow of the ``"bulb"`` section sized from :meth:`ship_particulars`; keyword
        overrides (Kracht coefficients or shape controls) replace the section's. Raises
        InvalidInput when the description has no bulb and no overrides are given."""
        from .bulb import BulbousBow
        from .description import BulbSpec

        d = self.description
        if d.bulb is None and not overrides:
            raise _native.InvalidInput('bulb is missing; expected a "bulb" section in the hull description')
        spec = d.bulb if d.bulb is not None else BulbSpec()
        ship = self.ship_particulars()
        if overrides:
            return BulbousBow(**ship, **{**spec.kracht, **spec.shape, **overrides})
        key = (tuple(ship.items()), repr(spec.to_dict()))
        if self._bow is None or self._bow[0] != key:  # the designer and the composition both ask
            self._bow = (key, BulbousBow(**ship, **spec.kracht, **spec.shape))
        return self._bow[1]

    def blend_placement(self) -> "fairlines.blend.BlendPlacement":
        """fairlines.seam_blend_placement of the bare hull and the description's bulb with the
        default options (cached for the current surface and bulb). Raises InvalidInput when the
        hull has no bulb or the bulb cannot meet it, NoBlendFits when no blend boundary fits."""
        from .blend import seam_blend_placement

        surface, bow = self.bare_hull_surface(), self.bulbous_bow()
        if self._placement is None or self._placement[0] is not surface or self._placement[1] is not bow:
            self._placement = (surface, bow, seam_blend_placement(surface, bow))
        return self._placement[2]

    def bare_hull_closed(self):
        """The bare hull closed by deck, transom and centre plane (fl.compose of it alone, default
        meshing): a ship without a bulb's composed hull, and what a bulb's share of the ship is
        measured against (fairlines.hydrostatics_composed). Kept until the hull changes: callers
        must not edit it."""
        surface = self.bare_hull_surface()
        if self._kept_closed(surface) is None:
            self._closed = (surface, _closed(surface))
        return self._closed[1]

    def _kept_closed(self, surface):
        """The bare hull closed, if already made for `surface` (else None)."""
        return self._closed[1] if self._closed is not None and self._closed[0] is surface else None

    def ship_meshes(self) -> tuple:
        """(composed_hull(), bare_hull_closed()): the ship's composed hull and what the bulb's
        share is measured against (fairlines.hydrostatics_composed.bulb_share). With a bulb the
        bare hull is closed on a second thread while the bulb is placed and composed (the engine
        releases the GIL: the designer measures the share on two builds). Raises InvalidInput
        when the bulb does not meet the hull."""
        surface = self.bare_hull_surface()
        if self.description.bulb is None or self._kept_closed(surface) is not None:
            return self.composed_hull(), self.bare_hull_closed()
        closed = _in_thread(lambda: _closed(surface))
        try:
            composed = self.composed_hull()
        finally:
            self._closed = (surface, closed())  # joined before a refusal leaves too
        return composed, self._closed[1]

    def composed_hull(self, blend: bool = True, bulb=None, **compose_options):
        """Bare hull + bulbous bow (+ a G2 blend when ``blend``) composed into one watertight half
        hull (fairlines.ComposedHull); a ship without a bulb (none described, none given) is its
        bare hull closed by deck, transom and centre plane. The default composition (no arguments)
        is kept until the hull changes: callers must not edit it. Raises InvalidInput when the
        bulb does not meet the hull."""
        from .compose import compose, compose_with_blend

        if bulb is None and self.description.bulb is None:
            if not compose_options:
                return self.bare_hull_closed()
            closed = compose([self.bare_hull_surface()], **compose_options)
            closed.blend_note = "no bulb: the bare hull closed"
            return closed
        b = self.bulbous_bow() if bulb is None else bulb
        placement = None
        default = bulb is None and blend and not compose_options
        if default:  # the placement the designer found, if it did
            try:
                placement = self.blend_placement()
            except _native.NoBlendFits:
                pass  # compose_with_blend says why in the plain union's note
        key = (self.bare_hull_surface(), b, placement)
        if default and self._composed is not None and all(x is y for x, y in zip(self._composed[0], key)):
            return self._composed[1]  # the designer measured the ship on it: one composition, not two
        composed = compose_with_blend(self.bare_hull_surface(), b, blend=blend, placement=placement, **compose_options)
        if default:
            self._composed = (key, composed)
        return composed

    # ---- fairness -------------------------------------------------------------------
    def fairness_report(self, **kwargs) -> dict:
        """fairlines.fairness.fairness_report of the bare hull (cuts judged on their own)."""
        from .fairness import fairness_report

        kwargs.setdefault("draft", self.description.principal.draft)
        return fairness_report(self.bare_hull_surface(), **kwargs)


def _closed(surface):
    """The bare hull surface closed by deck, transom and centre plane (fl.compose of it alone)."""
    from .compose import compose

    closed = compose([surface])
    closed.blend_note = "no bulb: the bare hull closed"
    return closed


def _in_thread(work):
    """Run work() on a thread; returns a function that joins it and gives work's value or
    raises its error."""
    out = {}

    def run():
        try:
            out["value"] = work()
        except BaseException as e:  # re-raised on the caller's thread
            out["error"] = e

    t = threading.Thread(target=run, name="fairlines-close-bare-hull", daemon=True)
    t.start()

    def result():
        t.join()
        if "error" in out:
            raise out["error"]
        return out["value"]

    return result
