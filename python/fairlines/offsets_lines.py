"""The lines of an offsets table besides its waterlines, as shipyards publish them: the deck
edge (half-breadth and height at side), the centre-line contour (the keel's, the stem's or the
stern's height at each station) and buttock heights (where a station crosses a buttock, on its
bottom). Each adds its points to the station's section, so the importer measures them.

Columns (names case-insensitive, values in the table's units, blank where a line misses the
station): ``deck_y`` and ``deck_z``; ``keel_z``; ``bt_<y>`` or ``buttock_<y>`` for the buttock
at half-breadth y.
"""

from __future__ import annotations

import re

import numpy as np

from ._native import InvalidInput

DECK_Y, DECK_Z, KEEL_Z, BUTTOCK = "deck_y", "deck_z", "keel_z", "buttock"
_BUTTOCK_HEADER = re.compile(r"(?:bt|buttock)_?\s*([0-9]*\.?[0-9]+)")
# Heights within this fraction of the table's height range of a line's own count as on it (the
# keel column's point where the waterline cells also put one).
SAME_HEIGHT = 1e-6


def line_kind(header: str):
    """(kind, buttock half-breadth in table units or None) of a column header, or None for a
    waterline column."""
    h = header.strip().lower()
    if h in (DECK_Y, DECK_Z, KEEL_Z):
        return h, None
    m = _BUTTOCK_HEADER.fullmatch(h)
    return (BUTTOCK, float(m.group(1))) if m else None


def station_lines(kinds: dict, cells: dict, unit: float) -> dict:
    """{"deck": (y, z) or None, "keel": z or None, "buttocks": [(y, z), ...]} of one station
    (m) from its cells {header: value in table units, NaN when blank}; `kinds` maps each line
    column's header to line_kind's answer."""
    val = {kind: cells[h] * unit for h, (kind, _) in kinds.items() if kind != BUTTOCK}
    deck = (val.get(DECK_Y, np.nan), val.get(DECK_Z, np.nan))
    buttocks = sorted((y * unit, cells[h] * unit) for h, (kind, y) in kinds.items()
                      if kind == BUTTOCK and np.isfinite(cells[h]))
    keel = val.get(KEEL_Z, np.nan)
    return {"deck": deck if np.isfinite(deck).any() else None, "keel": keel if np.isfinite(keel) else None,
            "buttocks": buttocks}


def section_with_lines(points: np.ndarray, lines: dict, label: str, source: str, beam: float,
                       height: float) -> np.ndarray:
    """The section's (y, z) points (keel up, from the waterlines) with the station's other
    lines: it starts at the keel column's point on the centre plane, ends at the deck edge,
    and takes each buttock's crossing in its place by height; `height` (m) is the table's range
    of heights, the scale of SAME_HEIGHT. Raises InvalidInput naming the
    station and the value where the lines contradict the waterlines."""
    where = f"{source}: station {label!r}"
    tol = SAME_HEIGHT * height
    pts = [tuple(map(float, p)) for p in points]
    if lines["keel"] is not None:
        zk = lines["keel"]
        low = [p for p in pts if p[0] > 0 and p[1] < zk - tol]
        if low:
            raise InvalidInput(f"{where}: half-breadth {low[0][0]:.6g} m at z = {low[0][1]:.6g} m lies below its "
                               f"keel_z {zk:.6g} m; expected the keel (the centre-line contour) below the offsets")
        while pts and pts[0][0] == 0.0 and pts[0][1] <= zk + tol:  # the contour point the zeros implied
            pts.pop(0)
        pts.insert(0, (0.0, zk))
    if lines["deck"] is not None:
        yd, zd = lines["deck"]
        if not (np.isfinite(yd) and np.isfinite(zd)):
            raise InvalidInput(f"{where}: deck_y is {yd:g}, deck_z {zd:g}; expected both or neither")
        if not 0.0 <= yd <= beam / 2:
            raise InvalidInput(f"{where}: deck_y is {yd:.6g} m; expected a half-breadth from 0 to B/2 = {beam / 2:g} m")
        high = [p for p in pts if p[0] > 0 and p[1] > zd + tol]
        if high:
            raise InvalidInput(f"{where}: half-breadth {high[0][0]:.6g} m at z = {high[0][1]:.6g} m lies above its "
                               f"deck_z {zd:.6g} m; expected the deck edge at the top of the section")
        pts = [p for p in pts if p[1] < zd - tol] + [(yd, zd)]
    for yb, zb in lines["buttocks"]:
        if not (pts[0][1] - tol <= zb <= pts[-1][1] + tol) or yb > beam / 2:
            raise InvalidInput(f"{where}: buttock y = {yb:.6g} m at z = {zb:.6g} m lies outside the section (z "
                               f"{pts[0][1]:.6g} to {pts[-1][1]:.6g} m, y up to B/2 = {beam / 2:g} m); expected "
                               "the height where the station crosses that buttock")
        at = next((i for i, p in enumerate(pts) if i and (p[1] > zb or (abs(p[1] - zb) <= tol and p[0] > yb))),
                  len(pts))
        if not any(abs(p[0] - yb) <= tol and abs(p[1] - zb) <= tol for p in pts):
            pts.insert(at, (yb, zb))
    return np.array(pts)
