"""Sheet layout of a lines plan: where each view goes on an A3 sheet, at which scale, and the
drawing primitives (lines, grid, labels, title block) in drawing metres at model scale.

Profile at the top left (x right, z up), half-breadth plan below it on the same x, body plan
to the right of the profile on the same z, title block in the lower right corner. The scale is
the largest round 1:N at which all of it fits the sheet without overlaps.
"""

from __future__ import annotations

import numpy as np

from .lines_plan import GAP_MM, MARGIN_MM, SHEET_MM, STATIONS_PER_LPP, _SCALES, Polyline, Text

__all__ = ["layout"]

#: Title block size (mm on paper).
TITLE_MM = (118.0, 92.0)
#: Waterlines are labelled in the half-breadth plan at this fraction of the drawn x range.
WL_LABEL_AT = 0.72
#: Clear space kept between two labels (mm on paper).
LABEL_PAD_MM = 0.8
#: Band left for labels outside a view (mm on paper).
LABEL_MM = 9.0


def _clip_x(p: np.ndarray, x0: float, x1: float) -> list[np.ndarray]:
    keep = (p[:, 0] >= x0) & (p[:, 0] <= x1)
    idx = np.flatnonzero(keep)
    if len(idx) < 2:
        return []
    return [p[r] for r in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if len(r) > 1]


def _frame(plan, xr, lo, hi):
    """Model extents the views need: (x0, x1, z_lo, z_top, y_max, d_max)."""
    p = plan.particulars
    z_lo = min(0.0, lo[2])
    z_top = max(p["depth"], hi[2])
    y_max = max(0.5 * p["beam"], hi[1])
    d_max = max([np.hypot(piece[:, 1], piece[:, 2] - zc).max() for _, (zc, _a), cuts in plan.diagonals
                 for c in cuts for piece in _clip_x(c, *xr)] + [0.0])
    return xr[0], xr[1], z_lo, z_top, y_max, d_max


def _choose_scale(x0, x1, z_lo, z_top, y_max, d_max):
    """Smallest N (largest drawing) at which the views and the title block fit the sheet."""
    W, H = SHEET_MM
    for n in _SCALES:
        k = 1000.0 / n  # mm per model metre
        gap = GAP_MM
        width = MARGIN_MM + LABEL_MM + (x1 - x0) * k + gap + 2 * y_max * k + LABEL_MM + MARGIN_MM
        height = MARGIN_MM + LABEL_MM + (z_top - z_lo) * k + gap + (y_max + d_max) * k + LABEL_MM + MARGIN_MM
        plan_right = MARGIN_MM + LABEL_MM + (x1 - x0) * k + LABEL_MM
        body_bottom = MARGIN_MM + LABEL_MM + (z_top - z_lo) * k + LABEL_MM
        title_fits = (W - MARGIN_MM - TITLE_MM[0] >= plan_right) or (H - MARGIN_MM - TITLE_MM[1] >= height - MARGIN_MM)
        title_below_body = H - MARGIN_MM - TITLE_MM[1] >= body_bottom
        if width <= W and height <= H and title_fits and title_below_body:
            return n
    return _SCALES[-1]


def layout(plan, xr, lo, hi) -> None:
    """Fill plan.scale, plan.offsets and plan.primitives (see the module docstring)."""
    x0, x1, z_lo, z_top, y_max, d_max = _frame(plan, xr, lo, hi)
    n = _choose_scale(x0, x1, z_lo, z_top, y_max, d_max)
    m = n / 1000.0  # model metres per paper mm
    gap = GAP_MM * m
    yc = z_lo - gap - y_max            # plan centre line
    xb = x1 + gap + y_max              # body plan centre line
    plan.scale = n
    plan.offsets = {"profile": (0.0, 0.0), "plan": (0.0, yc), "body": (xb, 0.0)}
    # Sheet placement: the profile's top-left label band starts at the margin.
    left = x0 - (MARGIN_MM + LABEL_MM) * m
    top = z_top + (MARGIN_MM + LABEL_MM) * m
    plan.sheet = (left, top - SHEET_MM[1] * m, left + SHEET_MM[0] * m, top)
    prims: list = []
    _grid(plan, prims, x0, x1, z_lo, z_top, y_max, d_max, yc, xb, m)
    _curves(plan, prims, x0, x1, yc, xb)
    _title_block(plan, prims, m)
    plan.primitives = _drop_overlapping_labels(prims, m)


def _drop_overlapping_labels(prims, m):
    """Station labels in the body plan crowd where the sections end close together: a
    label is dropped when it would overlap one already placed (boxes from the text size)."""
    boxes, out = [], []
    for pr in prims:
        if isinstance(pr, Text) and pr.layer in ("STATIONS", "WATERLINES"):
            w, h = (0.75 * pr.size * len(pr.text) + LABEL_PAD_MM) * m, pr.size * m
            box = (pr.x - 0.5 * w, pr.y, pr.x + 0.5 * w, pr.y + h)
            if any(b[0] < box[2] and box[0] < b[2] and b[1] < box[3] and box[1] < b[3] for b in boxes):
                continue
            boxes.append(box)
        out.append(pr)
    return out


def _line(prims, pts, layer, name=""):
    prims.append(Polyline(np.asarray(pts, float), layer, False, name))


def _grid(plan, prims, x0, x1, z_lo, z_top, y_max, d_max, yc, xb, m):
    p = plan.particulars
    lab = 0.5 * LABEL_MM * m
    spacing = p["lpp"] / STATIONS_PER_LPP
    # Stations: across profile and plan, numbered above the profile and below the plan.
    for label, x, _ in plan.stations:
        n = x / spacing
        layer = "PERPENDICULARS" if abs(n) < 1e-9 or abs(n - STATIONS_PER_LPP) < 1e-9 else "GRID"
        _line(prims, [[x, z_lo], [x, z_top]], layer)
        _line(prims, [[x, yc - d_max], [x, yc + y_max]], layer)
        size = 2.2 if n == int(n) else 1.6
        prims.append(Text(x, z_top + lab, label, size=size))
        prims.append(Text(x, yc - d_max - lab, label, size=size))
    for n, tag in ((0, "AP"), (STATIONS_PER_LPP, "FP")):
        x = n * spacing
        if x0 - 1e-9 <= x <= x1 + 1e-9:
            prims.append(Text(x, z_lo - 0.35 * lab, tag, size=2.2, va="top"))
    # Waterlines: straight in profile and body plan.
    for label, z, _ in plan.waterlines:
        layer = "DWL" if label == "DWL" else "GRID"
        _line(prims, [[x0, z], [x1, z]], layer)
        _line(prims, [[xb - y_max, z], [xb + y_max, z]], layer)
        if label == "DWL":  # right of each view, clear of the waterline numbers
            prims.append(Text(x1 + 0.3 * lab, z, "DWL", size=1.8, ha="left", layer="DWL"))
            prims.append(Text(xb + y_max + 0.3 * lab, z, "DWL", size=1.8, ha="left", layer="DWL"))
        else:
            prims.append(Text(x0 - 0.3 * lab, z, f"WL {label}", size=1.8, ha="right"))
            if abs(z - p["draft"]) > 2.0 * m:
                prims.append(Text(xb + y_max + 0.3 * lab, z, label, size=1.8, ha="left"))
    for pts, layer in (([[x0, 0], [x1, 0]], "BASELINE"), ([[xb - y_max, 0], [xb + y_max, 0]], "BASELINE")):
        _line(prims, pts, layer)
    prims.append(Text(x0 - 0.3 * lab, 0.0, "BL", size=1.8, ha="right"))
    # Buttocks: straight in plan and body plan.
    for label, y, _ in plan.buttocks:
        _line(prims, [[x0, yc + y], [x1, yc + y]], "GRID")
        prims.append(Text(x0 - 0.3 * lab, yc + y, f"B {label}", size=1.8, ha="right"))
        for s in (-1, 1):
            _line(prims, [[xb + s * y, z_lo], [xb + s * y, z_top]], "GRID")
        prims.append(Text(xb + y, z_lo - 0.35 * lab, f"B{label}", size=1.5, va="top"))
        prims.append(Text(xb - y, z_lo - 0.35 * lab, f"B{label}", size=1.5, va="top"))
    # Centre lines.
    _line(prims, [[x0, yc], [x1, yc]], "CENTRELINE")
    prims.append(Text(x0 - 0.3 * lab, yc, "CL", size=1.8, ha="right"))
    _line(prims, [[xb, z_lo], [xb, z_top]], "CENTRELINE")
    prims.append(Text(xb, z_top + 1.15 * lab, "CL", size=2.0))
    prims.append(Text(xb, z_lo - 0.35 * lab, "CL", size=1.5, va="top"))
    prims.append(Text(xb - 0.5 * y_max, z_lo - 1.3 * lab, "AFT", size=1.8, va="top"))
    prims.append(Text(xb + 0.5 * y_max, z_lo - 1.3 * lab, "FORE", size=1.8, va="top"))
    # Diagonal traces in the body plan.
    for label, (zc, ang), _ in plan.diagonals:
        t = np.tan(np.radians(ang))
        y_end = min(y_max, (zc - z_lo) / t if t > 0 else y_max)
        for s in (-1, 1):
            _line(prims, [[xb, zc], [xb + s * y_end, zc - y_end * t]], "DIAGONALS")
        prims.append(Text(xb + y_end + 0.2 * lab, zc - y_end * t, label, size=1.8, ha="left", layer="DIAGONALS"))
    prims.append(Text(0.5 * (x0 + x1), z_top + 1.8 * lab, "PROFILE", size=2.5))
    prims.append(Text(0.5 * (x0 + x1), yc + y_max + 0.6 * lab, "HALF-BREADTH PLAN", size=2.5))
    prims.append(Text(xb, z_top + 2.0 * lab, "BODY PLAN", size=2.5))


def _spread_x(waterlines, x0, x1):
    """x (inside the middle 80 % of [x0, x1]) where the waterlines in the half-breadth plan are
    furthest apart from each other: there their labels do not crowd."""
    xs = np.linspace(x0 + 0.1 * (x1 - x0), x1 - 0.1 * (x1 - x0), 41)
    ys = []
    for _, _, cuts in waterlines:
        pieces = [c for c in cuts if np.ptp(c[:, 0]) > 0]
        if pieces:
            c = max(pieces, key=lambda c: np.ptp(c[:, 0]))
            o = np.argsort(c[:, 0])
            ys.append(np.interp(xs, c[o, 0], c[o, 1], left=np.nan, right=np.nan))
    if len(ys) < 2:
        return x0 + WL_LABEL_AT * (x1 - x0)
    gaps = np.nan_to_num(np.min(np.diff(np.sort(np.array(ys), axis=0), axis=0), axis=0), nan=0.0)
    return float(xs[int(np.argmax(gaps))])


def _curves(plan, prims, x0, x1, yc, xb):
    mid = 0.5 * plan.particulars["lpp"]
    # Body plan: stations aft of midships on the left, forward on the right, midship both.
    for label, x, cuts in plan.stations:
        sides = [-1] if x < mid - 1e-9 else [1] if x > mid + 1e-9 else [-1, 1]
        for c in cuts:
            for s in sides:
                prims.append(Polyline(np.column_stack([xb + s * c[:, 1], c[:, 2]]), "STATIONS", True, f"ST {label}"))
        top = max((c for c in cuts), key=lambda c: c[:, 2].max(), default=None)
        if top is not None and x0 <= x <= x1:
            k = int(np.argmax(top[:, 2]))
            prims.append(Text(xb + sides[0] * top[k, 1], top[k, 2], label, size=1.5, va="bottom",
                              layer="STATIONS"))
    x_lab = _spread_x(plan.waterlines, x0, x1)
    for label, z, cuts in plan.waterlines:
        layer = "DWL" if label == "DWL" else "WATERLINES"
        for c in cuts:
            for piece in _clip_x(c, x0, x1):
                prims.append(Polyline(np.column_stack([piece[:, 0], yc + piece[:, 1]]), layer, True, f"WL {label}"))
                if piece[:, 0].min() <= x_lab <= piece[:, 0].max():
                    k = int(np.argmin(np.abs(piece[:, 0] - x_lab)))
                    prims.append(Text(piece[k, 0], yc + piece[k, 1], label, size=1.4, va="bottom", layer="WATERLINES"))
    for label, y, cuts in plan.buttocks:
        for c in cuts:
            for piece in _clip_x(c, x0, x1):
                prims.append(Polyline(piece[:, [0, 2]], "BUTTOCKS", True, f"B {label}"))
        longest = max(cuts, key=len, default=None)
        if longest is not None and len(_clip_x(longest, x0, x1)):
            piece = max(_clip_x(longest, x0, x1), key=len)
            k = int(np.argmax(piece[:, 0]))
            prims.append(Text(piece[k, 0], piece[k, 2], f"B{label}", size=1.5, ha="left", layer="BUTTOCKS"))
    for label, (zc, ang), cuts in plan.diagonals:
        for c in cuts:
            d = np.hypot(c[:, 1], c[:, 2] - zc)
            for piece in _clip_x(np.column_stack([c[:, 0], d, c[:, 2]]), x0, x1):
                prims.append(Polyline(np.column_stack([piece[:, 0], yc - piece[:, 1]]), "DIAGONALS", True, label))
        if cuts:
            c = max(cuts, key=len)
            d = np.hypot(c[:, 1], c[:, 2] - zc)
            k = int(np.argmax(d))
            if x0 <= c[k, 0] <= x1:
                prims.append(Text(c[k, 0], yc - d[k], label, size=1.8, va="top", layer="DIAGONALS"))
    for layer, curves in (("OUTLINE", plan.outline), ("KNUCKLES", plan.knuckles)):
        for c in curves:
            on_cl = np.abs(c[:, 1]).max() <= 1e-7 * plan.particulars["lpp"]
            for piece in _clip_x(c, x0, x1):
                prims.append(Polyline(piece[:, [0, 2]], layer, True))
                if not on_cl:  # the profile outline lies on the centre line of the other views
                    prims.append(Polyline(np.column_stack([piece[:, 0], yc + piece[:, 1]]), layer, True))
            if on_cl:
                continue
            for s, sel in ((-1, c[:, 0] <= mid), (1, c[:, 0] >= mid)):
                idx = np.flatnonzero(sel)
                for r in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if len(idx) else []:
                    if len(r) > 1 and np.ptp(c[r, 1]) + np.ptp(c[r, 2]) > 0:
                        prims.append(Polyline(np.column_stack([xb + s * c[r, 1], c[r, 2]]), layer, True))


def _fmt(h, key, fmt, unit=""):
    return (fmt % h[key] + unit) if h and key in h and h[key] is not None else "-"


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
                 ("Vol", _fmt(h, "volume", "%.1f", " m3")), ("Displ.", _fmt(h, "displacement", "%.1f", " t")),
                 ("LCB", _fmt(h, "lcb", "%.3f", " m fwd AP")), ("KB", _fmt(h, "vcb", "%.3f", " m"))]
    right_rows = [("Awp", _fmt(h, "waterplane_area", "%.1f", " m2")), ("LCF", _fmt(h, "lcf", "%.3f", " m")),
                  ("S wet", _fmt(h, "wetted_surface", "%.1f", " m2")), ("Cb", _fmt(h, "cb", "%.4f")),
                  ("Cp", _fmt(h, "cp", "%.4f")), ("Cm", _fmt(h, "cm", "%.4f")), ("Cwp", _fmt(h, "cwp", "%.4f")),
                  ("KMt", _fmt(h, "kmt", "%.3f", " m")), ("KMl", _fmt(h, "kml", "%.2f", " m")),
                  ("TPC", _fmt(h, "tpc", "%.2f", " t/cm")), ("MCT1cm", _fmt(h, "mct1cm", "%.1f", " t m/cm"))]
    y0 = y - 4.0 * m
    for col, rows in ((0, left_rows), (1, right_rows)):
        yy = y0
        xk = x_l + (3 + col * 58) * m
        for key, val in rows:
            prims.append(Text(xk, yy, key, layer="TITLE", size=2.0, ha="left"))
            prims.append(Text(xk + 17 * m, yy, val, layer="TITLE", size=2.0, ha="left"))
            yy -= row
    src = (h or {}).get("source", "no hydrostatics")
    prims.append(Text(x_l + 3 * m, y_b + 6.5 * m, f"Hydrostatics at the DWL: {src}; coefficients on Lpp, B, T",
                      layer="TITLE", size=1.6, ha="left"))
    prims.append(Text(x_l + 3 * m, y_b + 3.0 * m,
                      "Stations black, waterlines blue, buttocks red, diagonals green, knuckles magenta",
                      layer="TITLE", size=1.6, ha="left"))
