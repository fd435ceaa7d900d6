"""Real hull data back as a whole-ship design: measure the data, write a hull description.

``fl.import_design(hull_data)`` (hull_data a :class:`fairlines.offsets.HullData`) returns a
description dict (fairlines.description) that ``fl.Hull.from_dict`` builds. What is measured:

* stations across the data (its own stations for an offsets table; for point grids, plane
  cuts x = const of the grid's longitudinal lines), each reduced to its half-breadth y(z): the
  largest y of the section at each height;
* Lpp, B, T from the data (as the reader gives them), D the top of the data, the ends
  (aft-most and fore-most points: transom or stern, stem head);
* per station: the lowest point (the centre-line contour: keel, counter, forefoot, stem), the
  half-breadth at T (the design waterline) and at D (the deck line), the area below T;
  the volume and LCB by Simpson integration of those areas;
* the transom: its lower edge height and, when immersed, its width at T.

The basic curves pass near these measurements (``fit`` points); the SAC holds the measured
volume and LCB exactly and stays near the measured section fullness. An end station with no
breadth at any height below T is a vertical post (``ends.aft_post`` / ``fore_post``). The section
shape curves (the bilge corner ``corner_breadth`` / ``corner_height`` and ``top_corner``) are then
fitted per station: each is the value whose designed section (``fl.design_section`` with the
station's measured area) lies closest, in the least-squares sense, to the measured half-breadths. A bulb grid (role 'bulb') is left out of
the bare hull and measured into the ``bulb`` section's Kracht coefficients (cuts of its grid
from the FP to the nose); where the measured shapes are given (sections.given) it is measured
as hull instead and the given sections hold it (the notes name its Kracht coefficients). Hull below the keel line (a sonar dome) and above the deck at
midships (a sheer) is left out and noted: the description has neither.
"""

from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np

from . import _native, monotone_cubic
from .basic_curves import tersely
from .dry_ends import section_half_breadth
from .offsets import HullData, Section, lowest_at_each_x
from .preprocess.rebuild import distances

__all__ = ["import_design", "measure_hull_data", "measure_kracht", "MeasuredHull", "point_deviation", "data_points",
           "fidelity"]

#: Stations cut from a point grid (cosine-clustered toward both ends), and where the measured
#: shapes are given (they follow a dome's or a transom's quick changes along the hull).
GRID_STATIONS = 81
GIVEN_STATIONS = 161
#: A grid whose rows each lie within this fraction of Lpp of one x is cut into sections: where
#: shapes are given, its rows are the stations over its range (stations between them would be
#: cut from the chords joining the rows, which kink at each row and make the skin ring: DTMB
#: 5415's main grid waterlines 9-37 curvature sign changes against 1-9 at its rows, the whole
#: ship's cuts 822 against 438).
SECTION_ROW_TOL = 1e-2
#: ... but a row whose x range exceeds this share of its distance to the next is raked (DTMB
#: 5415's first row, 29 mm over 216 mm: its transom's lower edge) and stations cut it instead:
#: as a station it left the knuckle under the transom between stations, the keel line dipping.
SECTION_ROW_RAKE = 0.05
#: ... and a station cut between them is kept where the data there strays this far (of B) from
#: the straight line between the stations either side (_unlike_their_neighbours).
GIVEN_REFINE_TOL = 1e-2
#: ... where the basic curves then have a knot span per station, at most this many.
CLOSE_SPANS = 160
#: Two hull grids whose x ranges meet within this fraction of Lpp join there (skinning.knuckles).
JOINT_TOL = 1e-6
#: Heights at which each station's half-breadth y(z) is sampled.
Z_SAMPLES = 241
#: Fit weight of the measured points on the section shape curves (relative to fairness).
FIT_WEIGHT = 1.0e3
#: ... and on the basic curves, made dimensionless: weight w of the misfit squared against the
#: bending energy int f''^2 dx is FIT_STIFFNESS h^2 / Lpp^3, h the curve's scale (T for the
#: profile and sheer, B for the waterline and deck, B T for the SAC): the same pull at model
#: and at full scale (1e3 for the KCS at 230 m).
FIT_STIFFNESS = 1.0e10
#: Knot spans of the measured basic curves.
CURVE_SPANS = {"profile": 40, "dwl": 30, "deck": 24, "sac": 30}
# A contour point (an offsets table's stem or stern row) within this fraction of Lpp of a
# station is on it: the station's own lowest point holds there.
STATION_MATCH = 1e-6
#: Candidate values tried per station for each section shape curve: the bilge corner (its
#: breadth and height fractions, searched together on this grid) and the top corner.
CORNER_GRID = {"corner_breadth": np.linspace(0.05, 1.0, 11), "corner_height": np.linspace(0.0, 0.9, 10)}
TOP_CANDIDATES = np.linspace(0.1, 0.9, 9)
#: Pull of a station's corner toward its neighbour's (toward midships), as a misfit of this
#: fraction of B per unit distance in the (breadth, height) fractions: of near-equal fits the
#: one that continues the neighbour's wins, so the fitted curves stay fair.
CORNER_PULL = 0.01
#: Candidates of the template family's shape curves (fitted where a bulb cannot be composed
#: with the fitted corners' bow).
TEMPLATE_CANDIDATES = {"character": np.linspace(0.1, 0.9, 17), "deadrise": np.linspace(0.0, 30.0, 13),
                       "top_corner": TOP_CANDIDATES}
TEMPLATE_PASSES = 2
#: Refinement of the grid's best corner: coordinate steps (fractions), halved each pass.
CORNER_STEP, CORNER_PASSES = 0.05, 5
#: Bounds of the fitted shape curves, inside the section generator's: the spline's own bound is
#: met to the solver's round-off only.
SHAPE_BOUNDS = {"corner_breadth": {"lower": 0.03, "upper": 1.0}, "corner_height": {"lower": 0.0, "upper": 0.92},
                "top_corner": {"lower": 0.06, "upper": 0.94}, "character": {"lower": 0.06, "upper": 0.94},
                "deadrise": {"lower": 1e-3, "upper": 39.0}}
#: A fitted top corner must lower the station's misfit by this fraction to replace the default.
MISFIT_GAIN = 0.01
#: Knot spans of the fitted shape curves.
SHAPE_SPANS = 24
#: An end station whose half-breadth stays below this fraction of B/2 at every height is a
#: vertical post of zero width.
POST_FRACTION = 1e-3
#: A station whose waterline or immersed depth is below this fraction of B/2 or T is an end
#: station: its shape is not fitted (it follows its neighbours).
END_FRACTION = 0.08
#: Least stations an import needs (a hull description's least).
MIN_IMPORT_STATIONS = 4
#: Depth is measured within this fraction of Lpp of midships.
MIDSHIP_BAND = 0.05
#: Heights within this fraction of a section's height above its keel point are not compared
#: in the section fits.
KEEL_BAND = 1e-3
#: Data this far (fraction of T) below the keel line is a dome, not hull.
KEEL_TOL = 0.01
#: Stations cut from a bulb grid between the FP and the nose.
BULB_STATIONS = 41
#: Bisection steps toward the measured LCB when the sections cannot hold it.
LCB_BISECTIONS = 12
#: Volume and LCB corrections on the built surface (as the designer does).
MATCH_TOL = 1e-5
#: A station whose shape the fitted section family misses by more than this fraction of B
#: (RMS of the half-breadths) makes the importer give every measured station's shape.
GIVEN_MISFIT = 0.0025
#: Control points of each section when shapes are given (a skeg, a stern bulb need more
#: than the family's 20).
GIVEN_CONTROLS = 32
#: A deck edge that leaves D by more than this fraction of D somewhere is a sheer (a basic curve).
SHEER_TOL = 0.005
#: A change of the centre-line contour's slope dz/dx by more than this between stations is a
#: knot of the profile (it must turn quickly there).
PROFILE_TURN = 0.5
#: A waterline or deck line holds a flat of side where its half-breadths lie this close to B/2
#: (fractions of B/2): clipped to B/2 for the family's curves, as measured for close curves.
SIDE_FLAT_TOL, CLOSE_FLAT_TOL = 2e-3, 1e-4
#: Sides flaring beyond B by more than this fraction of B make the description's B_max.
FLARE_TOL = 1e-3
#: Given sections: least heights a station needs, and what counts as no breadth or no height
#: (fractions of B and D).
GIVEN_MIN_POINTS = 4
GIVEN_FLAT_TOL = 1e-4
#: Where the data's centre-plane contour has a nose inside the ends (a dome's forward end), the
#: next station lies this fraction of Lpp forward of it (on the stem above). DTMB 5415 measured
#: alike from 0.15 to 0.25 % (wetted surface +0.89 to +0.95 %); at 0.03 % the skin overshoots
#: across the step (the nose lost: max 2.25 % B), from 0.3 % the stem's foot is cut (max 1.82 %).
NOSE_GAP = 2e-3
#: A centre-plane line of the aft half that ends with no other going on aft within this fraction
#: of the contour's height of its end is a tail (KCS's propeller boss end under its counter),
#: and a station is put there (the cosine stations fell 0.6 and 0.4 m either side of it).
TAIL_HEIGHT = 0.1
#: Points of each given section, evenly along it (deck edge, side, bottom to the centre plane).
GIVEN_SHAPE_POINTS = 301
#: Bending penalty of a measured shape's fit against its points (sections.given_smoothing; the
#: engine's default 1e-6 near-interpolates a shape read off fair lines). Its points carry the
#: data's noise and the interpolation between offsets, which near-interpolated rang at a flat's
#: edge and between the offsets. From 1e-6, fairness report's sign changes (waterlines / buttocks /
#: frames / diagonals) and RMS distance to the data (% of B): Series 60 83 / 65 / 110 / 33,
#: 0.082 -> 63 / 41 / 47 / 29, 0.105; KCS 98 / 117 / 73 / 78, 0.067 -> 87 / 104 / 39 / 54, 0.081;
#: DTMB 5415 121 / 91 / 114 / 55, 0.200 -> 110 / 70 / 25 / 52, 0.221. 0.01: about half the gain;
#: 1.0: RMS 0.14 / 0.14 / 0.34 % and KCS's buttocks back to 123.
MEASURED_SHAPE_SMOOTHING = 0.1
#: Where a section list's fore end station starts this fraction of T or more above its neighbour
#: (a forefoot within one station spacing), stations are picked up between the two, one more per
#: this much of the rise: a skin through the two alone swung its rows under the keel (Series 60:
#: 0.51 m below the base at x 117.8 m).
END_RISE_STEP = 0.25


@dataclasses.dataclass
class MeasuredHull:
    """What :func:`measure_hull_data` reads off the data (metres, x from the AP)."""

    lpp: float
    beam: float
    draft: float
    depth: float
    x_aft: float
    x_fore: float
    x: np.ndarray           # stations
    z: np.ndarray           # heights of the half-breadth samples
    y: np.ndarray           # (stations, heights) half-breadth, NaN where the station has no hull
    z_low: np.ndarray       # lowest point of each station
    area: np.ndarray        # area below T (both sides) per station
    volume: float
    lcb: float
    bulb_points: np.ndarray | None = None
    notes: list = dataclasses.field(default_factory=list)
    z_top: np.ndarray | None = None  # highest point of each station (the deck edge: the sheer)
    contour: np.ndarray | None = None  # (n, 2) centre-plane contour points (x, z) off the stations

    def half_breadth(self, k: int, z0: float) -> float:
        """Half-breadth of station k at height z0 (NaN outside the section)."""
        return float(np.interp(z0, self.z, self.y[k], left=np.nan, right=np.nan))


def _crossings(lines: np.ndarray, x0: float) -> np.ndarray:
    """(y, z) where each polyline of `lines` (m lines, n points, 3) crosses the plane x = x0."""
    p, q = lines[:, :-1], lines[:, 1:]
    dp, dq = p[..., 0] - x0, q[..., 0] - x0
    hit = (dp * dq <= 0) & (p[..., 0] != q[..., 0])
    t = np.where(hit, dp / np.where(hit, dp - dq, 1.0), 0.0)
    pts = p + t[..., None] * (q - p)
    return pts[hit][:, 1:]


def _longitudinal_lines(points: np.ndarray) -> np.ndarray:
    """A grid's lines that run along the hull (the index direction in which x changes most)."""
    dx0 = np.abs(np.diff(points[..., 0], axis=0)).mean()
    dx1 = np.abs(np.diff(points[..., 0], axis=1)).mean()
    return points.transpose(1, 0, 2) if dx0 >= dx1 else points


def _smooth_in_z(zs: np.ndarray, ys: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Half-breadths of an offsets column between its waterlines by the shape-preserving
    cubic, so a round bilge is not cut by chords."""
    keep = np.concatenate([np.diff(zs) > 0, [True]])  # of equal heights the outermost (last)
    if keep.sum() < 3:
        return np.interp(z, zs[keep], ys[keep])
    return monotone_cubic.evaluate(zs[keep], ys[keep], z)


def _half_breadths(pieces: list, z: np.ndarray, smooth: bool = False) -> np.ndarray:
    """Largest y at each height z over the section pieces ((n, 2) (y, z), ordered along the
    section); NaN where no piece reaches. `smooth`: the pieces are offsets (few points per
    section), interpolated by a monotone cubic instead of chords."""
    out = np.full(z.shape, np.nan)
    for p in pieces:
        if len(p) < 2:
            continue
        order = np.argsort(p[:, 1], kind="stable")
        ys, zs = p[order, 0], p[order, 1]
        inside = (z >= zs[0]) & (z <= zs[-1])
        if inside.any():
            y = _smooth_in_z(zs, ys, z[inside]) if smooth else np.interp(z[inside], zs, ys)
            out[inside] = np.fmax(out[inside], y)
    return out


def _cut_points(lines: np.ndarray, x0: float) -> np.ndarray:
    """(y, z) where a grid's lines along the hull and its two boundary lines across them (a
    stem's or a dome's contour on the centre plane, where the lines along the hull end) cross
    the plane x = x0; without the boundaries a station just aft of a raked stem would stop at
    the nearest line above it."""
    edges = np.stack([lines[:, 0], lines[:, -1]])
    return np.concatenate([_crossings(lines, x0), _crossings(edges, x0)])


def _stations(data: HullData, lines: list, count: int = GRID_STATIONS, noses: bool = False,
              rows: list = ()) -> np.ndarray:
    """Stations: an offsets table's own, or `count` cosine-clustered across the grids; with
    `noses`, a station on each nose of the centre-plane contour inside the ends (a sonar dome's
    forward end under a stem that recedes above it) and one NOSE_GAP of Lpp forward of it, on the
    stem, so the profile can step up there (the cosine stations within NOSE_GAP of them dropped),
    and one on each tail of its aft half (:func:`_contour_tails`).
    `rows`: x of grids' section rows (:func:`_section_rows`), the stations over their ranges."""
    if data.sections:
        return np.array(sorted(s.x for s in data.sections))
    xs = np.concatenate([ln[..., 0].ravel() for ln in lines])
    lo, hi = float(xs.min()), float(xs.max())
    s = np.linspace(0.0, 1.0, count)
    x = lo + (hi - lo) * 0.5 * (1 - np.cos(np.pi * s))
    span = hi - lo
    x = np.clip(x, lo + 1e-6 * span, hi - 1e-6 * span)
    if noses:
        gap = NOSE_GAP * data.lpp
        extra = [v for n in _contour_noses(lines, data.beam) if lo + 2 * gap < n < hi - 2 * gap for v in (n, n + gap)]
        if extra:
            keep = np.min(np.abs(x[:, None] - np.array(extra)[None, :]), axis=1) > gap
            x = np.union1d(x[keep], extra)
        x = np.union1d(x, [t for t in _contour_tails(lines, data.beam, gap) if lo + 2 * gap < t < data.lpp / 2])
    for r, spread in rows:
        x = _with_rows(x, np.sort(r), spread)
    return x


def _section_rows(grids: list, lpp: float) -> list:
    """(x, x range) of the rows of each grid whose rows lie each within SECTION_ROW_TOL of Lpp of
    one x and apart from each other (each row's x range less than the gap between rows' mean x:
    its sections, at least 3; a transom's lines, all within a few cm of each other, are not)."""
    out = []
    for g in grids:
        rows = _row_spread(g.points, lpp)
        if rows is not None:
            spread, mean = rows
            gap = np.minimum(np.abs(np.diff(mean, prepend=np.inf)), np.abs(np.diff(mean, append=np.inf)))
            square = spread <= SECTION_ROW_RAKE * gap  # a raked row (a transom's edge) is left to the stations
            if square.sum() >= 3:
                out.append((mean[square], float(spread[square].max())))
    return out


def _row_spread(points: np.ndarray, lpp: float) -> tuple[np.ndarray, np.ndarray] | None:
    """(x range, mean x) of each row of the grid's `points`, in the direction whose rows are
    sections (:func:`_section_rows`), or None when neither direction's are."""
    for p in (points, points.transpose(1, 0, 2)):
        spread, mean = np.ptp(p[..., 0], axis=1), p[..., 0].mean(axis=1)
        if len(p) >= 3 and spread.max() <= SECTION_ROW_TOL * lpp and np.abs(np.diff(mean)).min() > spread.max():
            return spread, mean
    return None


def _with_rows(x: np.ndarray, r: np.ndarray, spread: float) -> np.ndarray:
    """The stations `x` with the rows `r` instead of those over the rows' range, the stations
    beyond it (cosine-clustered toward the hull's ends) thinned outward from the end rows, each
    interval at least half the last and the hull's end kept: the skin overshoots a long interval
    next to short ones (across DTMB 5415's transom, 1-10 mm apart, into its first row interval of
    216 mm it sagged 9 cm below the data). Where the data changes quickly among the thinned ones,
    _given_measure takes them back (:func:`_unlike_their_neighbours`). No station lies within a
    row's own x range (`spread`, m) of the end rows: it would cut across that row's points (DTMB
    5415's sections then hold no SAC)."""
    out, inside = [r], (x >= r[0]) & (x <= r[-1])
    for end, near, sign in ((r[0], r[1], -1.0), (r[-1], r[-2], 1.0)):
        beyond = np.sort(sign * (x[~inside] - end))
        beyond = beyond[beyond >= spread]
        if not len(beyond):
            continue
        kept, last, step = [], 0.0, abs(near - end)
        for b in beyond[:-1]:
            if b - last >= 0.5 * step:
                kept.append(b)
                step, last = b - last, b
        out.append(end + sign * np.append(kept, beyond[-1]))  # the hull's end kept
    return np.unique(np.concatenate(out))


def _contour_noses(lines: list, beam: float) -> list:
    """x of the interior forward extremes (noses) of the grids' boundary lines on the centre
    plane (y within GIVEN_FLAT_TOL of B)."""
    out = []
    for ln in lines:
        for edge in (ln[:, 0], ln[:, -1]):
            on = edge[:, 1] <= GIVEN_FLAT_TOL * beam
            x = edge[:, 0]
            for i in range(1, len(edge) - 1):
                if on[i - 1:i + 2].all() and x[i] >= x[i - 1] and x[i] >= x[i + 1] and x[i] > min(x[i - 1], x[i + 1]):
                    out.append(float(x[i]))
    return out


def _contour_tails(lines: list, beam: float, gap: float) -> list:
    """x of the aft ends of the grids' centre-plane lines (each grid's first and last longitudinal
    line, where on the centre plane: y within GIVEN_FLAT_TOL of B) that no centre-plane line goes
    on aft from: none of them lies more than `gap` aft within TAIL_HEIGHT of the contour's height
    (not where two grids join)."""
    edges = [e for ln in lines for e in (ln[0], ln[-1]) if (e[:, 1] <= GIVEN_FLAT_TOL * beam).all()]
    if not edges:
        return []
    pts = np.concatenate(edges)
    reach = TAIL_HEIGHT * float(np.ptp(pts[:, 2]))
    out = []
    for e in edges:
        t = e[int(np.argmin(e[:, 0]))]
        if not np.any((pts[:, 0] < t[0] - gap) & (np.abs(pts[:, 2] - t[2]) < reach)):
            out.append(float(t[0]))
    return out


def measure_hull_data(data: HullData, depth: float | None = None, dome: bool = False,
                      stations: int = GRID_STATIONS, bulb: bool = False, noses: bool = False,
                      rows: bool = False, extra: tuple | list | np.ndarray = ()) -> MeasuredHull:
    """Stations, half-breadths, lowest points, areas, volume and LCB of the data (module
    docstring); hull below the keel line (a sonar dome) is measured with `dome`, else left out;
    point grids are cut at `stations` stations; with `bulb` a bulb grid is measured as hull
    (its stations reach the centre plane's web up to D: :func:`_bulb_webs`), else set apart.
    `noses`: stations on the centre-plane contour's noses too (:func:`_stations`); `rows`: a
    grid's section rows are its stations (:data:`SECTION_ROW_TOL`); `extra`: more stations (m).
    Raises InvalidInput for data with fewer than 3 stations with hull below T."""
    hull_grids = [g for g in data.grids if bulb or g.role != "bulb"]
    lines = [_longitudinal_lines(g.points) for g in hull_grids]
    xs = _stations(data, lines, stations, noses, _section_rows(hull_grids, data.lpp) if rows else ())
    xs = np.union1d(xs, extra) if len(extra) else xs
    allp = np.concatenate([data.all_points()] if data.sections else [g.points.reshape(-1, 3) for g in hull_grids])
    D = float(depth if depth is not None else _depth_at_midship(allp, data))
    if depth is None and not D > data.draft:
        raise _native.InvalidInput(f"{data.name}: the data's top near midships is z = {D:.6g} m, not above T = "
                                   f"{data.draft:.6g} m (blank cells, or data that stop at the waterline?); expected "
                                   "the deck above T: give the depth (--depth)")
    zlo = float(allp[:, 2].min())
    z = np.linspace(zlo, max(D, float(allp[:, 2].max())), Z_SAMPLES)
    T = data.draft
    if not np.any(np.isclose(z, T)):
        z = np.sort(np.append(z, T))
    keel = _keel_height(allp, data)
    notes = []
    if zlo < keel - KEEL_TOL * T and not dome:
        notes.append(f"hull below the keel line (a sonar dome, to z = {zlo:.4g} m) left out: the description has no dome")
        z = z[z >= keel]
    elif zlo < keel - KEEL_TOL * T:
        notes.append(f"hull below the keel line (a sonar dome, to z = {zlo:.4g} m) held by the given sections")
    y = np.full((len(xs), len(z)), np.nan)
    z_low = np.full(len(xs), np.nan)
    by_x = {s.x: s for s in data.sections}
    for k, x0 in enumerate(xs):
        pieces = [by_x[x0].points] if data.sections else [_cut_points(ln, x0) for ln in lines]
        pieces = [p for p in pieces if len(p)]
        if not pieces:
            continue
        y[k] = _half_breadths(pieces, z, smooth=bool(data.sections))
        z_low[k] = max(min(p[:, 1].min() for p in pieces), z[0])
    on = np.isfinite(z_low) & (z_low < D) & np.isfinite(y).any(axis=1)  # stations with hull below the deck
    xs, y, z_low = xs[on], y[on], z_low[on]
    below = z <= T
    yb = np.nan_to_num(y[:, below])
    area = 2.0 * np.trapezoid(yb, z[below], axis=1)
    wet = area > 0
    if wet.sum() < 3:
        raise _native.InvalidInput(f"{data.name}: {int(wet.sum())} station(s) with hull below T = {T} m; expected at least 3")
    if len(xs) < MIN_IMPORT_STATIONS:
        raise _native.InvalidInput(f"{data.name}: {len(xs)} station(s) with hull below the deck; expected at least "
                                   f"{MIN_IMPORT_STATIONS} (a description's sections)")
    vol = monotone_cubic.integral(xs, area)
    lcb = monotone_cubic.integral(xs, area * xs) / vol
    apart = [g.points.reshape(-1, 3) for g in data.grids if g.role == "bulb" and not bulb]
    z_top = np.array([z[np.flatnonzero(np.isfinite(row))[-1]] for row in y])
    if bulb:
        z_top = _bulb_webs(xs, z, y, z_top, D, T)
    contour = _off_station_contour(data.contour, xs, data.lpp)
    ends = (float(xs[0]), float(xs[-1]))
    if len(contour):  # a stem or stern row reaching past the end stations moves the hull's ends there
        ends = (min(ends[0], float(contour[0, 0])), max(ends[1], float(contour[-1, 0])))
    return MeasuredHull(data.lpp, data.beam, T, D, *ends, xs, z, y, z_low, area, vol, lcb,
                        np.concatenate(apart) if apart else None, notes, z_top, contour)


def _off_station_contour(contour: np.ndarray, xs: np.ndarray, lpp: float) -> np.ndarray:
    """The centre-plane contour points (x, z) that are not on a station, in x order, the lowest
    at each x (fairlines.offsets.lowest_at_each_x)."""
    c = lowest_at_each_x(contour)
    return c[np.min(np.abs(c[:, :1] - xs[None, :]), axis=1) > STATION_MATCH * lpp] if len(c) else c


def _bulb_webs(x: np.ndarray, z: np.ndarray, y: np.ndarray, z_top: np.ndarray, D: float, T: float) -> np.ndarray:
    """Webs of zero half-breadth on the centre plane (`y` edited), which the hull's sections
    (each one curve from the keel to the deck) need to hold a bulb: across a station's open
    heights between hull below and above (a raked stem head over the bulb), and from the top
    of a station forward of the stem head that ends below T up to D. Returns the stations' tops."""
    reach = np.flatnonzero(z_top >= D * (1 - SHEER_TOL))
    head = reach[-1] if len(reach) else len(x)
    for k in range(len(x)):
        rows = np.flatnonzero(np.isfinite(y[k]))
        if len(rows):  # an open height inside the section would otherwise be bridged by a chord
            gap = np.arange(rows[0], rows[-1] + 1)
            y[k, gap] = np.nan_to_num(y[k, gap])
        if k > head and z_top[k] < T:
            y[k, (z > z_top[k]) & (z <= D)] = 0.0
            z_top[k] = D
    return z_top


def _depth_at_midship(points: np.ndarray, data: HullData) -> float:
    """Depth D: the top of the data at midships (the deck at side; a sheer rises beyond it),
    over MIDSHIP_BAND of Lpp and at least the stations next to midships, so a blank top cell at
    the midship station does not lower the deck."""
    d = np.abs(points[:, 0] - data.lpp / 2)
    near = np.unique(np.round(d, 9))
    reach = max(MIDSHIP_BAND * data.lpp, near[1] if len(near) > 1 else near[0])
    return float(points[d <= reach, 2].max())


def _keel_height(points: np.ndarray, data: HullData) -> float:
    """Height of the keel line: the lowest point between 0.2 and 0.8 Lpp (a dome or bulb at the
    bow may reach lower)."""
    mid = (points[:, 0] > 0.2 * data.lpp) & (points[:, 0] < 0.8 * data.lpp)
    return float(points[mid, 2].min()) if mid.any() else float(points[:, 2].min())


# ---- basic curves from the measurements ------------------------------------------------

def _flat_run(x: np.ndarray, f: np.ndarray, value: float, tol: float, min_length: float):
    """(x_from, x_to) of the longest run of stations where |f - value| <= tol, if it is at
    least min_length long."""
    ok = np.isfinite(f) & (np.abs(f - value) <= tol)
    best, start = None, None
    for k in range(len(x) + 1):
        if k < len(x) and ok[k]:
            start = k if start is None else start
        elif start is not None:
            run = (float(x[start]), float(x[k - 1]))
            if best is None or run[1] - run[0] > best[1] - best[0]:
                best = run
            start = None
    return best if best is not None and best[1] - best[0] >= min_length else None


def _fit_weight(m: MeasuredHull, scale: float) -> float:
    """Fit weight of a basic curve of this scale (m, or m^2 for the SAC): see FIT_STIFFNESS."""
    return FIT_STIFFNESS * scale**2 / m.lpp**3


def _pairs(x, f, lo=-math.inf, hi=math.inf) -> list:
    return [[float(a), float(b)] for a, b in zip(x, f) if np.isfinite(b) and lo <= a <= hi]


def _profile_spec(m: MeasuredHull, close: bool = False) -> dict:
    """Centre-line contour through the stations' lowest points; the keel flat where it is.
    `close`: passing close to them (FIT_STIFFNESS), with knots where they turn quickly."""
    mid = (m.x > 0.2 * m.lpp) & (m.x < 0.8 * m.lpp)  # the keel line (a dome or bulb may reach lower)
    zk = float(np.nanmin(m.z_low[mid] if mid.any() else m.z_low))
    x, z_low = _with_contour(m, m.x, m.z_low)
    spec = {"fit": _pairs(x, z_low), "fit_weight": _fit_weight(m, m.draft) if close else FIT_WEIGHT,
            "spans": CURVE_SPANS["profile"],
            "yB": float(z_low[0]), "yE": float(z_low[-1])}
    # An end above the water and narrow at the deck (a stem head, a cruiser stern) closes there:
    # the profile meets D.
    top = _deck_breadths(m)
    for key, k, x_end in (("yB", 0, m.x_aft), ("yE", -1, m.x_fore)):
        if top[k] < END_FRACTION * m.beam / 2 and m.z_low[k] > m.draft and x_end == m.x[k]:
            spec[key] = float(m.z_top[k])
    flat = _flat_run(m.x, m.z_low, zk, 1e-3 * m.draft, 0.1 * m.lpp)
    if flat is not None:
        dips = np.nanmin(m.z_low) < zk - 1e-3 * m.draft  # a dome below the keel line: not monotone
        spec.update(flat_from=flat[0], flat_to=flat[1], value=zk, monotone=not dips)
        spec["fit"] = [p for p in spec["fit"] if not flat[0] <= p[0] <= flat[1]]
    if close and (breaks := _profile_breaks(m, flat)):
        spec["breaks"] = breaks
    return spec


def _with_contour(m: MeasuredHull, x: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The stations' (x, lowest z) with the contour points off the stations among them."""
    if m.contour is None or not len(m.contour):
        return x, z
    xs = np.concatenate([x, m.contour[:, 0]])
    order = np.argsort(xs, kind="stable")
    return xs[order], np.concatenate([z, m.contour[:, 1]])[order]


def _profile_breaks(m: MeasuredHull, flat) -> list:
    """Stations where the measured centre-line contour turns by more than PROFILE_TURN (a change
    of slope dz/dx: a sternpost, a transom's lower edge, a stem's foot), as knots of the profile."""
    ok = np.isfinite(m.z_low)
    x, z = m.x[ok], m.z_low[ok]
    slope = np.diff(z) / np.diff(x)
    turn = np.abs(np.diff(slope))
    out = [float(x[i + 1]) for i in np.flatnonzero(turn > PROFILE_TURN)]
    if flat is not None:
        out = [b for b in out if not flat[0] <= b <= flat[1]]
    return out


def _at(m: MeasuredHull, z0: float) -> np.ndarray:
    return np.array([m.half_breadth(k, z0) for k in range(len(m.x))])


def _dwl_spec(m: MeasuredHull, xa: float, xf: float, close: bool = False) -> dict:
    """The design waterline's half-breadths inside [xa, xf]; `close`: passing close to them,
    and a raked immersed transom (the waterline ending wide inside the hull's ends) kept."""
    half = m.beam / 2
    raw = _at(m, m.draft)
    y = raw if close else np.minimum(raw, half)
    inside = (m.x > xa) & (m.x < xf)
    spec = {"fit": _pairs(m.x[inside], y[inside]), "fit_weight": _fit_weight(m, m.beam) if close else FIT_WEIGHT,
            "spans": CURVE_SPANS["dwl"], "yE": 0.0}
    k = 0 if xa <= m.x_aft + 1e-9 * m.lpp else (int(np.argmax(inside)) if close and inside.any() else None)
    immersed_transom = k is not None and np.isfinite(y[k]) and y[k] > END_FRACTION * half
    spec["yB"] = float(min(y[k], half)) if immersed_transom else 0.0
    return _with_side_flat(spec, m, raw, half, close)


def _with_side_flat(spec: dict, m: MeasuredHull, raw: np.ndarray, half: float, close: bool) -> dict:
    """The line's spec with its flat of side (_side_flat), if any, and no fit points on it."""
    flat = _side_flat(m, raw, half, close)
    if flat is not None:
        spec.update(flat_from=flat[0], flat_to=flat[1], value=half)
        spec["fit"] = [p for p in spec["fit"] if not flat[0] <= p[0] <= flat[1]]
    return spec


def _side_flat(m: MeasuredHull, raw: np.ndarray, half: float, close: bool):
    """The flat of side of a waterline or deck line of measured half-breadths `raw` (its
    longest run at `half`, at least 0.05 Lpp long): within SIDE_FLAT_TOL of half of the values
    clipped to half, or with `close` within CLOSE_FLAT_TOL of the values themselves (a line that
    only crests at B/2, or a little beyond it, has none: a flat forced on it would end in a
    quick turn, and a close fit rings there)."""
    if close:
        return _flat_run(m.x, raw, half, CLOSE_FLAT_TOL * half, 0.05 * m.lpp)
    return _flat_run(m.x, np.minimum(raw, half), half, SIDE_FLAT_TOL * half, 0.05 * m.lpp)


def _deck_breadths(m: MeasuredHull) -> np.ndarray:
    """Half-breadth of each station at its deck edge (its highest point)."""
    return np.array([row[np.flatnonzero(np.isfinite(row))[-1]] for row in m.y])


def _sheer_spec(m: MeasuredHull, close: bool = False) -> dict | None:
    """The deck edge's height where it leaves D by more than SHEER_TOL of D (None: no sheer)."""
    if np.max(np.abs(m.z_top - m.depth)) <= SHEER_TOL * m.depth:
        return None
    ends = [float(m.z_top[0]), float(m.z_top[-1])]
    if m.x_aft < m.x[0]:  # a contour reaching past the stations: the deck edge ends on its end point
        ends[0] = float(m.contour[0, 1])
    if m.x_fore > m.x[-1]:
        ends[1] = float(m.contour[-1, 1])
    return {"fit": _pairs(m.x, m.z_top), "fit_weight": _fit_weight(m, m.draft) if close else FIT_WEIGHT, "spans": CURVE_SPANS["deck"],
            "yB": ends[0], "yE": ends[1]}


def _max_breadth(m: MeasuredHull) -> dict:
    """{"B_max": ...} where the data's sides flare beyond B/2 by more than FLARE_TOL of B."""
    widest = 2 * float(np.nanmax(m.y))
    return {"B_max": widest} if widest > m.beam * (1 + FLARE_TOL) else {}


def _deck_spec(m: MeasuredHull, close: bool = False) -> dict:
    half = _max_breadth(m).get("B_max", m.beam) / 2
    raw = _deck_breadths(m)
    y = raw.copy() if close else np.minimum(raw, half)
    if _sheer_spec(m) is None:  # one deck height: a station ending below it (a stem, a stern) has no deck breadth
        y[m.z_top < m.depth * (1 - SHEER_TOL)] = 0.0
    # the aft end keeps its measured breadth (a transom); the stem head closes on the centre
    # plane where a bulb is to be composed with it, else it keeps its measured flare
    y_fore = 0.0 if m.bulb_points is not None or m.x_fore > m.x[-1] else float(y[-1])
    y_aft = 0.0 if m.x_aft < m.x[0] else float(min(y[0], half))  # past the stations: the contour's end point
    spec = {"fit": _pairs(m.x, y), "fit_weight": _fit_weight(m, m.beam) if close else FIT_WEIGHT, "spans": CURVE_SPANS["deck"],
            "yB": y_aft, "yE": y_fore}
    return _with_side_flat(spec, m, raw, half, close)


def _sac_spec(m: MeasuredHull, dwl, profile, xa: float, xf: float, close: bool = False) -> dict:
    """Volume and LCB of the data; the measured section fullness away from the ends, or with
    `close` the measured areas themselves (FIT_STIFFNESS)."""
    if close:
        return {"volume": m.volume, "lcb": m.lcb, "spans": CURVE_SPANS["sac"], "fit_weight": _fit_weight(m, m.beam * m.draft),
                "fit": [[float(x), float(a)] for x, a in zip(m.x, m.area) if a > 0]}
    box = 2 * dwl(m.x, outside=0.0) * np.maximum(m.draft - profile(m.x), 0.0)
    ok = (m.x > xa + 0.03 * (xf - xa)) & (m.x < xf - 0.03 * (xf - xa)) & (box > 0)
    s = np.where(ok, m.area / np.where(box > 0, box, 1.0), np.nan)
    s = np.clip(s, 0.05, 1.0)
    return {"volume": m.volume, "lcb": m.lcb, "spans": CURVE_SPANS["sac"], "fullness_fit": _pairs(m.x[ok], s[ok])}


def _posts(m: MeasuredHull) -> dict:
    """ends.aft_post / fore_post for an end station that reaches below T and has no breadth at
    any height (a vertical post of zero width)."""
    out = {}
    for end, k, x_end in (("aft", 0, m.x_aft), ("fore", -1, m.x_fore)):
        if x_end == m.x[k] and m.z_low[k] < m.draft and np.nanmax(np.nan_to_num(m.y[k])) <= POST_FRACTION * m.beam / 2:
            out[f"{end}_post"] = True
    return out


def _base_description(m: MeasuredHull, name: str, given: bool = False) -> dict:
    """The description of the measured basic curves; with `given`, every measured station's
    shape given (sections.given), the stations on the measured ones, the basic curves passing
    close to the measurements (FIT_STIFFNESS; knots where the profile turns quickly) and the
    SAC near the measured areas (so the given shapes need only small shifts to hold it)
    instead of near the measured fullness."""
    from .basic_curves import immersed_range, solve_curve
    from .description import BasicCurveSpec

    prof = _profile_spec(m, given)
    profile = solve_curve("profile", BasicCurveSpec.from_dict("profile", prof, "basic_curves.profile"), m.x_aft, m.x_fore,
                          lower=-m.draft, upper=float(np.max(m.z_top)), maximum=False)
    xa, xf = immersed_range(profile, m.draft)
    dwl = _dwl_spec(m, xa, xf, given)
    dwl_curve = solve_curve("dwl", BasicCurveSpec.from_dict("dwl", dwl, "basic_curves.dwl"), xa, xf, lower=0.0, upper=m.beam / 2)
    desc = {
        "name": name,
        "notes": "; ".join([f"imported: volume {m.volume:.6g} m^3, LCB {m.lcb:.6g} m from the AP measured from the data"] + m.notes),
        "principal": {"Lpp": m.lpp, "B": m.beam, "T": m.draft, "D": m.depth, **_max_breadth(m)},
        "ends": {"aft": m.x_aft, "fore": m.x_fore, **_posts(m)},
        "stations": {"count": 61},
        "sections": {"n_control": 20},
        "basic_curves": {"profile": prof, "dwl": dwl, "deck": _deck_spec(m, given),
                         "sac": _sac_spec(m, dwl_curve, profile, xa, xf, given),
                         **({"sheer": sheer} if (sheer := _sheer_spec(m, given)) is not None else {})},
    }
    if given:  # a knot span per station: the curves follow what the stations measure
        spans = min(len(m.x), CLOSE_SPANS)
        for spec in desc["basic_curves"].values():
            spec["spans"] = spans
        shapes = given_sections(m)
        desc["sections"] = {"n_control": GIVEN_CONTROLS, "given_smoothing": MEASURED_SHAPE_SMOOTHING, "given": shapes}
        desc["stations"] = {"x": [float(x) for x in m.x]}
        desc["notes"] += f"; the measured shapes of {len(shapes)} stations given (sections.given)"
    return desc


# ---- given sections: the measured shapes themselves ------------------------------------------

def measured_shape(m: MeasuredHull, k: int) -> np.ndarray | None:
    """Station k's measured half-breadths as a given section's points (y, z): from the top of
    the data (at most D) down to its lowest point, then along the bottom to the centre plane,
    resampled to GIVEN_SHAPE_POINTS evenly along the shape's length. None where the station
    holds fewer than GIVEN_MIN_POINTS heights."""
    y = m.y[k]
    ok = np.isfinite(y) & (m.z >= m.z_low[k] - 1e-12 * m.depth)
    if ok.sum() < GIVEN_MIN_POINTS:
        return None
    pts = np.column_stack([y[ok], m.z[ok]])[::-1]  # deck edge first
    if pts[-1, 1] > m.z_low[k]:
        pts = np.vstack([pts, _carried(pts[-2], pts[-1], m.z_low[k])])
    bottom = pts[-1]
    if bottom[0] > GIVEN_FLAT_TOL * m.beam:  # a flat bottom: out to the centre plane
        pts = np.vstack([pts, [0.0, bottom[1]]])
    else:
        pts[-1, 0] = 0.0
    return _even_along(pts, GIVEN_SHAPE_POINTS)


def _carried(far: np.ndarray, near: np.ndarray, z_end: float) -> np.ndarray:
    """The point (y, z_end) on the line of two samples (y, z) carried beyond `near` to the
    station's own lowest height (between the height samples), the half-breadth clamped to the
    two samples' range from 0: a shape then ends on its lowest point itself, not on whichever
    sample lies next above it (which jumps as the keel rises past the samples)."""
    y_end = near[0] + (near[0] - far[0]) * (z_end - near[1]) / (near[1] - far[1])
    return np.array([float(np.clip(y_end, 0.0, max(far[0], near[0]))), float(z_end)])


def _even_along(pts: np.ndarray, count: int) -> np.ndarray:
    """`count` points evenly along the polyline `pts` (its ends kept): a fixed count at fixed
    fractions of its length, so a shape changing a little from station to station moves its
    points a little (a height sample coming into the section would shift every fit parameter)."""
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    keep = np.concatenate([[True], np.diff(arc) > 0])
    arc, pts = arc[keep], pts[keep]
    s = np.linspace(0.0, arc[-1], count)
    return np.column_stack([np.interp(s, arc, pts[:, 0]), np.interp(s, arc, pts[:, 1])])


def given_sections(m: MeasuredHull) -> list:
    """Every measured station's shape as a given section ({"x", "points"}), but the ends'
    stations whose section is a point or a post."""
    out = []
    for k, x in enumerate(m.x):
        pts = measured_shape(m, k)
        if pts is None or np.ptp(pts[:, 1]) <= GIVEN_FLAT_TOL * m.depth or pts[:, 0].max() <= POST_FRACTION * m.beam / 2:
            continue
        out.append({"x": float(x), "points": pts.tolist()})
    return out


def _falls_below(points: np.ndarray, z0: float) -> float:
    """Half-breadth where a shape (deck edge first) first falls below z0 (NaN if never): the
    waterline point a given section is mapped by."""
    z = points[:, 1]
    i = np.flatnonzero((z[:-1] >= z0) & (z[1:] < z0))
    if not len(i):
        return math.nan
    a, b = points[i[0]], points[i[0] + 1]
    return float(a[0] + (a[1] - z0) / (a[1] - b[1]) * (b[0] - a[0]))


def _set_given_offsets(desc: dict, hull) -> None:
    """Each given section's offsets (sections.given[i].offsets) from `hull`'s basic curves to its
    own deck edge, waterline point and keel point. The curves are fair and, near corners they
    cannot turn (a waterline or deck line ending on the stem, the keel rising into a bulb), pass
    up to a few cm off the measured points, alternately above and below: shapes mapped onto them
    rang by as much from station to station (the KCS forebody's waterlines at the bulb's neck, 8-10
    curvature sign changes against 2-3 with the offsets). The keel keeps the profile's own point
    at the profile's breaks (a sternpost, a dome's nose): held at the measured step under DTMB
    5415's dome nose, 0.2 % Lpp between stations, the skin overshot (wetted surface +1.18 % for
    +0.89 %)."""
    shapes, pr = desc["sections"]["given"], desc["principal"]
    breaks = np.asarray(desc["basic_curves"]["profile"].get("breaks", []), dtype=float)
    deck, z_deck, wl, keel = hull.curve_points(np.array([g["x"] for g in shapes], dtype=float))
    for k, g in enumerate(shapes):
        pts = np.asarray(g["points"], dtype=float)
        yq = _falls_below(pts, pr["T"])
        at_break = bool(np.any(np.abs(breaks - g["x"]) <= 1e-9 * pr["Lpp"]))
        g["offsets"] = {"deck": [float(pts[0, 0] - deck[k]), float(pts[0, 1] - z_deck[k])],
                        "waterline": float(yq - wl[k]) if wl[k] > 0 and yq > 0 else 0.0,  # NaN compares false: none
                        "keel": 0.0 if at_break else float(pts[-1, 1] - keel[k])}


def station_misfit(hull, m: MeasuredHull) -> np.ndarray:
    """RMS (m) of the measured minus the built hull's designed half-breadths at each measured
    station inside the waterline's range (NaN elsewhere)."""
    xa, xf = hull.immersed_range()
    out = np.full(len(m.x), np.nan)
    inside = [k for k in range(len(m.x)) if xa < m.x[k] < xf]
    for k, spec in zip(inside, hull.section_specs([float(m.x[k]) for k in inside])):
        out[k] = _section_misfit(spec, m.z, m.y[k], need_area=False)
    return out


# ---- section shape curves, fitted per station -------------------------------------------

def _designed_half_breadth(spec, z: np.ndarray, need_area: bool = True) -> np.ndarray:
    """y(z) of the section fl.design_section makes of `spec` (NaN outside it; all NaN when the
    section cannot hold spec's area and `need_area`)."""
    design = _native.design_section(spec)
    if need_area and not design.area_met:
        return np.full(z.shape, np.nan)
    return section_half_breadth(design.curve, z, samples=201, outside=np.nan)


def _section_misfit(spec, z: np.ndarray, y: np.ndarray, need_area: bool = True) -> float:
    """RMS of measured minus designed half-breadth over the heights both hold above the keel
    point (at the keel's own height a flat bottom's half-breadth is any of its width)."""
    try:
        yd = _designed_half_breadth(spec, z, need_area)
    except (_native.InfeasibleFormParameters, _native.InvalidInput):
        return math.inf
    above = z > spec.z_keel + KEEL_BAND * (spec.z_deck - spec.z_keel)
    both = np.isfinite(yd) & np.isfinite(y) & above
    return float(np.sqrt(np.mean((yd[both] - y[both]) ** 2))) if both.sum() >= 3 else math.inf


def _corner_misfit(spec, m: MeasuredHull, y: np.ndarray, breadth: float, height: float, near) -> float:
    spec.corner_y, spec.corner_z = float(breadth), float(height)
    pull = 0.0 if near is None else CORNER_PULL * m.beam * math.hypot(breadth - near[0], height - near[1])
    return _section_misfit(spec, m.z, y) + pull


def _fit_corner(spec, m: MeasuredHull, y: np.ndarray, near=None) -> float:
    """Set spec's bilge corner to the grid point closest to the data (pulled toward `near`,
    the neighbouring station's corner), refined by coordinate steps; returns the misfit."""
    grid = [(_corner_misfit(spec, m, y, b, h, near), b, h) for b in CORNER_GRID["corner_breadth"]
            for h in CORNER_GRID["corner_height"]]
    best = min(grid)
    lo, hi = SHAPE_BOUNDS["corner_breadth"], SHAPE_BOUNDS["corner_height"]
    step = CORNER_STEP
    for _ in range(CORNER_PASSES):
        for db, dh in ((step, 0), (-step, 0), (0, step), (0, -step)):
            b = min(max(best[1] + db, lo["lower"]), lo["upper"])
            h = min(max(best[2] + dh, hi["lower"]), hi["upper"])
            best = min(best, (_corner_misfit(spec, m, y, b, h, near), b, h))
        step /= 2
    spec.corner_y, spec.corner_z = float(best[1]), float(best[2])
    return best[0]


def _fit_station(hull, m: MeasuredHull, k: int, near):
    """The fitted section spec of measured station k (None where it is not fitted)."""
    spec = hull.section_specs([float(m.x[k])])[0]
    if not spec.y_dwl > 0 or spec.y_dwl < END_FRACTION * m.beam / 2 or spec.draft - spec.z_keel < END_FRACTION * m.draft:
        return None
    spec.half_area = float(m.area[k] / 2)  # the data's own, which the SAC's fullness fit follows
    y = m.y[k]
    if not math.isfinite(_fit_corner(spec, m, y, near)):
        return None
    best = (_section_misfit(spec, m.z, y), spec.top_corner)
    for v in TOP_CANDIDATES:  # a top corner the data does not tell from the default keeps it
        spec.top_corner = float(v)
        misfit = _section_misfit(spec, m.z, y)
        best = (misfit, float(v)) if misfit < (1 - MISFIT_GAIN) * best[0] else best
    spec.top_corner = best[1]
    _fit_corner(spec, m, y, near)
    return spec


def fit_section_shapes(hull, m: MeasuredHull) -> dict:
    """Per measured station inside the hull's waterline (not at its ends), the bilge corner
    (corner_breadth, corner_height) and top_corner whose designed section is closest (least
    squares over the station's heights) to the data, the measured area setting the arc's
    weight. Stations are fitted from midships toward each end, each pulled toward the corner of
    the one before (CORNER_PULL). Returns {curve: [[x, value], ...]}."""
    xa, xf = hull.immersed_range()
    inside = [k for k in range(len(m.x)) if xa <= m.x[k] <= xf]
    mid = min(inside, key=lambda k: abs(m.x[k] - m.lpp / 2), default=None)
    fitted = {}
    for order in ([k for k in inside if k >= mid], [k for k in reversed(inside) if k <= mid]) if inside else ():
        near = fitted.get(mid)
        for k in order:
            spec = fitted.get(k) or _fit_station(hull, m, k, near)
            if spec is not None:
                fitted[k], near = spec, (spec.corner_y, spec.corner_z)
    out = {"corner_breadth": [], "corner_height": [], "top_corner": []}
    for k in sorted(fitted):
        spec = fitted[k]
        for name, value in (("corner_breadth", spec.corner_y), ("corner_height", spec.corner_z), ("top_corner", spec.top_corner)):
            out[name].append([float(m.x[k]), float(value)])
    return out


def fit_template_shapes(hull, m: MeasuredHull) -> dict:
    """Per measured station inside the hull's waterline (not at its ends), the deadrise,
    character and top_corner of the template family (no corner given) whose designed section is
    closest (least squares over the station's heights) to the data, the SAC's area setting the
    knob (clamped where the candidate cannot hold it). Returns {curve: [[x, value], ...]}."""
    xa, xf = hull.immersed_range()
    out = {name: [] for name in TEMPLATE_CANDIDATES}
    for k, x0 in enumerate(m.x):
        spec = hull.section_specs([float(x0)])[0] if xa < x0 < xf else None
        if spec is None or spec.y_dwl < END_FRACTION * m.beam / 2 or spec.draft - spec.z_keel < END_FRACTION * m.draft:
            continue
        for _ in range(TEMPLATE_PASSES):
            for name, cands in TEMPLATE_CANDIDATES.items():
                best = (math.inf, getattr(spec, name))
                for v in cands:
                    setattr(spec, name, float(v))
                    best = min(best, (_section_misfit(spec, m.z, m.y[k], need_area=False), float(v)))
                setattr(spec, name, best[1])
        for name in TEMPLATE_CANDIDATES:
            out[name].append([float(x0), float(getattr(spec, name))])
    return out


# ---- the whole description ----------------------------------------------------------------

def _builds(desc: dict):
    """The Hull of `desc` with its SAC solved, or None when the sections cannot hold it."""
    from .hull import Hull

    try:
        hull = Hull.from_json(desc)
        hull.basic_curves  # noqa: B018 (solves the SAC now)
        return hull
    except _native.InfeasibleFormParameters:
        return None


def _nearest_lcb(desc: dict, hull_free) -> tuple:
    """Bisect the SAC's LCB from where it falls when free (`hull_free`, built) toward the
    measured one; the hull with the nearest LCB the sections hold."""
    sac = desc["basic_curves"]["sac"]
    want, free = sac["lcb"], float(hull_free.hydrostatics(sac_stations=2).lcb)
    best, lo, hi = None, 0.0, 1.0
    for _ in range(LCB_BISECTIONS):
        t = 0.5 * (lo + hi)
        sac["lcb"] = free + t * (want - free)
        hull = _builds(desc)
        if hull is None:
            hi = t
        else:
            lo, best = t, (hull, sac["lcb"])
    if best is None:
        sac["lcb"] = free
        return _builds(desc), free
    sac["lcb"] = best[1]
    return best


def _closed_area(p: np.ndarray) -> float:
    """Area (both sides) of a half section (y, z) closed along the centre plane (shoelace)."""
    y, z = p[:, 0], p[:, 1]
    return float(abs(np.dot(y, np.roll(z, -1)) - np.dot(z, np.roll(y, -1))))


def measure_kracht(data: HullData, hull) -> dict | None:
    """Kracht coefficients of the data's bulb grid (role 'bulb'; its lines along the hull cut
    at stations from the FP to the nose): protrusion, breadth and area at the FP, nose height,
    lateral area and volume forward of the FP, on the built hull's midship area and volume.
    None when the data has no bulb grid reaching forward of the FP."""
    grids = [g for g in data.grids if g.role == "bulb"]
    if not grids:
        return None
    pts = np.concatenate([g.points.reshape(-1, 3) for g in grids])
    fp, nose = data.lpp, pts[np.argmax(pts[:, 0])]
    if nose[0] <= fp:
        return None
    lines = [_longitudinal_lines(g.points) for g in grids]
    xs = np.linspace(fp, nose[0], BULB_STATIONS)
    area, height, breadth = np.zeros(len(xs)), np.zeros(len(xs)), 0.0
    for k, x0 in enumerate(xs[:-1]):
        cut = np.concatenate([_crossings(ln, x0) for ln in lines])
        below = cut[cut[:, 1] <= data.draft]
        if len(below) >= 3:
            area[k], height[k] = _closed_area(below), np.ptp(below[:, 1])
        if k == 0 and len(cut):
            breadth = 2 * float(cut[:, 0].max())
    h = hull.hydrostatics()
    return {"c_lpr": float((nose[0] - fp) / data.lpp), "c_bb": breadth / data.beam, "c_zb": float(nose[2] / data.draft),
            "c_abt": float(area[0] / h.midship_area), "c_abl": monotone_cubic.integral(xs, height) / float(h.midship_area),
            "c_vpr": monotone_cubic.integral(xs, area) / float(h.volume)}


def _buildable(desc: dict, say) -> tuple:
    """(Hull of `desc`, what was relaxed): when the section family cannot hold the measured
    SAC, its LCB moves to the nearest it holds, then the fullness fit and the volume are left
    free in turn; each relaxation is noted in the description."""
    hull = _builds(desc)
    if hull is not None:
        return hull, []
    sac = desc["basic_curves"]["sac"]
    want = sac.pop("lcb")
    free = _builds(desc)
    if free is not None and "volume" in sac:
        sac["lcb"] = want
        hull, lcb = _nearest_lcb(desc, free)
        if hull is not None:
            desc["notes"] += f"; SAC LCB {lcb:.6g} m, the nearest to the measured {want:.6g} m the sections hold"
            say(f"relaxed: LCB {lcb:.6g} m (measured {want:.6g} m)")
            return hull, ["lcb"]
        sac.pop("lcb", None)
    relaxed = ["lcb"]
    for drop in ("fullness_fit", "volume"):
        if free is not None:
            break
        sac.pop(drop, None)
        relaxed.append(drop)
        free = _builds(desc)
    if free is None:
        raise _native.InfeasibleFormParameters(f"{desc['name']}: no SAC the sections hold, even without its volume and LCB")
    desc["notes"] += "; SAC " + ", ".join(relaxed) + " left free: the sections cannot hold the measured ones"
    say("relaxed: " + ", ".join(relaxed) + " left free")
    return free, relaxed


def _with_fitted_shapes(base: dict, built: tuple, m: MeasuredHull, say, fit) -> tuple:
    """(hull, description) with the section shape curves fitted to the data by `fit`
    (fit_section_shapes or fit_template_shapes), unless that costs a SAC target the default
    shapes meet (`built`: the default shapes' hull, description and relaxations)."""
    hull, desc, relaxed = built
    shaped = copy.deepcopy(base)
    shapes = fit(hull, m)
    if min(len(v) for v in shapes.values()) < 4:
        return hull, desc
    for curve, pts in shapes.items():
        shaped["basic_curves"][curve] = {"fit": pts, "fit_weight": FIT_WEIGHT, "spans": SHAPE_SPANS, **SHAPE_BOUNDS[curve]}
    say("fitted " + ", ".join(f"{k} at {len(v)} stations" for k, v in shapes.items()))
    try:
        hull_s, relaxed_s = _buildable(shaped, say)
    except _native.InfeasibleFormParameters:
        hull_s, relaxed_s = None, None
    if relaxed_s is not None and len(relaxed_s) <= len(relaxed):
        return hull_s, shaped
    say("fitted section shapes cost a SAC target: kept the default shapes")
    return hull, desc


@tersely  # it retries SACs the sections cannot hold and explains its own failures
def import_design(hull_data: HullData, *, depth: float | None = None, fit_shapes: bool = True, given: bool = True,
                  name: str | None = None, progress=None) -> dict:
    """A whole-ship hull description (a dict for ``fl.Hull.from_dict``) measured from
    `hull_data` (fairlines.offsets.HullData; module docstring says what is measured).

    depth       D (m); default the top of the data at midships.
    fit_shapes  fit the bilge corner (corner_breadth, corner_height) and top_corner curves per
                station (slower); where the measured bulb cannot be composed with their bow,
                the template family's deadrise, character and top_corner instead.
    given       where the fitted family still misses a station's shape by more than
                GIVEN_MISFIT of B, give every measured station's shape (sections.given); a
                bulb grid is then held by them (measured as hull), not composed.
    progress    callable(str) told of each step, or None.

    Raises InvalidInput for data that is not HullData, a depth not above T, data the
    description cannot hold (no hull below T at 3 stations); InfeasibleFormParameters when the
    measured basic curves contradict each other.
    """
    if not isinstance(hull_data, HullData):
        raise _native.InvalidInput(f"hull_data is a {type(hull_data).__name__}; expected fairlines.offsets.HullData "
                                   "(read_hull_data)")
    if depth is not None and not (isinstance(depth, (int, float)) and math.isfinite(depth) and depth > hull_data.draft):
        raise _native.InvalidInput(f"depth is {depth!r}; expected a depth D in metres above T = {hull_data.draft} m")
    say = progress or (lambda _msg: None)
    m = measure_hull_data(hull_data, depth)
    say(f"measured {len(m.x)} stations: volume {m.volume:.6g} m^3, LCB {m.lcb:.6g} m, D {m.depth:.4g} m")
    base = _base_description(m, name or hull_data.name)
    out = _designed(base, m, hull_data, fit_section_shapes if fit_shapes else None, say)
    if fit_shapes and "bulb" in out and not _composes(out):
        say("the fitted bilge corners leave a bow the measured bulb cannot meet in one seam: fitting the template's shapes")
        out = _designed(base, m, hull_data, fit_template_shapes, say)
        out["notes"] += "; template section shapes fitted: the bulb could not be composed with the fitted corners' bow"
    if given:
        from .hull import Hull

        fitted = Hull.from_json(out)
        worst = float(np.nanmax(station_misfit(fitted, m), initial=0.0))
        if worst > GIVEN_MISFIT * m.beam:
            say(f"the section family misses a station by {100 * worst / m.beam:.2f} % B (RMS): giving the measured shapes")
            md = _given_measure(hull_data, depth, fitted.basic_curves["profile"])
            gbase = _base_description(md, name or hull_data.name, given=True)
            gbase["skinning"] = _skin_knuckles(hull_data, md.x)
            shaped = _designed(gbase, md, hull_data, None, say)
            if "bulb" not in shaped or _composes(shaped):
                return shaped
            say("the measured bulb cannot meet the given shapes' bow in one seam: the fitted family's sections kept")
            out["notes"] += "; measured shapes not given: the bulb could not be composed with them"
    return out


def _end_span_sections(data: HullData, profile) -> list:
    """Sections picked up between a section list's fore end station and its neighbour where the
    end starts END_RISE_STEP T or more higher (a forefoot): each with its keel point on `profile`
    (a callable x -> the centre-plane contour's height, m, rising toward the end) and, at each
    height of the data's offsets above it, the half-breadth along that waterline: the
    shape-preserving cubic in x through the last four stations' half-breadths and, below the end
    station's lowest point, the place where the waterline closes on the profile. Not at the
    stern: there the waterlines close on a deadwood whose thickness the table does not give
    (Series 60: 0.1-0.3 m at station 0.5 under the AP's counter), and picked up they thinned it
    into a fin of 1-8 cm that the skin folded across the centre plane (1.4 cm at x 1.4 m)."""
    near = sorted(data.sections, key=lambda sec: sec.x)[-4:]
    if len(near) < 4 or min(len(sec.points) for sec in near) == 0:
        return []
    end, inner = near[-1], near[-2]
    low_in, low_end = float(inner.points[:, 1].min()), float(end.points[:, 1].min())
    n = math.ceil((low_end - low_in) / (END_RISE_STEP * data.draft)) - 1
    if n < 1:
        return []
    heights = np.unique(np.concatenate([sec.points[:, 1] for sec in near]))
    ys = np.array([_half_breadths([sec.points], heights, smooth=True) for sec in near])
    xn = np.array([sec.x for sec in near])
    run = np.linspace(inner.x, end.x, 201)
    rise = np.clip(np.maximum.accumulate(np.asarray(profile(run), float)), low_in, low_end)  # made one-way
    out = []
    for x in inner.x + (end.x - inner.x) * np.arange(1, n + 1) / (n + 1):
        z_keel = float(np.interp(x, run, rise))
        pts = [(0.0, z_keel)]
        for j, zj in enumerate(heights):
            have = np.isfinite(ys[:, j])
            if zj <= z_keel or not have[-2]:
                continue
            px, py = list(xn[have]), list(ys[have, j])
            if not have[-1]:  # the waterline closes on the profile before the end station
                px.append(float(np.interp(zj, rise, run)))
                py.append(0.0)
            pts.append((float(monotone_cubic.evaluate(np.array(px), np.array(py), np.array([x]))[0]), float(zj)))
        out.append(Section(float(x), np.array(pts), label="picked up"))
    return out


def _given_measure(hull_data: HullData, depth: float | None, profile=None) -> MeasuredHull:
    """The stations whose measured shapes are given: a section list's own and those picked up
    at a steep forefoot on `profile` (:func:`_end_span_sections`), a grid's section rows where it has them,
    graded into the stations beyond their range (:func:`_with_rows`), and of those left out there
    the ones whose data strays from their kept neighbours (:func:`_unlike_their_neighbours`);
    the volume and LCB those the data's chords hold (GIVEN_STATIONS cut from them, as the data's
    own facets: a cubic through the rows' areas holds DTMB 5415 +0.29 % more, its centre 0.007 %
    Lpp forward, both away from the data's)."""
    dense = measure_hull_data(hull_data, depth, dome=True, stations=GIVEN_STATIONS, bulb=True, noses=True)
    rows = [] if hull_data.sections else _section_rows(hull_data.grids, hull_data.lpp)
    picked = _end_span_sections(hull_data, profile) if hull_data.sections and profile is not None else []
    if picked:
        more = dataclasses.replace(hull_data, sections=sorted(hull_data.sections + picked, key=lambda sec: sec.x))
        md = measure_hull_data(more, depth, dome=True, stations=GIVEN_STATIONS, bulb=True, noses=True)
        where = ", ".join(f"{sec.x:.4g}" for sec in picked)
        note = (f"{len(picked)} stations (x {where} m) picked up along the waterlines toward the forefoot, which the data "
                "leaves to its last station spacing")
        return dataclasses.replace(md, volume=dense.volume, lcb=dense.lcb, notes=md.notes + [note])
    if not rows:
        return dense
    md = measure_hull_data(hull_data, depth, dome=True, stations=GIVEN_STATIONS, bulb=True, noses=True, rows=True)
    # between two rows the dense stations are the chords': kept, they step the sheer and ring
    spans = [(float(np.min(r)), float(np.max(r))) for r, _ in rows]
    back = [x for x in _unlike_their_neighbours(dense, md) if not any(lo < x < hi for lo, hi in spans)]
    if back:
        md = measure_hull_data(hull_data, depth, dome=True, stations=GIVEN_STATIONS, bulb=True, noses=True, rows=True,
                               extra=back)
    return dataclasses.replace(md, volume=dense.volume, lcb=dense.lcb)


def _skin_knuckles(hull_data: HullData, xs: np.ndarray) -> dict:
    """The skinning's knuckles over the given stations `xs` (m): where two hull grids join at
    a station (each grid's own surface: only C0 across the joint), and, aft of a grid's first
    square section row behind a raked one (a transom's edge), the skin ruled: the stations
    there are cut from the grid's chords and the transom face, and a C2 skin through them rang
    round the knuckle (DTMB 5415: lobes of 94, 21, 7, 2.2, 1.3, 0.4 deg along a waterline)."""
    tol = JOINT_TOL * hull_data.lpp
    hull = [g.points for g in hull_data.grids if g.role != "transom"]
    ends = [(float(p[..., 0].min()), float(p[..., 0].max())) for p in hull]
    joints = {hi for _, hi in ends if any(abs(hi - lo) <= tol for lo, _ in ends)}
    out: dict = {"knuckles": sorted(float(x) for x in xs[1:-1] if any(abs(x - j) <= tol for j in joints))}
    if any(g.role == "transom" for g in hull_data.grids):
        for p in hull:
            edge = _square_behind_raked(p, hull_data.lpp)
            if edge is not None:
                out["ruled_aft_of"] = edge
    return {k: v for k, v in out.items() if v}


def _square_behind_raked(p: np.ndarray, lpp: float) -> float | None:
    """x (m) of the grid's first square section row (:func:`_section_rows`) when the row aft
    of it is raked, else None."""
    rows = _row_spread(p, lpp)
    if rows is None:
        return None
    spread, mean = rows
    order = np.argsort(mean)
    gap = mean[order[1]] - mean[order[0]]
    return float(mean[order[1]]) if spread[order[0]] > SECTION_ROW_RAKE * gap else None


def _unlike_their_neighbours(dense: MeasuredHull, kept: MeasuredHull) -> np.ndarray:
    """x of the dense stations left out of `kept` whose measured half-breadths differ by more
    than GIVEN_REFINE_TOL of B from the straight line between kept's stations either side: where
    the data changes quickly between them (DTMB 5415's transom edge, where its waterline widens
    from 0.10 to 0.21 m within 27 mm), so a skin through them would overshoot (the waterline
    7 mm wide of the data, the keel line dipping)."""
    out = []
    for i, x in enumerate(dense.x):
        j = int(np.searchsorted(kept.x, x))
        if j == 0 or j == len(kept.x) or np.min(np.abs(kept.x - x)) <= 1e-9 * dense.lpp:
            continue
        t = (x - kept.x[j - 1]) / (kept.x[j] - kept.x[j - 1])
        miss = np.abs(dense.y[i] - ((1 - t) * kept.y[j - 1] + t * kept.y[j]))  # NaN where one has no hull
        if np.any(miss > GIVEN_REFINE_TOL * dense.beam):
            out.append(float(x))
    return np.asarray(out)


def _composes(desc: dict) -> bool:
    """Whether the hull of `desc` composes with its bulb."""
    from .hull import Hull

    try:
        Hull.from_json(desc).composed_hull()
        return True
    except _native.InvalidInput:
        return False


def _designed(base: dict, m: MeasuredHull, hull_data: HullData, fit, say) -> dict:
    """The description of `base` built, its section shapes fitted by `fit` (None: the defaults),
    its volume and LCB corrected on the surface, and its bulb measured (composed unless `m`
    measured it as hull)."""
    from .designer import match_targets
    from .hull import Hull

    desc = copy.deepcopy(base)
    hull, relaxed = _buildable(desc, say)
    if desc.get("sections", {}).get("given"):
        _set_given_offsets(desc, hull)
        hull, relaxed = _buildable(desc, say)
    if fit is not None:
        hull, desc = _with_fitted_shapes(base, (hull, desc, relaxed), m, say, fit)
    if "volume" in desc["basic_curves"]["sac"]:
        matched = Hull.from_json(desc)
        try:
            match_targets(matched, MATCH_TOL)
            hull = matched
        except _native.InfeasibleFormParameters:
            say("the surface's volume / LCB correction leaves what the sections hold: SAC targets kept as measured")
    out = hull.to_dict()
    out["notes"] = desc["notes"]
    skin = hull.skin()
    if skin.centre_plane_columns:  # the given sections run onto webs on the centre plane (KCS's boss end)
        out["notes"] += (f"; the skin kept at y >= 0 in {skin.centre_plane_columns} rows of its control net, off the "
                         f"given sections by up to {1000 * skin.centre_plane_miss:.2g} mm (folded across the centre "
                         "plane otherwise)")
    elif math.isinf(skin.centre_plane_refused_miss):
        out["notes"] += "; the skin crosses the centre plane where its rows are held by their runs"
    elif skin.centre_plane_refused_miss:  # DTMB 5415's recess between dome and stem
        out["notes"] += (f"; the skin crosses the centre plane: keeping it at y >= 0 would move the given sections "
                         f"by up to {1000 * skin.centre_plane_refused_miss:.2g} mm")
    kracht = measure_kracht(hull_data, hull)
    if kracht is not None and m.bulb_points is None:  # the sections hold the bulb: recognised, not composed
        out["notes"] += "; the bulb held by the sections (Kracht coefficients " + \
            ", ".join(f"{k} {v:.4g}" for k, v in kracht.items()) + ")"
        say("bulb held by the sections")
    elif kracht is not None:
        out["bulb"] = {"kracht": kracht}
        say("bulb: Kracht coefficients " + ", ".join(f"{k} {v:.4g}" for k, v in kracht.items()))
        out = _without_bulb_overlap(out, hull, kracht, say)
    return out


def _without_bulb_overlap(desc: dict, hull, kracht: dict, say) -> dict:
    """The description (`hull`'s, with the bulb's Kracht coefficients) with the SAC's volume
    lowered by what the composed bulb adds aft of the FP outside the bare hull (the data's hull
    grids already hold the bulb's neck), so the composed hull holds the measured volume plus
    the bulb's V_PR. Unchanged when the hull cannot be composed or rebuilt."""
    from .designer import match_targets
    from .hull import Hull

    sac = desc["basic_curves"]["sac"]
    if "volume" not in sac:
        return desc
    try:
        bare = hull.hydrostatics().volume
        composed_volume = _mesh_figures(hull.composed_hull(bulb=hull.bulbous_bow(**kracht)), desc["principal"]["T"])[0]
        overlap = composed_volume - bare - kracht["c_vpr"] * bare
        if overlap <= 0:
            return desc
        out = copy.deepcopy(desc)
        out["basic_curves"]["sac"]["volume"] = sac["volume"] - overlap
        rebuilt = Hull.from_json(out)
        match_targets(rebuilt, MATCH_TOL)
    except (_native.InvalidInput, _native.InfeasibleFormParameters):
        return desc
    say(f"bulb: {overlap:.4g} m^3 of it aft of the FP lies outside the bare hull; taken off the SAC's volume")
    result = rebuilt.to_dict()
    result["notes"], result["bulb"] = desc["notes"], desc["bulb"]
    return result


def point_deviation(surfaces, points: np.ndarray) -> np.ndarray:
    """Distance (m) from each point (n, 3) to the nearest of the surfaces (closest_point)."""
    best = np.full(len(np.asarray(points).reshape(-1, 3)), np.inf)
    for s in surfaces:
        best = np.minimum(best, distances(s, points))
    return best


def data_points(data: HullData, depth: float | None = None) -> np.ndarray:
    """The data's hull points a bare hull is judged against (n, 3): every section point, the
    'hull' and sonar dome grids' points (not the bulb's or the transom face's), up to the depth."""
    pts = data.all_points() if data.sections else np.concatenate([g.points.reshape(-1, 3) for g in data.grids
                                                                  if g.role in ("hull", "bow (sonar dome)")])
    top = pts[:, 2].max() if depth is None else depth
    return pts[pts[:, 2] <= top]


def fidelity(hull, data: HullData, *, max_points: int = 3000) -> dict:
    """How close the built `hull` (a fl.Hull) lies to the data: RMS and largest distance of the
    data's points (:func:`data_points`, at most `max_points`, evenly taken) to the hull as
    fractions of B, and its volume, LCB (m from the AP) and wetted surface (both sides) at T.
    The bulb grid's points join the data's; a hull with a bulb is judged composed (bare hull,
    bulb and blend)."""
    pr = hull.description.principal
    pts = data_points(data, pr.depth)
    bulb = [g.points.reshape(-1, 3) for g in data.grids if g.role == "bulb"]
    if bulb:  # the bulb is judged too, whether composed or held by the bare hull
        bulb = np.concatenate(bulb)
        pts = np.concatenate([pts, bulb[bulb[:, 2] <= pr.depth]])
    if hull.description.bulb is None:
        surfaces = [hull.bare_hull_surface()]
        h = hull.hydrostatics()
        volume, lcb, wetted = float(h.volume), float(h.lcb), float(h.wetted_surface)
    else:
        composed = hull.composed_hull()
        surfaces = [s for s, _loops in composed.trimmed_surfaces]
        volume, lcb, wetted = _mesh_figures(composed, pr.draft)
    pts = pts[:: max(1, len(pts) // max_points)]
    dev = point_deviation(surfaces, pts)
    return {"rms_of_B": float(np.sqrt(np.mean(dev**2)) / data.beam), "max_of_B": float(dev.max() / data.beam),
            "worst_point": pts[int(np.argmax(dev))].tolist(), "points": len(pts),
            "volume": volume, "lcb": lcb, "wetted_surface": wetted}


def _mesh_figures(composed, draft: float) -> tuple:
    """Volume, LCB and wetted surface (both sides) at `draft` of a composed half hull's mesh:
    the hull, bulb and blend faces below the waterline (clipped) make the wetted surface."""
    from .compose import FACE_PARTS
    from .hydrostatics_mesh import hydrostatics_of_mesh

    v, f = np.asarray(composed.mesh.vertices, float), np.asarray(composed.mesh.faces)
    h = hydrostatics_of_mesh(v, f, draft)
    outer = np.isin(composed.face_part, [FACE_PARTS.index(p) for p in ("hull", "bulb", "blend")])
    return float(h.volume), float(h.lcb), float(hydrostatics_of_mesh(v, f[outer], draft).wetted_surface)
