"""Sheet layout of a lines plan: where each view goes on an A3 sheet, at which scale, and the
drawing primitives (lines, grid, labels, title block) in drawing metres at model scale.

Two arrangements, whichever draws the profile larger (the stacked one on a tie):

* stacked (a long ship): profile across the top of the sheet, half-breadth plan below it on
  the same x, both as wide as the sheet allows; body plan below them at a larger scale of its
  own, title block beside it in the lower right corner;
* beside (a close-up of one end): body plan to the right of the profile on the same z and
  scale, half-breadth plan below the profile, title block in the lower right corner.

Scales are round 1:N (``SCALES``), the largest drawing at which everything fits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .lines_sheet import GAP_MM, MARGIN_MM, SHEET_MM, STATIONS_PER_LPP, SCALES, Polyline, Text

__all__ = ["layout"]

#: Title block size (mm on paper).
TITLE_MM = (118.0, 92.0)
#: Least significant digits of a title block figure (a 5.7 m model's volume, 0.5504 m3, and MCT1cm).
TITLE_SIGNIFICANT = 4
#: Characters per line of the title block's notes (1.6 mm text across its width).
NOTE_CHARS = 92
#: Waterlines are labelled in the half-breadth plan at this fraction of the drawn x range.
WL_LABEL_AT = 0.72
#: Clear space kept between two labels (mm on paper).
LABEL_PAD_MM = 0.8
#: A label's box as drawn (lines_render: DejaVu Sans at size / 0.72 mm to the em): the line's
#: height with its descent, and a digit's advance, in text sizes.
LABEL_H, LABEL_CHAR_W = 1.42, 0.91
#: Places along x tried for the half-breadth plan's waterline labels (best spread first), and
#: their text size (mm on paper).
WL_LABEL_PLACES, WL_LABEL_SIZE = 6, 1.4
#: A station's cut smaller than this on paper (mm) is a point of the hull and takes no number.
POINT_SECTION = 0.5
#: Band left for labels outside a view (mm on paper).
LABEL_MM = 9.0
#: Space between the half-breadth plan's labels and the body plan below it (mm on paper).
BODY_GAP_MM = 2.0
#: Label bands (in LABEL_MM) above a body plan of its own (title, centre line, station
#: numbers) and below it (buttock numbers, AFT / FORE).
BODY_BAND = 1.5


@dataclass
class _Frame:
    """Model extents the views need (m): x range drawn, z from the lowest point (or the base)
    to the deck, the largest half-breadth and the largest expanded diagonal offset."""

    x0: float
    x1: float
    z_lo: float
    z_top: float
    y_max: float
    d_max: float


@dataclass
class _Body:
    """Where the body plan goes: centre line at drawing x ``xb``, base at drawing y ``yb``,
    magnified ``f`` times over the main scale."""

    xb: float
    yb: float
    f: float

    def at(self, y, z) -> np.ndarray:
        """Drawing points of body-plan coordinates (y signed: < 0 aft side, z up)."""
        return np.column_stack([self.xb + self.f * np.asarray(y, float), self.yb + self.f * np.asarray(z, float)])


def _clip_x(p: np.ndarray, x0: float, x1: float) -> list[np.ndarray]:
    keep = (p[:, 0] >= x0) & (p[:, 0] <= x1)
    idx = np.flatnonzero(keep)
    if len(idx) < 2:
        return []
    return [p[r] for r in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if len(r) > 1]


def _frame(plan, xr, lo, hi) -> _Frame:
    p = plan.particulars
    d_max = max([np.hypot(piece[:, 1], piece[:, 2] - zc).max() for _, (zc, _a), cuts in plan.diagonals
                 for c in cuts for piece in _clip_x(c, *xr)] + [0.0])
    return _Frame(xr[0], xr[1], min(0.0, lo[2]), max(p["depth"], hi[2]), max(0.5 * p["beam"], hi[1]), d_max)


def _beside_scale(f: _Frame):
    """Smallest N at which profile + body plan side by side, the half-breadth plan and the
    title block fit the sheet, or None."""
    W, H = SHEET_MM
    for n in SCALES:
        k = 1000.0 / n  # mm per model metre
        width = MARGIN_MM + LABEL_MM + (f.x1 - f.x0) * k + GAP_MM + 2 * f.y_max * k + LABEL_MM + MARGIN_MM
        height = MARGIN_MM + LABEL_MM + (f.z_top - f.z_lo) * k + GAP_MM + (f.y_max + f.d_max) * k + LABEL_MM + MARGIN_MM
        plan_right = MARGIN_MM + LABEL_MM + (f.x1 - f.x0) * k + LABEL_MM
        body_bottom = MARGIN_MM + LABEL_MM + (f.z_top - f.z_lo) * k + LABEL_MM
        title_fits = (W - MARGIN_MM - TITLE_MM[0] >= plan_right) or (H - MARGIN_MM - TITLE_MM[1] >= height - MARGIN_MM)
        if width <= W and height <= H and title_fits and H - MARGIN_MM - TITLE_MM[1] >= body_bottom:
            return n
    return None


def _stacked_top_mm(f: _Frame, k: float) -> float:
    """Paper height (mm) from the sheet's top edge to the bottom of the half-breadth plan's
    labels in the stacked arrangement."""
    return MARGIN_MM + 2 * LABEL_MM + (f.z_top - f.z_lo) * k + GAP_MM + (f.y_max + f.d_max) * k + LABEL_MM


def _stacked_scales(f: _Frame):
    """(N, N_body) of the stacked arrangement: the smallest N at which profile and plan fit
    the sheet's width with the title block below them, and the body plan's N_body < N that
    fills the band left of the title block; or None."""
    W, H = SHEET_MM
    for n in SCALES:
        k = 1000.0 / n
        if 2 * (MARGIN_MM + LABEL_MM) + (f.x1 - f.x0) * k > W:
            continue
        top = _stacked_top_mm(f, k)
        if H - MARGIN_MM - TITLE_MM[1] < top:
            continue
        band_h = H - MARGIN_MM - top - BODY_GAP_MM - 2 * BODY_BAND * LABEL_MM
        band_w = W - 2 * MARGIN_MM - TITLE_MM[0] - GAP_MM - 2 * LABEL_MM
        kb = min(band_h / (f.z_top - f.z_lo), band_w / (2 * f.y_max))
        nb = next((s for s in SCALES if 1000.0 / s <= kb), None)
        return (n, nb) if nb is not None and nb < n else None
    return None


def layout(plan, xr, lo, hi) -> None:
    """Fill plan.scale, plan.body_scale, plan.offsets, plan.factors and plan.primitives (see
    the module docstring)."""
    f = _frame(plan, xr, lo, hi)
    stacked, beside = _stacked_scales(f), _beside_scale(f)
    if stacked is not None and (beside is None or stacked[0] <= beside):
        n, nb = stacked
    else:
        n = beside if beside is not None else SCALES[-1]
        nb = n
    m = n / 1000.0  # model metres per paper mm
    yc = f.z_lo - GAP_MM * m - f.y_max  # plan centre line
    W, H = SHEET_MM
    if nb == n:  # beside
        body = _Body(f.x1 + GAP_MM * m + f.y_max, 0.0, 1.0)
        left = f.x0 - (MARGIN_MM + LABEL_MM) * m
        top = f.z_top + (MARGIN_MM + LABEL_MM) * m
    else:
        spare = W - 2 * (MARGIN_MM + LABEL_MM) - (f.x1 - f.x0) * 1000.0 / n
        left = f.x0 - (MARGIN_MM + LABEL_MM + 0.5 * spare) * m
        top = f.z_top + (MARGIN_MM + 2 * LABEL_MM) * m
        body = _body_in_band(f, n, nb, left, top)
    plan.scale, plan.body_scale = n, nb
    plan.offsets = {"profile": (0.0, 0.0), "plan": (0.0, yc), "body": (body.xb, body.yb)}
    plan.factors = {"profile": 1.0, "plan": 1.0, "body": body.f}
    plan.sheet = (left, top - H * m, left + W * m, top)
    prims: list = []
    _grid(plan, prims, f, yc, body, m)
    _curves(plan, prims, f, yc, body, m)
    _title_block(plan, prims, m)
    plan.primitives = _drop_overlapping_labels(prims, m)


def _body_in_band(f: _Frame, n: float, nb: float, left: float, top: float) -> _Body:
    """The body plan centred in the band below the half-breadth plan, left of the title block."""
    m = n / 1000.0
    fb = n / nb
    band_top = top - (_stacked_top_mm(f, 1000.0 / n) + BODY_GAP_MM) * m
    band_bottom = top - (SHEET_MM[1] - MARGIN_MM) * m
    band_left = left + MARGIN_MM * m
    band_right = left + (SHEET_MM[0] - MARGIN_MM - TITLE_MM[0] - GAP_MM) * m
    height = fb * (f.z_top - f.z_lo) + 2 * BODY_BAND * LABEL_MM * m
    yb = band_top - 0.5 * (band_top - band_bottom - height) - BODY_BAND * LABEL_MM * m - fb * f.z_top
    return _Body(0.5 * (band_left + band_right), yb, fb)


def _label_box(x, y, text, size, ha, va, m):
    """A label's box (drawing metres) with LABEL_PAD_MM / 2 clear all round."""
    w, h, pad = LABEL_CHAR_W * size * len(text) * m, LABEL_H * size * m, 0.5 * LABEL_PAD_MM * m
    x0 = x - {"left": 0.0, "center": 0.5, "right": 1.0}[ha] * w
    y0 = y - {"bottom": 0.0, "baseline": 0.0, "center": 0.5, "top": 1.0}[va] * h
    return (x0 - pad, y0 - pad, x0 + w + pad, y0 + h + pad)


def _drop_overlapping_labels(prims, m):
    """Station and waterline labels crowd where the lines close up: a label moves to its first
    alternative place that overlaps no label already placed, or is dropped (boxes from the
    text size)."""
    boxes, out = [], []
    for pr in prims:
        if isinstance(pr, Text) and pr.layer in ("STATIONS", "WATERLINES"):
            for x, y, ha, va in ((pr.x, pr.y, pr.ha, pr.va),) + tuple(pr.alternatives):
                box = _label_box(x, y, pr.text, pr.size, ha, va, m)
                if not any(b[0] < box[2] and box[0] < b[2] and b[1] < box[3] and box[1] < b[3] for b in boxes):
                    break
            else:
                continue
            boxes.append(box)
            pr = Text(x, y, pr.text, pr.layer, pr.size, ha, va, pr.rotation)
        out.append(pr)
    return out


def _line(prims, pts, layer, name=""):
    prims.append(Polyline(np.asarray(pts, float), layer, False, name))


def _grid(plan, prims, f: _Frame, yc, body: _Body, m):
    """The grid of the three views (stations, waterlines, buttocks, centre lines, diagonal
    traces) with their labels, and the views' titles; ``yc`` the half-breadth plan's centre
    line, ``m`` drawing metres per mm of paper."""
    lab = 0.5 * LABEL_MM * m
    _station_grid(plan, prims, f, yc, lab)
    _waterline_grid(plan, prims, f, body, lab, m)
    _buttock_grid(plan, prims, f, yc, body, lab)
    _centre_lines(prims, f, yc, body, lab)
    _diagonal_traces(plan, prims, f, body, lab)
    (_, yb_top), = body.at([0.0], [f.z_top])
    prims.append(Text(0.5 * (f.x0 + f.x1), f.z_top + 1.8 * lab, "PROFILE", size=2.5))
    prims.append(Text(0.5 * (f.x0 + f.x1), yc + f.y_max + 0.6 * lab, "HALF-BREADTH PLAN", size=2.5))
    title = "BODY PLAN" if body.f == 1.0 else f"BODY PLAN  1:{plan.body_scale:g}"
    prims.append(Text(body.xb, yb_top + 2.0 * lab, title, size=2.5))


def _station_grid(plan, prims, f: _Frame, yc, lab):
    """Stations across profile and plan, numbered above the profile and below the plan; AP, FP."""
    spacing = plan.particulars["lpp"] / STATIONS_PER_LPP
    for label, x, _ in plan.stations:
        n = x / spacing
        layer = "PERPENDICULARS" if abs(n) < 1e-9 or abs(n - STATIONS_PER_LPP) < 1e-9 else "GRID"
        _line(prims, [[x, f.z_lo], [x, f.z_top]], layer)
        _line(prims, [[x, yc - f.d_max], [x, yc + f.y_max]], layer)
        size = 2.2 if n == int(n) else 1.6
        prims.append(Text(x, f.z_top + lab, label, size=size))
        prims.append(Text(x, yc - f.d_max - lab, label, size=size))
    for n, tag in ((0, "AP"), (STATIONS_PER_LPP, "FP")):
        x = n * spacing
        if f.x0 - 1e-9 <= x <= f.x1 + 1e-9:
            prims.append(Text(x, f.z_lo - 0.35 * lab, tag, size=2.2, va="top"))


def _waterline_grid(plan, prims, f: _Frame, body: _Body, lab, m):
    """Waterlines and the base line: straight in profile and body plan."""
    x0, x1 = f.x0, f.x1
    right = body.at([f.y_max], [0.0])[0, 0] + 0.3 * lab
    for label, z, _ in plan.waterlines:
        layer = "DWL" if label == "DWL" else "GRID"
        _line(prims, [[x0, z], [x1, z]], layer)
        _line(prims, body.at([-f.y_max, f.y_max], [z, z]), layer)
        zb = body.at([0.0], [z])[0, 1]
        if label == "DWL":  # right of each view, clear of the waterline numbers
            prims.append(Text(x1 + 0.3 * lab, z, "DWL", size=1.8, ha="left", layer="DWL"))
            prims.append(Text(right, zb, "DWL", size=1.8, ha="left", layer="DWL"))
        else:
            prims.append(Text(x0 - 0.3 * lab, z, f"WL {label}", size=1.8, ha="right"))
            if abs(z - plan.particulars["draft"]) * body.f > 2.0 * m:
                prims.append(Text(right, zb, label, size=1.8, ha="left"))
    _line(prims, [[x0, 0], [x1, 0]], "BASELINE")
    _line(prims, body.at([-f.y_max, f.y_max], [0.0, 0.0]), "BASELINE")
    prims.append(Text(x0 - 0.3 * lab, 0.0, "BL", size=1.8, ha="right"))


def _buttock_grid(plan, prims, f: _Frame, yc, body: _Body, lab):
    """Buttocks: straight in plan and body plan."""
    (_, yb_lo), = body.at([0.0], [f.z_lo])
    for label, y, _ in plan.buttocks:
        _line(prims, [[f.x0, yc + y], [f.x1, yc + y]], "GRID")
        prims.append(Text(f.x0 - 0.3 * lab, yc + y, f"B {label}", size=1.8, ha="right"))
        for s in (-1, 1):
            _line(prims, body.at([s * y, s * y], [f.z_lo, f.z_top]), "GRID")
            prims.append(Text(body.at([s * y], [0.0])[0, 0], yb_lo - 0.35 * lab, f"B{label}", size=1.5, va="top"))


def _centre_lines(prims, f: _Frame, yc, body: _Body, lab):
    """The half-breadth plan's and the body plan's centre lines, and the body plan's AFT / FORE."""
    (_, yb_lo), (_, yb_top) = body.at([0.0, 0.0], [f.z_lo, f.z_top])
    _line(prims, [[f.x0, yc], [f.x1, yc]], "CENTRELINE")
    prims.append(Text(f.x0 - 0.3 * lab, yc, "CL", size=1.8, ha="right"))
    _line(prims, body.at([0.0, 0.0], [f.z_lo, f.z_top]), "CENTRELINE")
    prims.append(Text(body.xb, yb_top + 1.15 * lab, "CL", size=2.0))
    prims.append(Text(body.xb, yb_lo - 0.35 * lab, "CL", size=1.5, va="top"))
    for s, side in ((-1, "AFT"), (1, "FORE")):
        prims.append(Text(body.at([0.5 * s * f.y_max], [0.0])[0, 0], yb_lo - 1.3 * lab, side, size=1.8, va="top"))


def _diagonal_traces(plan, prims, f: _Frame, body: _Body, lab):
    """The diagonals' traces in the body plan, labelled at their outer ends."""
    for label, (zc, ang), _ in plan.diagonals:
        t = np.tan(np.radians(ang))
        y_end = min(f.y_max, (zc - f.z_lo) / t if t > 0 else f.y_max)
        for s in (-1, 1):
            _line(prims, body.at([0.0, s * y_end], [zc, zc - y_end * t]), "DIAGONALS")
        end = body.at([y_end], [zc - y_end * t])[0]
        prims.append(Text(end[0] + 0.2 * lab, end[1] + 0.3 * lab, label, size=1.8, ha="left", va="bottom",
                          layer="DIAGONALS"))


def _waterline_label_places(waterlines, x0, x1, clear: float) -> dict:
    """Where each waterline's number goes in the half-breadth plan: label -> [(x, va)] (drawing
    metres, best first; va "bottom" above the line, "top" below it). First the x (inside the
    middle 80 % of [x0, x1]) where the numbered waterlines are furthest apart from each other, so
    the numbers stand in one column where they can; then the x where the waterline has the most
    room to the next line drawn (`_label_room`), a tenth of the range apart: every one with at
    least `clear` (a label's height), the best three at least, WL_LABEL_PLACES in all."""
    xs = np.linspace(x0 + 0.1 * (x1 - x0), x1 - 0.1 * (x1 - x0), 41)
    ys = {}
    for label, _, cuts in waterlines:
        pieces = [c for c in cuts if np.ptp(c[:, 0]) > 0]
        if pieces:
            c = max(pieces, key=lambda c: np.ptp(c[:, 0]))
            o = np.argsort(c[:, 0])
            ys[label] = np.interp(xs, c[o, 0], c[o, 1], left=np.nan, right=np.nan)
    numbered = np.array([y for label, y in ys.items() if label != "DWL"])
    if len(numbered) < 2:
        return {label: [(x0 + WL_LABEL_AT * (x1 - x0), "bottom")] for label in ys}
    gaps = np.nan_to_num(np.min(np.diff(np.sort(numbered, axis=0), axis=0), axis=0), nan=0.0)
    column = float(xs[int(np.argmax(gaps))])
    every = np.array(list(ys.values()))
    places = {}
    for i, (label, y) in enumerate(ys.items()):
        own = [(column, "bottom")]
        for room, x_at, va in sorted(_label_room(np.delete(every, i, axis=0), y, xs, clear), key=lambda q: -q[0]):
            if (room >= clear or len(own) < 4) and all(abs(x_at - x) >= 0.1 * (x1 - x0) for x, _ in own):
                own.append((float(x_at), va))
        places[label] = own[:WL_LABEL_PLACES]
    return places


def _label_room(others, y, xs, clear: float) -> list:
    """[(room, x, va)]: at each x, the room (drawing metres) above the waterline `y` (half-breadths
    at xs) to the next of the `others` (va "bottom") and below it to the next or the centre line
    ("top"); none where another line lies within a quarter of `clear` (which line a number names
    would be unclear) or the waterline is not drawn. A missing other waterline (nan) leaves room."""
    d = others - y
    above = np.nanmin(np.where(d >= 0, d, np.inf), axis=0, initial=np.inf)
    below = np.minimum(np.nanmin(np.where(d <= 0, -d, np.inf), axis=0, initial=np.inf), y)
    ok = (np.nanmin(np.abs(d), axis=0, initial=np.inf) >= 0.25 * clear) & np.isfinite(y)
    return [(r, x, va) for va, room in (("bottom", above), ("top", below)) for r, x in zip(np.where(ok, room, 0.0), xs)]


def _curves(plan, prims, f: _Frame, yc, body: _Body, m: float):
    x0, x1 = f.x0, f.x1
    mid = 0.5 * plan.particulars["lpp"]
    # Body plan: stations aft of midships on the left, forward on the right, midship both.
    for label, x, cuts in plan.stations:
        sides = [-1] if x < mid - 1e-9 else [1] if x > mid + 1e-9 else [-1, 1]
        for c in cuts:
            for s in sides:
                prims.append(Polyline(body.at(s * c[:, 1], c[:, 2]), "STATIONS", True, f"ST {label}"))
        # a station through a point of the hull (a bulb's nose) draws nothing to name
        if cuts and x0 <= x <= x1 and np.ptp(np.concatenate(cuts)[:, 1:], axis=0).max() > POINT_SECTION * m:
            prims.append(_station_label(label, cuts, sides[0], body, plan.particulars["draft"]))
    x_labs = _waterline_label_places(plan.waterlines, x0, x1, LABEL_H * WL_LABEL_SIZE * m)
    labels = []
    for label, z, cuts in plan.waterlines:
        layer = "DWL" if label == "DWL" else "WATERLINES"
        pieces = [piece for c in cuts for piece in _clip_x(c, x0, x1)]
        for piece in pieces:
            prims.append(Polyline(np.column_stack([piece[:, 0], yc + piece[:, 1]]), layer, True, f"WL {label}"))
        at = []  # the label's places, best first, each on the drawn piece that spans its x
        for x, va in x_labs.get(label, ()):
            for piece in pieces:
                if piece[:, 0].min() <= x <= piece[:, 0].max():
                    k = int(np.argmin(np.abs(piece[:, 0] - x)))
                    at.append((piece[k, 0], yc + piece[k, 1], "center", va))
        if at:
            labels.append(Text(at[0][0], at[0][1], label, size=WL_LABEL_SIZE, va=at[0][3], layer="WATERLINES",
                               alternatives=tuple(at[1:])))
    prims += sorted(labels, key=lambda t: t.text == "DWL")  # the DWL's last: it is named beside the profile too
    for label, y, cuts in plan.buttocks:
        pieces = [piece for c in cuts for piece in _clip_x(c, x0, x1)]
        for piece in pieces:
            prims.append(Polyline(piece[:, [0, 2]], "BUTTOCKS", True, f"B {label}"))
        if pieces:
            piece = max(pieces, key=len)
            k = int(np.argmax(piece[:, 0]))
            prims.append(Text(piece[k, 0], piece[k, 2], f"B{label}", size=1.5, ha="left", layer="BUTTOCKS"))
    for label, (zc, ang), cuts in plan.diagonals:
        pieces = [piece for c in cuts
                  for piece in _clip_x(np.column_stack([c[:, 0], np.hypot(c[:, 1], c[:, 2] - zc), c[:, 2]]), x0, x1)]
        for piece in pieces:
            prims.append(Polyline(np.column_stack([piece[:, 0], yc - piece[:, 1]]), "DIAGONALS", True, label))
        if pieces:
            piece = max(pieces, key=lambda q: q[:, 1].max())
            k = int(np.argmax(piece[:, 1]))
            prims.append(Text(piece[k, 0], yc - piece[k, 1], label, size=1.8, va="top", layer="DIAGONALS"))
    for layer, curves in (("OUTLINE", plan.outline), ("KNUCKLES", plan.knuckles)):
        for c in curves:
            on_cl = np.abs(c[:, 1]).max() <= 1e-7 * plan.particulars["lpp"]
            for piece in _clip_x(c, x0, x1):
                prims.append(Polyline(piece[:, [0, 2]], layer, True))
                if not on_cl:  # the profile outline lies on the centre line of the other views
                    prims.append(Polyline(np.column_stack([piece[:, 0], yc + piece[:, 1]]), layer, True))
                    _body_outline(prims, piece, layer, mid, body)


def _station_label(label, cuts, side, body: _Body, draft) -> Text:
    """A station's number in the body plan: at its top end, else (where the tops crowd) at its
    lower end on the centre line, else where it crosses half the draft."""
    pts = np.concatenate(cuts)
    hi, lo = pts[np.argmax(pts[:, 2])], pts[np.argmin(pts[:, 2])]
    places = [body.at([side * hi[1]], [hi[2]])[0], body.at([side * lo[1]], [lo[2]])[0]]
    ha = "right" if side < 0 else "left"
    alts = [(places[1][0], places[1][1], ha, "bottom")]
    for c in cuts:
        k = np.flatnonzero(np.diff(np.sign(c[:, 2] - 0.5 * draft)) != 0)
        if len(k):
            y = max(abs(np.interp(0.5 * draft, c[[i, i + 1], 2], c[[i, i + 1], 1])) if c[i, 2] != c[i + 1, 2]
                    else abs(c[i, 1]) for i in k)
            q = body.at([side * y], [0.5 * draft])[0]
            alts.append((q[0], q[1], ha, "bottom"))
            break
    return Text(places[0][0], places[0][1], label, size=1.5, va="bottom", layer="STATIONS", alternatives=tuple(alts))


def _body_outline(prims, c, layer, mid, body: _Body):
    """An outline or knuckle curve off the centre plane in the body plan: its part aft of
    midships on the left, forward on the right."""
    for s, sel in ((-1, c[:, 0] <= mid), (1, c[:, 0] >= mid)):
        idx = np.flatnonzero(sel)
        for r in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if len(idx) else []:
            if len(r) > 1 and np.ptp(c[r, 1]) + np.ptp(c[r, 2]) > 0:
                prims.append(Polyline(body.at(s * c[r, 1], c[r, 2]), layer, True))


def _fmt(h, key, decimals, unit=""):
    """h[key] with `decimals` decimals, more where it has fewer than TITLE_SIGNIFICANT
    significant digits (a model's 0.5504 m3 read 0.6, its MCT1cm 0.0), "-" when missing."""
    v = h.get(key) if h else None
    if v is None:
        return "-"
    if v and math.isfinite(v):
        decimals = max(decimals, TITLE_SIGNIFICANT - 1 - math.floor(math.log10(abs(v))))
    return f"{v:.{decimals}f}{unit}"


def _title_block(plan, prims, m):
    """Principal particulars and hydrostatics at the DWL in the lower right corner."""
    left_s, bottom_s, right_s, _ = plan.sheet
    w, hgt = TITLE_MM[0] * m, TITLE_MM[1] * m
    x_r = right_s - MARGIN_MM * m
    x_l = x_r - w
    y_b = bottom_s + MARGIN_MM * m
    y_t = y_b + hgt
    _line(prims, [[x_l, y_b], [x_r, y_b], [x_r, y_t], [x_l, y_t], [x_l, y_b]], "TITLE")
    p, h = plan.particulars, plan.hydrostatics
    row = 4.2 * m
    y = y_t - 5.0 * m
    prims.append(Text(x_l + 3 * m, y, (p["name"] or "Hull").upper(), layer="TITLE", size=3.2, ha="left"))
    y -= 5.5 * m
    prims.append(Text(x_l + 3 * m, y, f"{plan.title}    scale 1:{plan.scale:g} on A3    metres",
                      layer="TITLE", size=2.2, ha="left"))
    y -= 1.8 * m
    _line(prims, [[x_l, y], [x_r, y]], "TITLE")
    spacing = p["lpp"] / STATIONS_PER_LPP
    left_rows = [("Lpp", f"{p['lpp']:.3f} m"), ("B", f"{p['beam']:.3f} m"), ("T (DWL)", f"{p['draft']:.3f} m"),
                 ("D", f"{p['depth']:.3f} m"), ("Stations", f"0 (AP) .. 20 (FP)"), ("spacing", f"{spacing:.3f} m"),
                 ("Vol", _fmt(h, "volume", 1, " m3")), ("Displ.", _fmt(h, "displacement", 1, " t")),
                 ("LCB", _fmt(h, "lcb", 3, " m fwd AP")), ("KB", _fmt(h, "vcb", 3, " m"))]
    right_rows = [("Awp", _fmt(h, "waterplane_area", 1, " m2")), ("LCF", _fmt(h, "lcf", 3, " m")),
                  ("S wet", _fmt(h, "wetted_surface", 1, " m2")), ("Cb", _fmt(h, "cb", 4)),
                  ("Cp", _fmt(h, "cp", 4)), ("Cm", _fmt(h, "cm", 4)), ("Cwp", _fmt(h, "cwp", 4)),
                  ("KMt", _fmt(h, "kmt", 3, " m")), ("KMl", _fmt(h, "kml", 2, " m")),
                  ("TPC", _fmt(h, "tpc", 2, " t/cm")), ("MCT1cm", _fmt(h, "mct1cm", 1, " t m/cm"))]
    y0 = y - 4.0 * m
    for col, rows in ((0, left_rows), (1, right_rows)):
        yy = y0
        xk = x_l + (3 + col * 58) * m
        for key, val in rows:
            prims.append(Text(xk, yy, key, layer="TITLE", size=2.0, ha="left"))
            prims.append(Text(xk + 17 * m, yy, val, layer="TITLE", size=2.0, ha="left"))
            yy -= row
    src = f"Hydrostatics at the DWL: {(h or {}).get('source', 'none')}; coefficients on Lpp, B, T"
    notes = _wrap(src, NOTE_CHARS) + ["Stations black, waterlines blue, buttocks red, diagonals green, knuckles magenta"]
    for k, note in enumerate(reversed(notes)):
        prims.append(Text(x_l + 3 * m, y_b + (3.0 + 3.0 * k) * m, note, layer="TITLE", size=1.6, ha="left"))


def _wrap(text: str, width: int) -> list[str]:
    """Words of ``text`` in lines of at most ``width`` characters."""
    lines = [""]
    for word in text.split():
        if lines[-1] and len(lines[-1]) + 1 + len(word) > width:
            lines.append("")
        lines[-1] = f"{lines[-1]} {word}".strip()
    return lines
