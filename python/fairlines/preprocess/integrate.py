"""Integrals of the input itself: Simpson's rule on an offsets table, Green's theorem along
section polylines, and the hydrostatic coefficients from volume, centroids and areas."""

from __future__ import annotations

import dataclasses

import numpy as np

from .._native import InvalidInput
from ..offsets import HullData


def simpson(y, x) -> float:
    """∫ y dx by Simpson's rule on irregularly spaced x (a parabola through each pair of
    intervals; a final odd interval takes the parabola through the last three points)."""
    y, x = np.asarray(y, float), np.asarray(x, float)
    n = len(x) - 1
    if n < 1:
        return 0.0
    if n == 1:
        return 0.5 * (y[0] + y[1]) * (x[1] - x[0])
    total = 0.0
    for i in range(0, n - 1, 2):
        total += _parabola_integral(x[i:i + 3], y[i:i + 3], x[i], x[i + 2])
    if n % 2 == 1:
        total += _parabola_integral(x[n - 2:n + 1], y[n - 2:n + 1], x[n - 1], x[n])
    return total


def _parabola_integral(xs, ys, a, b):
    """∫_a^b of the parabola through three points (exact for quadratics)."""
    h0, h1 = xs[1] - xs[0], xs[2] - xs[1]
    if h0 <= 0 or h1 <= 0:
        raise InvalidInput(f"abscissae {list(xs)} are not increasing; expected sorted stations")
    c = np.polyfit(xs - xs[0], ys, 2)
    P = np.polyint(c)
    return float(np.polyval(P, b - xs[0]) - np.polyval(P, a - xs[0]))


def _section_integrals(hb, z, draft):
    """Half-section area below the draft ∫ y dz, its moment ∫ y z dz, and the half-breadth at
    the draft, by Simpson on the waterlines (blank cells dropped); the draft waterline is
    interpolated linearly when it is not a column."""
    ok = ~np.isnan(hb)
    hb, z = hb[ok], z[ok]
    if z[-1] < draft:
        raise InvalidInput(f"offsets reach z = {z[-1]:.6g} m; expected waterlines up to the draft {draft:.6g} m")
    below = z < draft
    zz = np.append(z[below], draft)
    yy = np.append(hb[below], np.interp(draft, z, hb))
    return simpson(yy, zz), simpson(yy * zz, zz), yy[-1]


def offsets_hydrostatics(data: HullData, draft=None) -> ImportHydrostatics:
    """Volume, centres and coefficients of the input offsets by Simpson's rule (both sides).

    Integration runs over the stations given (normally AP to FP) and the waterlines up to the
    draft; LCB is reported from the AP and in % Lpp from midships (+ forward).
    Raises InvalidInput for data without an offsets table or offsets below the draft."""
    if data.offsets is None:
        raise InvalidInput(f"{data.name}: no offsets table; expected data read by read_offsets_csv")
    T = data.draft if draft is None else float(draft)
    x, z, hb = data.offsets["x"], data.offsets["z"], data.offsets["half_breadths"]
    a, mz, ywl = np.array([_section_integrals(h, z, T) for h in hb]).T
    areas = 2 * a
    V = simpson(areas, x)
    lcb = simpson(areas * x, x) / V
    vcb = simpson(2 * mz, x) / V
    awp = 2 * simpson(ywl, x)
    lcf = 2 * simpson(ywl * x, x) / awp
    imid = int(np.argmin(np.abs(x - data.lpp / 2)))
    am = np.interp(data.lpp / 2, x, areas)
    # Girth method: each section's wetted girth below the draft, integrated along the ship
    # (ignores the longitudinal slope of the surface, so it reads a little low at the ends).
    girth = np.array([_girth(s.points, T) for s in data.sections])
    return coefficients(V, lcb, vcb, awp, lcf, am, data.lpp, data.beam, T, method="Simpson on the offsets table",
                        section_x=x, section_areas=areas, midship_station=data.offsets["labels"][imid],
                        area_fraction_check=_area_fraction_check(data, areas, am),
                        wetted_surface=2 * simpson(girth, np.array([s.x for s in data.sections])))


def _girth(p, draft):
    """Length of a (y, z) section polyline below the draft."""
    g = 0.0
    for k in range(len(p) - 1):
        a, b = p[k], p[k + 1]
        if a[1] > draft and b[1] > draft:
            continue
        if a[1] > draft or b[1] > draft:
            t = (draft - a[1]) / (b[1] - a[1])
            c = a + t * (b - a)
            a, b = (a, c) if b[1] > draft else (c, b)
        g += float(np.linalg.norm(b - a))
    return g


# A tabulated section area fraction further than this from the integrated one is reported.
AREA_FRACTION_TOL = 0.01


def _area_fraction_check(data, areas, am):
    """Compare a table's own 'area_fraction' column (if any) with the integrated section areas;
    list the stations where they disagree by more than AREA_FRACTION_TOL."""
    extra = data.offsets.get("extra") or []
    out = []
    for lab, a, e in zip(data.offsets["labels"], areas, extra):
        v = e.get("area_fraction") if e else None
        if v is not None and np.isfinite(v) and abs(v - a / am) > AREA_FRACTION_TOL:
            out.append({"station": lab, "tabulated": float(v), "integrated": float(a / am)})
    return out


def sections_hydrostatics(data: HullData, draft=None) -> ImportHydrostatics:
    """Hydrostatics of section polylines: each section's area and moment by the trapezoid rule
    (Green's theorem on the polyline), then Simpson's rule along the stations.
    Raises InvalidInput for stations not strictly increasing."""
    T = data.draft if draft is None else float(draft)
    x = np.array([s.x for s in data.sections])
    if np.any(np.diff(x) <= 0):
        raise InvalidInput(f"{data.name}: stations are not strictly increasing; expected sorted, distinct stations")
    areas = np.array([2 * polyline_area(s.points, T) for s in data.sections])
    mz = np.array([2 * _polyline_moment_z(s.points, T) for s in data.sections])
    ywl = np.array([half_breadth_at(s.points, T) for s in data.sections])
    V = simpson(areas, x)
    awp = 2 * simpson(ywl, x)
    return coefficients(V, simpson(areas * x, x) / V, simpson(mz, x) / V, awp, 2 * simpson(ywl * x, x) / awp,
                        np.interp(data.lpp / 2, x, areas), data.lpp, data.beam, T,
                        method="trapezoid on the sections, Simpson along the ship", section_x=x, section_areas=areas)


@dataclasses.dataclass
class ImportHydrostatics:
    """Hydrostatics of an imported hull at one draft (its input, or its rebuilt surfaces or
    meshes), both sides, in the names of :class:`fairlines.Hydrostatics`: lengths m from the
    AP / above base, areas m^2, volume m^3. ``lcb_pct`` is the LCB in % Lpp from midships
    (+ forward); ``wetted_surface`` is None where the method gives none."""
    draft: float
    volume: float
    lcb: float
    lcb_pct: float
    vcb: float
    waterplane_area: float
    lcf: float
    midship_area: float
    cb: float
    cm: float
    cp: float
    cwp: float
    method: str
    wetted_surface: float | None = None
    section_x: np.ndarray | None = None
    section_areas: np.ndarray | None = None
    midship_station: str | None = None
    area_fraction_check: list = dataclasses.field(default_factory=list)

    def as_dict(self, *, arrays: bool = True) -> dict:
        """The scalars (and, with ``arrays``, the section areas) as a plain dict of the same names."""
        d = dataclasses.asdict(self)
        return d if arrays else {k: v for k, v in d.items() if k not in ("section_x", "section_areas")}


def coefficients(V, lcb, vcb, awp, lcf, am, lpp, beam, draft, *, method, **extra) -> ImportHydrostatics:
    """The form coefficients of volume V (m^3), centres lcb, vcb (m), waterplane area awp (m^2)
    with centroid lcf (m), midship area am (m^2) on Lpp x B x T."""
    return ImportHydrostatics(
        draft=draft, volume=V, lcb=lcb, lcb_pct=100 * (lcb - lpp / 2) / lpp, vcb=vcb, waterplane_area=awp,
        lcf=lcf, midship_area=am, cb=V / (lpp * beam * draft), cm=am / (beam * draft), cp=V / (am * lpp),
        cwp=awp / (lpp * beam), method=method, **extra)


def polyline_area(p, draft):
    """Half-section area below the draft of a (y, z) polyline running bottom to top:
    ∫ y dz along the part with z <= draft (Green's theorem; centreplane and waterline add 0)."""
    y, z = p[:, 0], p[:, 1]
    area = 0.0
    for k in range(len(p) - 1):
        z0, z1, y0, y1 = z[k], z[k + 1], y[k], y[k + 1]
        if z0 > draft and z1 > draft:
            continue
        if z1 > draft or z0 > draft:  # clip the segment at the waterline
            t = (draft - z0) / (z1 - z0)
            yc = y0 + t * (y1 - y0)
            if z1 > draft:
                z1, y1 = draft, yc
            else:
                z0, y0 = draft, yc
        area += 0.5 * (y0 + y1) * (z1 - z0)
    return area


def _polyline_moment_z(p, draft):
    """∫ y z dz along the part of a (y, z) polyline below the draft (trapezoid on y z)."""
    below = p[:, 1] <= draft
    tot = 0.0
    for k in range(len(p) - 1):
        if not (below[k] or below[k + 1]):
            continue
        y0, y1, z0, z1 = p[k, 0], p[k + 1, 0], p[k, 1], p[k + 1, 1]
        if below[k] != below[k + 1]:
            t = (draft - z0) / (z1 - z0)
            yc = y0 + t * (y1 - y0)
            if below[k]:
                y1, z1 = yc, draft
            else:
                y0, z0 = yc, draft
        tot += 0.5 * (y0 * z0 + y1 * z1) * (z1 - z0)
    return tot


def half_breadth_at(p, z0):
    """Outermost half-breadth of a (y, z) polyline where it crosses z0 (0 if it does not)."""
    y, z = p[:, 0], p[:, 1]
    best = 0.0
    for k in range(len(p) - 1):
        if (z[k] - z0) * (z[k + 1] - z0) <= 0 and z[k] != z[k + 1]:
            t = (z0 - z[k]) / (z[k + 1] - z[k])
            best = max(best, y[k] + t * (y[k + 1] - y[k]))
    return best
