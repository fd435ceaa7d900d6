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
    n = np.cross(*fd_partials(surface, u, v, h))
    return n / np.linalg.norm(n)


def fd_partials(surface: fl.NurbsSurface, u: float, v: float, h: float = 1e-6) -> tuple[np.ndarray, np.ndarray]:
    """S_u, S_v by central differences of surface points (one-sided at the domain ends)."""
    (u0, u1), (v0, v1) = surface.domain_u, surface.domain_v
    ua, ub = max(u0, u - h), min(u1, u + h)
    va, vb = max(v0, v - h), min(v1, v + h)
    su = (np.asarray(surface.evaluate(ub, v)) - np.asarray(surface.evaluate(ua, v))) / (ub - ua)
    sv = (np.asarray(surface.evaluate(u, vb)) - np.asarray(surface.evaluate(u, va))) / (vb - va)
    return su, sv


def fd_normal_curvature(surface: fl.NurbsSurface, u: float, v: float, t: np.ndarray, step: float = 1e-4) -> float:
    """The surface's normal curvature (1/m, signed along fd_normal) at (u, v) in the unit
    tangent direction t: the second difference of surface points along the parameter line
    (u + a e, v + b e) whose tangent is t, over |tangent|^2 (one-sided at the domain's edge)."""
    su, sv = fd_partials(surface, u, v)
    g = np.array([[su @ su, su @ sv], [su @ sv, sv @ sv]])
    a, b = np.linalg.solve(g, [su @ t, sv @ t])
    c1 = a * su + b * sv
    (u0, u1), (v0, v1) = surface.domain_u, surface.domain_v
    e = step / np.linalg.norm(c1)

    def inside(k):
        return u0 <= u + a * k * e <= u1 and v0 <= v + b * k * e <= v1

    def p(k):
        return np.asarray(surface.evaluate(u + a * k * e, v + b * k * e))

    if inside(-1) and inside(1):
        c2 = (p(1) - 2 * p(0) + p(-1)) / e**2
    else:  # second-order one-sided: a blend's section turns fast just off its edge
        k = 1 if inside(3) else -1
        c2 = (2 * p(0) - 5 * p(k) + 4 * p(2 * k) - p(3 * k)) / e**2
    return float(fd_normal(surface, u, v) @ c2) / float(c1 @ c1)


#: Largest normal turn (deg) between neighbouring points of largest_normal_turn_deg's grid for a
#: blend that does not fold: folds measured 115-180 deg, the unfolded blends of bench_design_options
#: and bench_hull up to 60.
FOLD_DEG = 90.0


def largest_normal_turn_deg(surface: fl.NurbsSurface, nu: int = 241, nv: int = 61) -> float:
    """The largest angle (deg) between the normals at neighbouring points of an nu x nv grid of
    the surface, normals from differences of the grid's points (independent of the engine's).
    A fold, where the surface runs back over itself, turns its normal by up to 180 deg between
    neighbours; a fair blend at this grid turns it by a few degrees."""
    u, v = np.linspace(*surface.domain_u, nu), np.linspace(*surface.domain_v, nv)
    g = np.asarray(surface.evaluate_grid(u, v)).reshape(nu, nv, 3)
    n = np.cross(np.gradient(g, axis=0), np.gradient(g, axis=1))
    n /= np.linalg.norm(n, axis=2, keepdims=True)
    turn_u = np.einsum("ijk,ijk->ij", n[1:], n[:-1])
    turn_v = np.einsum("ijk,ijk->ij", n[:, 1:], n[:, :-1])
    return float(np.degrees(np.arccos(np.clip(min(turn_u.min(), turn_v.min()), -1.0, 1.0))))
