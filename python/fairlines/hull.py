"""A hull built from its description: basic curves -> sections -> fair-skinned surface.

``fl.Hull.from_json(path | text | dict)`` reads a description (fairlines.description documents
the format); ``fl.design_hull(...)`` (fairlines.designer) writes one from principal particulars.
Every build step is cached and :meth:`Hull.set` invalidates what an edit touches, so a slider
costs one rebuild of the curves, the sections and the skin.

Each section (fairlines.sections: ``fl.design_section``) is the fairest curve from the deck
point to the keel point through the DWL point with the SAC's area below it, convex below the
DWL and with one curvature sign above it (a flare or a convex top), kept inside 0 <= y <= B/2;
flats of side and bottom appear exactly where the area needs them. All sections share one knot
vector, so their control points are the surface's rows: ``fl.fair_skin`` interpolates each row
along the hull (v proportional to x), holding runs that stay constant (the parallel middle body)
exactly. The surface is the half hull y >= 0, u from the deck (0) to the keel (1), v from the
aft end (0) to the forward end (1).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from . import _native
from .basic_curves import BasicCurve, StemKeelAngle, immersed_range, solve_curve, solve_sac
from .description import FORM_ALIASES, FORM_KEYS, BasicCurveSpec, HullDescription, load_description
from .skinning import fair_skin

__all__ = ["Hull", "station_positions"]

# Stations cluster toward both ends: spacing 1 - c cos(2 pi s) over the hull (ratio
# (1 + c) / (1 - c) between the middle and the ends), where sections change fastest.
STATION_CLUSTERING = 0.6
# A station this close (fraction of the mean spacing) to a junction of the basic curves moves
# onto it, so flat parts and the waterline's ends are exact at a station.
SNAP_FRACTION = 0.5
# Sections whose DWL half-breadth or immersed depth is below this fraction of B / T have no
# DWL part (the waterline's ends).
NO_DWL_FRACTION = 1e-7
# A flared top turns into the convex bottom at the DWL, or on a counter at least this fraction
# of the section's height above its keel.
INFLECTION_FRACTION = 0.3
# Height (fraction of T) up the stem above which the waterlines leave it at the DWL's entrance
# angle; below they blunt toward the flat keel (StemKeelAngle).
FINE_STEM = 0.5
# Points along the waterline's range where the deck line must clear the DWL (no tumblehome).
DECK_CHECKS = 81
# The SAC keeps each station's fullness inside the band a fair section can have, shrunk by these
# fractions of its width: the least area is a V with a knuckle (far from fair), the largest a
# box with the tightest bilge the knots allow (what a Cm of 0.99 needs).
BAND_MARGIN = (0.15, 0.02)
BAND_TOP = 0.003  # at most this much fullness off the top of the band
BAND_BOX = 0.4    # stations whose immersed box is below this fraction of B T / 2 get a band


def station_positions(x_aft: float, x_fore: float, count: int, junctions: list[float] = ()) -> np.ndarray:
    """`count` stations on [x_aft, x_fore] clustered toward both ends, with the station nearest
    each junction (inside the range) moved onto it."""
    s = np.linspace(0.0, 1.0, count)
    x = x_aft + (x_fore - x_aft) * (s - STATION_CLUSTERING * np.sin(2 * np.pi * s) / (2 * np.pi))
    mean = (x_fore - x_aft) / (count - 1)
    for xj in sorted(junctions):
        if not x_aft + 1e-9 * mean < xj < x_fore - 1e-9 * mean:
            continue
        k = int(np.argmin(np.abs(x - xj)))
        if 0 < k < count - 1 and abs(x[k] - xj) < SNAP_FRACTION * mean and x[k - 1] < xj < x[k + 1]:
            x[k] = xj
    return x


def _inflection_height(draft: float, z_keel: float, depth: float, keel_angle: float) -> float:
    """Where a flared section's top turns into its convex bottom: the DWL, or higher on a
    counter whose flat bottom needs a bilge above the water (a smooth maximum of T and z_keel +
    INFLECTION_FRACTION (D - z_keel) g, over a width of a tenth of the draught). g fades from 1
    for a flat keel (-90 deg) to 0 for a steep one (a stem), whose flare runs down to the keel."""
    g = _smoothstep((-keel_angle - 10.0) / 50.0)
    a, b = draft, z_keel + INFLECTION_FRACTION * (depth - z_keel) * g
    w = 0.1 * draft
    return 0.5 * (a + b + math.sqrt((a - b) ** 2 + w * w))


def _smoothstep(r: float) -> float:
    r = min(max(r, 0.0), 1.0)
    return r * r * r * (10.0 - 15.0 * r + 6.0 * r * r)


class Hull:
    """A hull built from a HullDescription (see the module docstring)."""

    def __init__(self, description: HullDescription):
        self.description = description
        self._invalidate()

    def _invalidate(self) -> None:
        self._curves: dict[str, BasicCurve] | None = None
        self._banded = False
        self._sections: list | None = None
        self._skin = None
        self._ship = None

    # ---- construction ---------------------------------------------------------------
    @classmethod
    def from_json(cls, source: Any) -> Hull:
        """From a JSON file path, JSON text or a parsed dict (InvalidInput naming the field)."""
        return cls(HullDescription.from_dict(load_description(source)))

    def to_dict(self) -> dict:
        return self.description.to_dict()

    def to_json(self) -> str:
        import json

        return json.dumps(self.to_dict(), indent=2)

    # ---- editing --------------------------------------------------------------------
    def set(self, curve: str, parameter: str, value: float) -> None:
        """Change one form parameter of one basic curve (``set("sac", "volume", 27000)``); the
        next access rebuilds. InvalidInput names an unknown curve or parameter."""
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
        """Solved basic curves: profile, dwl, deck, sac, fullness and the optional ones."""
        if self._curves is None:
            try:
                self._curves = self._solve_curves()
            except BaseException:
                self._curves = None
                raise
        return self._curves

    def _solve_curves(self, with_bands: bool = False) -> dict[str, BasicCurve]:
        """All basic curves. The SAC is kept inside the fullness each station's section can have
        when `with_bands` (the bands cost two small solves per station, so they are computed
        only when a section asked for more or less than it can hold: see :attr:`sections`)."""
        out = self._shape_curves()
        self._curves = out  # the section specs of the fullness bands read them
        pr = self.description.principal
        bands = self._fullness_bands() if with_bands else None
        out["sac"], out["fullness"] = solve_sac(self.description.curves["sac"], out["dwl"], out["profile"], pr.draft, bands=bands)
        self._banded = with_bands
        return out

    def _shape_curves(self) -> dict[str, BasicCurve]:
        """Every basic curve but the SAC (which is designed within what these let sections hold)."""
        d = self.description
        pr = d.principal
        c = d.curves
        x0, x1 = d.x_aft, d.x_fore
        half_b = pr.breadth / 2
        out = {"profile": solve_curve("profile", c["profile"], x0, x1, lower=-pr.draft, upper=pr.depth, maximum=False)}
        xa, xf = immersed_range(out["profile"], pr.draft)
        out["dwl"] = solve_curve("dwl", c["dwl"], xa, xf, lower=0.0, upper=half_b)
        xs = np.linspace(xa, xf, DECK_CHECKS)
        clear = [(float(x), float(y), "deck >= DWL") for x, y in zip(xs, out["dwl"](xs))]
        out["deck"] = solve_curve("deck", c["deck"], x0, x1, lower=0.0, upper=half_b, at_least=clear)
        for name, lo, hi, default in (("flare", -0.9, 2.0, 0.0), ("keel_angle", -90.0, 80.0, -90.0)):
            spec = c.get(name, BasicCurveSpec(value=default))
            out[name] = solve_curve(name, spec, x0, x1, lower=lo, upper=hi, maximum=False)
        # Forward, the keel angle follows the stem: the waterlines leave it at the DWL's entrance
        # angle unless the description names another.
        ka = c.get("keel_angle")
        stem_angle = ka.stem_angle if ka is not None and ka.stem_angle is not None else self._entrance_angle(out["dwl"])
        out["keel_angle"] = StemKeelAngle(out["keel_angle"], out["profile"], stem_angle, pr.lpp / 2, FINE_STEM * pr.draft)
        if "deck_angle" in c:
            out["deck_angle"] = solve_curve("deck_angle", c["deck_angle"], x0, x1, lower=-80.0, upper=80.0)
        if "skeg" in c:
            out["skeg"] = solve_curve("skeg", c["skeg"], x0, x1, lower=0.0, upper=half_b)
            out["skeg_top"] = solve_curve("skeg_top", c["skeg_top"], out["skeg"].x_start, out["skeg"].x_end,
                                          lower=-pr.draft, upper=pr.depth)
        return out

    def _fullness_bands(self) -> list[tuple[float, float, float]]:
        """(x, least, largest) fullness of the section at each station inside the waterline's
        range: what a fair section through its DWL point between its deck and keel can hold,
        shrunk by BAND_MARGIN (fairlines.section_fullness_bands)."""
        xs = self.stations()
        xa, xf = self.immersed_range()
        xs = xs[(xs > xa) & (xs < xf)]
        specs = self.section_specs(xs, with_area=False)
        # Only the stations whose immersed box is small (the waterline's ends) can be held to a
        # narrow fullness; the others take the SAC's general bounds.
        pr = self.description.principal
        small = [i for i, q in enumerate(specs)
                 if np.isfinite(q.y_dwl) and q.y_dwl * (q.draft - q.z_keel) < BAND_BOX * pr.breadth * pr.draft / 2]
        xs, specs = xs[small], [specs[i] for i in small]
        band = np.asarray(_native.section_fullness_bands(specs))
        out = []
        for x, (lo, hi) in zip(xs, band):
            if np.isfinite(lo) and np.isfinite(hi):
                hi = min(hi, 1.0)
                w = max(hi - lo, 0.0)
                a, b = lo + BAND_MARGIN[0] * w, hi - min(BAND_MARGIN[1] * w, BAND_TOP)
                out.append((float(x), float(a), float(max(a, b))))
        return out

    @staticmethod
    def _entrance_angle(dwl: BasicCurve) -> float:
        """Half angle (deg) of the DWL at its forward end, kept inside 1 .. 60 deg."""
        return float(np.clip(math.degrees(math.atan(max(-dwl.derivative(dwl.x_end, 1), 0.0))), 1.0, 60.0))

    def immersed_range(self) -> tuple[float, float]:
        """x range of the design waterline (where the centre profile is below T), m."""
        dwl = self.basic_curves["dwl"]
        return dwl.x_start, dwl.x_end

    def junctions(self) -> list[float]:
        """x where a basic curve has a flat part's end or the waterline ends."""
        d = self.description
        out = set(self.immersed_range())
        for name, spec in d.curves.items():
            for x in (spec.flat_from, spec.flat_to):
                if x is not None:
                    out.add(float(x))
        return sorted(out)

    def stations(self) -> np.ndarray:
        """Stations of the designed sections (m): the description's list, or its count clustered
        toward the ends with stations on the junctions."""
        d = self.description
        if d.station_x is not None:
            return np.asarray(d.station_x, dtype=float)
        return station_positions(d.x_aft, d.x_fore, d.station_count, self.junctions())

    # ---- sections ---------------------------------------------------------------------
    def section_specs(self, x: Any = None, with_area: bool = True) -> list:
        """fl.SectionSpec of each station (or of the given x, m), read off the basic curves
        (without the SAC's area when `with_area` is false)."""
        d = self.description
        pr = d.principal
        bc = self._curves if not with_area else self.basic_curves
        xs = self.stations() if x is None else np.atleast_1d(np.asarray(x, dtype=float))
        tol = 1e-9 * pr.lpp
        if np.any(xs < d.x_aft - tol) or np.any(xs > d.x_fore + tol):
            raise _native.InvalidInput(f"x is {xs.tolist()}; expected stations on the hull ({d.x_aft} to {d.x_fore} m)")
        half_b = pr.breadth / 2
        names = ("deck", "profile", "dwl", "flare", "keel_angle") + (("sac",) if with_area else ())
        cols = {name: bc[name](xs, outside=math.nan) for name in names}
        deck_angle = bc["deck_angle"](xs) if "deck_angle" in bc else None
        skeg = (bc["skeg"](xs, outside=0.0), bc["skeg_top"](xs, outside=math.nan)) if "skeg" in bc else None
        specs = []
        for i, xi in enumerate(xs):
            s = _native.SectionSpec()
            s.x, s.y_max, s.n_control = float(xi), half_b, d.section_n_control
            s.y_deck = float(np.clip(cols["deck"][i], 0.0, half_b))
            s.z_deck = pr.depth
            s.z_keel = float(min(cols["profile"][i], pr.depth))
            s.alpha_keel = float(cols["keel_angle"][i])
            s.z_inflection = _inflection_height(pr.draft, s.z_keel, pr.depth, s.alpha_keel)
            if deck_angle is not None:
                s.alpha_deck = float(deck_angle[i])
            else:
                s.flare = float(cols["flare"][i])
            y_dwl = cols["dwl"][i]
            if np.isfinite(y_dwl) and y_dwl > NO_DWL_FRACTION * half_b and pr.draft - s.z_keel > NO_DWL_FRACTION * pr.draft:
                s.draft, s.y_dwl = pr.draft, float(min(y_dwl, half_b))
                if with_area:
                    s.half_area = float(max(cols["sac"][i], 0.0) / 2)
            if skeg is not None and skeg[0][i] > 0 and np.isfinite(skeg[1][i]):
                s.skeg_half_thickness = float(skeg[0][i])
                s.skeg_bottom = s.z_keel + float(skeg[0][i])
                s.skeg_top = float(skeg[1][i])
            specs.append(s)
        return specs

    @property
    def sections(self) -> list:
        """Section curves (3-D NurbsCurves, deck to keel, x order), all on one knot vector."""
        if self._sections is None:
            try:
                self._sections = list(_native.design_sections(self.section_specs()))
            except _native.InfeasibleFormParameters:
                if self._banded:
                    raise
                # A section cannot hold what the SAC asks: design the SAC again inside the
                # fullness every station's section can have, and the sections with it.
                self._curves = None
                self._curves = self._solve_curves(with_bands=True)
                self._sections = list(_native.design_sections(self.section_specs()))
        return self._sections

    def sections_at(self, x: Any) -> list:
        """The designed sections at any x (m), between the stations too."""
        return list(_native.design_sections(self.section_specs(x)))

    # ---- surface --------------------------------------------------------------------
    def skin(self):
        """The SkinResult of skinning the sections (cached)."""
        if self._skin is None:
            d = self.description
            self._skin = fair_skin(self.sections, params="station", e2=d.skin_e2, e3=d.skin_e3, hold_runs=True)
        return self._skin

    def bare_hull_surface(self) -> _native.NurbsSurface:
        """The half hull y >= 0: u from the deck to the keel, v from the aft to the forward end."""
        return self.skin().surface

    def hydrostatics(self, draft: float | None = None, **options) -> _native.Hydrostatics:
        """fl.hydrostatics of the bare hull at `draft` (default T), both sides, coefficients on
        Lpp and B with the midship section at Lpp / 2 (options override)."""
        d = self.description
        pr = d.principal
        options.setdefault("length", pr.lpp)
        options.setdefault("breadth", pr.breadth)
        options.setdefault("midship_x", pr.lpp / 2)
        return _native.hydrostatics(self.bare_hull_surface(), pr.draft if draft is None else draft, **options)

    # ---- bulbous bow ----------------------------------------------------------------
    def ship_particulars(self) -> dict[str, float]:
        """What a bulbous bow is sized from (fairlines.BulbousBow): Lpp, B, T at the FP, the FP
        at x = Lpp, A_MS (both sides) at Lpp / 2 and the ship's displacement volume (the bulb
        section's ``displacement_volume``, or the hull's own when it is the whole ship)."""
        d = self.description
        pr = d.principal
        key = (id(self.skin()), repr(d.bulb.to_dict() if d.bulb else None))
        if self._ship is not None and self._ship[0] == key:
            return dict(self._ship[1])
        h = self.hydrostatics()
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
        overrides (Kracht coefficients or shape controls) replace the section's."""
        from .compose import BulbousBow
        from .description import BulbSpec

        d = self.description
        if d.bulb is None and not overrides:
            raise _native.InvalidInput('bulb is missing; expected a "bulb" section in the hull description')
        spec = d.bulb if d.bulb is not None else BulbSpec()
        return BulbousBow(**self.ship_particulars(), **{**spec.kracht, **spec.shape, **overrides})

    def composed_hull(self, blend: bool = True, bulb=None, **compose_options):
        """Bare hull + bulbous bow (+ a C1 blend when ``blend``) composed into one watertight half
        hull (fairlines.ComposedHull). InvalidInput when the bulb does not meet the hull."""
        from .compose import compose_with_blend

        b = self.bulbous_bow() if bulb is None else bulb
        return compose_with_blend(self.bare_hull_surface(), b, blend=blend, **compose_options)

    # ---- fairness -------------------------------------------------------------------
    def fairness_report(self, **kwargs) -> dict:
        """fairlines.fairness.fairness_report of the bare hull (cuts judged on their own)."""
        from .fairness import fairness_report

        pr = self.description.principal
        kwargs.setdefault("draft", pr.draft)
        return fairness_report(self.bare_hull_surface(), **kwargs)



def _integer(path: str, value: Any, lo: int | None) -> int:
    """value as an int, or InvalidInput naming `path` (kept for fairlines.compose)."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or (lo is not None and int(value) < lo):
        raise _native.InvalidInput(f"{path} is {value!r}; expected {'an integer' if lo is None else f'an integer >= {lo}'}")
    return int(value)
