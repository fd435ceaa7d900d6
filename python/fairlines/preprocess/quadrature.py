"""Hydrostatics of NURBS half-hull surfaces by Gauss quadrature over the parameter domain, each
iso-line cut exactly at the waterline."""

from __future__ import annotations

import numpy as np

from .integrate import coefficients, polyline_area
from .sections import section_at


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
    am = 2 * sum(polyline_area(p, draft) for p in section_at(surfaces, lpp / 2, roles=roles))
    out = coefficients(V, 2 * tot["Mx"] / V, 2 * tot["Mz"] / V, 2 * tot["Awp"], tot["Mwp"] / tot["Awp"], am,
                        lpp, beam, draft)
    out["wetted_surface"] = 2 * tot["S"]
    out["method"] = "Gauss quadrature on the NURBS surface"
    return out
