"""Pre-processor (pipeline step 1, SPEC §2): from hull data read by :mod:`fairlines.offsets` to
form parameters found automatically, a rebuilt faired surface, its deviation from every input
point, and the hydrostatics of both the input and the surface.

Hydrostatics are computed three independent ways:

* ``offsets_hydrostatics``: Simpson's rule on the offsets table itself (irregular spacing in
  both directions, the half-breadths read as a section's polyline below the draft);
* ``mesh_hydrostatics``: exact integrals over a triangle mesh (an input grid triangulated, or a
  surface tessellated) clipped at the waterline, by the divergence theorem;
* ``surface_hydrostatics``: Gauss quadrature over the NURBS parameter domain, each iso-line
  cut exactly at the waterline.

The volume identities used by both surface paths, with n the outward normal of the half-hull
below the draft: V = ∫ y n_y dS, V·LCB = ∫ x y n_y dS, V·VCB = ∫ z y n_y dS, and the
half-waterplane A_wp = -∫ n_z dS. The field (0, y f(x, z), 0) has no flux through the
centreplane, the waterplane or any plane x = const, so neither the waterplane, nor a cut at a
transom or a perpendicular, needs closing.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from . import _native
from ._native import InvalidInput
from .grid_faces import grid_triangles
from .hydrostatics_mesh import hydrostatics_of_mesh
from .offsets import HullData, knuckles

# A section point counts as on the flat of side / flat of bottom when within this fraction of
# B/2 of the maximum half-breadth, or of T of the keel.
FLAT_TOL = 0.005
# A station has a flat of bottom when it runs along the keel line over at least this fraction of B.
FOB_MIN_HALF_WIDTH = 0.02
# A forefoot reaching further below the baseline than this fraction of T is a sonar dome (a
# skinned bare hull may dip a little below the baseline between stations; that is not one).
DOME_MIN_DEPTH = 0.05
# A grid point whose distance at its fitting parameters is below this fraction of Lpp is not
# projected onto the surface again (the bound is then the deviation to within rounding).
DEVIATION_EXACT_TOL = 1e-9
# Least-squares fairing of a structured grid keeps at least this many control points a direction.
GRID_MIN_CONTROL = 12
# Gauss-Legendre points per knot span (u) and per sub-interval (v) for surface integrals.
GAUSS_POINTS = 6
# Sub-intervals per submerged v-interval in the surface integrals.
V_SUBINTERVALS = 24
# Samples along each iso-line used to find where it crosses the waterline (then bisected).
CROSSING_SAMPLES = 256


# ---- 1-D integration ---------------------------------------------------------------------

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


# ---- hydrostatics of an offsets table ----------------------------------------------------

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


def offsets_hydrostatics(data: HullData, draft=None) -> dict:
    """Volume, centres and coefficients of the input offsets by Simpson's rule (both sides).

    Integration runs over the stations given (normally AP to FP) and the waterlines up to the
    draft; LCB is reported from the AP and in % Lpp from midships (+ forward)."""
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
    out = _coefficients(V, lcb, vcb, awp, lcf, am, data.lpp, data.beam, T)
    out.update(method="Simpson on the offsets table", section_x=x, section_areas=areas,
               midship_station=data.offsets["labels"][imid])
    out["area_fraction_check"] = _area_fraction_check(data, areas, am)
    # Girth method: each section's wetted girth below the draft, integrated along the ship
    # (ignores the longitudinal slope of the surface, so it reads a little low at the ends).
    girth = np.array([_girth(s.points, T) for s in data.sections])
    out["wetted_surface"] = 2 * simpson(girth, np.array([s.x for s in data.sections]))
    return out


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


def sections_hydrostatics(data: HullData, draft=None) -> dict:
    """Hydrostatics of section polylines: each section's area and moment by the trapezoid rule
    (Green's theorem on the polyline), then Simpson's rule along the stations."""
    T = data.draft if draft is None else float(draft)
    x = np.array([s.x for s in data.sections])
    if np.any(np.diff(x) <= 0):
        raise InvalidInput(f"{data.name}: stations are not strictly increasing; expected sorted, distinct stations")
    areas = np.array([2 * _polyline_area(s.points, T) for s in data.sections])
    mz = np.array([2 * _polyline_moment_z(s.points, T) for s in data.sections])
    ywl = np.array([_half_breadth_at(s.points, T) for s in data.sections])
    V = simpson(areas, x)
    awp = 2 * simpson(ywl, x)
    out = _coefficients(V, simpson(areas * x, x) / V, simpson(mz, x) / V, awp, 2 * simpson(ywl * x, x) / awp,
                        np.interp(data.lpp / 2, x, areas), data.lpp, data.beam, T)
    out.update(method="trapezoid on the sections, Simpson along the ship", section_x=x, section_areas=areas)
    return out


def _coefficients(V, lcb, vcb, awp, lcf, am, lpp, beam, draft):
    return {
        "draft": draft, "volume": V, "LCB": lcb, "LCB_pct_Lpp_from_midship": 100 * (lcb - lpp / 2) / lpp,
        "VCB": vcb, "Awp": awp, "LCF": lcf, "Am": am,
        "Cb": V / (lpp * beam * draft), "Cm": am / (beam * draft), "Cp": V / (am * lpp),
        "Cwp": awp / (lpp * beam),
    }


# ---- triangle meshes ---------------------------------------------------------------------

def grid_mesh(points):
    """Triangles of a structured (rows, cols, 3) grid: vertices (n, 3), faces (m, 3); faces of
    zero area (a grid row collapsed to a point) are dropped."""
    ni, nj = points.shape[:2]
    faces = grid_triangles(ni, nj)
    tri = points.reshape(-1, 3)[faces]
    area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    return points.reshape(-1, 3), faces[area > 0]


def mesh_hydrostatics(meshes, draft, lpp, beam) -> dict:
    """Hydrostatics of one or more triangle meshes [(vertices, faces), ...] of the half hull,
    clipped at the draft (the engine's :func:`fairlines.hydrostatics_of_mesh`); both sides
    reported. Each mesh is oriented on its own. Raises InvalidInput for malformed meshes."""
    parts = [hydrostatics_of_mesh(v, f, draft, orient=True, midship_x=lpp / 2) for v, f in meshes]
    V = sum(h.volume for h in parts)
    awp = sum(h.waterplane_area for h in parts)
    out = _coefficients(V, sum(h.volume * h.lcb for h in parts) / V, sum(h.volume * h.vcb for h in parts) / V, awp,
                        sum(h.waterplane_area * h.lcf for h in parts) / awp, sum(h.midship_area for h in parts),
                        lpp, beam, draft)
    out["wetted_surface"] = sum(h.wetted_surface for h in parts)
    out["method"] = "divergence theorem on a triangle mesh"
    return out


# ---- NURBS surfaces ----------------------------------------------------------------------

def _gauss(a, b, n):
    t, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (b - a) * t + 0.5 * (a + b), 0.5 * (b - a) * w


def _submerged_intervals(surface, us, draft):
    """For each u, the v-intervals where z(u, v) <= draft, as arrays (u_index, v0, v1); the
    waterline crossings are bracketed on CROSSING_SAMPLES samples, then bisected (all at once)."""
    v0, v1 = surface.domain_v
    vs = np.linspace(v0, v1, CROSSING_SAMPLES)
    zz = surface.evaluate_grid(us, vs)[:, :, 2] - draft
    below = zz <= 0
    ii, jj = np.nonzero(below[:, :-1] != below[:, 1:])
    a, b = vs[jj].copy(), vs[jj + 1].copy()
    a_below = below[ii, jj]
    for _ in range(48):  # bisection to the waterline crossing, every bracket at once
        m = 0.5 * (a + b)
        m_below = surface.evaluate(us[ii], m)[:, 2] <= draft if len(m) else np.zeros(0, bool)
        same = m_below == a_below
        a = np.where(same, m, a)
        b = np.where(same, b, m)
    cross = 0.5 * (a + b)
    out_i, out_a, out_b = [], [], []
    for i in range(len(us)):
        if not below[i].any():
            continue
        bounds = ([vs[0]] if below[i, 0] else []) + list(cross[ii == i]) + ([vs[-1]] if below[i, -1] else [])
        for k in range(0, len(bounds) - 1, 2):
            out_i.append(i)
            out_a.append(bounds[k])
            out_b.append(bounds[k + 1])
    return np.array(out_i, int), np.array(out_a), np.array(out_b)


def surface_hydrostatics(surfaces, draft, lpp, beam, *, roles=None) -> dict:
    """Hydrostatics of NURBS half-hull surfaces below the draft by Gauss quadrature: in u per
    knot span, in v over each submerged interval (cut at the waterline by bisection). Midship
    area Am is the section of the surfaces at x = Lpp/2 (Green's theorem on the cut)."""
    tot = dict.fromkeys(("V", "Mx", "Mz", "S", "Awp", "Mwp"), 0.0)
    tg, tw = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    for surf in surfaces:
        ku = np.unique(surf.knots_u)
        h = 0.5 * np.diff(ku)
        ug = (h[:, None] * tg + 0.5 * (ku[:-1] + ku[1:])[:, None]).ravel()
        uw = (h[:, None] * tw).ravel()
        iu, va, vb = _submerged_intervals(surf, ug, draft)
        if not len(iu):
            continue
        # V_SUBINTERVALS Gauss panels on each submerged interval, all evaluated in one call.
        edges = va[:, None] + (vb - va)[:, None] * np.linspace(0, 1, V_SUBINTERVALS + 1)
        hv = 0.5 * np.diff(edges, axis=1)
        vg = (hv[:, :, None] * tg + 0.5 * (edges[:, :-1] + edges[:, 1:])[:, :, None]).reshape(len(iu), -1)
        vw = (hv[:, :, None] * tw).reshape(len(iu), -1)
        w = (uw[iu][:, None] * vw).ravel()
        d = surf.derivatives(np.repeat(ug[iu], vg.shape[1]), vg.ravel(), 1)
        p, n = d[:, 0, 0], np.cross(d[:, 1, 0], d[:, 0, 1])
        terms = {
            "V": np.sum(w * p[:, 1] * n[:, 1]), "Mx": np.sum(w * p[:, 0] * p[:, 1] * n[:, 1]),
            "Mz": np.sum(w * p[:, 2] * p[:, 1] * n[:, 1]), "S": np.sum(w * np.linalg.norm(n, axis=1)),
            "Awp": -np.sum(w * n[:, 2]), "Mwp": -np.sum(w * p[:, 0] * n[:, 2]),
        }
        # Same orientation rule as the mesh path: side-like patches have ∫ y n_y > 0, end
        # faces ∫ (x - x_mid) n_x > 0.
        side = np.sum(w * np.abs(n[:, 1])) >= np.sum(w * np.abs(n[:, 0]))
        sgn = np.sign(terms["V"] if side else np.sum(w * (p[:, 0] - lpp / 2) * n[:, 0])) or 1.0
        for k in tot:
            tot[k] += terms[k] if k == "S" else sgn * terms[k]
    V = 2 * tot["V"]
    am = 2 * sum(_polyline_area(p, draft) for p in section_at(surfaces, lpp / 2, roles=roles))
    out = _coefficients(V, 2 * tot["Mx"] / V, 2 * tot["Mz"] / V, 2 * tot["Awp"], tot["Mwp"] / tot["Awp"], am,
                        lpp, beam, draft)
    out["wetted_surface"] = 2 * tot["S"]
    out["method"] = "Gauss quadrature on the NURBS surface"
    return out


def surface_meshes(surfaces, n_u=240, n_v=160):
    """Fine quad-split triangle meshes of the surfaces (the independent hydrostatics path)."""
    out = []
    for s in surfaces:
        us = np.linspace(*s.domain_u, n_u)
        vs = np.linspace(*s.domain_v, n_v)
        out.append(grid_mesh(s.evaluate_grid(us, vs)))
    return out


_SAMPLE_CACHE: dict = {}


def _dense(surface, n_u=400, n_v=120):
    key = id(surface)
    hit = _SAMPLE_CACHE.get(key)
    if hit is None or hit[0] is not surface:
        us = np.linspace(*surface.domain_u, n_u)
        vs = np.linspace(*surface.domain_v, n_v)
        hit = (surface, surface.evaluate_grid(us, vs))
        if len(_SAMPLE_CACHE) > 32:  # a bounded cache: surfaces of earlier runs are dropped
            _SAMPLE_CACHE.clear()
        _SAMPLE_CACHE[key] = hit
    return hit[1]


def section_at(surfaces, x0, roles=None):
    """Cuts of the surfaces by the plane x = x0 as (y, z) polylines, one per surface that
    reaches x0, each running in the surface's v direction (keel to top). End faces (role
    'transom') are skipped: they lie in a plane x ≈ const and have no section of their own."""
    out = []
    for k, s in enumerate(surfaces):
        if roles is not None and roles[k] == "transom":
            continue
        g = _dense(s)
        f = g[:, :, 0] - x0
        pts = []
        for j in range(g.shape[1]):
            col = f[:, j]
            idx = np.flatnonzero((col[:-1] <= 0) != (col[1:] <= 0))
            if not idx.size:
                continue
            i = idx[0]
            t = col[i] / (col[i] - col[i + 1])
            p = (1 - t) * g[i, j] + t * g[i + 1, j]
            pts.append(p[1:])
        if len(pts) >= 2:
            out.append(np.array(pts))
    return out


def _polyline_area(p, draft):
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


# ---- form parameters ---------------------------------------------------------------------

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


def _half_breadth_at(p, z0):
    """Outermost half-breadth of a (y, z) polyline where it crosses z0 (0 if it does not)."""
    y, z = p[:, 0], p[:, 1]
    best = 0.0
    for k in range(len(p) - 1):
        if (z[k] - z0) * (z[k + 1] - z0) <= 0 and z[k] != z[k + 1]:
            t = (z0 - z[k]) / (z[k + 1] - z[k])
            best = max(best, y[k] + t * (y[k + 1] - y[k]))
    return best


def section_parameters(pieces, draft, beam):
    """Per-section form parameters of one station cut into (y, z) polylines."""
    if not pieces:
        return None
    allp = np.concatenate(pieces)
    area = 2 * sum(_polyline_area(p, draft) for p in pieces)
    ymax = allp[:, 0].max()
    keel = allp[:, 1].min()
    top = pieces[int(np.argmax([p[:, 1].max() for p in pieces]))]
    deck = top[np.argmax(top[:, 1])]
    bottom = pieces[int(np.argmin([p[:, 1].min() for p in pieces]))]
    # Flat of side: the height range over which the half-breadth stays within FLAT_TOL of B/2.
    fos = allp[allp[:, 0] >= (1 - FLAT_TOL) * beam / 2]
    # Flat of bottom: the half-width over which the section stays on the keel line.
    fob = allp[allp[:, 1] <= keel + FLAT_TOL * draft]
    d = np.diff(bottom[:2], axis=0)[0] if len(bottom) >= 2 else np.array([1.0, 0.0])
    d_top = np.diff(top[-2:], axis=0)[0] if len(top) >= 2 else np.array([0.0, 1.0])
    kn = [float(p[k, 1]) for p in pieces for k in knuckles(p)]
    return {
        "area": area, "half_breadth_dwl": max(_half_breadth_at(p, draft) for p in pieces),
        "max_half_breadth": float(ymax), "keel_z": float(keel),
        "deck": [float(deck[0]), float(deck[1])],
        "fos_z": [float(fos[:, 1].min()), float(fos[:, 1].max())] if len(fos) else None,
        "fob_half_width": float(fob[:, 0].max()) if len(fob) else 0.0,
        "bottom_angle_deg": float(np.degrees(np.arctan2(d[1], d[0]))),
        "deck_angle_deg": float(np.degrees(np.arctan2(d_top[1], d_top[0]))),
        "area_coefficient": area / max(2 * ymax * (draft - keel), 1e-300) if ymax > 0 else 0.0,
        "knuckles_z": kn,
        "bottom_segment": [float(d[0]), float(d[1])], "deck_segment": [float(d_top[0]), float(d_top[1])],
    }


def form_parameters(surfaces, data: HullData, n_stations=41, roles=None) -> dict:
    """Basic curves and per-section parameters read off the rebuilt surfaces.

    Returns the SAC (x, area), DWL, deck and keel-profile curves at ``n_stations`` stations,
    the flat-of-side and flat-of-bottom extents, the end angles of the DWL and SAC, and the
    bow features found (bulb with Kracht's ratios, sonar dome)."""
    L, B, T = data.lpp, data.beam, data.draft
    pts = np.concatenate([_dense(s).reshape(-1, 3) for s in surfaces])
    x_aft, x_fwd = float(pts[:, 0].min()), float(pts[:, 0].max())
    xs = np.linspace(x_aft, x_fwd, n_stations)
    xs[0] += 1e-6 * L
    xs[-1] -= 1e-6 * L
    stations = []
    for x0 in xs:
        sp = section_parameters(section_at(surfaces, x0, roles=roles), T, B)
        if sp is not None:
            sp["x"] = float(x0)
            stations.append(sp)
    x = np.array([s["x"] for s in stations])
    sac = np.array([s["area"] for s in stations])
    dwl = np.array([s["half_breadth_dwl"] for s in stations])
    am = float(sac.max())
    fos_x = x[[s["fos_z"] is not None and s["fos_z"][0] <= T for s in stations]]
    fob_x = x[[s["fob_half_width"] >= FOB_MIN_HALF_WIDTH * B and s["keel_z"] <= FLAT_TOL * T for s in stations]]
    wet = dwl > 0
    xe, ye = x[wet], dwl[wet]
    # End angles of the DWL: half-angle of entrance (forward end) and of run (aft end), degrees.
    entrance = float(np.degrees(np.arctan2(ye[-2] - ye[-1], xe[-1] - xe[-2]))) if len(xe) > 2 else 0.0
    run = float(np.degrees(np.arctan2(ye[1] - ye[0], xe[1] - xe[0]))) if len(xe) > 2 else 0.0
    sub = pts[pts[:, 2] <= T]
    bow = {"kind": "none"}
    below_base = pts[(pts[:, 2] < -DOME_MIN_DEPTH * T) & (pts[:, 0] > 0.5 * L)]
    protrusion = float(sub[:, 0].max() - L) if len(sub) else 0.0
    if len(below_base):
        bow = {"kind": "sonar dome", "depth_below_baseline": float(-below_base[:, 2].min()),
               "x_aft_end": float(below_base[:, 0].min()), "x_fwd_end": float(below_base[:, 0].max())}
    elif protrusion > 0.005 * L:
        at_fp = section_at(surfaces, L, roles=roles)
        abt = 2 * sum(_polyline_area(p, T) for p in at_fp)
        bulb_pts = sub[sub[:, 0] >= L]
        tip = bulb_pts[np.argmax(bulb_pts[:, 0])]
        bb = 2 * max((p[p[:, 1] <= 0.8 * T, 0].max() if np.any(p[:, 1] <= 0.8 * T) else 0.0) for p in at_fp) \
            if at_fp else 0.0
        bow = {"kind": "bulb", "C_LPR": protrusion / L, "C_BB": bb / B, "C_ZB": float(tip[2]) / T,
               "C_ABT": abt / am, "length_beyond_fp": protrusion}
    roles = roles or []
    if "bulb" in roles and bow["kind"] != "bulb":
        bow["kind"] = "bulb"
    return {
        "SAC": {"x": x.tolist(), "area": sac.tolist(),
                "entrance_slope": float((sac[-2] - sac[-1]) / (x[-1] - x[-2])),
                "run_slope": float((sac[1] - sac[0]) / (x[1] - x[0]))},
        "DWL": {"x": x.tolist(), "half_breadth": dwl.tolist(), "entrance_angle_deg": entrance,
                "run_angle_deg": run},
        "deck": {"x": x.tolist(), "y": [s["deck"][0] for s in stations], "z": [s["deck"][1] for s in stations]},
        "profile": {"x": x.tolist(), "keel_z": [s["keel_z"] for s in stations],
                    "x_aft_end": x_aft, "x_fwd_end": x_fwd},
        "FOS": {"x_aft": float(fos_x.min()) if fos_x.size else None,
                "x_fwd": float(fos_x.max()) if fos_x.size else None},
        "FOB": {"x_aft": float(fob_x.min()) if fob_x.size else None,
                "x_fwd": float(fob_x.max()) if fob_x.size else None},
        "bow": bow,
        "sections": stations,
    }


# ---- rebuild -----------------------------------------------------------------------------

@dataclasses.dataclass
class Rebuild:
    """The rebuilt hull: one NURBS surface per input block, with its role, and the deviation
    of the surfaces from every input point."""
    surfaces: list
    roles: list
    names: list
    deviation: dict


def _hermite_slopes(s, f, corners):
    """Left and right slopes df/ds at the nodes of a shape-preserving (Fritsch–Carlson) cubic
    Hermite interpolant: no overshoot on flats (a flat bottom stays flat, a half-breadth
    stays >= 0), and at knuckles (``corners``) each side takes its own secant, so the corner
    is kept instead of being rounded."""
    h = np.diff(s)
    delta = np.diff(f) / h
    d = np.empty(len(s))
    d[0], d[-1] = delta[0], delta[-1]
    for k in range(1, len(s) - 1):
        a, b = delta[k - 1], delta[k]
        if a * b <= 0:
            d[k] = 0.0
        else:
            w1, w2 = 2 * h[k] + h[k - 1], h[k] + 2 * h[k - 1]
            d[k] = (w1 + w2) / (w1 / a + w2 / b)
    left, right = d.copy(), d.copy()
    for k in corners:
        left[k], right[k] = delta[k - 1], delta[k]
    return left, right


def _resample_section(points, n):
    """n points along a section at equal steps of chord length (SPEC §5 step b), on a
    shape-preserving cubic Hermite curve through the offsets that keeps flats flat and
    knuckles sharp. (A global interpolating cubic through a flat bottom and a tight bilge
    overshoots below the baseline and across the centreplane.)"""
    p = np.asarray(points, float)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    corners = knuckles(p)
    out_s = np.linspace(0.0, s[-1], n)
    # Every knuckle becomes a sample too (replacing the nearest interior sample, never an end
    # point), so the skinned surface has a grid line through it.
    taken = set()
    for k in corners:
        free = [i for i in range(1, n - 1) if i not in taken]
        if not free:
            break
        i = min(free, key=lambda i: abs(out_s[i] - s[k]))
        out_s[i] = s[k]
        taken.add(i)
    out_s = np.sort(out_s)
    idx = np.clip(np.searchsorted(s, out_s, side="right") - 1, 0, len(s) - 2)
    h = s[idx + 1] - s[idx]
    t = (out_s - s[idx]) / h
    h00, h10 = 2 * t ** 3 - 3 * t ** 2 + 1, t ** 3 - 2 * t ** 2 + t
    h01, h11 = -2 * t ** 3 + 3 * t ** 2, t ** 3 - t ** 2
    res = []
    for c in range(2):
        left, right = _hermite_slopes(s, p[:, c], corners)
        res.append(h00 * p[idx, c] + h10 * h * right[idx] + h01 * p[idx + 1, c] + h11 * h * left[idx + 1])
    return np.column_stack(res)


def sections_grid(data: HullData, n_v=61):
    """The offsets' sections as one (stations, n_v, 3) grid for skinning."""
    rows = []
    for s in data.sections:
        yz = _resample_section(s.points, n_v)
        rows.append(np.column_stack([np.full(n_v, s.x), yz]))
    return np.array(rows)


def rebuild(data: HullData, *, n_v=61, n_control=None, progress=None, deviation=True) -> Rebuild:
    """Fair surfaces through the data: the sections skinned into one surface (offsets and
    section lists), or one surface per structured grid; then the deviation of every input
    point from the surfaces.

    ``n_control``: None fairs each structured grid by least squares on half as many control
    points as grid lines (at least GRID_MIN_CONTROL) and interpolates the few stations of an
    offsets table; 'interpolate' interpolates everything; (nu, nv) fixes the counts."""
    say = progress or (lambda msg: None)
    surfaces, roles, names, blocks, fits = [], [], [], [], []
    if data.sections:
        grid = sections_grid(data, n_v)
        blocks.append(("hull", "hull", grid))
    for g in data.grids:
        blocks.append((g.name, g.role, g.points))
    for b, (name, role, grid) in enumerate(blocks):
        if n_control == "interpolate" or (n_control is None and data.sections and b == 0):
            nu, nv = None, None
        elif n_control is None:
            nu, nv = (min(n, max(GRID_MIN_CONTROL, -(-n // 2))) for n in grid.shape[:2])
        else:
            nu, nv = min(n_control[0], grid.shape[0]), min(n_control[1], grid.shape[1])
        say(f"fitting {name}: {grid.shape[0]} x {grid.shape[1]} points, "
            + ("interpolated" if nu is None else f"{nu} x {nv} control points (least squares)"))
        fit = _native.fit_surface(grid, 3 if grid.shape[0] > 3 else grid.shape[0] - 1,
                                  3 if grid.shape[1] > 3 else grid.shape[1] - 1, nu, nv)
        surfaces.append(fit.surface)
        fits.append(fit)
        roles.append(role)
        names.append(name)
    dev = None
    if deviation:
        say(f"measuring the deviation from every input point ({len(data.all_points())} points)")
        dev = deviation_report(data, surfaces, names, fits)
    return Rebuild(surfaces, roles, names, dev)


def deviation_report(data: HullData, surfaces, names, fits=None) -> dict:
    """Distance of every input point from the surface of its block: max, RMS and where the
    maximum occurs (x, y, z of the input point and its block).

    Section points are projected onto the surface (closest point). A grid point is first
    measured against the surface point at its fitting parameters, an upper bound of its
    distance; where that bound exceeds DEVIATION_EXACT_TOL it is projected from there by
    Gauss-Newton (an interpolating fit meets its grid to rounding, so the bound is already
    exact there)."""
    d_all, where = [], []
    off = 0
    if data.sections:
        pts = data.all_points()[: sum(len(s.points) for s in data.sections)]
        for p in pts:
            _, _, q = surfaces[0].closest_point(p)
            d_all.append(float(np.linalg.norm(q - p)))
            where.append((names[0], p))
        off = 1
    for k, g in enumerate(data.grids):
        s, pts = surfaces[k + off], g.points.reshape(-1, 3)
        if fits is not None:
            f = fits[k + off]
            uu, vv = np.meshgrid(f.params_u, f.params_v, indexing="ij")
            d = np.linalg.norm(s.evaluate(uu.ravel(), vv.ravel()) - pts, axis=1)
            far = d > DEVIATION_EXACT_TOL * data.lpp
            if far.any():
                q = project_points(s, pts[far], uu.ravel()[far], vv.ravel()[far])
                d[far] = np.minimum(d[far], np.linalg.norm(q - pts[far], axis=1))
        else:
            d = np.empty(len(pts))
            for i in range(len(pts)):
                _, _, q = s.closest_point(pts[i])
                d[i] = float(np.linalg.norm(q - pts[i]))
        d_all += d.tolist()
        where += [(names[k + off], p) for p in pts]
    d = np.array(d_all)
    i = int(np.argmax(d))
    return {"n_points": int(len(d)), "max": float(d.max()), "rms": float(np.sqrt(np.mean(d ** 2))),
            "max_at": {"block": where[i][0], "x": float(where[i][1][0]), "y": float(where[i][1][1]),
                       "z": float(where[i][1][2])},
            "rms_pct_B": 100 * float(np.sqrt(np.mean(d ** 2))) / data.beam}


def project_points(surface, pts, u0, v0, iterations=12):
    """Foot points on the surface of points near parameters (u0, v0), by Gauss-Newton on
    |S(u, v) - P|^2 for all points at once, kept inside the domain."""
    u, v = np.array(u0, float), np.array(v0, float)
    (ua, ub), (va, vb) = surface.domain_u, surface.domain_v
    for _ in range(iterations):
        d = surface.derivatives(u, v, 1)
        r = pts - d[:, 0, 0]
        su, sv = d[:, 1, 0], d[:, 0, 1]
        a, b, c = np.sum(su * su, 1), np.sum(su * sv, 1), np.sum(sv * sv, 1)
        f, g = np.sum(su * r, 1), np.sum(sv * r, 1)
        det = a * c - b * b
        ok = det > 1e-300
        du = np.where(ok, (c * f - b * g) / np.where(ok, det, 1), 0)
        dv = np.where(ok, (a * g - b * f) / np.where(ok, det, 1), 0)
        u, v = np.clip(u + du, ua, ub), np.clip(v + dv, va, vb)
    return surface.evaluate(u, v)


def input_hydrostatics(data: HullData) -> dict:
    """Hydrostatics of the input itself: Simpson on an offsets table, or the exact integrals
    of the triangulated point grids (the trapezoid rule's surface counterpart)."""
    if data.offsets is not None:
        return offsets_hydrostatics(data)
    if data.sections:
        return sections_hydrostatics(data)
    return mesh_hydrostatics([grid_mesh(g.points) for g in data.grids], data.draft, data.lpp, data.beam)


# ---- import / build (the command line's two steps) ---------------------------------------

HULL_JSON_TYPE = "fairlines_imported_hull"


def _jsonable(obj):
    if isinstance(obj, dict):
        return {k: _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        return float(obj) if np.isfinite(obj) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def import_hull(data: HullData, progress=None) -> dict:
    """The hull description written by ``fairlines import``: principal dimensions, the form
    parameters found automatically (basic curves, per-section parameters, bow features), the
    hydrostatics of the input, the published particulars and the input data itself."""
    from .offsets import hull_data_to_dict
    say = progress or (lambda msg: None)
    say("integrating the input (Simpson / trapezoid)")
    hyd = input_hydrostatics(data)
    for c in hyd.get("area_fraction_check", []):
        data.notes.append(f"station {c['station']!r}: tabulated area fraction {c['tabulated']:.3f} but the "
                          f"half-breadths integrate to {c['integrated']:.3f}; the half-breadths are used")
    say("skinning the sections into surfaces")
    rb = rebuild(data, progress=progress, deviation=False)
    say("reading the form parameters off the surfaces")
    fp = form_parameters(rb.surfaces, data, roles=rb.roles)
    try:
        description = hull_description(fp, data)
    except ValueError as exc:  # a hull whose forebody does not fit the description: say why
        description = None
        data.notes.append(f"no editable forebody description: {exc}")
    return _jsonable({
        "type": HULL_JSON_TYPE,
        "hull_description": description,
        "name": data.name,
        "principal": {"lpp": data.lpp, "beam": data.beam, "draft": data.draft},
        "form_parameters": fp,
        "subdomains": [{"name": n, "role": r} for n, r in zip(rb.names, rb.roles)],
        "hydrostatics_input": {k: v for k, v in hyd.items() if k not in ("section_x", "section_areas")},
        "published": data.published,
        "notes": data.notes,
        "input": hull_data_to_dict(data),
    })


def load_imported(doc) -> tuple:
    """(document, HullData) from a hull.json path or its dict; InvalidInput on anything else."""
    import json
    import pathlib

    from .offsets import hull_data_from_dict
    if not isinstance(doc, dict):
        path = pathlib.Path(doc)
        try:
            doc = json.loads(path.read_text())
        except OSError as exc:
            raise InvalidInput(f"cannot read {path}: {exc.strerror or exc}") from None
        except json.JSONDecodeError as exc:
            raise InvalidInput(f"{path}: not JSON ({exc.msg} at line {exc.lineno}); expected a hull.json "
                             "written by 'fairlines import'") from None
    if doc.get("type") != HULL_JSON_TYPE:
        raise InvalidInput(f"hull description type is {doc.get('type')!r}; expected {HULL_JSON_TYPE!r} "
                         "(written by 'fairlines import')")
    if "input" not in doc:
        raise InvalidInput("hull description has no 'input' entry; expected the data written by 'fairlines import'")
    return doc, hull_data_from_dict(doc["input"])


def build_hull(doc, out_dir=None, *, progress=None, mesh=(240, 160)) -> dict:
    """Rebuild the faired hull of an imported description: surfaces, deviation from every input
    point, hydrostatics of the input and of the surface (NURBS quadrature and, independently,
    a fine triangle mesh), next to the published particulars. Writes into ``out_dir`` (when
    given) one JSON and one OBJ per surface and ``report.json``."""
    import json
    import pathlib

    from .io import save_json, tessellate, write_obj
    say = progress or (lambda msg: None)
    doc, data = load_imported(doc)
    say("integrating the input (Simpson / trapezoid)")
    hin = input_hydrostatics(data)
    rb = rebuild(data, progress=progress)
    say("hydrostatics of the NURBS surface (Gauss quadrature)")
    hs = surface_hydrostatics(rb.surfaces, data.draft, data.lpp, data.beam, roles=rb.roles)
    say(f"hydrostatics of a {mesh[0]} x {mesh[1]} triangle mesh of the surface")
    hm = mesh_hydrostatics(surface_meshes(rb.surfaces, *mesh), data.draft, data.lpp, data.beam)
    report = _jsonable({
        "name": data.name, "principal": {"lpp": data.lpp, "beam": data.beam, "draft": data.draft},
        "deviation": rb.deviation,
        "hydrostatics": {"input": {k: v for k, v in hin.items() if k not in ("section_x", "section_areas")},
                         "surface": hs, "surface_mesh": hm},
        "published": data.published, "subdomains": [{"name": n, "role": r} for n, r in zip(rb.names, rb.roles)],
        "notes": data.notes,
    })
    if out_dir is not None:
        out = pathlib.Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        for name, s in zip(rb.names, rb.surfaces):
            stem = "surface_" + "".join(c if c.isalnum() else "_" for c in name)
            save_json(s, out / f"{stem}.json")
            write_obj(out / f"{stem}.obj", *tessellate(s, 96, 48))
        (out / "report.json").write_text(json.dumps(report, indent=1))
    report["_surfaces"] = rb.surfaces
    return report


def comparison_table(report) -> str:
    """Text table: input, surface, mesh of the surface, published, for the main particulars."""
    h = report["hydrostatics"]
    pub = report.get("published", {})
    rows = [("volume", "volume", "m3", "{:.6g}"), ("LCB % Lpp fwd of midship", "LCB_pct_Lpp_from_midship", "%",
                                                   "{:+.3f}"),
            ("Cb", "Cb", "", "{:.4f}"), ("Cp", "Cp", "", "{:.4f}"), ("Cm", "Cm", "", "{:.4f}"),
            ("Cwp", "Cwp", "", "{:.4f}"), ("wetted surface (no deck)", "wetted_surface", "m2", "{:.6g}")]
    lines = [f"{'':28s}{'input':>12s}{'surface':>12s}{'mesh':>12s}{'published':>12s}"]
    for label, key, _, fmt in rows:
        def cell(d):
            v = d.get(key) if d else None
            return f"{fmt.format(v):>12s}" if v is not None else f"{'-':>12s}"
        lines.append(f"{label:28s}" + cell(h["input"]) + cell(h["surface"]) + cell(h["surface_mesh"]) + cell(pub))
    d = report["deviation"]
    if d:
        m = d["max_at"]
        lines.append(f"deviation of the surface from {d['n_points']} input points: max {d['max']:.4g} m at "
                     f"({m['x']:.4g}, {m['y']:.4g}, {m['z']:.4g}) [{m['block']}], RMS {d['rms']:.4g} m "
                     f"= {d['rms_pct_B']:.4f} % of B")
    return "\n".join(lines)


# ---- editable form-parameter description (issue 4's hull description) -----------------------

# A basic curve stays on its midship value (the parallel middle body) while within this
# fraction of its scale (B/2, T, Am, or 1 degree for angles).
PARALLEL_TOL = 0.002
# The description's range ends at the last station whose keel lies below this fraction of T.
STEM_KEEL_FRACTION = 0.5
# Interior points handed to each basic curve beyond its parallel part.
DESCRIPTION_POINTS = 5


def _downward_angle(dy, dz):
    """Section tangent angle in degrees from the downward vertical toward +y, for a section
    running down from deck to keel whose upward segment is (dy, dz): 0 vertical, < 0 flare,
    -90 horizontal at the keel."""
    return float(np.degrees(np.arctan2(-dy, dz)))


def hull_description(fp: dict, data: HullData, *, n_stations=25) -> dict:
    """The forebody (midships to the FP) as a bare-hull description of basic curves with form
    parameters (the hull JSON of ``fl.Hull.from_json``, issue 4): each curve's midship value and
    the end of its parallel part, points read off the imported hull beyond it, its end value,
    and the integral parameters (forebody volume and LCB, waterplane area, entrance angle)."""
    L, B, T = data.lpp, data.beam, data.draft
    st = [s for s in fp["sections"] if s["x"] >= L / 2 - 1e-9 * L and s["x"] <= L]
    if len(st) < 4:
        raise InvalidInput(f"{data.name}: {len(st)} stations between midships and the FP; expected at least 4")
    x = np.array([s["x"] for s in st])
    # The description's stem is vertical at the end of its range: end the range at the last
    # station whose keel is still below STEM_KEEL_FRACTION of the draft (a raked forefoot
    # forward of it is left to auxiliary sections or the bulb).
    keel = np.array([s["keel_z"] for s in st])
    deep = np.flatnonzero(keel <= STEM_KEEL_FRACTION * T)
    x0, x1 = L / 2, min(L, float(x[deep[-1]]))
    st = [s for s in st if s["x"] <= x1]
    x = x[: len(st)]
    top = float(np.median([s["deck"][1] for s in st[: max(2, len(st) // 4)]]))
    curves = {
        "sac": (np.array([s["area"] for s in st]), max(fp["SAC"]["area"])),
        "dwl": (np.minimum([s["half_breadth_dwl"] for s in st], B / 2), B / 2),
        "deck": (np.minimum([s["deck"][0] for s in st], B / 2), B / 2),
        "profile": (np.array([s["keel_z"] for s in st]), T),
        "deck_angle": (np.array([_downward_angle(*s["deck_segment"]) for s in st]), None),
        "bottom_angle": (np.array([_downward_angle(*s["bottom_segment"]) for s in st]), None),
    }
    fos_low = np.array([s["fos_z"][0] if s["fos_z"] else np.nan for s in st])
    fob = np.minimum([s["fob_half_width"] for s in st], B / 2)
    out = {}

    def spec(f, scale, x_end=x1):
        tol = PARALLEL_TOL * scale if scale else 1.0
        n_flat = int(np.argmax(np.abs(f - f[0]) > tol)) if np.any(np.abs(f - f[0]) > tol) else len(f)
        flat_to = float(x[max(n_flat - 1, 0)])
        flat_to = min(max(flat_to, x0 + 1e-3 * L), x_end - 1e-2 * L)
        inner = (x > flat_to + 1e-3 * L) & (x < x_end - 1e-3 * L)
        k = np.flatnonzero(inner)
        if len(k) > DESCRIPTION_POINTS:
            k = k[np.round(np.linspace(0, len(k) - 1, DESCRIPTION_POINTS)).astype(int)]
        # Room for every condition (start value, slope and curvature, end value, points,
        # integrals) and some freedom left for fairness.
        return {"flat_to": flat_to, "value": float(f[0]), "yE": float(np.interp(x_end, x, f)),
                "points": [[float(x[i]), float(f[i])] for i in k], "n_control": len(k) + 9}
    # Where the flat side reaches below the DWL, the DWL and deck lie on it (within FLAT_TOL):
    # say so exactly, as the section design requires.
    on_fos = ~np.isnan(fos_low) & (fos_low < T)
    for name in ("dwl", "deck"):
        curves[name] = (np.where(on_fos, B / 2, curves[name][0]), curves[name][1])
    for name, (f, scale) in curves.items():
        # Lengths and areas are >= 0 by definition; a skinned surface dipping a hair below the
        # baseline between stations must not hand a negative keel height on.
        out[name] = spec(f if scale is None else np.maximum(f, 0.0), scale)
    # The flat side as a basic curve: its lower end at every station from midships on where the
    # side is flat, rising to the deck where the flat side ends (fairlines.sections continues
    # a curve that ends on the deck smoothly; one that ended lower would stop abruptly).
    fos_ok = np.flatnonzero(~np.isnan(fos_low))
    fos_ok = fos_ok[: int(np.argmax(np.diff(np.append(fos_ok, -9)) != 1)) + 1] if len(fos_ok) else fos_ok
    if len(fos_ok) >= 2 and fos_ok[-1] + 1 < len(x):
        end = float(x[fos_ok[-1] + 1])
        f = np.where(np.arange(len(x)) <= fos_ok[-1], np.nan_to_num(fos_low, nan=top), top)
        out["fos"] = spec(f, T, end) | {"x_end": end, "yE": top}
    else:
        out["fos"] = {"value": T, "flat_to": x0 + 1e-3 * L, "x_end": x0 + 2e-3 * L, "yE": T}
    fob_end = fp["FOB"]["x_fwd"] if fp["FOB"]["x_fwd"] else x0 + 2e-3 * L
    out["fob"] = spec(fob, B / 2, fob_end) | {"x_end": float(fob_end), "yE": 0.0}
    fore = x >= x0
    out["sac"]["volume"] = float(simpson(curves["sac"][0][fore], x[fore]))
    out["sac"]["lcb"] = float(simpson(curves["sac"][0][fore] * x[fore], x[fore]) / out["sac"]["volume"])
    out["dwl"]["waterplane_area"] = float(2 * simpson(curves["dwl"][0][fore], x[fore]))
    return _jsonable({
        "name": f"{data.name}, forebody read off the imported hull",
        "notes": "Written by fairlines import: basic curves and form parameters found automatically "
                 "(SPEC §2 step 1); edit any value and rebuild with fl.Hull.from_json.",
        "principal": {"Lpp": L, "B": B, "T": T, "D": top},
        "range": {"x_start": x0, "x_end": x1},
        "stations": {"count": int(n_stations)},
        "basic_curves": out,
        "sections": {"n_control": 16},
        "skinning": {"start": "parallel", "end": "free"},
    })
