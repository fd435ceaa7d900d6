"""Rebuilding hull data as NURBS surfaces (sections resampled and skinned, grids fitted) and the
deviation of the surfaces from every input point."""

from __future__ import annotations

import dataclasses

import numpy as np

from .. import _native
from ..offsets import HullData, knuckles


# A grid point whose distance at its fitting parameters is below this fraction of Lpp is not
# projected onto the surface again (the bound is then the deviation to within rounding).
DEVIATION_EXACT_TOL = 1e-9


# Least-squares fairing of a structured grid keeps at least this many control points a direction.
GRID_MIN_CONTROL = 12


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


def resample_section(points, n):
    """n points along a section at equal steps of chord length (the fair-skinning
    parametrisation of Kim & Hwangbo 2008), on a shape-preserving cubic Hermite curve
    through the offsets that keeps flats flat and knuckles sharp. (A global interpolating
    cubic through a flat bottom and a tight bilge overshoots below the baseline and across
    the centreplane.)"""
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
        yz = resample_section(s.points, n_v)
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
        d_all += distances(surfaces[0], pts).tolist()
        where += [(names[0], p) for p in pts]
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
            d = distances(s, pts)
        d_all += d.tolist()
        where += [(names[k + off], p) for p in pts]
    d = np.array(d_all)
    i = int(np.argmax(d))
    return {"n_points": int(len(d)), "max": float(d.max()), "rms": float(np.sqrt(np.mean(d ** 2))),
            "max_at": {"block": where[i][0], "x": float(where[i][1][0]), "y": float(where[i][1][1]),
                       "z": float(where[i][1][2])},
            "rms_pct_B": 100 * float(np.sqrt(np.mean(d ** 2))) / data.beam}


def distances(surface, pts) -> np.ndarray:
    """Distance (m) from each of ``pts`` (m, 3) to the surface: the engine's global closest-point
    search for the batch (``NurbsSurface.closest_points``). Raises InvalidInput for bad shapes
    or non-finite values."""
    pts = np.asarray(pts, float).reshape(-1, 3)
    return np.linalg.norm(surface.closest_points(pts)[2] - pts, axis=1)


def project_points(surface, pts, u0, v0):
    """Foot points (m, 3) on the surface of points ``pts`` (m, 3) near parameters (u0, v0):
    the engine's local Newton (``NurbsSurface.closest_points``), kept inside the domain.
    Raises InvalidInput for bad shapes or non-finite values."""
    return surface.closest_points(pts, u0, v0)[2]
