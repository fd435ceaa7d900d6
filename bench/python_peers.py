"""The Python implementations the engine replaced, kept as peers for the benchmarks only
(measured in the same process against the engine calls that replaced them)."""

import numpy as np

from fairlines.preprocess.integrate import coefficients, polyline_area
from fairlines.preprocess.sections import section_at


def _clip_positive(tri: np.ndarray, c: float) -> list[np.ndarray]:
    """Part of triangle tri (3, 3) with x >= c, as a fan of triangles."""
    poly = []
    for k in range(3):
        p, q = tri[k], tri[(k + 1) % 3]
        if p[0] >= c:
            poly.append(p)
        if (p[0] - c) * (q[0] - c) < 0:
            t = (c - p[0]) / (q[0] - p[0])
            poly.append(p + t * (q - p))
    return [np.array([poly[0], poly[i], poly[i + 1]]) for i in range(1, len(poly) - 1)]


def python_measure_kracht(mesh, *, x_fp: float, lpp: float, beam: float, draft_fp: float,
                   midship_area: float, displacement_volume: float) -> dict:
    """Kracht coefficients measured on a closed, outward-oriented half-hull mesh (y >= 0),
    on its part below the waterline z = draft_fp (a raked stem reaches forward of the FP
    above it, and is not bulb).

    Protrusion = max x - x_fp; nose height = z of the foremost point; bulb breadth = 2 max y
    on the section x = x_fp; section area at FP = 2 * x-component of the area vector of the
    surface forward of FP (closed-surface identity: the waterplane's n_x is 0); lateral area =
    centre-plane area forward of FP; volume forward of FP = 2 * sum (x - x_fp) n_x dA over the
    surface forward of FP (divergence theorem with the field (x - x_fp, 0, 0), which vanishes
    on the cut and has no flux through the waterplane).
    """
    V = np.asarray(mesh.vertices, float)
    tris = V[np.asarray(mesh.faces)]
    keep = (tris[:, :, 0].max(axis=1) > x_fp) & (tris[:, :, 2].min(axis=1) < draft_fp)
    ax = vol = lat = ymax = 0.0
    nose = np.array([-np.inf, 0.0, 0.0])
    for t in tris[keep]:
        cp = bool(np.all(t[:, 1] == 0.0))
        for low in _clip_below(t, draft_fp) if t[:, 2].max() > draft_fp else [t]:
            for k in range(3):  # section crossing points
                p, q = low[k], low[(k + 1) % 3]
                if (p[0] - x_fp) * (q[0] - x_fp) <= 0 and p[0] != q[0]:
                    s = (x_fp - p[0]) / (q[0] - p[0])
                    ymax = max(ymax, p[1] + s * (q[1] - p[1]))
            for piece in _clip_positive(low, x_fp):
                n = 0.5 * np.cross(piece[1] - piece[0], piece[2] - piece[0])
                ax += n[0]
                vol += (piece[:, 0].mean() - x_fp) * n[0]
                if cp:
                    lat += np.linalg.norm(n)
                front = piece[np.argmax(piece[:, 0])]
                if front[0] > nose[0]:
                    nose = front
    return dict(
        c_lpr=(nose[0] - x_fp) / lpp,
        c_bb=2.0 * ymax / beam,
        c_zb=float(nose[2]) / draft_fp,
        c_abt=2.0 * ax / midship_area,
        c_abl=lat / midship_area,
        c_vpr=2.0 * vol / displacement_volume,
    )


def _clip_below(tri: np.ndarray, z0: float) -> list[np.ndarray]:
    """Part of triangle tri (3, 3) with z <= z0, as a fan of triangles."""
    poly = []
    for k in range(3):
        p, q = tri[k], tri[(k + 1) % 3]
        if p[2] <= z0:
            poly.append(p)
        if (p[2] - z0) * (q[2] - z0) < 0:
            t = (z0 - p[2]) / (q[2] - p[2])
            poly.append(p + t * (q - p))
    return [np.array([poly[0], poly[i], poly[i + 1]]) for i in range(1, len(poly) - 1)]


def python_mesh_hydrostatics(mesh, draft: float, *, half: bool = True) -> dict:
    """Displaced volume (m^3), LCB and KB (m) of a closed, outward-oriented mesh floating at
    z = draft, by the divergence theorem over the surface below the waterline with fields
    that vanish on the waterplane: (0, 0, z - T) for the volume, (0, 0, x (z - T)) for the
    x-moment and (0, 0, (z^2 - T^2) / 2) for the z-moment. ``half``: the mesh is the
    starboard half (volume doubled, centroid unchanged)."""
    tris = np.asarray(mesh.vertices, float)[np.asarray(mesh.faces)]
    T = float(draft)
    vol = mx = mz = 0.0
    for t in tris[tris[:, :, 2].min(axis=1) < T]:
        for p in _clip_below(t, T) if t[:, 2].max() > T else [t]:
            nz = 0.5 * np.cross(p[1] - p[0], p[2] - p[0])[2]
            # exact for linear integrands: mean over the vertices; quadratic z^2 and x z use
            # the edge-midpoint rule (exact for quadratics on a triangle)
            mid = 0.5 * (p + np.roll(p, -1, axis=0))
            vol += (p[:, 2].mean() - T) * nz
            mx += np.mean(mid[:, 0] * (mid[:, 2] - T)) * nz
            mz += np.mean(0.5 * (mid[:, 2] ** 2 - T * T)) * nz
    if vol <= 0.0:
        raise ValueError(f"draft {draft} m gives no displaced volume; expected a draft above the keel")
    f = 2.0 if half else 1.0
    return dict(volume=f * vol, lcb=mx / vol, kb=mz / vol)


# Gauss-Legendre points per knot span (u) and per sub-interval (v) for surface integrals.
GAUSS_POINTS = 6


# Sub-intervals per submerged v-interval in the surface integrals.
V_SUBINTERVALS = 24


# Samples along each iso-line used to find where it crosses the waterline (then bisected).
CROSSING_SAMPLES = 256


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


def python_surface_hydrostatics(surfaces, draft, lpp, beam, *, roles=None):
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
    am = 2 * sum(polyline_area(p, draft) for p in section_at(surfaces, lpp / 2, roles=roles))
    return coefficients(V, 2 * tot["Mx"] / V, 2 * tot["Mz"] / V, 2 * tot["Awp"], tot["Mwp"] / tot["Awp"], am,
                        lpp, beam, draft, method="Gauss quadrature on the NURBS surface", wetted_surface=2 * tot["S"])


def python_project_points(surface, pts, u0, v0, iterations=12):
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
