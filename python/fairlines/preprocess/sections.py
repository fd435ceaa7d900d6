"""Sections of rebuilt surfaces by planes x = const as (y, z) polylines."""

from __future__ import annotations

import numpy as np


# Samples of a surface for cutting sections: fine in u (along the hull), coarser in v (girth).
SECTION_SAMPLES_U = 400
SECTION_SAMPLES_V = 120


def dense_samples(surface):
    """(SECTION_SAMPLES_U, SECTION_SAMPLES_V, 3) grid of surface points on equally spaced
    parameters, the polylines :func:`section_at` cuts (compute once, pass to every cut)."""
    us = np.linspace(*surface.domain_u, SECTION_SAMPLES_U)
    vs = np.linspace(*surface.domain_v, SECTION_SAMPLES_V)
    return surface.evaluate_grid(us, vs)


def section_at(surfaces, x0, roles=None, *, samples=None):
    """Cuts of the surfaces by the plane x = x0 as (y, z) polylines, one per surface that
    reaches x0, each running in the surface's v direction (keel to top). End faces (role
    'transom') are skipped: they lie in a plane x ≈ const and have no section of their own.
    ``samples``: the surfaces' :func:`dense_samples`, when several cuts share them."""
    if samples is None:
        samples = [dense_samples(s) for s in surfaces]
    out = []
    for k, s in enumerate(surfaces):
        if roles is not None and roles[k] == "transom":
            continue
        g = samples[k]
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
