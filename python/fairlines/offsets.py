"""Readers for existing hull data, converted to the project's conventions
(metres, x forward from the AP, y half-breadth >= 0, z up from the baseline).

Every reader returns a :class:`HullData`: metres, x forward from the aft perpendicular (AP),
y half-breadth >= 0, z up from the baseline. Three kinds of input are understood:

* offsets tables (CSV, stations x waterlines of half-breadths), absolute or normalised;
* lists of section points (CSV ``x,y,z`` rows, one station after the other);
* structured point grids: the DTMB 5415 ``*_x/_y/_z.dat`` triples and Tecplot ``f=point``
  zones such as the KCS grid.

Poor data is handled explicitly: unsorted stations or waterlines are sorted and the fact is
recorded in ``HullData.notes``; exact duplicate stations are merged (noted), conflicting ones
raise; blank cells are dropped from their section (noted); unreadable or negative cells,
sections that fold back (cross themselves) and grids with holes raise
:class:`fairlines.InvalidInput` (a ``ValueError``) naming the file, row/column or station and
what was expected; so does every other malformed input, whatever the reader.
"""

from __future__ import annotations

import csv
import dataclasses
import pathlib
import re

import numpy as np

from . import monotone_cubic
from ._native import InvalidInput, limits
from .offsets_lines import line_kind, section_with_lines, station_lines

# Two stations closer than this fraction of Lpp are the same station (duplicates).
STATION_MATCH_TOL = 1e-9
# Stations may lie beyond the perpendiculars (overhangs, a bulb), but not by more than this
# fraction of Lpp: further out, Lpp or the units are wrong.
STATION_RANGE_MARGIN = 0.25
# Turning angle (degrees) between two section segments above which the point is a knuckle.
KNUCKLE_ANGLE_DEG = 35.0
# Principal dimensions outside this range (metres) are refused: from a small tank model to
# the largest ships; beyond it the unit is wrong (millimetres) or the value is a typo.
LENGTH_RANGE_M = (0.1, 1000.0)
# Points of one station a section list may hold: the fold-back check compares every pair of
# segments, so this bounds its work.
MAX_SECTION_POINTS = 5000
# Row labels of an absolute table's centre-plane contour rows: x of the stem or the stern at
# each waterline (blank where it misses one), as some shipyards' tables end.
CONTOUR_ROWS = ("stem", "stern")
# A contour row's x within this fraction of |x| (at least of a metre) of a station's is on it.
CONTOUR_ON_STATION = 1e-9
# Metres per millimetre (tables published in mm).
MM = 1e-3
# Largest half-breadth fraction a normalised table may hold (fractions of a waterline's own
# maximum, or of B/2, are at most 1 in principle; measured data overshoots a little).
HALF_BREADTH_FRACTION_MAX = 10.0


@dataclasses.dataclass
class Section:
    """One station: points (m, 2) as (y, z) in metres, ordered from the keel (or the lowest
    point on the centreplane) up to the top of the data."""
    x: float
    points: np.ndarray
    label: str = ""


@dataclasses.dataclass
class PointGrid:
    """A structured grid (rows, cols, 3) in the project's metres and axes. ``role`` names the part of the hull
    it covers ('hull', 'bow', 'bulb', 'transom', ...)."""
    name: str
    points: np.ndarray
    role: str = "hull"


@dataclasses.dataclass
class HullData:
    """Hull geometry read from a file, in the project's metres and axes.

    ``sections`` (offsets tables, section lists) or ``grids`` (structured grids) hold the
    geometry; ``offsets`` keeps the table itself (x of the stations, z of the waterlines,
    half-breadths with NaN where a cell was blank) for Simpson integration. ``notes`` lists
    every repair made to the data. ``published`` carries particulars stated by the source, in the names of
    :class:`fairlines.preprocess.ImportHydrostatics` (volume, lcb_pct, cb, cm, cp, cwp, wetted_surface)."""
    name: str
    lpp: float
    beam: float
    draft: float
    sections: list = dataclasses.field(default_factory=list)
    grids: list = dataclasses.field(default_factory=list)
    offsets: dict | None = None
    notes: list = dataclasses.field(default_factory=list)
    published: dict = dataclasses.field(default_factory=dict)
    source: str = ""
    #: (n, 2) points (x, z), m, of the centre-plane contour between or beyond the stations: an
    #: offsets table's stem and stern rows (x of the contour at each waterline).
    contour: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((0, 2)))

    def all_points(self) -> np.ndarray:
        """Every input point as (n, 3) x, y, z."""
        pts = [np.column_stack([np.full(len(s.points), s.x), s.points]) for s in self.sections]
        pts += [g.points.reshape(-1, 3) for g in self.grids]
        if len(self.contour):
            pts.append(np.column_stack([self.contour[:, 0], np.zeros(len(self.contour)), self.contour[:, 1]]))
        return np.concatenate(pts) if pts else np.zeros((0, 3))


def _positive(name, value):
    """A principal dimension in metres within LENGTH_RANGE_M; InvalidInput with a units hint."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InvalidInput(f"{name} is {value!r}; expected a positive number of metres") from None
    if not np.isfinite(v) or v <= 0:
        raise InvalidInput(f"{name} is {value!r}; expected a positive number of metres")
    lo, hi = LENGTH_RANGE_M
    if not lo <= v <= hi:
        hint = " (millimetres? divide by 1000)" if v > hi else ""
        raise InvalidInput(f"{name} is {value!r}; expected {lo} to {hi} m{hint}")
    return v


def _dimensions(lpp, beam, draft):
    """(Lpp, beam, draft) checked: each in LENGTH_RANGE_M, beam and draft below Lpp."""
    lpp, beam, draft = _positive("Lpp", lpp), _positive("beam", beam), _positive("draft", draft)
    for name, v in (("beam", beam), ("draft", draft)):
        if v >= lpp:
            raise InvalidInput(f"{name} is {v} m; expected less than Lpp = {lpp} m (same unit: metres)")
    return lpp, beam, draft


def _cell(text, path, row, col):
    """A table cell as float, NaN when blank; InvalidInput naming the cell otherwise."""
    t = text.strip()
    if t == "" or t.lower() in ("nan", "na", "-"):
        return np.nan
    try:
        v = float(t)
    except ValueError:
        raise InvalidInput(f"{path}: row {row}, column {col!r} is {t!r}; expected a number") from None
    if not np.isfinite(v):
        raise InvalidInput(f"{path}: row {row}, column {col!r} is {t!r}; expected a finite number")
    return v


def _csv_rows(path):
    """Non-comment, non-empty CSV rows with their 1-based line numbers, and the comment lines."""
    path = pathlib.Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise InvalidInput(f"cannot read {path}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise InvalidInput(f"{path} is not a text file; expected CSV") from None
    rows, comments = [], []
    for lineno, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith("#"):
            comments.append(line.lstrip("# ").rstrip())
            continue
        if not line.strip():
            continue
        rows.append((lineno, next(csv.reader([line]))))
    if not rows:
        raise InvalidInput(f"{path}: no data rows; expected a header line and one row per station")
    return rows, comments


def _float_or_none(text):
    """float(text) if it is a finite number, else None."""
    try:
        v = float(text)
    except ValueError:
        return None
    return v if np.isfinite(v) else None


def _waterline_height(label, path, draft, normalised):
    """z of a waterline column header: 'tan_line'/'baseline' is 0, 'wl_<z/T>' a fraction of the
    draft, a bare number metres (absolute tables) or z/T (normalised tables)."""
    lab = label.strip().lower()
    if lab in ("tan_line", "baseline", "base", "bl"):
        return 0.0
    m = re.fullmatch(r"(?:wl_?|z=?)?\s*([-+0-9.eE]+)\s*(?:m)?", lab)
    v = _float_or_none(m.group(1)) if m else None
    if v is None:
        raise InvalidInput(f"{path}: column header {label!r}; expected 'tan_line', 'wl_<z/T>' or a height")
    if lab.startswith("wl") or normalised:
        return v * draft
    return v


def read_offsets_csv(path, lpp, beam, draft, *, n_stations=20, normalised=None, name=None) -> HullData:
    """Read an offsets table: one row per station, one column per waterline, half-breadths.

    Normalised tables (like ``series60_cb080_offsets.csv``) have a ``station`` column with
    station numbers counted from the FP (``FP``, ``0.5``, ... ``AP``; ``n_stations`` intervals
    between the perpendiculars), waterline headers ``tan_line``/``wl_<z/T>``, half-breadths as
    fractions of each column's ``max_half_beam`` row (or of B/2 when there is none).
    Absolute tables have an ``x`` column (metres forward of the AP), headers giving z in
    metres, half-breadths in metres. Extra columns such as ``area_fraction`` are kept in
    ``offsets['extra']``. ``normalised`` None decides from the first header ('station' or 'x').
    Raises InvalidInput naming the row, column and value of any cell it cannot use.
    """
    lpp, beam, draft = _dimensions(lpp, beam, draft)
    if isinstance(n_stations, bool) or not isinstance(n_stations, (int, np.integer)) or not 1 <= n_stations <= 1000:
        raise InvalidInput(f"n_stations is {n_stations!r}; expected an integer from 1 to 1000 (intervals between the perpendiculars)")
    rows, comments = _csv_rows(path)
    t = _table_layout(path, rows[0][1], comments, lpp, beam, draft, n_stations, normalised)
    labels, xs, table, extra, contour = _station_rows(t, rows[1:])
    notes = []
    z, table = _waterlines_rising(t, table, notes)
    labels, xs, table, extra = _stations_from_ap(t, labels, xs, table, extra, notes)
    lines = [station_lines(t.lines, cells, t.unit) for cells in extra] if t.lines else None
    table = _fill_end_blanks(labels, xs, table, z, notes, lines)
    contour = _contour_points(t, contour, xs, notes)
    lines = _keels_from_contour(contour, labels, xs, table, z, lines, notes)
    sections = _sections_of_table(t, labels, xs, table, z, notes, lines)
    data = HullData(name or pathlib.Path(path).stem, lpp, beam, draft, sections=sections,
                    offsets={"x": xs, "z": z, "half_breadths": table, "labels": labels, "extra": extra},
                    notes=notes, source=str(path), contour=np.concatenate([c for c in contour.values()] or [np.zeros((0, 2))]))
    data.published = _published_from_comments(comments)
    return data


@dataclasses.dataclass
class _Layout:
    """What an offsets table's header says: its columns, units and the ship they scale to."""
    path: object
    header: list
    normalised: bool
    unit: float  # metres per table unit of an absolute table
    wl_cols: list
    extra_cols: list
    lines: dict  # header -> offsets_lines.line_kind of the deck, keel and buttock columns
    z: np.ndarray  # waterline heights (m), in column order
    lpp: float
    beam: float
    n_stations: int


def _table_layout(path, header, comments, lpp, beam, draft, n_stations, normalised) -> _Layout:
    """Read the header row: which columns are waterlines (and their heights) and which extra."""
    header = [h.strip() for h in header]
    first, unit = _unit_of(header[0], comments)
    if normalised is None:
        if first not in ("station", "x"):
            raise InvalidInput(f"{path}: first column is {header[0]!r}; expected 'station' (normalised) or 'x' (metres)")
        normalised = first == "station"
    wl_cols, extra_cols, lines = [], [], {}
    for k, h in enumerate(header[1:], 1):
        if (kind := line_kind(h)) is not None:
            if normalised:
                raise InvalidInput(f"{path}: column {h!r} in a normalised table; expected deck, keel and buttock "
                                   "columns in an absolute table (x in m or mm)")
            lines[h] = kind
        (extra_cols if kind is not None or h.lower() in ("area_fraction", "area", "note") else wl_cols).append(k)
    if len(wl_cols) < 2:
        raise InvalidInput(f"{path}: {len(wl_cols)} waterline column(s); expected at least 2")
    z = np.array([_waterline_height(header[k], path, draft, normalised) for k in wl_cols])
    if not normalised:
        z = z * unit
    if np.any(np.abs(z) > lpp):
        k = wl_cols[int(np.flatnonzero(np.abs(z) > lpp)[0])]
        raise InvalidInput(f"{path}: column header {header[k]!r} puts a waterline {np.abs(z).max():.6g} m from the "
                           f"baseline but Lpp is {lpp} m; expected heights in metres")
    return _Layout(path, header, normalised, unit, wl_cols, extra_cols, lines, z, lpp, beam, n_stations)


def _station_rows(t: _Layout, rows):
    """(labels, x (m), half-breadths (m), extra cells) of the station rows, in table order, and
    the contour rows {"stem" / "stern": (line number, x (m) at each waterline, NaN blank)}."""
    scale_row = None
    labels, xs, table, extra, contour = [], [], [], [], {}
    for lineno, row in rows:
        row = row + [""] * max(0, len(t.header) - len(row))
        lab = row[0].strip()
        if lab.lower() in ("max_half_beam", "scale"):
            scale_row = np.array([_cell(row[k], t.path, lineno, t.header[k]) for k in t.wl_cols])
            continue
        if lab.lower() in CONTOUR_ROWS:
            if t.normalised:
                raise InvalidInput(f"{t.path}: row {lineno} is a {lab} contour in a normalised table; expected it in an "
                                   "absolute table (x of the contour at each waterline, in the x column's unit)")
            if lab.lower() in contour:
                raise InvalidInput(f"{t.path}: row {lineno} gives the {lab} contour a second time; expected one row")
            contour[lab.lower()] = (lineno, np.array([_cell(row[k], t.path, lineno, t.header[k]) for k in t.wl_cols]) * t.unit)
            continue
        labels.append(lab)
        xs.append(_station_x(t, lab, lineno))
        table.append(_half_breadths(t, row, lineno))
        extra.append({t.header[k]: _cell(row[k], t.path, lineno, t.header[k]) for k in t.extra_cols})
    if len(xs) < 3:
        raise InvalidInput(f"{t.path}: {len(xs)} station(s); expected at least 3")
    xs, table = np.array(xs), np.array(table)
    check_station_range(xs, t.lpp, str(t.path))
    if t.normalised:
        hb_scale = scale_row if scale_row is not None else np.ones(len(t.wl_cols))
        if np.any(np.isnan(hb_scale)) or np.any(hb_scale <= 0):
            raise InvalidInput(f"{t.path}: max_half_beam row has blank or non-positive entries; expected one per waterline")
        table = table * hb_scale * t.beam / 2
    return labels, xs, table, extra, contour


def _contour_points(t: _Layout, rows: dict, xs: np.ndarray, notes: list) -> dict:
    """{"stem" / "stern": (n, 2) points (x, z), m, in x order} of the contour rows, each checked:
    within the stations' range margin, the stem in the fore half, the stern in the aft half."""
    out = {}
    for which, (lineno, x) in sorted(rows.items()):
        ok = np.isfinite(x)
        if not ok.any():
            raise InvalidInput(f"{t.path}: row {lineno} ({which}) has no values; expected the x of the {which} at "
                               "one waterline at least")
        check_station_range(x[ok], t.lpp, f"{t.path}: row {lineno} ({which})")
        mid = 0.5 * (float(np.min(xs)) + float(np.max(xs)))
        wrong = x[ok][(x[ok] < mid) if which == "stem" else (x[ok] > mid)]
        if wrong.size:
            half = "fore" if which == "stem" else "aft"
            raise InvalidInput(f"{t.path}: row {lineno} ({which}) puts it at x = {wrong[0]:.6g} m; expected the {which} "
                               f"in the {half} half of the stations ({'above' if which == 'stem' else 'below'} x = {mid:.6g} m)")
        pts = np.column_stack([x[ok], t.z[ok]])
        out[which] = pts[np.argsort(pts[:, 0], kind="stable")]
        notes.append(f"the table's {which} row read as the centre-plane contour ({int(ok.sum())} points)")
    return out


def lowest_at_each_x(points: np.ndarray) -> np.ndarray:
    """(m, 2) of centre-plane contour points (n, 2) (x, z), m: one per distinct x, in x order,
    the lowest there (a vertical stretch of the contour is a section's lowest point there)."""
    pts = np.asarray(points, float).reshape(-1, 2)
    if not len(pts):
        return pts
    pts = pts[np.lexsort((pts[:, 1], pts[:, 0]))]
    x, first = np.unique(pts[:, 0], return_index=True)
    return np.column_stack([x, pts[first, 1]])


def _keels_from_contour(contour: dict, labels, xs, table, z, lines, notes):
    """The stations' lines with a keel height read off the stem and stern rows where the table
    gives none: where a row spans the station, the shape-preserving cubic in x through the row's
    points, kept between the highest zero waterline below the first offset and that offset
    (what the zero cells say); at a station with no offsets (on the centre plane), the row's
    lowest point on it. A station with offsets that the row crosses keeps what its zero cells
    say: read from the row, a vertical stem below them made the profile, a height over x, dip
    under the keel and the waterlines run out along the centre plane. Returns `lines` (made
    when the table has no line columns)."""
    read = []
    heights = [lowest_at_each_x(pts).T for pts in contour.values()]  # each row as z(x)
    for k, x in enumerate(xs):
        if lines is not None and lines[k]["keel"] is not None:
            continue
        for px, pz in heights:
            on = np.abs(px - x) <= CONTOUR_ON_STATION * max(abs(x), 1.0)
            filled = np.flatnonzero(table[k] > 0)
            if not filled.size and on.any():  # a station on the centre plane (a stem, a post): it starts there
                zk = float(pz[on].min())
            elif filled.size and not on.any() and len(px) >= 2 and px[0] < x < px[-1]:
                zeros = np.flatnonzero((table[k] == 0) & (z < z[filled[0]]))
                low = z[zeros[-1]] if zeros.size else z[filled[0]]
                zk = float(np.clip(monotone_cubic.evaluate(px, pz, np.array([x]))[0], low, z[filled[0]]))
            else:
                continue
            if lines is None:
                lines = [{"deck": None, "keel": None, "buttocks": []} for _ in xs]
            lines[k]["keel"] = zk
            read.append(labels[k])
    if read:
        notes.append(f"keel height of station(s) {', '.join(map(repr, read))} read off the stem / stern row")
    return lines


def _station_x(t: _Layout, lab: str, lineno: int) -> float:
    """x (m from the AP) of a row: a station number counted from the FP, or x in table units."""
    if not t.normalised:
        xpos = _cell(lab, t.path, lineno, t.header[0]) * t.unit
        if np.isnan(xpos):
            raise InvalidInput(f"{t.path}: row {lineno} has no x; expected metres forward of the AP")
        return xpos
    st = {"FP": 0.0, "AP": float(t.n_stations)}.get(lab.upper(), None)
    if st is None:
        st = _float_or_none(lab)
        if st is None:
            raise InvalidInput(f"{t.path}: row {lineno} station is {lab!r}; expected FP, AP or a number")
    return (t.n_stations - st) / t.n_stations * t.lpp


def _half_breadths(t: _Layout, row, lineno: int) -> np.ndarray:
    """A row's half-breadths (m, or fractions in a normalised table), each checked for range."""
    vals = np.array([_cell(row[k], t.path, lineno, t.header[k]) for k in t.wl_cols]) * (1.0 if t.normalised else t.unit)
    bad = np.flatnonzero(vals < 0)
    if bad.size:
        k = t.wl_cols[bad[0]]
        raise InvalidInput(f"{t.path}: row {lineno}, column {t.header[k]!r} is {vals[bad[0]]}; "
                           "expected a half-breadth >= 0")
    wide = np.flatnonzero(vals > (HALF_BREADTH_FRACTION_MAX if t.normalised else t.beam))
    if wide.size:
        k = t.wl_cols[wide[0]]
        raise InvalidInput(f"{t.path}: row {lineno}, column {t.header[k]!r} is {vals[wide[0]]}; expected a half-breadth "
                           + ("fraction <= " + str(HALF_BREADTH_FRACTION_MAX) if t.normalised
                              else f"<= B = {t.beam} m (metres?)"))
    return vals


def _waterlines_rising(t: _Layout, table, notes):
    """Waterlines must rise left to right: sort them (noted), refuse duplicates."""
    z = t.z
    zo = np.argsort(z, kind="stable")
    if np.any(np.diff(z[zo]) <= 0):
        i = np.flatnonzero(np.diff(z[zo]) <= 0)[0]
        raise InvalidInput(f"{t.path}: two waterline columns at z = {z[zo][i]:.6g} m; expected distinct waterlines")
    if np.any(zo != np.arange(len(z))):
        notes.append("waterline columns were not in rising order; sorted")
    return z[zo], table[:, zo]


def _stations_from_ap(t: _Layout, labels, xs, table, extra, notes):
    """Stations sorted from the AP forward, exact duplicates merged (noted), conflicting ones refused."""
    so = np.argsort(xs, kind="stable")
    if np.any(so != np.arange(len(xs))) and not np.all(so == np.arange(len(xs))[::-1]):
        notes.append("stations were not in order; sorted from AP to FP")
    keep = [so[0]]
    for i in so[1:]:
        if abs(xs[i] - xs[keep[-1]]) > STATION_MATCH_TOL * t.lpp:
            keep.append(i)
            continue
        a, b = table[keep[-1]], table[i]
        if not np.allclose(np.nan_to_num(a, nan=-1), np.nan_to_num(b, nan=-1), rtol=0, atol=1e-9 * t.beam):
            raise InvalidInput(f"{t.path}: station {labels[i]!r} appears twice with different half-breadths; "
                               "expected one row per station")
        notes.append(f"station {labels[i]!r} appeared twice with the same values; merged")
    return [labels[i] for i in keep], xs[keep], table[keep], [extra[i] for i in keep]


def _along_waterline(xs: np.ndarray, col: np.ndarray, i: int, zero_ok: bool = False) -> float | None:
    """Half-breadth of a waterline (the table's column `col`, NaN where blank) at station i,
    from the stations either side that have it: the polynomial through up to two on each side
    (a cubic, or a quadratic next to an end). None when a side has none or, unless `zero_ok`,
    a neighbour other than an end station (where a hull closes) is off the hull (0)."""
    before = [k for k in range(i) if not np.isnan(col[k])][-2:]
    after = [k for k in range(i + 1, len(xs)) if not np.isnan(col[k])][:2]
    if not before or not after:
        return None
    off = [k for k in (before[-1], after[0]) if col[k] <= 0 and k not in (0, len(xs) - 1)]
    if off and not zero_ok:
        return None
    if col[before[-1]] == 0 and col[after[0]] == 0:
        return 0.0  # the keel (or the centre plane) on both sides
    ks = before + after
    return float(np.polynomial.Polynomial.fit(xs[ks], col[ks], len(ks) - 1)(xs[i]))


def _fill_end_blanks(labels, xs, table, z, notes, lines=None):
    """A station's blank cells above its highest offset and below its lowest, on waterlines the
    stations either side have, filled along those waterlines (:func:`_along_waterline`; noted):
    a missing deck-level cell would otherwise end the section low and lower its deck edge, a
    missing keel cell start it high as a flat of bottom. The end stations, waterlines a side
    lacks, below a station's keel or above its deck edge (`lines`, offsets_lines.station_lines
    of each station, where the table gives them), above a station whose highest offset is 0
    (the hull ends on the centre plane there) or where a neighbour other than an end station is
    0, stay blank."""
    table = np.array(table, dtype=float)
    x = np.asarray(xs, float)
    for i in range(1, len(xs) - 1):
        given = np.flatnonzero(~np.isnan(table[i]))
        if not len(given):
            continue
        filled = []
        for below, js in ((True, range(given[0] - 1, -1, -1)),
                          (False, range(given[-1] + 1, len(z)) if table[i, given[-1]] > 0 else ())):
            for j in js:
                if lines is not None and _beyond_lines(lines[i], z[j], below):
                    break
                v = _along_waterline(x, table[:, j], i, zero_ok=below)
                if v is None:
                    break
                table[i, j] = max(v, 0.0)
                filled.append(z[j])
        if filled:
            notes.append(f"station {labels[i]!r}: {len(filled)} blank cell(s) at z = "
                         + ", ".join(f"{v:.4g}" for v in sorted(filled))
                         + " m below its lowest or above its highest offset filled along their waterlines from the "
                         "stations either side")
    return table


def _beyond_lines(lines: dict, z: float, below: bool) -> bool:
    """Whether height z (m) lies below the station's keel point (`below`) or above its deck edge."""
    if below:
        return lines["keel"] is not None and z < lines["keel"]
    return lines["deck"] is not None and z > lines["deck"][1]


def _sections_of_table(t: _Layout, labels, xs, table, z, notes, lines=None):
    """One (y, z) section per station, with the table's deck, keel and buttock lines (`lines`,
    offsets_lines.station_lines of each station); blank cells are left out of it (noted)."""
    sections = []
    for k, (lab, xpos, hb) in enumerate(zip(labels, xs, table)):
        missing = np.isnan(hb)
        if missing.all():
            raise InvalidInput(f"{t.path}: station {lab!r} has no half-breadths; expected at least one number")
        if missing.any():
            notes.append(f"station {lab!r}: {int(missing.sum())} blank cell(s) at z = "
                         + ", ".join(f"{v:.4g}" for v in z[missing]) + " m left out of the section")
        points = section_from_offsets(hb, z)
        if lines is not None:
            points = section_with_lines(points, lines[k], lab, str(t.path), t.beam, float(np.ptp(z)))
        sections.append(Section(float(xpos), points, lab))
    if lines is not None:
        if t.lines:
            notes.append("the table's " + ", ".join(t.lines) + " column(s) read into the sections")
        check_sections(sections, str(t.path))
    return sections


def _unit_of(first_header, comments):
    """(first column name, metres per table unit): 'x_mm' / 'x [mm]' / 'x (mm)' or a comment
    line 'units: mm' make an absolute table millimetres (as shipyards publish offsets)."""
    m = re.fullmatch(r"\s*(\w+?)\s*(?:_|\[|\()?\s*(mm|m)?\s*[\])]?\s*", first_header.lower())
    name, unit = (m.group(1), m.group(2)) if m else (first_header.strip().lower(), None)
    if unit is None and any(re.search(r"\bunits?\s*[:=]\s*mm\b", c.lower()) for c in comments):
        unit = "mm"
    return name, MM if unit == "mm" else 1.0


def _published_from_comments(comments):
    """Published coefficients quoted in a table's header ('Cp 0.805, Cm 0.994, ...')."""
    text = " ".join(comments)
    out = {}
    for key in ("Cp", "Cm", "Cwp", "Cb"):
        m = re.search(rf"\b{key}\s+(0?\.\d+)", text)
        if m:
            out[key.lower()] = float(m.group(1))
    m = re.search(r"LCB\s+(\d+(?:\.\d*)?|\.\d+)\s*%\s*Lpp\s+(forward|aft)", text.replace("\n", " "))
    if m:
        out["lcb_pct"] = float(m.group(1)) * (1 if m.group(2) == "forward" else -1)
    return out


def section_from_offsets(half_breadths, z) -> np.ndarray:
    """(y, z) points of one station from its half-breadths at waterlines z (blank cells NaN).

    Where the lowest waterlines read 0 the section does not reach them: it starts on the
    centreplane at the highest such zero below the first non-zero offset (a point of the
    profile). A non-zero offset on the lowest waterline means a flat of bottom: the section
    starts on the centreplane at that height. Zeros above non-zero offsets end the section on the
    centreplane (a stem or stern above the data)."""
    hb = np.asarray(half_breadths, float)
    z = np.asarray(z, float)
    ok = ~np.isnan(hb)
    hb, z = hb[ok], z[ok]
    nz = np.flatnonzero(hb > 0)
    if nz.size == 0:  # a section entirely on the centreplane (a stem at FP): its profile line
        return np.column_stack([np.zeros(len(z)), z])
    first, last = nz[0], nz[-1]
    pts = [(0.0, z[first - 1] if first > 0 else z[first])]
    pts += [(hb[k], z[k]) for k in range(first, last + 1)]
    if last + 1 < len(z):
        pts.append((0.0, z[last + 1]))
    return np.array(pts)


def read_sections_csv(path, lpp, beam, draft, *, name=None) -> HullData:
    """Read section points: CSV rows ``x,y,z`` in metres (the project's axes), one station after another,
    each station's points ordered from the keel up. Stations need not be in order (noted);
    a station given twice raises; a section that crosses itself raises."""
    lpp, beam, draft = _dimensions(lpp, beam, draft)
    rows, _ = _csv_rows(path)
    start = 0
    if rows[0][1] and not _is_number(rows[0][1][0]):
        header = [h.strip().lower() for h in rows[0][1]]
        if header[:3] != ["x", "y", "z"]:
            raise InvalidInput(f"{path}: header is {rows[0][1]!r}; expected x,y,z")
        start = 1
    groups: dict = {}
    order = []
    last_x = None
    for lineno, row in rows[start:]:
        if len(row) < 3:
            raise InvalidInput(f"{path}: row {lineno} has {len(row)} value(s); expected x,y,z")
        x, y, z = (_cell(row[k], path, lineno, "xyz"[k]) for k in range(3))
        if np.isnan(x) or np.isnan(z):
            raise InvalidInput(f"{path}: row {lineno} has a blank x or z; expected numbers")
        if np.isnan(y):
            continue
        if y < 0:
            raise InvalidInput(f"{path}: row {lineno}, y is {y}; expected a half-breadth >= 0")
        if y > beam or abs(z) > lpp:
            raise InvalidInput(f"{path}: row {lineno}, (y, z) = ({y}, {z}) m lies outside the ship "
                               f"(B = {beam} m, Lpp = {lpp} m); expected metres")
        if abs(x) > (1 + STATION_RANGE_MARGIN) * lpp + lpp:
            raise InvalidInput(f"{path}: row {lineno}, x is {x} m but Lpp is {lpp} m; "
                               "expected stations between the perpendiculars (is x in metres?)")
        key = round(x / lpp / STATION_MATCH_TOL)
        if key != last_x and key in groups:
            raise InvalidInput(f"{path}: row {lineno}: station x = {x} m appears in two separate blocks; "
                             "expected each station's points together")
        if key not in groups:
            groups[key] = (x, [])
            order.append(key)
        groups[key][1].append((y, z))
        last_x = key
    notes = []
    xs = [groups[k][0] for k in order]
    if np.any(np.diff(xs) < 0):
        notes.append("stations were not in order; sorted from AP to FP")
    sections = []
    for k in sorted(order, key=lambda k: groups[k][0]):
        x, pts = groups[k]
        pts = np.array(pts)
        if not 2 <= len(pts) <= MAX_SECTION_POINTS:
            raise InvalidInput(f"{path}: station x = {x} m has {len(pts)} point(s); expected 2 to {MAX_SECTION_POINTS}")
        sections.append(Section(float(x), pts, f"x={x:g}"))
    data = HullData(name or pathlib.Path(path).stem, lpp, beam, draft, sections=sections, notes=notes,
                    source=str(path))
    check_station_range([s.x for s in data.sections], lpp, str(path))
    check_sections(data.sections, source=str(path))
    return data


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def _orient(a, b, c):
    """Twice the signed area of triangles (a, b, c), broadcast over rows."""
    return (b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1]) - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0])


def _first_crossing(p):
    """(i, j) of the first pair of non-adjacent segments of polyline p that cross at an
    interior point of both, or None; each segment is tested against all later ones at once."""
    a, b = p[:-1], p[1:]
    for i in range(len(a) - 2):
        q1, q2 = a[i + 2:], b[i + 2:]
        d1, d2 = _orient(q1, q2, a[i]), _orient(q1, q2, b[i])
        d3, d4 = _orient(a[i], b[i], q1), _orient(a[i], b[i], q2)
        hit = np.flatnonzero((d1 * d2 < 0) & (d3 * d4 < 0))
        if hit.size:
            return i, i + 2 + int(hit[0])
    return None


def check_station_range(xs, lpp, source=""):
    """Stations must lie near the perpendiculars: x from -margin to (1 + margin) Lpp.
    Raises InvalidInput naming the first station outside."""
    if len(xs) == 0:
        raise InvalidInput(f"{source}: no stations; expected at least one")
    lo, hi = float(np.min(xs)), float(np.max(xs))
    m = STATION_RANGE_MARGIN * lpp
    if lo < -m or hi > lpp + m:
        raise InvalidInput(f"{source}: stations run from x = {lo:.6g} to {hi:.6g} m but Lpp is {lpp:.6g} m; "
                         "expected stations between the perpendiculars (is Lpp in metres?)")


def check_sections(sections, source=""):
    """Refuse sections that fold back on themselves (a polyline that crosses itself) or
    repeat a point; such data has no fair surface through it.
    Raises InvalidInput naming the section and the point."""
    for s in sections:
        p = s.points
        seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
        if np.any(seg == 0):
            k = int(np.flatnonzero(seg == 0)[0])
            raise InvalidInput(f"{source}: station {s.label or s.x} repeats point {k + 1} "
                             f"(y={p[k, 0]:.6g}, z={p[k, 1]:.6g}); expected distinct points")
        crossing = _first_crossing(p)
        if crossing:
            i, j = crossing
            raise InvalidInput(f"{source}: station {s.label or s.x} folds back: segment {i + 1} "
                               f"crosses segment {j + 1} near z = {p[j, 1]:.6g} m; "
                               "expected a section that does not cross itself")


def knuckles(points, angle_deg=KNUCKLE_ANGLE_DEG) -> np.ndarray:
    """Indices of polyline points where the direction turns by more than ``angle_deg``."""
    p = np.asarray(points, float)
    if len(p) < 3:
        return np.zeros(0, int)
    d = np.diff(p, axis=0)
    d /= np.linalg.norm(d, axis=1)[:, None]
    cosang = np.clip(np.sum(d[:-1] * d[1:], axis=1), -1, 1)
    return np.flatnonzero(np.degrees(np.arccos(cosang)) > angle_deg) + 1


# ---- structured grids -------------------------------------------------------------------

def _check_grid(points, where):
    if points.ndim != 3 or points.shape[2] != 3 or min(points.shape[:2]) < 2:
        raise InvalidInput(f"{where}: grid shape {points.shape}; expected (rows >= 2, cols >= 2, 3)")
    if not np.all(np.isfinite(points)):
        i, j = np.argwhere(~np.all(np.isfinite(points), axis=2))[0]
        raise InvalidInput(f"{where}: point ({i + 1}, {j + 1}) is not a number; expected a complete grid")


def read_xyz_grid(x_path, y_path, z_path, name="grid", role="hull") -> PointGrid:
    """A structured grid from three whitespace-separated matrices of x, y and z (same shape).
    Raises InvalidInput for unreadable or mismatched matrices."""
    mats = []
    for p in (x_path, y_path, z_path):
        try:
            mats.append(np.loadtxt(p, ndmin=2))
        except OSError as exc:
            raise InvalidInput(f"cannot read {p}: {exc.strerror or exc}") from None
        except ValueError as exc:
            raise InvalidInput(f"{p}: {exc}; expected a whitespace-separated matrix of numbers") from None
    if not (mats[0].shape == mats[1].shape == mats[2].shape):
        raise InvalidInput(f"{x_path}: x, y, z matrices have shapes {[m.shape for m in mats]}; expected one shape")
    pts = np.stack(mats, axis=-1)
    _check_grid(pts, str(x_path))
    return PointGrid(name, pts, role)


def read_tecplot(path) -> list:
    """Zones of a Tecplot ASCII file with ``f=point`` data as (i, j, 3) arrays, i fastest in the
    file (Windows line endings accepted).
    Raises InvalidInput for a file that is not point-format Tecplot or a zone whose size does not match its data."""
    try:
        text = pathlib.Path(path).read_text(errors="strict")
    except (OSError, UnicodeDecodeError) as exc:
        raise InvalidInput(f"cannot read {path}: {exc}") from None
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    zones, k = [], 0
    while k < len(lines):
        line = lines[k].strip()
        m = re.match(r"zone\b.*?\bi\s*=\s*(\d+).*?\bj\s*=\s*(\d+)", line, re.IGNORECASE)
        k += 1
        if not m:
            continue
        ni, nj = int(m.group(1)), int(m.group(2))
        if not (1 <= ni and 1 <= nj and ni * nj <= limits.MAX_RESULT_VALUES // 3):
            raise InvalidInput(f"{path}: line {k}: zone i={ni} j={nj}; expected i, j >= 1 and "
                               f"i*j <= {limits.MAX_RESULT_VALUES // 3} points")
        vals = []
        while len(vals) < 3 * ni * nj and k < len(lines):
            if re.match(r"\s*zone\b", lines[k], re.IGNORECASE):
                break
            for tok in lines[k].split():
                try:
                    vals.append(float(tok))
                except ValueError:
                    raise InvalidInput(f"{path}: line {k + 1} has {tok!r}; expected a number") from None
            k += 1
        if len(vals) != 3 * ni * nj:
            raise InvalidInput(f"{path}: zone {len(zones) + 1} has {len(vals) // 3} points; expected i*j = {ni * nj}")
        zones.append(np.array(vals).reshape(nj, ni, 3).transpose(1, 0, 2))
    if not zones:
        raise InvalidInput(f"{path}: no 'Zone i=.. j=..' header; expected Tecplot point data")
    return zones


def read_tecplot_hull(path, lpp, beam, draft, *, name=None) -> HullData:
    """A Tecplot point-grid file whose zones are hull patches already in the project's metres and axes (rows
    stations from aft forward, columns keel to top, like the reference grids once converted).
    Each zone becomes one subdomain; negative y (a port-side grid) is mirrored."""
    lpp, beam, draft = _dimensions(lpp, beam, draft)
    grids = []
    for k, z in enumerate(read_tecplot(path)):
        pts = z.copy()
        pts[..., 1] = np.abs(pts[..., 1])
        _check_grid(pts, f"{path} zone {k + 1}")
        grids.append(PointGrid(f"zone {k + 1}", pts, "hull"))
    return HullData(name or pathlib.Path(path).stem, lpp, beam, draft, grids=grids, source=str(path))


def read_dtmb5415(folder, *, published=None) -> HullData:
    """DTMB 5415 model: the bow, main and transom grids of ``folder`` converted to the project's axes.

    Source frame: metres, FP near x = 0, AP at x = -5.719, z = 0 at the keel line. The main
    grid's rows are stations; it overlaps the bow grid forward of the bow grid's first row (a
    plane section), so the main grid is cut there (a section interpolated linearly between its
    neighbouring rows) and the bow grid, which carries the sonar dome, covers the rest.
    Raises InvalidInput for a missing or malformed grid file."""
    folder = pathlib.Path(folder)
    lpp, beam, draft = 5.719, 0.768, 0.248
    grids = {}
    for part in ("bow", "main", "transom"):
        g = read_xyz_grid(*(folder / f"DTMB5415_{part}_offset_{c}.dat" for c in "xyz"), name=part)
        g.points[..., 0] += lpp  # AP at source x = -5.719 becomes x = 0
        grids[part] = g
    bow, main = grids["bow"], grids["main"]
    x_cut = bow.points[0, :, 0]
    if np.ptp(x_cut) > 1e-9 * lpp:
        raise InvalidInput(f"{folder}: bow grid's first row is not a plane section; expected constant x")
    x_cut = float(x_cut[0])
    xm = main.points[:, :, 0].mean(axis=1)
    k = int(np.searchsorted(xm, x_cut))
    if not 0 < k < len(xm) or np.any(np.ptp(main.points[k - 1:k + 1, :, 0], axis=1) > 1e-6 * lpp):
        raise InvalidInput(f"{folder}: the main grid has no plane sections either side of x = {x_cut:.4f} m "
                         "(where the bow grid begins); expected stations there")
    t = (x_cut - xm[k - 1]) / (xm[k] - xm[k - 1])
    cut_row = (1 - t) * main.points[k - 1] + t * main.points[k]
    main.points = np.concatenate([main.points[:k], cut_row[None]], axis=0)
    main.role = "hull"
    bow.role = "bow (sonar dome)"
    grids["transom"].role = "transom"
    pub = {"volume": 0.554, "lcb_pct": -0.683, "cb": 0.507, "cm": 0.821}
    pub.update(published or {})
    return HullData("DTMB 5415 (model 1:24.83)", lpp, beam, draft,
                    grids=[grids["main"], bow, grids["transom"]],
                    notes=[f"main grid cut at x = {x_cut:.4f} m where the bow grid begins"],
                    published=pub, source=str(folder))


def read_kcs(folder, *, lpp=230.0, beam=32.2, draft=10.8) -> HullData:
    """KCS: the NMRI two-block grids ``kcs_bow2.dat`` and ``kcs_stn2.dat`` scaled by Lpp.

    Source frame: coordinates / Lpp, origin midship on the calm waterline, X downstream (FP at
    X = -0.5), Y starboard, Z up. In the project's axes: x = (0.5 - X) Lpp, y = Y Lpp, z = Z Lpp + T.
    Raises InvalidInput for a missing or malformed grid file."""
    folder = pathlib.Path(folder)
    lpp, beam, draft = _dimensions(lpp, beam, draft)
    grids = []
    roles = {("kcs_bow2.dat", 0): ("bulb", "bulb"), ("kcs_bow2.dat", 1): ("forebody", "hull"),
             ("kcs_stn2.dat", 0): ("transom overhang", "transom"), ("kcs_stn2.dat", 1): ("afterbody", "hull")}
    for fname in ("kcs_bow2.dat", "kcs_stn2.dat"):
        zones = read_tecplot(folder / fname)
        if len(zones) != 2:
            raise InvalidInput(f"{folder / fname}: {len(zones)} zone(s); expected 2 (two-block grid)")
        for z, pts in enumerate(zones):
            conv = np.column_stack([(0.5 - pts[..., 0].ravel()) * lpp, np.abs(pts[..., 1].ravel()) * lpp,
                                    pts[..., 2].ravel() * lpp + draft]).reshape(pts.shape)
            name, role = roles[(fname, z)]
            _check_grid(conv, f"{folder / fname} zone {z + 1}")
            grids.append(PointGrid(name, conv, role))
    pub = {"volume": 52030.0, "cb": 0.6505, "cm": 0.9849, "lcb_pct": -1.48, "wetted_surface": 9424.0}
    return HullData("KCS", lpp, beam, draft, grids=grids, published=pub, source=str(folder))


# ---- detection and plain-data (JSON) form -----------------------------------------------

def read_hull_data(path, lpp=None, beam=None, draft=None, *, fmt="auto", n_stations=20) -> HullData:
    """Read any supported input. ``fmt``: 'offsets' (CSV table), 'sections' (x,y,z CSV),
    'dtmb5415' (folder of the three grid triples), 'kcs' (folder with kcs_bow2.dat and
    kcs_stn2.dat) or 'auto' (from the path: a folder by its files, a CSV by its header).
    Lpp, beam and draft (metres) are needed for tables and section lists; the reference grids
    default to their published model/ship dimensions.
    Raises InvalidInput for a missing path, an unknown format or any value the reader refuses."""
    p = pathlib.Path(path)
    if not p.exists():
        raise InvalidInput(f"{p} does not exist; expected an offsets CSV, a section CSV or a grid folder")
    if fmt == "auto":
        if p.is_dir():
            if (p / "DTMB5415_main_offset_x.dat").exists():
                fmt = "dtmb5415"
            elif (p / "kcs_bow2.dat").exists():
                fmt = "kcs"
            else:
                raise InvalidInput(f"{p}: folder holds neither DTMB5415_*_offset_*.dat nor kcs_*2.dat; "
                                 "expected one of the reference grid folders")
        elif p.suffix.lower() in (".dat", ".plt", ".tec"):
            fmt = "tecplot"
        else:
            rows, _ = _csv_rows(p)
            first = [h.strip().lower() for h in rows[0][1]]
            fmt = "sections" if first[:3] == ["x", "y", "z"] else "offsets"
    if fmt == "dtmb5415":
        data = read_dtmb5415(p)
    elif fmt == "kcs":
        kw = {k: v for k, v in (("lpp", lpp), ("beam", beam), ("draft", draft)) if v is not None}
        data = read_kcs(p, **kw)
    elif fmt in ("offsets", "sections", "tecplot"):
        missing = [n for n, v in (("--lpp", lpp), ("--beam", beam), ("--draft", draft)) if v is None]
        if missing:
            raise InvalidInput(f"{p}: {', '.join(missing)} not given; expected the principal dimensions in metres")
        if fmt == "offsets":
            data = read_offsets_csv(p, lpp, beam, draft, n_stations=n_stations)
        elif fmt == "sections":
            data = read_sections_csv(p, lpp, beam, draft)
        else:
            data = read_tecplot_hull(p, lpp, beam, draft)
    else:
        raise InvalidInput(f"format is {fmt!r}; expected auto, offsets, sections, tecplot, dtmb5415 or kcs")
    if fmt in ("dtmb5415", "kcs"):
        for name, v in (("Lpp", lpp), ("beam", beam), ("draft", draft)):
            if v is not None and fmt == "dtmb5415":
                data.notes.append(f"{name} {v} ignored: the DTMB 5415 grid is at model scale, {name} fixed")
    return data


def hull_data_to_dict(data: HullData) -> dict:
    """JSON-ready form of HullData (lists of floats; NaN cells as null)."""
    def clean(a):
        return [[None if not np.isfinite(v) else float(v) for v in row] for row in np.asarray(a)]
    d = {"name": data.name, "lpp": data.lpp, "beam": data.beam, "draft": data.draft, "source": data.source,
         "notes": list(data.notes), "published": dict(data.published),
         "sections": [{"x": s.x, "label": s.label, "points": s.points.tolist()} for s in data.sections],
         "grids": [{"name": g.name, "role": g.role, "points": g.points.tolist()} for g in data.grids]}
    if len(data.contour):
        d["contour"] = np.asarray(data.contour).tolist()
    if data.offsets is not None:
        o = data.offsets
        d["offsets"] = {"x": o["x"].tolist(), "z": o["z"].tolist(), "half_breadths": clean(o["half_breadths"]),
                        "labels": list(o["labels"]), "extra": o["extra"]}
    return d


def hull_data_from_dict(d: dict) -> HullData:
    """Inverse of hull_data_to_dict; InvalidInput naming a missing entry.
    Raises InvalidInput naming a missing entry."""
    try:
        data = HullData(d["name"], _positive("lpp", d["lpp"]), _positive("beam", d["beam"]),
                        _positive("draft", d["draft"]), source=d.get("source", ""),
                        notes=list(d.get("notes", [])), published=dict(d.get("published", {})))
        data.sections = [Section(float(s["x"]), np.array(s["points"], float), s.get("label", ""))
                         for s in d.get("sections", [])]
        data.grids = [PointGrid(g["name"], np.array(g["points"], float), g.get("role", "hull"))
                      for g in d.get("grids", [])]
        data.contour = np.array(d.get("contour", []), float).reshape(-1, 2)
        if d.get("offsets"):
            o = d["offsets"]
            hb = np.array([[np.nan if v is None else v for v in row] for row in o["half_breadths"]], float)
            data.offsets = {"x": np.array(o["x"], float), "z": np.array(o["z"], float), "half_breadths": hb,
                            "labels": list(o["labels"]), "extra": o.get("extra", [])}
    except KeyError as exc:
        raise InvalidInput(f"hull input data has no {exc.args[0]!r} entry") from None
    if not data.sections and not data.grids:
        raise InvalidInput("hull input data has neither sections nor grids; expected one of them")
    for g in data.grids:
        _check_grid(g.points, f"grid {g.name!r}")
    return data
