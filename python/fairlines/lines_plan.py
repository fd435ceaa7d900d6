"""Lines plan of a hull: profile (sheer) plan, half-breadth plan and body plan.

The hull is one NURBS surface, a list of surfaces (optionally with trimming loops) or a
composed hull; its lines are exact plane sections (:mod:`fairlines.plane_sections`).
Conventions (metres; x forward from the AP, y half-breadth, z up from the base line):

* profile plan, bow to the right: buttocks in true shape, stations and waterlines as straight
  lines, the outline (stem, keel, deck at side, transom / aft cut);
* half-breadth plan below it, on the same x: waterlines in true shape above the centre line,
  diagonals expanded (true shape, distance along the diagonal from the centre line) below it;
* body plan to the right of the profile, on the same z: aft stations on the left of the
  centre line, fore stations on the right, with the traces of waterlines, buttocks and
  diagonals.

Stations are numbered 0 at the AP to 20 at the FP (spacing Lpp / 20), with half stations at
the ends and more beyond them wherever the hull extends. Knuckles (a normal-angle jump of more
than :data:`KNUCKLE_ANGLE_DEG` across a knot line) are drawn in every view.

:func:`lines_plan` builds a :class:`LinesPlan`: the lines themselves and the drawing as
primitives (polylines and texts in drawing metres, model scale), which
:mod:`fairlines.lines_render` writes as SVG / PDF / PNG (matplotlib) and DXF (ezdxf).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from ._native import InvalidInput, NurbsSurface
from .hydrostatics_composed import CAP_PARTS, composed_hydrostatics, waterplane_from_sections  # noqa: F401  (re-exported)
from .hydrostatics_surface import hydrostatics, midship_x
from .lines_layout import layout
from .lines_sheet import SHEET_MM, STATIONS_PER_LPP, Polyline, Text
from .plane_sections import boundary_curves, chain_segments, even_odd_inside, plane_sections

__all__ = ["LinesPlan", "Polyline", "Text", "lines_plan", "closeup", "default_stations", "nice_step", "KNUCKLE_ANGLE_DEG"]

#: Normal-angle jump (degrees) across a knot line above which it is drawn as a knuckle.
KNUCKLE_ANGLE_DEG = 3.0
#: Boundary points of one subdomain within this fraction of the hull's size of another
#: subdomain are a seam between them, not an edge of the hull, and are not drawn.
SEAM_TOLERANCE = 1e-4
#: Boundary points with |y| below this fraction of the hull's size are on the centre plane.
CENTRE_PLANE_TOLERANCE = 1e-7
#: A station on an end of the hull is cut this fraction of Lpp inside it.
END_NUDGE = 1e-9
@dataclass
class LinesPlan:
    """The lines of a hull and their drawing.

    ``stations``, ``waterlines``, ``buttocks``, ``diagonals``: lists of (label, value, polylines
    (k, 3) in model metres); ``knuckles`` and ``outline``: lists of (k, 3) polylines;
    ``particulars`` (lpp, beam, draft, depth, name); ``hydrostatics`` (dict or None, with its
    ``source``); ``scale`` N of 1:N on an A3 sheet (profile and half-breadth plan);
    ``body_scale`` N of the body plan (larger when it has a band of the sheet of its own);
    ``primitives``: the drawing (Polyline and Text in drawing metres at 1:``scale``);
    ``offsets``: where each view's origin sits in the drawing, ``factors`` each view's
    magnification over 1:``scale``.
    """

    stations: list
    waterlines: list
    buttocks: list
    diagonals: list
    knuckles: list
    outline: list
    particulars: dict
    hydrostatics: dict | None
    scale: float = 1.0
    primitives: list = field(default_factory=list)
    offsets: dict = field(default_factory=dict)
    factors: dict = field(default_factory=dict)
    body_scale: float = 1.0
    sheet_mm: tuple = SHEET_MM
    title: str = "LINES PLAN"

    def save(self, path, dpi: int = 200) -> None:
        """Write the drawing; the format follows the suffix: .svg, .pdf, .png or .dxf."""
        from . import lines_render
        lines_render.save(self, path, dpi=dpi)

    def to_model(self, view: str, points: np.ndarray) -> np.ndarray:
        """Drawing coordinates (k, 2) of ``view`` back to the model's plane coordinates:
        (x, z) for "profile", (x, y) for "plan", (y, z) for "body" (y signed: < 0 aft side)."""
        ox, oy = self.offsets[view]
        return (np.asarray(points, float)[:, :2] - [ox, oy]) / self.factors.get(view, 1.0)


def nice_step(span: float, count: float) -> float:
    """A round step (1, 2, 2.5 or 5 x 10^k) near span / count."""
    raw = span / count
    k = math.floor(math.log10(raw))
    return min((m * 10 ** k for m in (1, 2, 2.5, 5, 10)), key=lambda s: abs(math.log(s / raw)))


def default_stations(lpp: float, x_min: float, x_max: float, step: float = 1.0) -> list[float]:
    """Station numbers (0 at AP .. 20 at FP) inside [x_min, x_max]: every ``step`` stations,
    half stations in the end intervals and every half station beyond the perpendiculars."""
    n = [float(k) for k in np.arange(0.0, STATIONS_PER_LPP + 0.5 * step, step)]
    n += [0.5, 1.5, STATIONS_PER_LPP - 1.5, STATIONS_PER_LPP - 0.5]
    beyond = min(0.5, step)
    k = beyond
    while -k * lpp / STATIONS_PER_LPP > x_min or (STATIONS_PER_LPP + k) * lpp / STATIONS_PER_LPP < x_max:
        n += [-k, STATIONS_PER_LPP + k]
        k += beyond
    eps = 1e-9 * lpp
    return sorted(s for s in set(n) if x_min - eps <= s * lpp / STATIONS_PER_LPP <= x_max + eps)


def _as_patches(hull) -> list[tuple[NurbsSurface, list | None]]:
    if isinstance(hull, NurbsSurface):
        return [(hull, None)]
    if hasattr(hull, "trimmed_surfaces"):
        return [(s, [np.asarray(l, float) for l in loops]) for s, loops in hull.trimmed_surfaces]
    out = []
    for item in hull:
        if isinstance(item, NurbsSurface):
            out.append((item, None))
        elif isinstance(item, tuple) and len(item) == 2 and isinstance(item[0], NurbsSurface):
            out.append((item[0], None if item[1] is None else [np.asarray(l, float) for l in item[1]]))
        else:
            raise InvalidInput(f"hull entry is {type(item).__name__}; expected a NurbsSurface or (surface, loops)")
    if not out:
        raise InvalidInput("hull is empty; expected at least one surface")
    return out


def _cut_all(patches, normal, offset, refine=1):
    out = []
    for s, loops in patches:
        out += [c.points for c in plane_sections(s, normal, offset, loops=loops, refine=refine) if len(c.points) > 1]
    return out


def _knuckles(patches) -> list[np.ndarray]:
    """Knot lines of full multiplicity across which the normal turns more than the threshold."""
    out = []
    cos_lim = math.cos(math.radians(KNUCKLE_ANGLE_DEG))
    for s, loops in patches:
        for direction in ("u", "v"):
            knots = np.asarray(s.knots_u if direction == "u" else s.knots_v)
            deg = s.degree_u if direction == "u" else s.degree_v
            other = np.asarray(s.knots_v if direction == "u" else s.knots_u)
            vals, counts = np.unique(knots[deg + 1:len(knots) - deg - 1], return_counts=True)
            t = np.linspace(other[0], other[-1], 201)
            for k, m in zip(vals, counts):
                if m < deg:
                    continue
                eps = 1e-7 * (knots[-1] - knots[0])
                uv = [(np.full_like(t, k + d), t) if direction == "u" else (t, np.full_like(t, k + d)) for d in (-eps, eps)]
                n0 = np.asarray(s.normal(*uv[0]))
                n1 = np.asarray(s.normal(*uv[1]))
                sharp = np.einsum("ij,ij->i", n0, n1) < cos_lim
                if loops is not None:
                    sharp &= even_odd_inside(np.column_stack(uv[0]), loops)
                pts = np.asarray(s.evaluate(*uv[0]))
                for run in _runs(sharp):
                    if len(run) > 1:
                        out.append(pts[run])
    return out


def _runs(mask: np.ndarray) -> list[np.ndarray]:
    idx = np.flatnonzero(mask)
    if len(idx) == 0:
        return []
    return np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)


def _outline(patches) -> list[np.ndarray]:
    """Surface edges that are edges of the hull: every boundary point on the centre plane
    (the profile outline), and elsewhere the points that lie on no other subdomain (not a
    seam); degenerate (pole) edges are left out."""
    out = []
    scale = max(float(np.ptp(np.concatenate([b for s, l in patches for b in boundary_curves(s, l)]), axis=0).max()), 1.0)
    for i, (s, loops) in enumerate(patches):
        for b in boundary_curves(s, loops):
            if np.ptp(b, axis=0).max() < SEAM_TOLERANCE:
                continue
            keep = np.abs(b[:, 1]) <= CENTRE_PLANE_TOLERANCE * scale
            for j, (other, _) in enumerate(patches):
                if j != i and not keep.all():
                    far = np.full(len(b), np.inf)
                    far[~keep] = np.linalg.norm(other.closest_points(b[~keep])[2] - b[~keep], axis=1)
                    keep |= far > SEAM_TOLERANCE * scale
            if len(patches) == 1:
                keep[:] = True
            for run in _runs(keep):
                if len(run) > 1:
                    out.append(b[run])
    return out


def _mesh_outline(composed) -> list[np.ndarray]:
    """Edges of a composed hull's mesh between a cap face (centre plane, deck, aft cut) and a
    surface face: the hull's outline at the mesh resolution, its points on the surfaces."""
    F = np.asarray(composed.mesh.faces)
    V = np.asarray(composed.mesh.vertices)
    cap = np.isin(np.asarray(composed.face_part), CAP_PARTS)
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    owner_cap = np.tile(cap, 3)
    key = np.sort(e, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, owner_cap = key[order], owner_cap[order]
    same = np.all(key[1:] == key[:-1], axis=1)
    pairs = np.flatnonzero(same & (owner_cap[1:] != owner_cap[:-1]))
    segs = [tuple(k) for k in key[pairs]]
    return [V[chain + [chain[0]] if closed else chain] for chain, closed in chain_segments(segs)]


def _split_on_centre_plane(curves, lpp):
    """Curves cut where they leave or join the centre plane, so each piece is on it or off it."""
    out = []
    for c in curves:
        on = np.abs(c[:, 1]) <= CENTRE_PLANE_TOLERANCE * lpp
        cuts = np.flatnonzero(on[1:] != on[:-1]) + 1
        start = 0
        for k in list(cuts) + [len(c)]:
            # a piece off the plane keeps its end points on it, so the drawing stays joined
            lo, hi = max(start - 1, 0), min(k + 1, len(c))
            piece = c[start:k] if on[start] else c[lo:hi]
            if len(piece) > 1:
                out.append(piece)
            start = k
    return out


def _densify(p: np.ndarray, per: int = 8) -> np.ndarray:
    t = np.linspace(0, 1, per, endpoint=False)[:, None, None]
    return np.concatenate([(p[:-1] + t * (p[1:] - p[:-1])).reshape(-1, 3), p[-1:]])


def _extent(patches):
    pts = np.concatenate([b for s, loops in patches for b in boundary_curves(s, loops)]
                         + [np.asarray(s.evaluate_grid(np.linspace(*s.domain_u, 33), np.linspace(*s.domain_v, 33))).reshape(-1, 3)
                            for s, _ in patches])
    return pts.min(axis=0), pts.max(axis=0)


def _hydrostatics(hull, patches, p, dwl_cuts=()) -> dict | None:
    """Hydrostatics at the design draft for the title block, with where they come from."""
    try:
        if len(patches) == 1 and patches[0][1] is None:
            from .fairness import surface_extent
            h = _quadrature(patches[0][0], p)
            # the surface, not its wetted part (a dry counter or transom is modelled too)
            lo, hi = (float(e[0]) for e in surface_extent(patches[0][0]))
            full = lo <= 1e-6 * p["lpp"] and hi >= p["lpp"] * (1 - 1e-6)
            h["source"] = "NURBS quadrature" + ("" if full else f", modelled part x {lo:.1f}-{hi:.1f} m only")
            return h
        if hasattr(hull, "mesh"):
            return composed_hydrostatics(hull, p["draft"], lpp=p["lpp"], beam=p["beam"], waterline_cuts=dwl_cuts)
    except (ValueError, RuntimeError):
        return None
    return None


def _quadrature(s, p) -> dict:
    return hydrostatics(s, p["draft"], length=p["lpp"], breadth=p["beam"],
                                midship_x=midship_x(s, 0.5 * p["lpp"])).as_dict()


def lines_plan(hull, *, lpp: float, beam: float, draft: float, depth: float, name: str = "",
               stations: Sequence[float] | None = None, waterlines: Sequence[float] | None = None,
               buttocks: Sequence[float] | None = None, diagonals: Sequence[tuple[float, float]] | None = None,
               hydrostatics: dict | None = None, x_range: tuple[float, float] | None = None,
               title: str = "LINES PLAN") -> LinesPlan:
    """Lines plan of a hull.

    hull         a NurbsSurface (half hull, y >= 0), a list of surfaces or of (surface, loops)
                 pairs ((k, 2) (u, v) trimming loops, kept inside), or a ComposedHull.
    lpp, beam, draft, depth   principal particulars (m): Lpp (AP at x = 0), B, design draft T
                 (the DWL), depth D.
    name         ship name for the title block.
    stations     station numbers (0 = AP, 20 = FP; default :func:`default_stations`).
    waterlines   heights (m above base) besides the DWL (default: a round step near T / 5 up
                 to D); buttocks: half-breadths (m; default a round step near B / 8).
    diagonals    (height on the centre line (m), angle below the horizontal (deg)) pairs;
                 default three 45 deg diagonals through B/4, 3B/8 and B/2 above the base.
    hydrostatics dict for the title block (default: computed at T, see ``LinesPlan``).
    x_range      (x_from, x_to) m: draw only this part (close-ups, quarter stations by
                 default); lines are clipped to it. See :func:`closeup`.

    Raises InvalidInput for non-positive particulars, draft above depth, or a bad hull entry.
    """
    p = dict(lpp=float(lpp), beam=float(beam), draft=float(draft), depth=float(depth), name=name)
    for k in ("lpp", "beam", "draft", "depth"):
        if not (np.isfinite(p[k]) and p[k] > 0):
            raise InvalidInput(f"{k} is {p[k]!r}; expected a length > 0 (m)")
    if p["draft"] > p["depth"]:
        raise InvalidInput(f"draft {p['draft']} m is above depth {p['depth']} m; expected draft <= depth")
    patches = _as_patches(hull)
    lo, hi = _extent(patches)
    x0, x1 = (lo[0], hi[0]) if x_range is None else (max(lo[0], x_range[0]), min(hi[0], x_range[1]))
    if stations is not None:
        st_nums = list(stations)
    else:  # a close-up gets quarter stations
        st_nums = default_stations(p["lpp"], x0, x1, 1.0 if x_range is None else 0.25)
    dz = nice_step(p["draft"], 5)
    if waterlines is None:
        waterlines = [z for z in np.arange(dz, hi[2], dz) if abs(z - p["draft"]) > 0.3 * dz]
    wls = sorted(set([float(z) for z in waterlines] + [p["draft"]]))
    dy = nice_step(0.5 * p["beam"], 4)
    if buttocks is None:
        buttocks = [y for y in np.arange(dy, hi[1], dy) if hi[1] - y > 0.2 * dy]
    if diagonals is None:
        diagonals = [(f * p["beam"], 45.0) for f in (0.25, 0.375, 0.5)]
    spacing = p["lpp"] / STATIONS_PER_LPP
    # A station on an end of the hull (the aft cut of a forebody) is cut a hair inside it.
    nudge = END_NUDGE * p["lpp"]
    st = [(_station_label(n), n * spacing,
           _cut_all(patches, (1, 0, 0), float(np.clip(n * spacing, lo[0] + nudge, hi[0] - nudge)))) for n in st_nums]
    wl = [("DWL" if z == p["draft"] else f"{z:g}", z, _cut_all(patches, (0, 0, 1), z)) for z in wls]
    bl = [(f"{y:g}", y, _cut_all(patches, (0, 1, 0), y)) for y in buttocks]
    dg = []
    for k, (zc, ang) in enumerate(diagonals):
        a = math.radians(ang)
        cuts = _cut_all(patches, (0, math.sin(a), math.cos(a)), zc * math.cos(a))
        if cuts:
            dg.append((f"D{k + 1}", (zc, ang), cuts))
    outline = _mesh_outline(hull) if hasattr(hull, "face_part") else _outline(patches)
    plan = LinesPlan(st, wl, bl, dg, _knuckles(patches), _split_on_centre_plane(outline, p["lpp"]), p,
                     hydrostatics if hydrostatics is not None else _hydrostatics(hull, patches, p, wl[wls.index(p["draft"])][2]),
                     title=title)
    layout(plan, (x0, x1), lo, hi)
    return plan


def closeup(hull, end: str = "bow", fraction: float = 0.15, **kw) -> LinesPlan:
    """Lines plan of the bow (``end="bow"``: from (1 - fraction) Lpp forward) or the stern
    (``"stern"``: aft of fraction Lpp), at the scale that fills the sheet; other keywords as
    :func:`lines_plan` (lpp, beam, draft, depth required). Raises InvalidInput for another end."""
    lpp = float(kw["lpp"])
    if end == "bow":
        xr = ((1.0 - fraction) * lpp, np.inf)
    elif end == "stern":
        xr = (-np.inf, fraction * lpp)
    else:
        raise InvalidInput(f"end is {end!r}; expected 'bow' or 'stern'")
    kw.setdefault("title", f"LINES PLAN - {end.upper()} CLOSE-UP")
    return lines_plan(hull, x_range=xr, **kw)


def _station_label(n: float) -> str:
    return f"{n:g}"
