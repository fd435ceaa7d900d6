"""The one real hull the blend-geometry tests use: the whole container ship composed with its
bulb and blend, and finite-difference surface normals (independent of the engine's own)."""

import functools

import numpy as np

import fairlines as fl


@functools.lru_cache(maxsize=1)
def container_ship_composed() -> fl.ComposedHull:
    hull = fl.design_hull(lpp=244.8, breadth=32.25, draft=11.0, depth=19.0, cb=0.65, lcb=118.73, bulb=True)
    return hull.composed_hull()


def fd_normal(surface: fl.NurbsSurface, u: float, v: float, h: float = 1e-6) -> np.ndarray:
    """Unit normal by central differences of surface points (one-sided at the domain ends)."""
    (u0, u1), (v0, v1) = surface.domain_u, surface.domain_v
    ua, ub = max(u0, u - h), min(u1, u + h)
    va, vb = max(v0, v - h), min(v1, v + h)
    su = (np.asarray(surface.evaluate(ub, v)) - np.asarray(surface.evaluate(ua, v))) / (ub - ua)
    sv = (np.asarray(surface.evaluate(u, vb)) - np.asarray(surface.evaluate(u, va))) / (vb - va)
    n = np.cross(su, sv)
    return n / np.linalg.norm(n)
